"""Steady-sliding certificates with friction bands, checked against the solve_ivp oracle.

A table with a point at the belt speed (u = 1, a measured curve sampled at v = V) puts the
steady-sliding equilibrium on a band edge; the certificate then needs a Lyapunov function
valid on both bands (the energy on the bands where ``C + sigma e_0 e_0'`` stays positive
semi-definite for the secant slope ``sigma``, or a common quadratic one; see
``stickslip.kernel.system.prepare_bands``). Reference for "never sticks again": the oracle of
tests/friction_oracle.py run far beyond the certificate.
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import EngineOptions, Slider, Verdict, elastic_foundation, rigid_base, simulate
from stickslip.model import TableFriction
from stickslip.model.parameters import Foundation
from tests.friction_oracle import friction_oracle_simulate

TABLE = TableFriction((0.5, 1.0, 2.0), (0.5, 0.3, 0.6))  # weakening below u = 1, strengthening above


@pytest.mark.parametrize(("n_dof", "lam"), [
    (1, 0.3),
    # the other pairs repeat the same certificate with a long oracle run each (8-15 s)
    pytest.param(2, 0.45, marks=pytest.mark.slow),
    pytest.param(1, 0.45, marks=pytest.mark.slow), pytest.param(2, 0.3, marks=pytest.mark.slow),
])
def test_equilibrium_on_a_band_edge_is_certified(n_dof: int, lam: float) -> None:
    structure = rigid_base(0.1) if n_dof == 1 else elastic_foundation(0.1, Foundation(1.5, 1.0, 0.5))
    slider = Slider(lam, friction=TABLE)
    assert 1.0 in slider.friction.bands(lam, 2.0)[0]
    r = simulate(structure, slider)
    assert r.verdict is Verdict.STEADY_SLIDING, r.status.message
    oracle = friction_oracle_simulate(structure, slider, r.t_certified + 300.0)
    # no switch after the certificate: the slider stays in slip-I for ever
    assert not np.any(oracle.event_times > r.t_certified + 1e-6)
    assert oracle.pieces[-1].mode == 0


def test_a_decaying_oscillation_is_not_a_slip_oscillation() -> None:
    # measured: the 2DOF case at lambda = 0.45 spirals into the equilibrium on the edge u = 1;
    # the Poincare section is a band edge at a positive distance from u = 1, so the shrinking
    # motion is never taken for a periodic one
    structure = elastic_foundation(0.1, Foundation(1.5, 1.0, 0.5))
    r = simulate(structure, Slider(0.45, friction=TABLE), run_to_t_max=True,
                 options=EngineOptions(t_max=400.0))
    assert r.verdict is Verdict.STEADY_SLIDING


def test_stability_at_a_kink_reports_the_worse_side() -> None:
    # TABLE has slopes -0.4 lam below u = 1 and +0.3 lam above (f from 0.5 to 0.3 to 0.6)
    from stickslip.analysis.stability import one_sided_slopes, steady_sliding_stability

    slider = Slider(0.45, friction=TABLE)
    left, right = one_sided_slopes(slider)
    assert left == pytest.approx(-0.4 * 0.45) and right == pytest.approx(0.3 * 0.45)
    stab = steady_sliding_stability(rigid_base(0.1), slider)
    assert stab.kink and stab.slope == left
    assert stab.growth_rate == pytest.approx(-(0.1 - 0.5 * 0.4 * 0.45), abs=1e-12)
