"""The single-degree-of-freedom shortcut of basin runs against full runs of every state.

``stickslip.kernel.batch.run_states`` stops a 1-DOF run at its first stick phase and takes
the rest of the motion from the start-up run, shifted in time (derivation in its
docstring: every stick phase ends at the same breakaway state). These tests run the same
states both ways (``join_startup=True`` and ``False``) and require the same verdicts, the
same cycles and the same certificate times to rounding.
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import Foundation, Slider, elastic_foundation, rigid_base
from stickslip.kernel import engine
from stickslip.kernel.batch import run_states
from stickslip.model.friction import LinearFriction, StribeckFriction
from stickslip.sweep.basin import sample_box

# bistable or stick-slip points (start-up verdict stick-slip, steady sliding stable):
# Coulomb above the Eq. (36) boundary (about 1.9 at zeta = 0.1), the linear law with a
# small weakening slope, and the Stribeck law of benchmarks/bench_basin.py
CASES = {
    "coulomb": Slider(2.5),
    "linear": Slider(2.5, friction=LinearFriction(0.05)),
    "stribeck": Slider(2.0, friction=StribeckFriction(0.2, tolerance=1e-3)),
}
BOX = {"xi": (-4.0, 4.0), "v": (-3.0, 1.5)}
# cycle detection tolerance and budgets of EngineOptions' defaults, as basin runs use them
T_MAX, MAX_EVENTS, CYCLE_TOL, MAX_PERIOD = 1e4, 100_000, 1e-9, 8


def _both(structure, slider, states):  # type: ignore[no-untyped-def]
    """Joined and full runs, both without the early certificates (whose states are certified
    at time 0 without a run: tests/test_escape_certificate.py), and the statuses with them."""
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    args = (structure.mass, structure.damping, structure.stiffness, float(slider.lam),
            float(slider.gamma), edges, intercepts, slopes, np.ascontiguousarray(states), T_MAX,
            MAX_EVENTS, CYCLE_TOL, MAX_PERIOD)
    joined, full = run_states(*args, True, False), run_states(*args, False, False)
    early = run_states(*args, True, True)
    np.testing.assert_array_equal(early[1][:, engine.I_STATUS], full[1][:, engine.I_STATUS])
    return joined, full


def _states(structure, slider, n=300):  # type: ignore[no-untyped-def]
    states = sample_box(structure, slider, n, BOX, seed=3)
    # stick states (v = 1 exactly) across the stick interval, and the start-up state itself
    xi_stick = np.linspace(-slider.lam * (1.0 + 2.0 * slider.gamma), slider.lam, 7)[1:-1] - 0.2
    stick = np.column_stack([xi_stick, np.ones_like(xi_stick)])
    startup = np.array([[-slider.gamma * slider.lam, 1.0]])
    return np.vstack([states, stick, startup])


@pytest.mark.parametrize("name", sorted(CASES))
def test_shortcut_gives_the_verdicts_cycles_and_times_of_full_runs(name: str) -> None:
    structure = rigid_base(0.1)
    slider = CASES[name]
    states = _states(structure, slider)
    (f_join, i_join), (f_full, i_full) = _both(structure, slider, states)
    status = i_full[:, engine.I_STATUS]
    # every state certified both ways, with the same certificate
    np.testing.assert_array_equal(i_join[:, engine.I_STATUS], status)
    assert np.all((status == engine.STATUS_STEADY) | (status == engine.STATUS_CYCLE))
    cycle = status == engine.STATUS_CYCLE
    assert 0 < cycle.sum() < len(states), "the box should hold both basins (bistable point)"
    np.testing.assert_array_equal(i_join[cycle, engine.I_CYCLE_K], i_full[cycle, engine.I_CYCLE_K])
    # the same cycle: breakaway times and extremes agree to rounding of the event location
    for column in (engine.F_PERIOD, engine.F_AMPLITUDE, engine.F_XI_MIN, engine.F_XI_MAX,
                   engine.F_STICK_RATIO, engine.F_CYCLE_MAX_VELOCITY):
        np.testing.assert_allclose(f_join[cycle, column], f_full[cycle, column], rtol=1e-9,
                                   atol=1e-9, err_msg=engine_column_name(column))
    # the joined run's clock: the stick phase's time shift (derivation in run_states)
    for column in (engine.F_T_CERTIFIED, engine.F_T_END, engine.F_T_LAST_STICK):
        np.testing.assert_allclose(f_join[cycle, column], f_full[cycle, column], rtol=1e-9,
                                   atol=1e-9, err_msg=engine_column_name(column))
    np.testing.assert_allclose(f_join[~cycle, engine.F_T_CERTIFIED], f_full[~cycle, engine.F_T_CERTIFIED],
                               rtol=1e-9, atol=1e-9)
    # counts add up: the shared stick phase is counted once
    for column in (engine.I_N_STICK, engine.I_N_BREAKAWAY, engine.I_N_SEGMENTS):
        np.testing.assert_array_equal(i_join[:, column], i_full[:, column])
    # the shortcut was taken where the state sticks (no velocity maximum is tracked there)
    assert np.isnan(f_join[cycle, engine.F_MAX_VELOCITY]).all()
    assert not np.isnan(f_full[:, engine.F_MAX_VELOCITY]).any()


def engine_column_name(column: int) -> str:
    """Name of a float-summary column, for failure messages."""
    return next(k for k, v in vars(engine).items() if k.startswith("F_") and v == column)


def test_horizon_applies_to_the_joined_clock() -> None:
    # a horizon shorter than the start-up run's certificate: a direct run of a state that
    # sticks late cannot certify its cycle before t_max, and neither may the joined one
    structure, slider = rigid_base(0.1), CASES["stribeck"]
    states = _states(structure, slider, n=200)
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    full = run_states(structure.mass, structure.damping, structure.stiffness, slider.lam, slider.gamma,
                      edges, intercepts, slopes, states, T_MAX, MAX_EVENTS, CYCLE_TOL, MAX_PERIOD, False)
    t_cert = full[0][full[1][:, engine.I_STATUS] == engine.STATUS_CYCLE, engine.F_T_CERTIFIED]
    t_max = float(np.median(t_cert))
    # the join alone (early certificates off: their states are certified at time 0, without
    # a run), and with them (the trap region certifies whatever the horizon, as before the
    # escape region: compared with full runs that have it too)
    short = [run_states(structure.mass, structure.damping, structure.stiffness, slider.lam, slider.gamma,
                        edges, intercepts, slopes, states, t_max, MAX_EVENTS, CYCLE_TOL, MAX_PERIOD, join,
                        early)
             for join, early in ((True, False), (False, False), (True, True), (False, True))]
    np.testing.assert_array_equal(short[2][1][:, engine.I_STATUS], short[3][1][:, engine.I_STATUS])
    short = short[:2]
    status_join, status_full = short[0][1][:, engine.I_STATUS], short[1][1][:, engine.I_STATUS]
    assert (status_full == engine.STATUS_T_MAX).sum() > 10
    np.testing.assert_array_equal(status_join, status_full)
    (f_join, i_join), (f_full, i_full) = short
    # a run cut by the horizon ends at it and reports no cycle, joined or not
    cut = status_full == engine.STATUS_T_MAX
    np.testing.assert_array_equal(f_join[cut, engine.F_T_END], t_max)
    np.testing.assert_array_equal(f_full[cut, engine.F_T_END], t_max)
    assert np.isnan(f_join[cut, engine.F_PERIOD]).all() and np.isnan(f_full[cut, engine.F_PERIOD]).all()
    np.testing.assert_array_equal(i_join[:, engine.I_CYCLE_K], i_full[:, engine.I_CYCLE_K])
    np.testing.assert_allclose(f_join[~cut, engine.F_T_CERTIFIED], f_full[~cut, engine.F_T_CERTIFIED],
                               rtol=1e-9, atol=1e-9)


def test_start_up_run_gets_the_time_a_joined_clock_runs_ahead_by() -> None:
    # a state stuck at the far end of the stick range (just below the breakaway) joins the
    # start-up run late in its stick phase: its clock runs ahead of the start-up run's, and
    # with a horizon just above its own certificate the start-up run alone (certified later
    # on its clock) would be cut; it is given the extra time (run_states)
    structure, slider = rigid_base(0.1), CASES["coulomb"]
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    args = (structure.mass, structure.damping, structure.stiffness, slider.lam, slider.gamma,
            edges, intercepts, slopes)
    # breakaway at S = xi + 2 zeta = lambda (stick force of Eq. 20, rigid base): xi_b = lambda - 0.2
    near_breakaway = np.array([[slider.lam - 0.2 - 1e-3, 1.0]])
    full = run_states(*args, near_breakaway, T_MAX, MAX_EVENTS, CYCLE_TOL, MAX_PERIOD, False)
    t_cert = float(full[0][0, engine.F_T_CERTIFIED])
    assert full[1][0, engine.I_STATUS] == engine.STATUS_CYCLE
    startup = run_states(*args, np.array([[-slider.gamma * slider.lam, 1.0]]), T_MAX, MAX_EVENTS,
                         CYCLE_TOL, MAX_PERIOD, False)
    assert startup[0][0, engine.F_T_CERTIFIED] > t_cert + 1.0  # the start-up run certifies later
    for t_max in (t_cert * (1 + 1e-9), t_cert * (1 - 1e-9)):
        joined = run_states(*args, near_breakaway, t_max, MAX_EVENTS, CYCLE_TOL, MAX_PERIOD, True)
        direct = run_states(*args, near_breakaway, t_max, MAX_EVENTS, CYCLE_TOL, MAX_PERIOD, False)
        assert joined[1][0, engine.I_STATUS] == direct[1][0, engine.I_STATUS]


def test_no_shortcut_with_a_foundation() -> None:
    # two degrees of freedom: a stick state does not fix the foundation's state, so every
    # state runs to its own verdict, bit for bit as without the shortcut
    structure = elastic_foundation(0.1, Foundation(0.05, 1.0, 0.1))
    slider = Slider(3.0)
    states = sample_box(structure, slider, 60, {"xi": (-3.0, 3.0), "v": (-2.0, 1.5)}, seed=5)
    (f_join, i_join), (f_full, i_full) = _both(structure, slider, states)
    np.testing.assert_array_equal(i_join, i_full)
    np.testing.assert_array_equal(f_join, f_full)


@pytest.mark.parametrize("friction", [None, StribeckFriction(0.2, tolerance=1e-4)])
def test_lean_n_dof_runs_give_the_labels_and_times_of_full_runs(friction) -> None:  # type: ignore[no-untyped-def]
    # N DOF basin runs are lean (engine.run_prepared: no extremes, the quick event search,
    # "the same roots to rounding"): against full runs of the same states, the same statuses,
    # steps and stick phases, and end and certificate times to rounding
    structure = elastic_foundation(0.05, Foundation(1.0, 1.0, 0.1))
    slider = (Slider(3.0) if friction is None
              else Slider(0.05 * 0.2 * float(np.exp(5.0)), friction=friction))
    states = sample_box(structure, slider, 40, {"xi": (-0.7, 0.7), "v": (-0.7, 1.3),
                                                "xi_a": (-0.2, 0.2), "v_a": (-0.2, 0.2)}, seed=2)
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    prepared = engine.prepared_tables(structure.mass, structure.damping, structure.stiffness,
                                      float(slider.lam), float(slider.gamma), edges, intercepts,
                                      slopes)
    statuses = set()
    for state in states:
        runs = [engine.run_prepared(structure.mass, float(slider.lam), float(slider.gamma), edges,
                                    prepared, np.ascontiguousarray(state), T_MAX, MAX_EVENTS,
                                    CYCLE_TOL, MAX_PERIOD, False, False, False, lean)
                for lean in (True, False)]
        (f_lean, i_lean), (f_full, i_full) = (run[4:6] for run in runs)
        np.testing.assert_array_equal(i_lean, i_full)
        statuses.add(int(i_full[engine.I_STATUS]))
        for k in (engine.F_T_END, engine.F_T_CERTIFIED, engine.F_PERIOD):
            assert f_lean[k] == pytest.approx(f_full[k], rel=1e-9, abs=1e-12, nan_ok=True)
        assert np.isnan(f_lean[engine.F_MAX_VELOCITY])  # not tracked
    # both verdicts are among the states (the case is bistable)
    assert {engine.STATUS_STEADY, engine.STATUS_CYCLE} <= statuses
