"""Stick-slip cycles whatever the start (issue 13, point 4).

Sources: on the rigid base the breakaway state is unique, so a cycle exists exactly where the
start-up run stick-slips, above the root of Eq. (36); a reported cycle must be reproduced by
:func:`stickslip.simulate` started on it (certified, same period); a stable cycle attracts
nearby breakaway states, at the rate of its largest Floquet multiplier (return map iterated).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from stickslip import (
    InitialState,
    Slider,
    Verdict,
    critical_lambda_exact,
    elastic_foundation,
    optimal_foundation_fit,
    rigid_base,
    simulate,
)
from stickslip.analysis.cycles import _ReturnMap, find_cycles
from stickslip.analysis.simulation import EngineOptions

from .cli_helpers import run_cli


@pytest.mark.parametrize("zeta", [0.05, 0.2])
def test_rigid_base_cycle_exists_exactly_above_eq36(zeta: float) -> None:
    lam_c = critical_lambda_exact(zeta)
    assert find_cycles(rigid_base(zeta), Slider(lam_c * (1 + 1e-4)), seeds=4).cycles
    assert not find_cycles(rigid_base(zeta), Slider(lam_c * (1 - 1e-4)), seeds=4).cycles


def test_foundation_cycle_is_reproduced_and_attracts_nearby_states() -> None:
    structure, slider = elastic_foundation(0.1, optimal_foundation_fit(0.1)), Slider(15.0)
    search = find_cycles(structure, slider, seeds=6, max_period=1)
    assert len(search.cycles) == 1
    cycle = search.cycles[0]
    b = cycle.breakaway_state
    run = simulate(structure, slider, initial=InitialState(b[:2], b[2:]), record=False)
    assert run.verdict is Verdict.STICK_SLIP and run.period == pytest.approx(cycle.period, rel=1e-9)
    # the start-up run lands on the same cycle (README: period 33.9767)
    assert simulate(structure, slider, record=False).period == pytest.approx(cycle.period, rel=1e-8)
    assert cycle.stable
    pmap = _ReturnMap(structure, slider, EngineOptions())
    fixed = pmap.reduce(b)
    x = fixed + np.array([1e-3, -1e-3])
    errors = []
    for _ in range(6):
        x = pmap(x, 1)
        errors.append(float(np.max(np.abs(x - fixed))))
    # attracted, at the rate of the Floquet multipliers: one return shrinks the 1e-3 offset by
    # the largest multiplier (the long, damped stick phase makes it tiny here)
    mu = float(max(abs(cycle.multipliers)))
    assert errors[0] <= 10.0 * (mu + 1e-9) * 1e-3
    assert errors[-1] <= errors[0] + 1e-9


def test_cycles_command_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["cycles", "--lam", "3", "--zeta", "0.1", "--seeds", "3", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    [cycle] = payload["cycles"]
    assert {"period", "amplitude", "stick_ratio", "stable", "multipliers", "breakaway_state"} <= set(cycle)
    # Nakano's breakaway state on the rigid base: xi = lambda - 2 zeta, xi' = 1 (Eq. 20)
    assert cycle["breakaway_state"] == pytest.approx([3.0 - 0.2, 1.0])
    assert cycle["period"] == pytest.approx(simulate(rigid_base(0.1), Slider(3.0)).period, rel=1e-9)
