"""A massive rate-and-state slider through a hold of its drive, and LuGre's steady friction at V < 0.

Both were found by an independent audit. A hold (drive speed 0 from t = 20 s) starts a layer
in which the friction rises from 0 with steps far below the round-off of t = 20; the stiff
engine's step-size floor counted from t = 0 and stopped the run ("step size fell to
round-off"). The reference here is the test's own integration (scipy Radau, rtol 1e-10) of
the slider ``m x'' = k (X(t) - x) - N mu`` in the variables ``(x, mu, ln theta)`` with the
regularised law ``v = 2 v_ref exp(-psi/a) sinh(mu/a)``, ``psi = mu_ref + b ln(v_ref theta /
d_c)`` (Rice, Lapusta and Ranjith 2001) and the aging law ``theta' = 1 - |v| theta / d_c``
(Dieterich 1979), each schedule segment in its own local time; the audit's Radau and LSODA
runs (rtol 1e-10 to 1e-12) gave theta = 93.6445 s at the end of the hold.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from stickslip.analysis.memory import simulate_memory
from stickslip.model.state_friction import (
    LuGreFriction,
    MemorySystem,
    RateStateFriction,
    SpeedSchedule,
)

M, K, LOAD = 1.0, 750.0075, 1.0  # kg, N/m (1.5 k_c of Rice and Ruina), N
A, B, D_C, MU_REF, V_REF, V = 0.01, 0.015, 1e-5, 0.6, 1e-6, 1e-5
HOLD = (20.0, 120.0)  # s


def _reference(times: list[float]) -> dict[float, tuple[float, float]]:
    """``(theta, mu)`` at ``times`` (s), each segment integrated in its own local time."""
    lvd = math.log(V_REF / D_C)

    def slip(mu: float, lt: float) -> float:
        return 2 * V_REF * math.exp(-(MU_REF + B * (lvd + lt)) / A) * math.sinh(mu / A)

    def rhs(_t: float, y: np.ndarray, drive: float) -> list[float]:
        x, mu, lt = y  # x: the slider's displacement (the spring's deflection), m
        psi = MU_REF + B * (lvd + lt)
        v = 2 * V_REF * math.exp(-psi / A) * math.sinh(mu / A)
        dlt = math.exp(-lt) - abs(v) / D_C
        # v = drive - x' is the slip speed, so v' = -x'' = -(N mu - k x) / m in a segment
        vdot = -(LOAD * mu - K * x) / M
        e = math.exp(psi / A) / (2 * V_REF)
        return [drive - v, (A * e * vdot + math.sinh(mu / A) * B * dlt) / math.cosh(mu / A), dlt]

    psi0 = MU_REF + B * math.log(V_REF / V)
    mu_ss = A * math.asinh(V / (2 * V_REF) * math.exp(psi0 / A))
    y = np.array([LOAD * mu_ss / K, mu_ss, math.log(D_C / V)])
    out: dict[float, tuple[float, float]] = {}
    segments = [(0.0, HOLD[0], V, V), (HOLD[0], HOLD[1], 0.0, V), (HOLD[1], 160.0, V, 0.0)]
    for t0, t1, drive, before in segments:
        if drive != before:  # the slip speed jumps with the drive (the contact's speed is continuous)
            v_new = slip(y[1], y[2]) + drive - before
            y[1] = A * math.asinh(v_new / (2 * V_REF) * math.exp((MU_REF + B * (lvd + y[2])) / A))
        sol = solve_ivp(rhs, (0.0, t1 - t0), y, args=(drive,), method="Radau", rtol=1e-10,
                        atol=[1e-13, 1e-13, 1e-10], dense_output=True,
                        first_step=1e-40 if drive != before else None)
        assert sol.status == 0, sol.message
        for t in times:
            if t0 <= t <= t1:
                _x, mu, lt = sol.sol(t - t0)
                out[t] = (math.exp(lt), mu)
        y = sol.y[:, -1]
    return out


def test_a_massive_slider_runs_through_a_hold() -> None:
    law = RateStateFriction(A, B, D_C, MU_REF, V_REF)
    system = MemorySystem(np.eye(1), np.zeros((1, 1)), np.array([[K]]), 0, LOAD, law,
                          SpeedSchedule((0.0, HOLD[0], HOLD[1]), (V, 0.0, V)))
    times = [19.0, 60.0, 119.999, 140.0, 159.0]
    run = simulate_memory(system, t_max=160.0, history_times=np.array(times))
    assert "round-off" not in run.reason, run.reason
    ref = _reference(times)
    theta = np.asarray(run.history["state"])
    mu = np.asarray(run.history["mu"])
    for i, t in enumerate(times):
        assert theta[i] == pytest.approx(ref[t][0], rel=1e-6), t
        assert mu[i] == pytest.approx(ref[t][1], rel=1e-6, abs=1e-9), t
    # the audit's independent value at the end of the hold (its Radau and LSODA runs)
    assert theta[2] == pytest.approx(93.6445, rel=2e-5)


def test_lugre_steady_friction_opposes_the_slip_both_ways() -> None:
    # at steady sliding z' = 0: z = g(V) sign(V) / sigma0 and F = sigma0 z + sigma2 V
    # (Canudas de Wit et al. 1995, Eq. 4), odd in V
    law = LuGreFriction(1e5, 316.2, 0.4, 1.0, 1.5, 1e-3)
    for v in (0.1, 5e-4, 1e-3):
        g = 1.0 + 0.5 * math.exp(-((v / 1e-3) ** 2))
        assert law.steady_mu(v) == pytest.approx(g + 0.4 * v, rel=1e-14)
        assert law.steady_mu(-v) == pytest.approx(-(g + 0.4 * v), rel=1e-14)
        assert law.steady_mu(-v) == pytest.approx(
            law.sigma0 * law.steady_state(-v, 1.0) + law.sigma2 * -v, rel=1e-12)
