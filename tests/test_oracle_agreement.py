"""The 2DOF engine against an independent solve_ivp oracle (tests/oracle.py).

The oracle integrates the same piecewise equations with DOP853 (rtol = atol = 1e-12,
max_step = 0.01) and terminal events. On cases away from the stick-slip boundary (no
grazes) both must see the same mode sequence, the same event times to the oracle's
accuracy, and the same verdict. Cases and horizons are those of benchmarks/bench_engine.py,
where the oracle was checked against Eqs. (34)-(35) and an expm re-propagation.
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import Slider, Verdict, elastic_foundation, simulate
from stickslip.analysis.theory import optimal_foundation_fit
from tests.oracle import oracle_simulate_structure

CASES = [
    # zeta, K scale, lambda: steady sliding and stick-slip, tuned and detuned
    (0.1, 1.0, 0.5),
    (0.05, 0.5, 0.5),
    (0.1, 2.0, 15.0),
    (0.2, 1.0, 15.0),
]


@pytest.mark.parametrize(("zeta", "k_scale", "lam"), CASES)
def test_events_and_verdict_agree_with_solve_ivp(zeta: float, k_scale: float, lam: float) -> None:
    structure = elastic_foundation(zeta, optimal_foundation_fit(zeta).scaled(k_scale))
    slider = Slider(lam, gamma=2.0)
    ours = simulate(structure, slider)
    assert ours.verdict is not Verdict.UNDETERMINED
    # the oracle runs past our certificate so that its tail verdict is meaningful
    horizon = max(50.0, 1.25 * ours.t_end)
    oracle = oracle_simulate_structure(structure, slider, horizon)
    n = ours.event_times.size
    assert np.array_equal(oracle.event_modes[:n], ours.event_modes)
    assert np.allclose(oracle.event_times[:n], ours.event_times, rtol=0.0, atol=1e-8)
    assert oracle.verdict() == ours.verdict.value
