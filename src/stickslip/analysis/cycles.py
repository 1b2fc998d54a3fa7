"""The stick-slip cycles that exist at a parameter point, whatever the start (DESIGN.md section 9).

A stick-slip cycle is a fixed point of the breakaway-to-breakaway return map. At a breakaway
the slider moves with the belt (``xi' = 1``) and its stick force has just reached the static
limit, ``S = lambda`` (Eq. 20), so the state is fixed by the foundation's coordinates: for
the rigid base the breakaway state is unique, with a foundation it is ``b = (xi_a, xi_a', ...)``
and ``xi`` follows from ``S = lambda``. The return map ``P(b)``, the next breakaway state, is
evaluated exactly by the engine (exact propagation, graze-proof events; the breakaway time is
an event of the run). Cycles are the solutions of ``P^k(b) = b`` (period ``k`` stick phases),
found by Newton's method from many seeds (the breakaway states of runs from a box of initial
states). The Jacobian of ``P^k`` is exact: the product, along the recorded phases of the run
that evaluates the map, of the phase flows ``expm(A t)`` and the saltation matrices of every
event (entering stick, breakaway, friction-band edges), composed with the projection onto the
breakaway section (:meth:`_ReturnMap.linearise` derives it). Its eigenvalues are the cycle's
non-trivial Floquet multipliers (the stick phase removes the slider's own coordinates, so the
rigid-base cycle has none and is stable as soon as it exists). Every reported cycle is then
certified by a run of :func:`stickslip.simulate` started on it (its breakaway state repeats),
which also gives the period, amplitude and stick ratio.

The section has two pieces: breakaways onto slip-I (``S = lambda``) and onto slip-II
(``S = -lambda (1 + 2 gamma)``, possible with a foundation, when the foundation pushes the
stuck slider forward). Each breakaway state reached by a seeding run lies on one of them; the
map ``P^k`` of a piece goes ``k`` breakaways on (of either kind, as the engine counts them)
and must land on the same piece. A cycle whose breakaways go onto both modes is found on
either piece and reported once (the slip-I piece first).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions, SimulationResult, run_engine
from stickslip.analysis.verdict import Verdict
from stickslip.kernel.linalg import expm
from stickslip.kernel.system import SLIP_I, SLIP_II, STICK, mode_kind_band, mode_matrices
from stickslip.model._validate import random_seed
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure, to_user_order

FloatArray = NDArray[np.float64]
#: Events allowed per friction band in a run of the return map: a stick-slip cycle crosses
#: each band edge a few times, and a run spans at most ``2 max_period + 1`` breakaways (the
#: Coulomb law, one band: 400 events; a Stribeck interpolant of 100 bands: 40,000).
RETURN_EVENTS = 400


@dataclass(frozen=True)
class Cycle:
    """One stick-slip cycle (dimensionless; times in ``tau``, displacements in ``V/omega_n``).

    Attributes
    ----------
    breakaway_state : ndarray, shape (2 n_dof,)
        The full state at the cycle's breakaway (shifted coordinates).
    breakaway_onto : str
        ``slip-I`` or ``slip-II``: the section of ``breakaway_state`` (the slip mode that
        breakaway goes onto).
    stick_phases : int
        Stick phases per cycle (period-k).
    period, amplitude, stick_ratio : float
        Of the certified cycle (as :func:`stickslip.simulate` reports them).
    multipliers : ndarray of complex
        Floquet multipliers of the return map ``P^k`` (empty for the rigid base).
    stable : bool
        Every multiplier inside the unit circle.
    """

    breakaway_state: FloatArray
    stick_phases: int
    period: float
    amplitude: float
    stick_ratio: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    stable: bool
    breakaway_onto: str = "slip-I"
    proof_radius: float = float("nan")
    """Radius of a ball about ``breakaway_state``'s foundation coordinates holding exactly one
    fixed point of ``P^k`` and no shorter period (:func:`stickslip.analysis.cycle_proof.prove_existence`);
    every listed cycle has one."""
    orbit: tuple[FloatArray, ...] = field(default=(), repr=False)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, with the keys of ``stickslip cycles --json``."""
        return {
            "breakaway_onto": self.breakaway_onto,
            "period": self.period,
            "amplitude": self.amplitude,
            "stick_ratio": self.stick_ratio,
            "stick_phases": self.stick_phases,
            "stable": self.stable,
            "multipliers": [{"re": float(m.real), "im": float(m.imag), "abs": float(abs(m))}
                            for m in self.multipliers],
            "breakaway_state": [float(x) for x in self.breakaway_state],
            "proof_radius": float(self.proof_radius),
        }


@dataclass(frozen=True)
class CycleSearch:
    """Result of :func:`find_cycles`: every distinct cycle found, and how hard it was looked for."""

    structure: Structure
    slider: Slider
    cycles: tuple[Cycle, ...]
    n_seeds: int
    n_map_evaluations: int
    #: slip oscillations (:mod:`stickslip.analysis.slip_oscillations`), when searched for
    slip_oscillations: tuple[Any, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``cycles`` and ``slip_oscillations`` (lists) and the search's size."""
        return {
            "cycles": [c.to_dict() for c in self.cycles],
            "n_cycles": len(self.cycles),
            "slip_oscillations": [c.to_dict() for c in self.slip_oscillations],
            "lambda": self.slider.lam,
            "zeta": self.structure.zeta,
            "gamma": self.slider.gamma,
            "structure": self.structure.name,
            "friction": self.slider.friction.describe(),
            "n_seeds": self.n_seeds,
            "n_map_evaluations": self.n_map_evaluations,
        }


class _ReturnMap:
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

    def _run(self, state: FloatArray, count: int, *, on_section: bool = True
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
        run = self._run(state, count, on_section=False)
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
        run = self._run(self.state(b), k)
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
        run = self._run(self.state(b), k)
        if run is None:
            return None
        result, times = run
        t_hit = float(times[-1])
        seg_t, seg_mode, seg_z = result.segment_times, result.segment_modes, result.segment_states
        q, v, _ = result.state_at(np.array([t_hit]))
        z_hit = np.concatenate([q[0], v[0]])
        last = int(np.searchsorted(seg_t, t_hit, side="left")) - 1  # the phase ending at t_hit
        if last < 0 or int(seg_mode[last]) != STICK:
            return None
        jac = self.lift.copy()
        for i in range(last + 1):
            mode = int(seg_mode[i])
            t_end = t_hit if i == last else float(seg_t[i + 1])
            # the kernel's expm (the engine's own, tested against scipy's): no BLAS calls, which
            # on a busy machine contend with the numba threads (scipy's took ~5 ms per 4x4 there)
            jac = expm(self.flow_matrix[mode] * (t_end - float(seg_t[i]))) @ jac
            z_event = z_hit if i == last else seg_z[i + 1]
            normal = self._normal(mode)
            f_minus = self._field(mode, z_event)
            rate = float(normal @ f_minus)
            if not np.isfinite(rate) or rate == 0.0:
                return None  # a grazing event: the map is not differentiable here
            f_plus = np.zeros_like(f_minus) if i == last else self._field(int(seg_mode[i + 1]),
                                                                           z_event)
            # saltation (f_plus = 0 at the free final event: the projection onto the section)
            jac = jac + np.outer(f_plus - f_minus, normal @ jac) / rate
        if not np.all(np.isfinite(jac)):
            return None
        return self.reduce(z_hit), self.reduce(jac)


def _newton(pmap: _ReturnMap, b0: FloatArray, k: int, tol: float = 1e-11,
            max_iter: int = 30, residuals: list[float] | None = None
            ) -> tuple[FloatArray, FloatArray] | None:
    """Newton's method on ``P^k(b) - b = 0`` with the exact Jacobian of :meth:`_ReturnMap.linearise`.

    Returns the fixed point and ``D P^k`` there, or None. ``residuals``, when given, receives
    ``max |P^k(b) - b|`` of every iterate (for tests of the convergence rate).
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


def find_cycles(
    structure: Structure,
    slider: Slider,
    *,
    seeds: int = 24,
    box: float = 4.0,
    max_period: int = 2,
    seed: int = 0,
    options: EngineOptions | None = None,
    slip_oscillations: bool = False,
) -> CycleSearch:
    """Every stick-slip cycle found at this parameter point, with its stability.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (dimensionless), any friction law.
    seeds : int
        Initial states drawn uniformly in ``[-box, box]`` for every position and
        ``[-box, 1.5]`` for every velocity (shifted coordinates), plus the startup state; the
        breakaway states their runs reach seed Newton's method.
    box : float
        Half-width of the seeding box (units ``V/omega_n`` and ``V``).
    max_period : int
        Longest cycle looked for, in stick phases.
    seed : int
        Random seed of the seeding.
    options : EngineOptions, optional
        Horizon of the seeding runs.
    slip_oscillations : bool
        Also look for the periodic motions that never stick, stable and unstable
        (:func:`stickslip.analysis.slip_oscillations.find_slip_oscillations`, its own seeds).

    Returns
    -------
    CycleSearch
        The distinct cycles found, each with its period, amplitude and Floquet multipliers.
    """
    if slip_oscillations:
        from stickslip.analysis.slip_oscillations import find_slip_oscillations

        search = find_cycles(structure, slider, seeds=seeds, box=box, max_period=max_period, seed=seed,
                             options=options)
        return replace(search, slip_oscillations=find_slip_oscillations(
            structure, slider, seeds=seeds, seed=seed, options=options))
    if structure.contact_dof != 0:  # search the contact-first twin; states back in user order
        inner, perm = structure.contact_first()
        search = find_cycles(inner, slider, seeds=seeds, box=box, max_period=max_period, seed=seed,
                             options=options)
        mapped = tuple(replace(c, breakaway_state=to_user_order(c.breakaway_state, perm))
                       for c in search.cycles)
        return replace(search, structure=structure, cycles=mapped)
    from stickslip.analysis.cycle_proof import prove_existence  # it builds on _ReturnMap

    opts = options or EngineOptions()
    n = structure.n_dof
    pmaps = {d: _ReturnMap(structure, slider, opts, d) for d in (SLIP_I, SLIP_II)}
    pmap = pmaps[SLIP_I]
    rng = np.random.default_rng(random_seed(seed))
    starts = [np.concatenate([structure.kinetic_equilibrium_offset() * -slider.gamma * slider.lam,
                              np.eye(n)[0]])]
    for _ in range(int(seeds)):
        starts.append(np.concatenate([rng.uniform(-box, box, n), rng.uniform(-box, 1.5, n)]))
    breakaways: list[FloatArray] = []
    for start in starts:
        found = pmap.next_breakaways(start, 2 * max_period + 1)
        breakaways += found[-max_period:] if found else []
    cycles: list[Cycle] = []
    # the section's two pieces: breakaways onto slip-I first (the paper's), then onto slip-II
    for direction, name in ((SLIP_I, "slip-I"), (SLIP_II, "slip-II")):
        pm = pmaps[direction]
        on_section = [z for z in breakaways if pm.direction_of(z) == direction]
        if n == 1:  # the breakaway state is unique: try it even when no run reached it
            on_section = on_section[:1] or [pm.state(np.zeros(0))]
        for k in range(1, int(max_period) + 1):
            for state in on_section:
                if n == 1:
                    solution: tuple[FloatArray, FloatArray] | None = (np.zeros(0), np.zeros((0, 0)))
                    if pm(np.zeros(0), k) is None:
                        solution = None
                else:
                    solution = _newton(pm, pm.reduce(state), k)
                if solution is None:
                    continue
                b, jac = solution
                full = pm.state(b)
                scale = max(1.0, float(np.max(np.abs(full))))
                if any(np.max(np.abs(full - z)) <= 1e-7 * scale
                       for c in cycles for z in (c.breakaway_state, *c.orbit)):
                    continue  # a cycle found before, from this or another of its breakaways
                radius = 0.0 if n == 1 else prove_existence(structure, slider, b, k, opts, direction)
                if radius is None:
                    continue  # no proof that a cycle of exactly k stick phases is there
                certified = run_engine(structure, slider, InitialState(full[:n], full[n:]), opts,
                                       False, False)
                if certified.verdict is not Verdict.STICK_SLIP or certified.cycle_length != k:
                    continue
                if any(c.stick_phases == k and c.breakaway_onto != name
                       and abs(c.period - certified.period) <= 1e-8 * c.period
                       and abs(c.amplitude - certified.amplitude) <= 1e-8 * max(1.0, c.amplitude)
                       for c in cycles):
                    continue  # a cycle with breakaways onto both modes, found on the other piece
                multipliers = (np.asarray(np.linalg.eigvals(jac), dtype=np.complex128) if jac.size
                               else np.zeros(0, dtype=np.complex128))
                stable = bool(np.all(np.abs(multipliers) < 1.0))
                orbit = tuple(pm.next_breakaways(full, k)) if n > 1 else ()
                cycles.append(Cycle(full, k, certified.period, certified.amplitude,
                                    certified.stick_ratio, multipliers, stable, name, radius, orbit))
            if n == 1:
                break
    cycles.sort(key=lambda c: (c.stick_phases, c.amplitude))
    return CycleSearch(structure, slider, tuple(cycles), len(starts),
                       sum(m.evaluations for m in pmaps.values()))


def cycle_exists(structure: Structure, slider: Slider, **kwargs: Any) -> bool:
    """True when :func:`find_cycles` finds at least one stick-slip cycle.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.
    slider : Slider
        The frictional contact: ``lambda``, ``gamma`` and the friction law.
    **kwargs
        Keywords of :func:`find_cycles`.

    Returns
    -------
    bool
        Whether a stick-slip cycle was found.
    """
    return len(find_cycles(structure, slider, **kwargs).cycles) > 0

