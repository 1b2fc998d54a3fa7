"""The run's own rounding carried to the state a cycle proof finds in its ball (issue 29, point 1).

A proof that the return map contracts a ball and that the *computed* state is in it says
nothing about the motion from the user's start when the run amplifies its rounding (a
chaotic transient among unstable cycles). Source of the chaotic case: an independent audit
(an event-driven DOP853 integration at rtol = atol = 1e-11 of the paper's 2DOF model,
lambda = 8.64491378838684, zeta = 0.004626523877929044, M = 0.8192950007726704,
K = 0.5329182031654399, zeta_a = 0.001356455026308398): from xi = 3.1990732730153972,
xi' = 1.0678655709303815 (foundation at rest) the engine's and the oracle's breakaway times
part by more than 1e-3 before tau = 2400, long before the engine's run enters the proven ball
of its period-2 cycle, so the engine's certificate of that state was not a proof.
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import Foundation, InitialState, Slider, elastic_foundation, simulate
from stickslip.analysis.engine_run import EngineOptions, run_engine
from stickslip.analysis.return_map import ReturnMap
from stickslip.analysis.run_rounding import run_rounding
from stickslip.analysis.verdict import RunStatus, Verdict

LAM, ZETA = 8.64491378838684, 0.004626523877929044
FOUNDATION = Foundation(0.8192950007726704, 0.5329182031654399, 0.001356455026308398)


def _run(xi: float, v: float):  # type: ignore[no-untyped-def]
    structure = elastic_foundation(ZETA, FOUNDATION)
    return simulate(structure, Slider(LAM), initial=InitialState(np.array([xi, 0.0]),
                                                                 np.array([v, 0.0])))


def test_a_chaotic_transient_is_not_certified() -> None:
    run = _run(3.1990732730153972, 1.0678655709303815)
    assert run.verdict is Verdict.UNDETERMINED and run.status is RunStatus.UNPROVEN_CYCLE
    assert "period-2 cycle proven" in run.certificate
    assert "the run's rounding carried to it" in run.certificate
    assert "need not be the motion from its start" in run.certificate


def test_a_settling_run_carries_little_rounding_into_the_ball() -> None:
    # the same machine from xi = 4.108850619643629, xi' = -6.323661182749353: the audit's
    # oracle settles on the same period-2 cycle as the engine
    run = _run(4.108850619643629, -6.323661182749353)
    assert run.verdict is Verdict.STICK_SLIP and run.cycle_proof.stick_phases == 2
    proof = run.cycle_proof
    assert 0.0 < proof.run_error <= proof.margin
    assert proof.run_gain < 1e3
    assert "its rounding carried there at most" in run.certificate
    payload = proof.to_dict()
    assert payload["run_rounding_bound"] == proof.run_error
    assert payload["margin"] == proof.margin


def test_the_gain_of_one_return_is_the_maps_jacobian() -> None:
    # a chain of two returns from a breakaway state b_0: the error made up to the first
    # breakaway b_1 reaches the end through D P(b_1), which ReturnMap.linearise forms forward
    # (a product in the other order, by another code path)
    structure = elastic_foundation(ZETA, FOUNDATION)
    slider = Slider(LAM)
    start = run_engine(structure, slider, None, EngineOptions(), False, False)
    pmap = ReturnMap(structure, slider, EngineOptions())
    b0 = pmap.reduce(start.final_state)
    recorded = pmap.recorded_run(pmap.state(b0), 2)
    assert recorded is not None
    result, hits = recorded
    rounding = run_rounding(pmap, [(result, float(hits[-1]))])
    assert rounding is not None
    b1 = pmap(b0, 1)
    _, jac = pmap.linearise(b1, 1)
    expected = max(1.0, float(np.linalg.norm(jac, 2)))
    print(f"gain {rounding.gain:.6g}, ||D P(b_1)|| {expected:.6g}")
    assert rounding.gain == pytest.approx(expected, rel=1e-6)
    assert rounding.bound > 0.0
