"""Independent solve_ivp reference for velocity-dependent friction laws (tests only).

Extends the Coulomb oracle of ``tests/oracle.py`` (same stick dynamics, stick force and event
logic) with the smooth friction law itself, not the engine's band table: while sliding, DOF 0
feels ``F(1 - v_0) - gamma lambda`` (slip-I) or ``-F(v_0 - 1) - gamma lambda`` (slip-II), with
``F`` the law's exact ``value`` (DESIGN.md section 8). Band edges are not events here (``F``
is continuous), so this checks the engine's band switching too. DOP853 with tight tolerances
and a bounded step; never used by the package.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from tests.oracle import (
    RESTART_GUARD,
    SLIP_I,
    STICK,
    FloatArray,
    OraclePiece,
    OracleResult,
    _System,
)


class _FrictionSystem(_System):
    """The Coulomb oracle's system with the slip forcing replaced by a friction law."""

    def __init__(self, mass: FloatArray, damping: FloatArray, stiffness: FloatArray, lam: float,
                 gamma: float, law: Callable[[float], float]) -> None:
        super().__init__(mass, damping, stiffness, lam, gamma)
        self.law = law
        self.minv_e0 = np.linalg.inv(mass)[:, 0]

    def force(self, mode: int, v0: float) -> float:
        gl = self.gamma * self.lam
        if mode == SLIP_I:
            return self.law(max(1.0 - v0, 0.0)) - gl
        return -self.law(max(v0 - 1.0, 0.0)) - gl

    def rhs(self, mode: int) -> Callable[[float, FloatArray], FloatArray]:
        if mode == STICK:
            return super().rhs(mode)
        a, n = self.A[mode], self.n

        def f(t: float, y: FloatArray) -> FloatArray:
            out = a @ y
            out[n:] += self.minv_e0 * self.force(mode, y[n])
            return out

        return f

    def event_rate(self, mode: int, k: int, y: FloatArray) -> float:
        c = self.events[mode][k][0]
        return float(c @ self.rhs(mode)(0.0, y))


def friction_oracle_simulate(structure: Any, slider: Any, t_max: float, initial: Any = None, *,
                             max_step: float = 0.01, rtol: float = 1e-12, atol: float = 1e-12,
                             max_events: int = 10000) -> OracleResult:
    """Simulate ``structure`` with ``slider`` (its ``friction.value`` is the law) by solve_ivp.

    Event modes are 0 slip-I, 1 slip-II, 2 stick (no bands). The contact is DOF 0: a
    structure with its contact elsewhere is refused (pass ``structure.contact_first()[0]``).
    """
    if getattr(structure, "contact_dof", 0) != 0:
        raise ValueError(f"the friction oracle takes the contact on DOF 0, got contact_dof = "
                         f"{structure.contact_dof}: pass structure.contact_first()[0]")
    if initial is None:
        from stickslip.model import startup_state

        initial = startup_state(structure, slider)
    lam, gamma = float(slider.lam), float(slider.gamma)

    def law(u: float) -> float:
        return float(slider.friction.value(u, lam, gamma))

    system = _FrictionSystem(structure.mass, structure.damping, structure.stiffness, lam, gamma, law)
    n = system.n
    y = np.concatenate([np.asarray(initial.position, float), np.asarray(initial.velocity, float)])
    mode = system.initial_mode(y)
    initial_mode = mode
    if mode == STICK:
        y[n] = 1.0
    t = 0.0
    event_times: list[float] = []
    event_modes: list[int] = []
    pieces: list[OraclePiece] = []
    masked: set[int] = set()
    status = "t_max"
    while t < t_max:
        if len(event_times) >= max_events:
            status = "max_events"
            break
        sol = solve_ivp(system.rhs(mode), (t, t_max), y, method="DOP853",
                        events=system.event_functions(mode, t, masked), dense_output=True,
                        max_step=max_step, rtol=rtol, atol=atol)
        if sol.status == -1:
            raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
        if sol.status == 0:
            pieces.append(OraclePiece(t, t_max, mode, sol.sol))
            t = t_max
            break
        hits = [(te[0], k) for k, te in enumerate(sol.t_events) if len(te)]
        t_e, k = min(hits)
        y_e = np.array(sol.y_events[k][0], dtype=np.float64)
        direction = system.events[mode][k][2]
        if k not in masked and t_e - t < RESTART_GUARD and direction * system.event_rate(mode, k, y_e) <= 0.0:
            masked = masked | {k}
            continue
        masked = set()
        pieces.append(OraclePiece(t, t_e, mode, sol.sol if t_e > t else None))
        y_e[n] = 1.0
        new_mode = system.after_event(mode, k, y_e)
        event_times.append(float(t_e))
        event_modes.append(new_mode)
        t, y, mode = float(t_e), y_e, new_mode
    return OracleResult(
        event_times=np.asarray(event_times, dtype=np.float64),
        event_modes=np.asarray(event_modes, dtype=np.int64),
        initial_mode=initial_mode, t_end=t, status=status, pieces=pieces, n_dof=n,
        _system=system,
    )


def kind_events(segment_times: FloatArray, segment_modes: Any) -> tuple[FloatArray, FloatArray]:
    """The engine's switches between slip-I, slip-II and stick (band changes dropped)."""
    from stickslip.kernel.system import mode_kind_band

    kinds = np.array([mode_kind_band(int(m))[0] for m in segment_modes], dtype=np.int64)
    keep = np.nonzero(kinds[1:] != kinds[:-1])[0] + 1
    return np.asarray(segment_times)[keep], kinds[keep]
