"""Linear stability of steady sliding: eigenvalues, Routh-Hurwitz and the simulation agree.

References: the rigid-base criterion ``zeta - delta > 0`` (Routh-Hurwitz for
``s^2 + 2 (zeta - delta) s + 1``; :func:`stickslip.analysis.stability.routh_hurwitz_1dof`) and
the quartic's Hurwitz conditions for the elastic foundation
(:func:`stickslip.analysis.stability.routh_hurwitz_quartic`, derivation in its docstring);
numpy's eigenvalues are independent of both.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from stickslip import Slider, Verdict, elastic_foundation, rigid_base, simulate
from stickslip.analysis.stability import (
    quartic_coefficients,
    routh_hurwitz_2dof,
    slip_matrix,
    steady_sliding_stability,
)
from stickslip.model import InitialState
from stickslip.model.friction import LinearFriction, StribeckFriction
from stickslip.model.parameters import Foundation

FOUNDATION = Foundation(1.5, 1.0, 0.5)


def _near_equilibrium(structure, slider, kick: float = 0.02) -> InitialState:
    # steady sliding: xi' = 0, K q = (F(1) - gamma lam) e_0; a small kick in position
    n = structure.n_dof
    force = float(slider.friction.value(1.0, slider.lam, slider.gamma)) - slider.gamma * slider.lam
    q = np.linalg.solve(structure.stiffness, np.eye(n)[0]) * force
    q[0] += kick
    return InitialState(q, np.zeros(n))


def test_quartic_coefficients_are_the_characteristic_polynomial() -> None:
    st = elastic_foundation(0.1, FOUNDATION)
    for slope in (-0.5, -0.1, 0.0, 0.3):
        coef = quartic_coefficients(st.mass, st.damping + np.diag([slope, 0.0]), st.stiffness)
        roots = np.sort_complex(np.roots(coef))
        eig = np.sort_complex(np.linalg.eigvals(slip_matrix(st, slope)))
        assert np.allclose(roots, eig, atol=1e-10)


@pytest.mark.parametrize("delta", [-0.2, 0.0, 0.05, 0.09, 0.099, 0.101, 0.11, 0.3])
def test_rigid_base_eigenvalues_match_routh_hurwitz(delta: float) -> None:
    zeta = 0.1
    stab = steady_sliding_stability(rigid_base(zeta), Slider(2.0, friction=LinearFriction(delta)))
    assert stab.delta_local == pytest.approx(delta)
    assert stab.routh_hurwitz == (zeta - delta > 0)
    assert stab.stable == stab.routh_hurwitz
    # xi'' + 2 (zeta - delta) xi' + xi = 0: real part -(zeta - delta) while underdamped
    assert stab.growth_rate == pytest.approx(-(zeta - delta), abs=1e-12)


def test_foundation_threshold_eigenvalues_equal_routh_hurwitz() -> None:
    st = elastic_foundation(0.1, FOUNDATION)

    def growth(delta: float) -> float:
        return float(np.max(np.linalg.eigvals(slip_matrix(st, -2.0 * delta)).real))

    d_eig = brentq(growth, 0.0, 2.0, xtol=1e-14)
    d_rh = brentq(lambda d: 0.5 if routh_hurwitz_2dof(st, -2.0 * d) else -0.5, 0.0, 2.0, xtol=1e-14)
    print(f"foundation {FOUNDATION}: delta_crit eigenvalues {d_eig:.12f}, Routh-Hurwitz {d_rh:.12f}")
    assert d_rh == pytest.approx(d_eig, rel=1e-9)
    for delta in np.linspace(-0.5, 1.5, 41):
        assert routh_hurwitz_2dof(st, -2.0 * delta) == (growth(delta) < 0.0)


@pytest.mark.parametrize("side", [0.8, 1.2])
@pytest.mark.parametrize("n_dof", [1, 2])
def test_simulation_agrees_on_both_sides_of_the_threshold(n_dof: int, side: float) -> None:
    zeta, lam = 0.1, 3.0
    st = rigid_base(zeta) if n_dof == 1 else elastic_foundation(zeta, FOUNDATION)
    if n_dof == 1:
        d_crit = zeta
    else:
        d_crit = brentq(lambda d: float(np.max(np.linalg.eigvals(slip_matrix(st, -2 * d)).real)), 0.0, 2.0)
    slider = Slider(lam, friction=LinearFriction(side * d_crit))
    result = simulate(st, slider, initial=_near_equilibrium(st, slider))
    assert result.steady_sliding_stable == (side < 1.0)
    assert (result.growth_rate < 0) == (side < 1.0)
    if side < 1.0:
        assert result.verdict is Verdict.STEADY_SLIDING
        assert result.n_stick == 0
    else:
        # the small kick grows until the slider reaches the belt speed and sticks
        assert result.verdict is Verdict.STICK_SLIP
        assert result.n_stick >= 1


def test_stribeck_slope_is_the_exact_derivative() -> None:
    law = StribeckFriction(0.4, exponent=1.5, viscous=0.03)
    lam, gamma, h = 2.0, 2.0, 1e-6
    fd = (law.value(1.0 + h, lam, gamma) - law.value(1.0 - h, lam, gamma)) / (2 * h)
    assert law.slope_at(1.0, lam, gamma) == pytest.approx(float(fd), rel=1e-7)
    result = simulate(rigid_base(0.1), Slider(lam, gamma=gamma, friction=law), record=False)
    expected = steady_sliding_stability(rigid_base(0.1), Slider(lam, gamma=gamma, friction=law))
    assert result.growth_rate == expected.growth_rate
    assert result.to_dict()["growth_rate"] == expected.growth_rate
