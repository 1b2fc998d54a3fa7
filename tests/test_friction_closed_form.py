"""The rigid base with the linear friction law: the simulated boundary is Eq. (36) at zeta - delta.

Reference: :func:`stickslip.analysis.theory.critical_lambda_linear` (Nakano's exact boundary,
paper Eq. (36), with the effective damping ``zeta - delta``; derivation in its docstring).

Measured (bisection to 1e-9 relative, gamma = 2):

    zeta   delta   simulated        closed form      rel. diff
    0.1    0.05    0.910669990747   0.91066999089    1.6e-10
    0.2   -0.1     4.48419313616    4.48419313633    3.8e-11
    0.3    0.1     2.72498923528    2.72498923556    1.0e-10
    0.05  -0.05    1.47011778914    1.47011778919    3.4e-11
    0.45   0.2     3.51672904517    3.51672904565    1.4e-10
    0.1   -0.2     4.48419313616    4.48419313633    3.8e-11
"""

from __future__ import annotations

import math

import pytest

from stickslip import Slider, Verdict, rigid_base, simulate
from stickslip.analysis.theory import critical_lambda_approx, critical_lambda_linear
from stickslip.model.friction import LinearFriction

CASES = [(0.1, 0.05), (0.2, -0.1), (0.3, 0.1), (0.05, -0.05), (0.45, 0.2), (0.1, -0.2)]


def _verdict(lam: float, zeta: float, delta: float, gamma: float = 2.0) -> Verdict:
    result = simulate(rigid_base(zeta), Slider(lam, gamma=gamma, friction=LinearFriction(delta)))
    assert result.verdict in (Verdict.STEADY_SLIDING, Verdict.STICK_SLIP), result.status.message
    return result.verdict


def _bisect(zeta: float, delta: float, rel_tol: float = 1e-9) -> float:
    # bracket from the simplified Eq. (39) at zeta - delta, independent of Eq. (36)
    approx = critical_lambda_approx(zeta - delta)
    lo, hi = 0.5 * approx, 2.0 * approx
    assert _verdict(lo, zeta, delta) is Verdict.STEADY_SLIDING
    assert _verdict(hi, zeta, delta) is Verdict.STICK_SLIP
    while hi - lo > rel_tol * hi:
        mid = 0.5 * (lo + hi)
        if _verdict(mid, zeta, delta) is Verdict.STICK_SLIP:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@pytest.mark.parametrize(("zeta", "delta"), CASES)
def test_simulated_boundary_is_eq_36_at_effective_damping(zeta: float, delta: float) -> None:
    # reference: Eq. (36) with zeta -> zeta - delta (critical_lambda_linear)
    exact = critical_lambda_linear(zeta, delta)
    # validity of the closed form (its docstring): startup sticks, the floor u* is never reached
    zeta_e = zeta - delta
    assert 2 * zeta <= 3.0 * exact
    if delta > 0:
        assert 2.0 * exact / (2 * delta) > 1 + math.hypot(exact - 2 * zeta_e, 1.0)
    found = _bisect(zeta, delta)
    print(f"zeta={zeta} delta={delta}: simulated {found:.12g}, closed form {exact:.12g}")
    assert abs(found / exact - 1.0) < 1e-6


@pytest.mark.parametrize("delta", [0.1, 0.15])
def test_no_effective_damping_means_stick_slip_at_any_lambda(delta: float) -> None:
    # reference: critical_lambda_linear docstring, zeta - delta <= 0 gives lambda_c = 0; lambda
    # chosen inside its validity range (startup sticks, u* = gamma lam/(2 delta) > 1 + hypot(lam, 1))
    zeta = 0.1
    assert critical_lambda_linear(zeta, delta) == 0.0
    for lam in (0.5, 1.0, 3.0):
        assert _verdict(lam, zeta, delta) is Verdict.STICK_SLIP


def test_zero_slope_is_the_coulomb_boundary() -> None:
    from stickslip.analysis.theory import critical_lambda_exact

    assert critical_lambda_linear(0.2, 0.0) == critical_lambda_exact(0.2)


def test_floor_reached_changes_the_answer() -> None:
    # outside the validity range: u* = gamma lam / (2 delta) = 0.5 < 1, steady sliding sits in the
    # floored band (F = 0, ordinary damping), so zeta - delta = 0 does not force stick-slip there
    assert _verdict(0.05, 0.1, 0.1) is Verdict.STEADY_SLIDING
