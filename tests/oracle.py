"""Independent reference simulator of the piecewise-linear stick-slip system (test oracle).

Built directly from the paper's dimensionless equations (Section 2.3, Eqs. 19-27) written in
matrix form for a linear structure with one frictional contact on DOF ``c`` (``contact_dof``,
0 by default; handled natively with index sets, not by reordering); it does not use any
code of the ``stickslip`` package. It integrates each friction mode with
``scipy.integrate.solve_ivp`` (DOP853, tight tolerances, bounded step) and switches modes on
terminal events. It is a cross-check and a benchmark baseline, never the engine: it can miss a
graze shorter than one step and its event times carry the integrator's error.

Modes and coordinates (``q`` measured from the kinetic-friction equilibrium, Eqs. 15-16;
``v = q'`` in units of the belt speed):

* ``0`` slip-I (``v_0 < 1``): ``Mass q'' + C q' + K q = 0`` (Eqs. 22-24);
* ``1`` slip-II (``v_0 > 1``): ``Mass q'' + C q' + K q = -2 gamma lam e_0`` (Eqs. 25-27);
* ``2`` stick (``v_0 = 1``, ``q_0'' = 0``): the other DOFs obey
  ``Mass_rr q_r'' = -(C q' + K q)_r``; the force holding the stick is
  ``S = (Mass q'' + C q' + K q)_0`` and stick holds while
  ``-lam (1 + 2 gamma) <= S <= lam`` (Eqs. 19-21).

Every mode is an affine ODE ``y' = A y + b`` in ``y = (q, v)``, and every event function is
affine in ``y``, so both are precomputed matrices.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import OdeSolution, solve_ivp

FloatArray = NDArray[np.float64]

SLIP_I = 0
SLIP_II = 1
STICK = 2
MODE_NAMES = {SLIP_I: "slip-I", SLIP_II: "slip-II", STICK: "stick"}

#: An event closer than this to the restart time, crossing the wrong way, is ignored.
RESTART_GUARD = 1e-12


@dataclass(frozen=True)
class OraclePiece:
    """One integrated interval in a single mode, with its dense output."""

    t_start: float
    t_end: float
    mode: int
    sol: OdeSolution | None  # None for a zero-length piece


@dataclass
class OracleResult:
    """Outcome of :func:`oracle_simulate`.

    ``event_times[i]`` is the time of the i-th mode switch after ``t = 0`` and
    ``event_modes[i]`` the mode entered there (0 slip-I, 1 slip-II, 2 stick).
    ``status`` is ``"t_max"`` (horizon reached) or ``"max_events"`` (event budget exhausted).
    """

    event_times: FloatArray
    event_modes: NDArray[np.int64]
    initial_mode: int
    t_end: float
    status: str
    pieces: list[OraclePiece] = field(repr=False)
    n_dof: int
    n_ignored_restart_events: int = 0
    _system: Any = field(default=None, repr=False)

    @property
    def sol(self) -> list[tuple[float, float, int, OdeSolution | None]]:
        """Dense output as ``(t_start, t_end, mode, OdeSolution)`` tuples."""
        return [(p.t_start, p.t_end, p.mode, p.sol) for p in self.pieces]

    @property
    def stick_start_times(self) -> FloatArray:
        """Times at which a stick phase starts (excluding an initial stick at t = 0)."""
        return self.event_times[self.event_modes == STICK]

    def verdict(self, tail_fraction: float = 0.3) -> str:
        """``"stick-slip"`` if a stick phase starts in the last ``tail_fraction`` of
        ``[0, t_end]``, else ``"steady-sliding"`` (a heuristic, not a certificate)."""
        t_tail = (1.0 - tail_fraction) * self.t_end
        starts = self.stick_start_times
        return "stick-slip" if starts.size and starts.max() >= t_tail else "steady-sliding"

    def mode_at(self, t: float) -> int:
        return self._piece(t).mode

    def _piece(self, t: float) -> OraclePiece:
        if not (0.0 <= t <= self.t_end):
            raise ValueError(f"t = {t} outside [0, {self.t_end}]")
        for p in self.pieces:
            if p.t_start <= t <= p.t_end and p.sol is not None:
                return p
        for p in self.pieces:  # zero-length piece only
            if p.t_start <= t <= p.t_end:
                return p
        raise ValueError(f"no piece covers t = {t}")

    def state_at(self, t: float) -> tuple[FloatArray, FloatArray]:
        """Positions and velocities ``(q, v)`` at time ``t`` from the dense output."""
        p = self._piece(t)
        if p.sol is None:
            raise ValueError(f"t = {t} lies only on a zero-length piece")
        y = np.asarray(p.sol(t), dtype=np.float64)
        n = self.n_dof
        q, v = y[:n].copy(), y[n:].copy()
        if p.mode == STICK:
            v[self._system.c] = 1.0
        return q, v

    def stick_force_at(self, t: float) -> float:
        """Stick force ``S`` that would hold the slider at the state at time ``t``."""
        q, v = self.state_at(t)
        v[self._system.c] = 1.0
        return float(self._system.stick_force(np.concatenate([q, v])))


class _System:
    """Affine mode dynamics and affine event functions for given matrices."""

    def __init__(
        self,
        mass: FloatArray,
        damping: FloatArray,
        stiffness: FloatArray,
        lam: float,
        gamma: float,
        contact_dof: int = 0,
    ) -> None:
        n = mass.shape[0]
        self.n = n
        c = int(contact_dof)
        self.c = c
        r = np.array([i for i in range(n) if i != c], dtype=np.int64)  # the other DOFs
        self.lam = float(lam)
        self.gamma = float(gamma)
        self.upper = self.lam
        self.lower = -self.lam * (1.0 + 2.0 * self.gamma)
        minv = np.linalg.inv(mass)
        ident = np.eye(n)
        zero = np.zeros((n, n))

        # slip modes: q' = v, v' = Minv (f - C v - K q)
        a_slip = np.block([[zero, ident], [-minv @ stiffness, -minv @ damping]])
        e0 = np.zeros(n)
        e0[c] = 1.0
        b_slip1 = np.zeros(2 * n)
        b_slip2 = np.concatenate([np.zeros(n), minv @ (-2.0 * self.gamma * self.lam * e0)])

        # stick: q' = v, v_0' = 0, Mass_rr v_r' = -(C v + K q)_r   (with v_0 = 1 held)
        a_stick = np.zeros((2 * n, 2 * n))
        a_stick[:n, n:] = ident
        if n > 1:
            mrr_inv = np.linalg.inv(mass[np.ix_(r, r)])
            a_stick[n + r, :n] = -mrr_inv @ stiffness[r, :]
            a_stick[n + r, n:] = -mrr_inv @ damping[r, :]
        # S = (Mass a + C v + K q)_c with a_c = 0: linear in y
        s_row = np.concatenate([stiffness[c, :], damping[c, :]])
        if n > 1:
            s_row = s_row + mass[c, r] @ a_stick[n + r, :]
        self.s_row = s_row
        self.a_stick = a_stick

        self.A = {SLIP_I: a_slip, SLIP_II: a_slip, STICK: a_stick}
        self.b = {SLIP_I: b_slip1, SLIP_II: b_slip2, STICK: np.zeros(2 * n)}

        # events: (row c, offset d, direction, target-mode-or-None); g(y) = c.y + d
        c_v0 = np.zeros(2 * n)
        c_v0[n + c] = 1.0
        self.events: dict[int, list[tuple[FloatArray, float, int, str]]] = {
            SLIP_I: [(c_v0, -1.0, +1, "v0=1 from below")],
            SLIP_II: [(c_v0, -1.0, -1, "v0=1 from above")],
            STICK: [
                (s_row, -self.upper, +1, "S=lam"),
                (s_row, -self.lower, -1, "S=-lam(1+2gamma)"),
            ],
        }

    def rhs(self, mode: int) -> Callable[[float, FloatArray], FloatArray]:
        a, b = self.A[mode], self.b[mode]

        def f(t: float, y: FloatArray) -> FloatArray:
            return a @ y + b

        return f

    def stick_force(self, y: FloatArray) -> float:
        return float(self.s_row @ y)

    def event_rate(self, mode: int, k: int, y: FloatArray) -> float:
        c, _, _, _ = self.events[mode][k]
        return float(c @ (self.A[mode] @ y + self.b[mode]))

    def event_functions(self, mode: int, t_start: float, masked: set[int]) -> list[Callable]:
        funcs = []
        for k, (c, d, direction, _) in enumerate(self.events[mode]):

            def g(t: float, y: FloatArray, c: FloatArray = c, d: float = d) -> float:
                return float(c @ y + d)

            if k in masked:
                # hold g on the pre-crossing side during the guard window after the restart
                def g_masked(
                    t: float,
                    y: FloatArray,
                    g: Callable = g,
                    direction: int = direction,
                ) -> float:
                    val = g(t, y)
                    if t - t_start < RESTART_GUARD:
                        return -direction * max(abs(val), 1e-300)
                    return val

                fn: Callable[..., float] = g_masked
            else:
                fn = g
            fn.terminal = True  # type: ignore[attr-defined]
            fn.direction = direction  # type: ignore[attr-defined]
            funcs.append(fn)
        return funcs

    def initial_mode(self, y: FloatArray) -> int:
        v0 = y[self.n + self.c]
        if v0 < 1.0:
            return SLIP_I
        if v0 > 1.0:
            return SLIP_II
        s = self.stick_force(y)
        if s > self.upper:
            return SLIP_I
        if s < self.lower:
            return SLIP_II
        return STICK

    def after_event(self, mode: int, k: int, y: FloatArray) -> int:
        """Mode entered after event ``k`` of ``mode`` at state ``y`` (v_0 already set to 1)."""
        if mode == SLIP_I:
            return STICK if self.stick_force(y) >= self.lower else SLIP_II
        if mode == SLIP_II:
            return STICK if self.stick_force(y) <= self.upper else SLIP_I
        return SLIP_I if k == 0 else SLIP_II


def oracle_simulate(
    mass: Any,
    damping: Any,
    stiffness: Any,
    lam: float,
    gamma: float,
    q0: Any,
    v0: Any,
    t_max: float,
    *,
    max_step: float = 0.01,
    rtol: float = 1e-12,
    atol: float = 1e-12,
    max_events: int = 10000,
    contact_dof: int = 0,
) -> OracleResult:
    """Simulate the stick-slip system with solve_ivp (DOP853) and terminal events.

    Parameters
    ----------
    mass, damping, stiffness : array_like, shape (n, n)
        Dimensionless matrices; the frictional contact acts on DOF ``contact_dof``.
    lam, gamma : float
        ``lambda`` and ``gamma`` of the paper (Section 2.3).
    q0, v0 : array_like, shape (n,)
        Initial positions and velocities in shifted coordinates (Eqs. 15-16).
    t_max : float
        Dimensionless time horizon.
    max_step, rtol, atol : float
        Passed to solve_ivp.
    max_events : int
        Stop (status ``"max_events"``) after this many mode switches.
    """
    mass = np.atleast_2d(np.asarray(mass, dtype=np.float64))
    damping = np.atleast_2d(np.asarray(damping, dtype=np.float64))
    stiffness = np.atleast_2d(np.asarray(stiffness, dtype=np.float64))
    n = mass.shape[0]
    system = _System(mass, damping, stiffness, lam, gamma, contact_dof)
    c = system.c
    y = np.concatenate(
        [np.asarray(q0, dtype=np.float64).reshape(n), np.asarray(v0, dtype=np.float64).reshape(n)]
    )
    mode = system.initial_mode(y)
    initial_mode = mode
    if mode == STICK:
        y[n + c] = 1.0

    t = 0.0
    t_max = float(t_max)
    event_times: list[float] = []
    event_modes: list[int] = []
    pieces: list[OraclePiece] = []
    n_ignored = 0
    status = "t_max"
    masked: set[int] = set()

    while t < t_max:
        if len(event_times) >= max_events:
            status = "max_events"
            break
        sol = solve_ivp(
            system.rhs(mode),
            (t, t_max),
            y,
            method="DOP853",
            events=system.event_functions(mode, t, masked),
            dense_output=True,
            max_step=max_step,
            rtol=rtol,
            atol=atol,
        )
        if sol.status == -1:
            raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
        if sol.status == 0:
            pieces.append(OraclePiece(t, t_max, mode, sol.sol))
            t = t_max
            break
        # a terminal event: take the earliest one reported
        hits = [(te[0], k) for k, te in enumerate(sol.t_events) if len(te)]
        t_e, k = min(hits)
        y_e = np.array(sol.y_events[k][0], dtype=np.float64)
        direction = system.events[mode][k][2]
        if k not in masked and t_e - t < RESTART_GUARD and direction * system.event_rate(mode, k, y_e) <= 0.0:
            # spurious root at the restart time, crossing the wrong way: ignore it and
            # integrate again with this event held off during the guard window
            n_ignored += 1
            masked = masked | {k}
            continue
        masked = set()
        pieces.append(OraclePiece(t, t_e, mode, sol.sol if t_e > t else None))
        y_e[n + c] = 1.0  # every switch happens at (or enters) v_0 = 1 exactly
        new_mode = system.after_event(mode, k, y_e)
        event_times.append(float(t_e))
        event_modes.append(new_mode)
        t, y, mode = float(t_e), y_e, new_mode

    return OracleResult(
        event_times=np.asarray(event_times, dtype=np.float64),
        event_modes=np.asarray(event_modes, dtype=np.int64),
        initial_mode=initial_mode,
        t_end=t,
        status=status,
        pieces=pieces,
        n_dof=n,
        n_ignored_restart_events=n_ignored,
        _system=system,
    )


def oracle_simulate_structure(
    structure: Any, slider: Any, t_max: float, initial: Any = None, **kwargs: Any
) -> OracleResult:
    """Convenience wrapper taking ``stickslip.model`` objects (``Structure``, ``Slider``,
    optionally an ``InitialState``; default ``startup_state``). Only reads their numbers."""
    if initial is None:
        from stickslip.model import startup_state

        initial = startup_state(structure, slider)
    return oracle_simulate(
        structure.mass,
        structure.damping,
        structure.stiffness,
        slider.lam,
        slider.gamma,
        initial.position,
        initial.velocity,
        t_max,
        contact_dof=getattr(structure, "contact_dof", 0),
        **kwargs,
    )
