"""Friction laws in the engine against an independent solve_ivp oracle (tests/friction_oracle.py).

The oracle integrates the law's exact ``F(u)`` (no bands) with DOP853, rtol = atol = 1e-12,
max_step = 0.01; the engine integrates the band table exactly. Cases are away from the
stick-slip boundary (no grazes). Both must switch between slip-I, slip-II and stick in the
same order, at the same times, and reach the same verdict.

Tolerances: linear law 1e-8 (exact bands; measured <= 1e-11). Stribeck law with
``tolerance = 1e-6`` 5e-5 (the engine integrates the interpolant, ``|F - F_PL| <= 1e-6
lambda``; measured 6e-7 to 1.2e-5).
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import Slider, Verdict, elastic_foundation, rigid_base, simulate
from stickslip.model.friction import LinearFriction, StribeckFriction
from stickslip.model.parameters import Foundation
from tests.friction_oracle import friction_oracle_simulate, kind_events

FOUNDATION = Foundation(1.5, 1.0, 0.5)
STRIBECK_A = StribeckFriction(0.3, viscous=0.02, tolerance=1e-6)
STRIBECK_B = StribeckFriction(0.2, exponent=2.0, viscous=0.1, tolerance=1e-6)

CASES = [
    # n_dof, zeta, lambda, law, event-time tolerance
    (1, 0.1, 3.0, LinearFriction(0.05), 1e-8),
    (1, 0.1, 0.5, LinearFriction(0.05), 1e-8),
    (1, 0.1, 2.0, LinearFriction(-0.1), 1e-8),
    (2, 0.1, 3.0, LinearFriction(0.03), 1e-8),
    (2, 0.1, 0.5, LinearFriction(-0.05), 1e-8),
    (1, 0.1, 2.0, STRIBECK_A, 5e-5),
    (1, 0.05, 1.0, STRIBECK_B, 5e-5),
    # the same machine and law as tests/test_friction_stribeck_refinement.py's 1e-6 row, which
    # checks its events against this oracle in the default run (and proves its cycle: 40 s)
    pytest.param(2, 0.1, 3.0, STRIBECK_A, 5e-5, marks=pytest.mark.slow),
]


@pytest.mark.parametrize(("n_dof", "zeta", "lam", "law", "tol"), CASES)
def test_events_and_verdict_agree_with_solve_ivp(n_dof, zeta, lam, law, tol) -> None:
    structure = rigid_base(zeta) if n_dof == 1 else elastic_foundation(zeta, FOUNDATION)
    slider = Slider(lam, gamma=2.0, friction=law)
    ours = simulate(structure, slider)
    assert ours.verdict in (Verdict.STEADY_SLIDING, Verdict.STICK_SLIP), ours.status.message
    horizon = max(50.0, 1.25 * ours.t_end)
    oracle = friction_oracle_simulate(structure, slider, horizon)
    times, kinds = kind_events(ours.segment_times, ours.segment_modes)
    n = times.size
    assert oracle.event_times.size >= n
    assert np.array_equal(oracle.event_modes[:n], kinds)
    if n:
        err = np.max(np.abs(oracle.event_times[:n] - times))
        print(f"{law.describe()[:40]} n_dof={n_dof} lam={lam}: {n} events, max |dt| = {err:.1e}")
        assert err <= tol
    assert oracle.verdict() == ours.verdict.value
