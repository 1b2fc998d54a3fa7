"""The 1DOF system, where the paper's Eqs. (34)-(36) are exact (Nakano).

These tests would catch an engine that misses a graze: at the boundary of Eq. (36) the
slider velocity only touches the belt speed, inside a single sub-step.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stickslip import Slider, Verdict, rigid_base, simulate
from stickslip.analysis.theory import (
    critical_lambda_approx,
    critical_lambda_exact,
    stick_slip_amplitude_ratio,
    stick_slip_period,
)

ZETAS = [0.005, 0.01, 0.03, 0.1, 0.2, 0.3, 0.45, 0.6]


def _verdict(lam: float, zeta: float, gamma: float = 2.0) -> Verdict:
    result = simulate(rigid_base(zeta), Slider(lam, gamma=gamma))
    assert result.verdict is not Verdict.UNDETERMINED, result.status.message
    return result.verdict


def _critical_lambda_by_bisection(zeta: float, rel_tol: float = 1e-9) -> float:
    # bracket from the simplified Eq. (39), independent of Eq. (36)
    lo = 0.5 * critical_lambda_approx(zeta)
    hi = 2.0 * critical_lambda_approx(zeta)
    assert _verdict(lo, zeta) is Verdict.STEADY_SLIDING
    assert _verdict(hi, zeta) is Verdict.STICK_SLIP
    while hi - lo > rel_tol * hi:
        mid = 0.5 * (lo + hi)
        if _verdict(mid, zeta) is Verdict.STICK_SLIP:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("zeta", ZETAS)
def test_simulated_boundary_equals_eq_36(zeta: float) -> None:
    # reference: root of Nakano's exact boundary, paper Eq. (36)
    found = _critical_lambda_by_bisection(zeta)
    exact = critical_lambda_exact(zeta)
    digits = -math.log10(abs(found / exact - 1.0) + 1e-17)
    print(f"zeta={zeta:<6} simulated {found:.12g} | Eq. (36) {exact:.12g} | digits {digits:.1f}")
    assert abs(found / exact - 1.0) < 1e-6


@pytest.mark.parametrize("zeta", ZETAS)
def test_verdict_flips_exactly_at_eq_36(zeta: float) -> None:
    # reference: paper Eq. (36); 1e-7 relative on either side of its root
    exact = critical_lambda_exact(zeta)
    assert _verdict(exact * (1 + 1e-7), zeta) is Verdict.STICK_SLIP
    assert _verdict(exact * (1 - 1e-7), zeta) is Verdict.STEADY_SLIDING


@pytest.mark.parametrize("gamma", [0.0, 0.5, 2.0, 10.0])
def test_gamma_does_not_move_the_1dof_boundary(gamma: float) -> None:
    # paper Section 3, citing Nakano [11]: gamma does not affect occurrence
    zeta = 0.1
    exact = critical_lambda_exact(zeta)
    assert _verdict(exact * (1 + 1e-6), zeta, gamma) is Verdict.STICK_SLIP
    assert _verdict(exact * (1 - 1e-6), zeta, gamma) is Verdict.STEADY_SLIDING


@pytest.mark.parametrize("lam", [0.05, 0.5, 1.0, 3.0, 20.0])
def test_undamped_period_and_amplitude_equal_eqs_34_35(lam: float) -> None:
    # reference: paper Eq. (34) (period 2 pi / (f_ss/f_n)) and Eq. (35) (amplitude sqrt(1+lam^2))
    result = simulate(rigid_base(0.0), Slider(lam, gamma=2.0))
    assert result.verdict is Verdict.STICK_SLIP
    assert result.period == pytest.approx(stick_slip_period(lam), rel=1e-9)
    assert result.amplitude == pytest.approx(stick_slip_amplitude_ratio(lam), rel=1e-9)
    # the stick phase of the cycle lasts 2 lam (from xi = -lam to xi = +lam at unit speed)
    assert result.stick_ratio * result.period == pytest.approx(2 * lam, rel=1e-9)


def test_stick_intervals_last_2_lam_and_repeat_with_the_period() -> None:
    # closed form (undamped, paper Eqs. 34-35): every stick phase after the start-up one lasts
    # 2 lam (xi from -lam to +lam at unit speed), and they start one period apart
    lam = 1.5
    result = simulate(rigid_base(0.0), Slider(lam, gamma=2.0), run_to_t_max=True)
    intervals = result.stick_intervals()
    assert intervals.shape[1] == 2 and len(intervals) >= 4
    whole = intervals[1:-1]  # the last one may be cut at the horizon
    np.testing.assert_allclose(whole[:, 1] - whole[:, 0], 2 * lam, rtol=1e-9)
    np.testing.assert_allclose(np.diff(intervals[1:, 0]), stick_slip_period(lam), rtol=1e-9)
    assert intervals[0, 0] == 0.0 and intervals[-1, 1] <= result.t_end
    later = result.stick_intervals(t_start=intervals[1, 0] + lam)  # cut inside a phase
    assert later[0, 0] == intervals[1, 0] + lam and later[0, 1] == intervals[1, 1]


def test_undamped_trajectory_is_the_exact_circle() -> None:
    # closed form: in slip-I, xi^2 + xi'^2 = 1 + lam^2 (energy conservation, zeta = 0)
    lam = 2.0
    result = simulate(rigid_base(0.0), Slider(lam, gamma=2.0))
    t = np.linspace(0.0, result.t_end, 3001)
    q, v, modes = result.state_at(t)
    slip = modes == 0
    radius = np.hypot(q[slip, 0], v[slip, 0])
    assert np.allclose(radius, math.sqrt(1 + lam**2), rtol=1e-12)
    assert np.all(v[modes == 2, 0] == 1.0)


def test_startup_state_is_stuck_at_the_kinetic_offset() -> None:
    # DESIGN.md section 1: startup xi = -gamma lam, xi' = 1 for the rigid base
    result = simulate(rigid_base(0.1), Slider(2.0, gamma=2.0))
    assert result.initial.position[0] == pytest.approx(-4.0)
    assert result.initial_mode.label == "stick"
    # the first breakaway is at S = 2 zeta + xi = lam (Eq. 20), i.e. xi = lam - 2 zeta
    first_break = result.segment_states[1]
    assert first_break[0] == pytest.approx(2.0 - 0.2, abs=1e-12)
    assert result.event_times[0] == pytest.approx(2.0 - 0.2 + 4.0, abs=1e-12)
