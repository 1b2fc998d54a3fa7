"""A basin's stick-slip labels are proven cycles on N DOF (sweep.basin_cycles, kernel.cycle_balls).

References: every label and period is checked against :func:`stickslip.simulate` run from
the same state (its own run, then its cycle proof: Newton on the exact return map and a
contraction ball), an independent path through the proof code; the slideway example's cycle
is the 20.94 ms one-stick-phase cycle of ``stickslip cycles --config`` (test_cycle_proof.py),
whose runs see a two-phase repeat first. Ball membership is checked against direct maps of
the return map from points on and beyond the ball's boundary.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from stickslip import Foundation, InitialState, Slider, elastic_foundation, simulate
from stickslip.analysis.engine_run import EngineOptions
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.io.machine_file import machine_from_file, read_machine_file
from stickslip.kernel import engine
from stickslip.model.friction import StribeckFriction
from stickslip.sweep.basin import basin_stability, sample_box, state_names
from stickslip.sweep.basin_cycles import PILOT_STATES, ProvenBalls, pilot_balls

SLIDEWAY = Path(__file__).resolve().parent.parent / "examples" / "slideway" / "machine.toml"


def _slideway():  # type: ignore[no-untyped-def]
    machine, _ = machine_from_file(read_machine_file(SLIDEWAY),
                                   {"mu_s": 0.15, "mu_k": 0.10, "load": 2600.0, "speed": 0.5e-3})
    structure, slider = machine.to_dimensionless()
    return machine, structure.contact_first()[0], slider


def _weak_foundation():  # type: ignore[no-untyped-def]
    """bench_basin's foundation case: lambda = 0.05 * 0.2 * e^5, exponential Stribeck
    v_s/V = 0.2 (tolerance 1e-4), zeta = 0.05, foundation ratios 1, 1, 0.1."""
    slider = Slider(0.05 * 0.2 * float(np.exp(5.0)), friction=StribeckFriction(0.2, tolerance=1e-4))
    return elastic_foundation(0.05, Foundation(1.0, 1.0, 0.1)), slider


def _direct(structure, slider, state):  # type: ignore[no-untyped-def]
    n = structure.n_dof
    return simulate(structure, slider, initial=InitialState(state[:n], state[n:]), record=False)


def _assert_same_as_simulate(structure, slider, states, result) -> int:  # type: ignore[no-untyped-def]
    stick_slip = 0
    for i, state in enumerate(states):
        run = _direct(structure, slider, state)
        assert result.verdict[i] == run.verdict.code, (i, run.verdict, run.certificate)
        if run.verdict is Verdict.STICK_SLIP:
            stick_slip += 1
            assert result.int_summary[i, engine.I_CYCLE_K] == run.cycle_length
            assert result.float_summary[i, engine.F_PERIOD] == pytest.approx(run.period, rel=1e-7)
            assert result.float_summary[i, engine.F_AMPLITUDE] == pytest.approx(run.amplitude, rel=1e-6)
    return stick_slip


def test_slideway_basin_reports_the_one_phase_cycle() -> None:
    """The example whose runs repeat after two stick phases: every stick-slip state of its
    basin gets the proven one-phase cycle, 20.94 ms, as simulate does."""
    machine, structure, slider = _slideway()
    box = {name: (-3.0, 3.0) for name in state_names(structure.n_dof)}
    box["v"] = (-2.0, 0.5)
    states = sample_box(structure, slider, 24, box, seed=3)
    result = basin_stability(structure, slider, states)
    assert _assert_same_as_simulate(structure, slider, states, result) >= 5
    stick_slip = result.verdict == Verdict.STICK_SLIP.code
    assert np.all(result.int_summary[stick_slip, engine.I_CYCLE_K] == 1)
    seconds = result.float_summary[stick_slip, engine.F_PERIOD] * machine.reference_system().time_scale
    assert np.allclose(seconds, 20.94e-3, atol=0.01e-3)


def test_foundation_basin_labels_equal_simulate_and_balls_stop_runs_early() -> None:
    """bench_basin's 2-DOF case: the labels are simulate's; the stick-slip runs end in the
    proven ball (no repeat measured: mismatch NaN) after fewer stick phases than the repeat
    test needs."""
    structure, slider = _weak_foundation()
    box = {"xi": (-0.7, 0.7), "v": (-0.7, 1.3), "xi_a": (-0.2, 0.2), "v_a": (-0.2, 0.2)}
    states = sample_box(structure, slider, 48, box, seed=1)
    result = basin_stability(structure, slider, states)
    assert _assert_same_as_simulate(structure, slider, states, result) >= 10
    stick_slip = result.verdict == Verdict.STICK_SLIP.code
    assert np.all(np.isnan(result.float_summary[stick_slip, engine.F_CYCLE_MISMATCH]))
    # the same states without balls: each runs until its breakaway state repeats to 1e-9
    from stickslip.sweep.basin import BasinSystem, run_state_batch

    plain = BasinSystem.prepare(structure, slider, len(states))
    _, isum = run_state_batch(plain, states, EngineOptions())
    assert np.all(isum[stick_slip, engine.I_STATUS] == engine.STATUS_CYCLE)
    assert (result.int_summary[stick_slip, engine.I_N_STICK].mean()
            < 0.8 * isum[stick_slip, engine.I_N_STICK].mean())


def test_ball_membership_is_the_proven_ball() -> None:
    """The fixed point is inside its ball and a point just beyond the boundary (in the
    adapted norm) is not; a point on the boundary maps back inside (the contraction)."""
    structure, slider = _weak_foundation()
    box = {"xi": (-0.7, 0.7), "v": (-0.7, 1.3), "xi_a": (-0.2, 0.2), "v_a": (-0.2, 0.2)}
    states = sample_box(structure, slider, PILOT_STATES, box, seed=1)
    balls = pilot_balls(structure, slider, states, EngineOptions())
    assert len(balls) == 1  # one stable cycle (find_cycles lists one at this point)
    row, chol = balls.data[0], balls.norm[0]
    from stickslip.kernel.cycle_balls import B_CENTER, B_RHO

    section = balls.section
    b_hat, rho = row[B_CENTER:], row[B_RHO]
    assert balls.holding(section.state(b_hat))[0] == 0
    rng = np.random.default_rng(5)
    for _ in range(3):
        u = rng.normal(size=b_hat.size)
        step = np.linalg.solve(chol, u / np.linalg.norm(u)) * rho
        assert balls.holding(section.state(b_hat + 1.001 * step))[0] == -1
        image = section(b_hat + 0.999 * step, int(row[2]))
        assert image is not None and balls.holding(section.state(image))[0] == 0


def test_one_dof_basin_has_no_balls() -> None:
    """The rigid base needs no proof (unique breakaway state): no pilot, the old path."""
    from stickslip import rigid_base

    structure, slider = rigid_base(0.1), Slider(2.5)
    states = sample_box(structure, slider, 8, {"xi": (-4.0, 4.0), "v": (-3.0, 1.5)}, seed=1)
    assert len(pilot_balls(structure, slider, states, EngineOptions())) == 0
    assert len(ProvenBalls.empty(structure, slider, EngineOptions())) == 0


def test_unprovable_candidate_is_undetermined(monkeypatch: pytest.MonkeyPatch) -> None:
    """A candidate no proof holds becomes ``unproven-cycle``: undetermined, never stick-slip."""
    import stickslip.sweep.basin_cycles as basin_cycles

    structure, slider = _weak_foundation()
    monkeypatch.setattr(basin_cycles, "prove_run",
                        lambda result, opts, **_: replace(result, status=RunStatus.UNPROVEN_CYCLE,
                                                     verdict=Verdict.UNDETERMINED))
    box = {"xi": (-0.7, 0.7), "v": (-0.7, 1.3), "xi_a": (-0.2, 0.2), "v_a": (-0.2, 0.2)}
    states = sample_box(structure, slider, 12, box, seed=1)
    result = basin_stability(structure, slider, states)
    direct = [_direct(structure, slider, s).verdict for s in states]
    for code, verdict in zip(result.verdict, direct, strict=True):
        expected = Verdict.UNDETERMINED if verdict is Verdict.STICK_SLIP else verdict
        assert code == expected.code
