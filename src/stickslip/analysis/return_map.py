"""The breakaway-to-breakaway return map ``P`` of a stick-slip motion and its exact Jacobian.

A stick-slip cycle is a fixed point of ``P^k`` (the section is the set of
breakaway states, ``xi' = 1`` and the stick force at its static limit, Eq. 20). :class:`ReturnMap`
evaluates ``P^k`` with bare engine runs (:func:`stickslip.analysis.engine_run.run_engine`) and
its Jacobian from the saltation matrices of every event; :func:`newton_fixed_point` solves
``P^k(b) = b``. :func:`stickslip.find_cycles` searches with them and
:mod:`stickslip.analysis.cycle_proof` proves their fixed points.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.engine_run import EngineOptions, SimulationResult, run_engine
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.kernel.linalg import expm
from stickslip.kernel.system import SLIP_I, SLIP_II, STICK, mode_kind_band, mode_matrices
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]


class PhaseFactor(NamedTuple):
    """One phase of a linearised run (:meth:`ReturnMap.phase_factors`)."""

    propagator: FloatArray  #: ``expm(A t)``
    jump: FloatArray  #: ``f^+ - f^-``, the field's jump at the event ending the phase
    normal: FloatArray  #: ``n``, the event surface's normal
    rate: float  #: ``n . f^-``
    mode: int  #: the phase's mode code
    duration: float  #: ``t``, dimensionless
#: Events allowed per friction band in a run of the return map: a stick-slip cycle crosses
#: each band edge a few times, and a run spans at most ``2 max_period + 1`` breakaways (the
#: Coulomb law, one band: 400 events; a Stribeck interpolant of 100 bands: 40,000).
RETURN_EVENTS = 400


class ReturnMap:
    """``P(b)``: the next breakaway state after the breakaway state built from ``b``.

    Also holds what the exact Jacobian needs: the per-mode matrices of the affine flows
    ``z' = A z + c`` (:func:`stickslip.kernel.system.mode_matrices`, one slip-I and one
    slip-II mode per friction band, and stick), the stick-force row and the lift
    ``d state / d b``.
    """

    def __init__(self, structure: Structure, slider: Slider, options: EngineOptions,
                 direction: int = SLIP_I) -> None:
        self.structure, self.slider = structure, slider
        #: the section: breakaways onto slip-I (``S = lambda``) or onto slip-II
        #: (``S = -lambda (1 + 2 gamma)``), Eq. (20)
        self.direction = int(direction)
        self.level = (float(slider.lam) if direction == SLIP_I
                      else -float(slider.lam) * (1.0 + 2.0 * float(slider.gamma)))
        edges, intercepts, slopes = slider.friction.bands(float(slider.lam), float(slider.gamma))
        #: the friction bands' edges in the sliding speed ``u`` (their event surfaces)
        self.edges: FloatArray = np.asarray(edges, dtype=np.float64)
        self.options = EngineOptions(t_max=options.t_max, max_events=RETURN_EVENTS * len(intercepts))
        self.n = structure.n_dof
        self.evaluations = 0
        #: runs that ended at the horizon or an event budget before their breakaways
        self.cut_short = 0
        n2 = 2 * self.n
        ahat, stick_row = mode_matrices(
            np.ascontiguousarray(structure.mass, dtype=np.float64),
            np.ascontiguousarray(structure.damping, dtype=np.float64),
            np.ascontiguousarray(structure.stiffness, dtype=np.float64),
            float(slider.lam), float(slider.gamma),
            np.ascontiguousarray(intercepts, dtype=np.float64),
            np.ascontiguousarray(slopes, dtype=np.float64),
        )
        #: ``A`` (modes, 2n, 2n) and ``c`` (modes, 2n) of ``z' = A z + c`` per mode code
        self.flow_matrix: FloatArray = np.asarray(ahat[:, :n2, :n2])
        self.flow_constant: FloatArray = np.asarray(ahat[:, :n2, n2])
        #: normal of the stick mode's events: ``S = stick_row . z`` (Eq. 20 with ``xi'' = 0``)
        self.stick_normal: FloatArray = np.asarray(stick_row[:n2])
        #: normal of every slip-mode event (the slider velocity reaching a value): ``e_{v_0}``
        self.slip_normal = np.zeros(n2)
        self.slip_normal[self.n] = 1.0
        #: ``d state(b) / d b`` (2n, 2n - 2): the foundation coordinates are copied, and
        #: ``xi`` moves to keep ``S = lambda`` (see :meth:`state`)
        n, row = self.n, self.stick_normal
        self.lift = np.zeros((n2, n2 - 2))
        self.lift[1:n, : n - 1] = np.eye(n - 1)
        self.lift[n + 1:, n - 1:] = np.eye(n - 1)
        self.lift[0, : n - 1] = -row[1:n] / row[0]
        self.lift[0, n - 1:] = -row[n + 1:] / row[0]

    def state(self, b: FloatArray) -> FloatArray:
        """Breakaway state from the foundation coordinates ``b``: ``xi' = 1`` and ``S`` at the
        section's level (``lambda`` onto slip-I, ``-lambda (1 + 2 gamma)`` onto slip-II)."""
        n, row = self.n, self.stick_normal
        q = np.zeros(n)
        v = np.zeros(n)
        v[0] = 1.0
        q[1:], v[1:] = b[: n - 1], b[n - 1:]
        # S = s_j z_j (the stick force of Eq. 20 with xi'' = 0; K_0j q_j + C_0j v_j for a
        # diagonal mass, with the stick mode's accelerations added for a coupled one)
        rest = row[1:n] @ q[1:] + row[n:] @ v
        q[0] = (self.level - rest) / row[0]
        return np.concatenate([q, v])

    def reduce(self, state: FloatArray) -> FloatArray:
        """The foundation coordinates of a full state."""
        n = self.n
        return np.concatenate([state[1:n], state[n + 1:]])

    def recorded_run(self, state: FloatArray, count: int, *, on_section: bool = True
                     ) -> tuple[SimulationResult, FloatArray] | None:
        """The recorded run from ``state`` and the times of its next ``count`` breakaways.

        None when there are fewer: in particular when steady sliding is certified, after which
        the slider never sticks again. A run that certifies its cycle early is continued (up
        to the event budget) to reach ``count`` breakaways.
        """
        n = self.n
        initial = InitialState(state[:n], state[n:])
        for run_on in (False, True):
            self.evaluations += 1
            # the engine alone: the map's runs are no verdicts (simulate proves its candidates)
            result = run_engine(self.structure, self.slider, initial, self.options, True, run_on)
            # the start is itself a breakaway: the engine may register it at t = 0 or within
            # rounding of it (its stick force equals lambda only to rounding); it is not "next"
            times = [t for t in result.breakaway_times if t > 1e-9][:count]
            if len(times) >= count or result.verdict is not Verdict.STICK_SLIP:
                break
        if len(times) < count and result.status in (RunStatus.T_MAX, RunStatus.MAX_EVENTS,
                                                    RunStatus.MAX_STEPS):
            self.cut_short += 1
        if len(times) < count or (on_section and
                                  self.breakaway_direction(result, times[-1]) != self.direction):
            return None  # fewer breakaways, or the k-th is not onto this section's slip mode
        return result, np.array(times)

    @staticmethod
    def breakaway_direction(result: SimulationResult, t: float) -> int:
        """``SLIP_I`` or ``SLIP_II``: the slip mode a breakaway at ``t`` goes onto."""
        i = int(np.searchsorted(result.segment_times, t, side="left"))
        if i >= result.segment_times.size or abs(float(result.segment_times[i]) - t) > 1e-12 * max(1.0, t):
            i = max(0, i - 1)
        return mode_kind_band(int(result.segment_modes[i]))[0]

    def direction_of(self, state: FloatArray) -> int:
        """The section a breakaway state lies on: the nearer of the two stick-force levels."""
        force = float(self.stick_normal @ state)
        low = -float(self.slider.lam) * (1.0 + 2.0 * float(self.slider.gamma))
        return SLIP_I if abs(force - float(self.slider.lam)) <= abs(force - low) else SLIP_II

    def next_breakaways(self, state: FloatArray, count: int) -> list[FloatArray]:
        """The full states of the next ``count`` breakaways after starting at ``state``.

        Empty when there are fewer (see :meth:`_run`).
        """
        run = self.recorded_run(state, count, on_section=False)
        if run is None:
            return []
        result, times = run
        q, v, _ = result.state_at(times)
        return [np.concatenate([q[i], v[i]]) for i in range(len(times))]

    def signature(self, b: FloatArray, k: int) -> tuple[int, ...] | None:
        """The kinds of the phases (slip-I, slip-II, stick; friction bands merged) from the
        breakaway built from ``b`` up to the ``k``-th next breakaway; None when there are fewer.

        A change of the signature along a branch is a grazing: a phase appears or vanishes.
        """
        run = self.recorded_run(self.state(b), k)
        if run is None:
            return None
        result, times = run
        kinds = [mode_kind_band(int(m))[0] for m, t in zip(result.segment_modes, result.segment_times,
                                                        strict=True) if t < times[-1]]
        merged = [kind for i, kind in enumerate(kinds) if i == 0 or kind != kinds[i - 1]]
        while merged and merged[0] == STICK:  # the start's own stick phase (within rounding of 0)
            merged.pop(0)
        return tuple(merged)

    def __call__(self, b: FloatArray, k: int) -> FloatArray | None:
        states = self.next_breakaways(self.state(b), k)
        return None if not states else self.reduce(states[-1])

    def _field(self, mode: int, z: FloatArray) -> FloatArray:
        """Vector field ``A z + c`` of mode ``mode`` at the state ``z`` (per unit ``tau``)."""
        return np.asarray(self.flow_matrix[mode] @ z + self.flow_constant[mode])

    def _normal(self, mode: int) -> FloatArray:
        """Normal of the event surfaces that end a phase of mode ``mode``."""
        return self.stick_normal if mode == STICK else self.slip_normal

    def linearise(self, b: FloatArray, k: int) -> tuple[FloatArray, FloatArray] | None:
        """``P^k(b)`` and its exact Jacobian ``D P^k(b)``, from one recorded run.

        Parameters
        ----------
        b : ndarray, shape (2 n_dof - 2,)
            Foundation coordinates of a breakaway state (``V/omega_n`` and ``V``).
        k : int
            Breakaways to go (the map ``P^k``).

        Returns
        -------
        (ndarray, ndarray) or None
            ``P^k(b)`` (shape ``(2 n_dof - 2,)``) and ``D P^k(b)`` (square, dimensionless);
            None when the run does not reach ``k`` breakaways or an event is grazing (the
            map is not differentiable there).

        Notes
        -----
        Full state ``z = (q, v)`` (2 n_dof), shifted coordinates of Eqs. (15)-(16). Between
        events the motion is affine in each mode, ``z' = A z + c``: slip-I and slip-II
        (Eqs. 22-27; a friction band with ``F(u) = a + s u`` adds ``s`` to ``C_00`` and a
        constant force) and stick (Eqs. 19 and 21: ``xi' = 1``, ``xi'' = 0``, the foundation
        driven). A perturbation carried through a phase of duration ``t`` is therefore
        ``delta z -> expm(A t) delta z`` (``c`` drops out).

        Events. A phase ends when ``g(z) = n . z - g_0`` reaches zero at ``t_e``. The
        perturbed motion reaches it at ``t_e + dt`` with ``n . (delta z^- + f^- dt) = 0``,
        ``dt = -n . delta z^- / (n . f^-)``, where ``f^-`` and ``f^+`` are the fields of the
        modes before and after at the event state. Comparing the two motions at a common time
        after the event gives the saltation matrix

            ``delta z^+ = S delta z^-,   S = I + (f^+ - f^-) n^T / (n . f^-)``.

        Every event of a slip mode is the slider velocity reaching a value (the belt speed
        ``xi' = 1``, or a band edge ``xi' = 1 -+ u_edge``), so ``n = e_{v_0}`` and
        ``n . f^- = xi''``. Every event of the stick mode is the stick force
        ``S = stick_row . z`` (Eq. 20 with ``xi'' = 0``, ``2 zeta (1 - xi_a') + xi - xi_a``
        for the paper's foundation) reaching ``lambda`` (breakaway, to slip-I) or
        ``-lambda (1 + 2 gamma)`` (to slip-II), so ``n = stick_row`` and ``n . f^- = S'``.

        * Entering stick (slip reaches ``xi' = 1`` with Eq. 20 satisfied): the stick field
          has ``f^+_{v_0} = 0`` (Eq. 19), so with ``w = f^- - f^+`` (``e_{v_0} . w = xi''``)
          ``S = I - w e_{v_0}^T / (e_{v_0} . w)``, the oblique projection onto
          ``delta xi' = 0`` along ``w``: the perturbation enters stick obeying Eq. (19), its
          velocity error turned, through the arrival time, into the shift
          ``-w delta xi' / xi''``. For the paper's structures (diagonal mass) the two fields
          differ only in the slider's acceleration (at ``xi' = 1`` Eq. 21 is Eq. 24), so
          ``w = xi'' e_{v_0}`` and ``S = I - e_{v_0} e_{v_0}^T``: entering stick zeroes
          ``delta xi'`` and nothing else. The stick matrix (``v_0' = 0``) keeps it zero.
        * Breakaway (``S`` reaches ``lambda``, stick to slip-I): ``n = stick_row``,
          ``n . f^- = S' > 0``; ``f^+ - f^-`` is the jump of the slider's acceleration from 0
          (stick) to that of slip-I at ``u = 0``, so a perturbation of the stick force
          (``n . delta z^-``) becomes one of the slider velocity.
        * Friction band edges, and slip-I to slip-II at the belt speed: ``n = e_{v_0}``.
          With a continuous piecewise-linear law ``f^+ = f^-`` at a band edge, so ``S = I``,
          but ``S`` is computed from the two modes' matrices, never assumed.

        The start and the end. ``state(b)`` is affine, ``delta z_0 = L delta b`` with
        ``delta xi = -(K_0j delta q_j + C_0j delta v_j) / K_00`` (``j >= 1``) from
        ``S = lambda``, so ``stick_row . delta z_0 = 0``: the breakaway at the start (which
        the engine registers at ``tau = 0`` or within rounding of it) acts on it as the identity.
        The ``k``-th breakaway time is free: the map's value is where the motion hits the
        section ``S = lambda``, ``delta z_hit = (I - f^- n^T / (n . f^-)) delta z^-`` with
        the stick field ``f^-`` and ``n = stick_row`` (tangent to the section:
        ``n . delta z_hit = 0``, ``delta xi' = 0``). Altogether, with ``R`` the linear map
        :meth:`reduce`,

            ``D P^k = R Pi_hit expm(A_N t_N) S_{N-1} ... S_1 expm(A_1 t_1) L``

        over the ``N`` phases of the run up to the ``k``-th breakaway (the phase list of
        :func:`stickslip.simulate` with ``record=True``; the event states are the recorded
        phase starts).
        """
        run = self.recorded_run(self.state(b), k)
        if run is None:
            return None
        result, times = run
        factors = self.phase_factors(result, float(times[-1]))
        if factors is None:
            return None
        z_hit, steps = factors
        jac = self.lift.copy()
        for propagator, jump, normal, rate, _, _ in steps:
            jac = propagator @ jac
            # saltation (a zero f_plus at the free final event: the projection onto the section)
            jac = jac + np.outer(jump, normal @ jac) / rate
        if not np.all(np.isfinite(jac)):
            return None
        return self.reduce(z_hit), self.reduce(jac)

    def phase_factors(self, result: SimulationResult, t_hit: float
                      ) -> tuple[FloatArray, list[PhaseFactor]] | None:
        """The state at the breakaway ``t_hit`` and the factors of the linearised run up to it.

        Phase ``i`` (mode ``(A, c)``, duration ``t``) contributes ``S_i expm(A t)`` with the
        saltation ``S_i = I + (f^+ - f^-) n^T / (n . f^-)`` of the event that ends it
        (:meth:`linearise` derives it; at ``t_hit``, ``f^+ = 0``: the projection onto the
        section). The run's first phase starts at ``tau = 0``.

        Parameters
        ----------
        result : SimulationResult
            A recorded run that has a breakaway at ``t_hit``.
        t_hit : float
            The breakaway's time.

        Returns
        -------
        (ndarray, list of PhaseFactor) or None
            The full state at ``t_hit`` and one :class:`PhaseFactor` per phase;
            None when the phase ending at ``t_hit`` is no stick phase or an event is grazing.
        """
        seg_t, seg_mode, seg_z = result.segment_times, result.segment_modes, result.segment_states
        q, v, _ = result.state_at(np.array([t_hit]))
        z_hit = np.concatenate([q[0], v[0]])
        last = int(np.searchsorted(seg_t, t_hit, side="left")) - 1  # the phase ending at t_hit
        if last < 0 or int(seg_mode[last]) != STICK:
            return None
        steps: list[PhaseFactor] = []
        for i in range(last + 1):
            mode = int(seg_mode[i])
            t_end = t_hit if i == last else float(seg_t[i + 1])
            # the kernel's expm (the engine's own, tested against scipy's): no BLAS calls, which
            # on a busy machine contend with the numba threads (scipy's took ~5 ms per 4x4 there)
            propagator = expm(self.flow_matrix[mode] * (t_end - float(seg_t[i])))
            z_event = z_hit if i == last else seg_z[i + 1]
            normal = self._normal(mode)
            f_minus = self._field(mode, z_event)
            rate = float(normal @ f_minus)
            if not np.isfinite(rate) or rate == 0.0:
                return None  # a grazing event: the map is not differentiable here
            f_plus = np.zeros_like(f_minus) if i == last else self._field(int(seg_mode[i + 1]),
                                                                           z_event)
            steps.append(PhaseFactor(propagator, f_plus - f_minus, normal, rate, mode,
                                     t_end - float(seg_t[i])))
        return z_hit, steps


def newton_fixed_point(pmap: ReturnMap, b0: FloatArray, k: int, tol: float = 1e-11,
            max_iter: int = 30, residuals: list[float] | None = None
            ) -> tuple[FloatArray, FloatArray] | None:
    """Newton's method on ``P^k(b) - b = 0`` with the exact Jacobian of :meth:`ReturnMap.linearise`.

    Parameters
    ----------
    pmap : ReturnMap
        The map.
    b0 : ndarray
        Start (foundation coordinates, ``V/omega_n`` and ``V``).
    k : int
        Breakaways per map evaluation.
    tol : float
        Converged when ``max |P^k(b) - b| <= tol max(1, max |b|)``.
    max_iter : int
        Bound on the iterations.
    residuals : list of float, optional
        Receives ``max |P^k(b) - b|`` of every iterate (for tests of the convergence rate).

    Returns
    -------
    (ndarray, ndarray) or None
        The fixed point and ``D P^k`` there; None without convergence.
    """
    b = b0.copy()
    for _ in range(max_iter):
        evaluated = pmap.linearise(b, k)
        if evaluated is None:
            return None
        pb, jac = evaluated
        residual = pb - b
        size = float(np.max(np.abs(residual)))
        if residuals is not None:
            residuals.append(size)
        if size <= tol * max(1.0, float(np.max(np.abs(b)))):
            return b, jac
        try:
            step = np.linalg.solve(jac - np.eye(b.size), -residual)
        except np.linalg.LinAlgError:
            return None
        b = b + step
        if not np.all(np.isfinite(b)):
            return None
    return None
