"""The slip escape region (issue 21, points 2-3): states that provably reach the belt speed and stick.

``stickslip.kernel.outer_certificate`` builds, once per 1-DOF system, a region outside the
unstable slip cycle from which every motion reaches the belt speed within a bounded time and
sticks (argument in its docstring); ``run_states`` gives such a state the start-up run's
verdict without running it. References here, none of them the region itself:

* the engine without any early certificate (``engine.run``: ``prepare_bands``, no shortcut),
  run to ten times the default horizon: a certified state must stick-slip there, on the
  start-up run's cycle;
* the same engine stopped at the first stick phase: it must come within the region's time
  bound, at a position inside the static range the region promises;
* the independent solve_ivp oracle of tests/friction_oracle.py (the exact Stribeck law, not
  the band table) for states just outside the region's inner boundary and far out;
* dense sampling of the band table for the global secant range and the power bound;
* for states above the belt speed (decelerated to it and stuck, ``slip_ii_stick_time``): the
  direct run to its first stick phase, which must come by the time bound and in the range;
* systems where a check fails (no unstable cycle, slopes that stop the rotation, Coulomb,
  two degrees of freedom) build no region, and then every summary is the one without it.

The bistable case is issue 21's (as in tests/test_early_certificate.py): zeta = 0.05,
exponential Stribeck law (n = 1), ``v_s/V = 0.2``, ``lambda = 0.05 * 0.2 * e^5``.
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import Foundation, InitialState, Slider, elastic_foundation, rigid_base
from stickslip.analysis.simulation import EngineOptions
from stickslip.kernel import engine
from stickslip.kernel.batch import prepare_states, run_states
from stickslip.kernel.outer_certificate import (
    ESCAPE_R_MIN,
    ESCAPE_RHO0,
    ESCAPE_TIME,
    ESCAPE_TURNS,
    ESCAPE_XI_LO,
    escape_certifies,
    friction_floor,
    global_secant_range,
    power_bound,
    slip_ii_stick_time,
)
from stickslip.kernel.system import TRAP_RHO0
from stickslip.model.friction import CoulombFriction, StribeckFriction, TableFriction, evaluate_bands
from tests.friction_oracle import friction_oracle_simulate

ZETA = 0.05
U_S = 0.2
LAM = ZETA * U_S * float(np.exp(1.0 / U_S))
OPTS = EngineOptions()
STICK = 2


def _weak_case() -> tuple:  # type: ignore[type-arg]
    return rigid_base(ZETA), Slider(LAM, friction=StribeckFriction(U_S, tolerance=1e-4))


def _kernel(structure, slider, early: bool = True):  # type: ignore[no-untyped-def]
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    return prepare_states(structure.mass, structure.damping, structure.stiffness, slider.lam,
                          slider.gamma, edges, intercepts, slopes, early)


def _run_states(structure, slider, states, early: bool, t_max: float = OPTS.t_max):  # type: ignore[no-untyped-def]
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    return run_states(structure.mass, structure.damping, structure.stiffness, slider.lam,
                      slider.gamma, edges, intercepts, slopes, np.ascontiguousarray(states), t_max,
                      OPTS.max_events, OPTS.cycle_tol, OPTS.max_period, True, early)


def _certified(kernel, states) -> np.ndarray:  # type: ignore[no-untyped-def]
    prepared, r_in, r_hi, data = kernel
    return np.array([escape_certifies(np.array([z[0], z[1], 1.0]), prepared[15], r_in, r_hi, data)
                     for z in states])


def _direct(structure, slider, z0, t_max, stop_at_stick):  # type: ignore[no-untyped-def]
    """The engine without early certificates (prepare_bands) from ``z0``."""
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    if not stop_at_stick:
        return engine.run(structure.mass, structure.damping, structure.stiffness, slider.lam,
                          slider.gamma, edges, intercepts, slopes, np.asarray(z0, dtype=np.float64),
                          t_max, 100 * OPTS.max_events, OPTS.cycle_tol, OPTS.max_period, False, False)
    from stickslip.kernel.system import prepare_bands

    prepared = prepare_bands(structure.mass, structure.damping, structure.stiffness, slider.lam,
                             slider.gamma, edges, intercepts, slopes)
    return engine.run_prepared(structure.mass, slider.lam, slider.gamma, edges, prepared,
                               np.asarray(z0, dtype=np.float64), t_max, 100 * OPTS.max_events,
                               OPTS.cycle_tol, OPTS.max_period, False, False, True, False)


def _ring_points(kernel, factor: float, angles) -> np.ndarray:  # type: ignore[no-untyped-def]
    """States at ``factor`` times the stored inner radius at clockwise angles ``angles``."""
    prepared, r_in = kernel[0], kernel[1]
    z_eq = prepared[15]
    out = []
    for phi in angles:
        r = factor * r_in[min(int(phi / (2 * np.pi) * r_in.size), r_in.size - 1)]
        out.append([z_eq[0] + r * np.cos(phi), -r * np.sin(phi)])
    return np.array(out)


@pytest.fixture(scope="module")
def weak() -> dict:  # type: ignore[type-arg]
    structure, slider = _weak_case()
    kernel = _kernel(structure, slider)
    rng = np.random.default_rng(11)
    z_eq = kernel[0][15]
    states = np.column_stack([z_eq[0] + rng.uniform(-0.7, 0.7, 300), rng.uniform(-0.7, 1.3, 300)])
    on = _run_states(structure, slider, states, True)
    off = _run_states(structure, slider, states, False)
    return {"structure": structure, "slider": slider, "kernel": kernel, "states": states,
            "on": on, "off": off, "escaped": _certified(kernel, states)}


def test_the_region_lies_outside_the_unstable_cycle_and_holds_most_stick_slip_states(weak: dict) -> None:  # type: ignore[type-arg]
    prepared, r_in, r_hi, data = weak["kernel"]
    assert r_in.size > 0
    # the bounding trajectory starts beyond the trap region's (which lies inside the cycle)
    assert data[ESCAPE_RHO0] > prepared[22][TRAP_RHO0]
    assert data[ESCAPE_TURNS] >= 1 and np.all(r_hi > r_in)
    escaped = weak["escaped"]
    # measured: more than half of this box; none of them at or above the belt speed
    assert 0.4 < escaped.mean() < 0.8
    assert np.all(weak["states"][escaped, 1] < 1.0)
    # a state just inside the inner boundary is not certified, one just outside is (bins
    # whose inner bound lies below the outer one)
    angles = np.linspace(0.2, 6.0, 12)
    assert not _certified(weak["kernel"], _ring_points(weak["kernel"], 0.999, angles)).any()
    assert _certified(weak["kernel"], _ring_points(weak["kernel"], 1.001, angles)).all()


def test_labels_equal_the_runs_without_early_certificates(weak: dict) -> None:  # type: ignore[type-arg]
    (f_on, i_on), (f_off, i_off) = weak["on"], weak["off"]
    np.testing.assert_array_equal(i_on[:, engine.I_STATUS], i_off[:, engine.I_STATUS])
    escaped = weak["escaped"]
    assert escaped.sum() > 100
    # certified at once, on the start-up run's cycle (the same as the full join's)
    assert np.all(f_on[escaped, engine.F_T_END] == 0.0)
    assert np.all(i_on[escaped, engine.I_STATUS] == engine.STATUS_CYCLE)
    for column in (engine.F_PERIOD, engine.F_AMPLITUDE, engine.F_STICK_RATIO):
        np.testing.assert_array_equal(f_on[escaped, column], f_off[escaped, column])
    # states outside the region: the summaries of the runs without it (trap aside)
    others = ~escaped & (f_on[:, engine.F_T_CERTIFIED] == f_off[:, engine.F_T_CERTIFIED])
    np.testing.assert_array_equal(i_on[others], i_off[others])


def test_certified_states_stick_in_time_and_in_range_and_cycle_in_long_direct_runs(weak: dict) -> None:  # type: ignore[type-arg]
    structure, slider = weak["structure"], weak["slider"]
    data = weak["kernel"][3]
    escaped_states = weak["states"][weak["escaped"]]
    startup_period = weak["off"][0][weak["escaped"], engine.F_PERIOD][0]
    for z in escaped_states:
        # to the first stick phase: within the time bound, in the promised static range
        _, _, _, _, fsum, isum, z_end = _direct(structure, slider, z, 10.0 * OPTS.t_max, True)
        assert isum[engine.I_STATUS] == engine.STATUS_STUCK
        assert fsum[engine.F_T_END] <= data[ESCAPE_TIME]
        assert z_end[1] == 1.0 and z_end[0] >= data[ESCAPE_XI_LO]
        # and the whole motion: a stick-slip cycle, the start-up run's
        _, _, _, _, fsum, isum, _ = _direct(structure, slider, z, 10.0 * OPTS.t_max, False)
        assert isum[engine.I_STATUS] == engine.STATUS_CYCLE
        assert fsum[engine.F_PERIOD] == pytest.approx(startup_period, rel=1e-9)


def test_the_oracle_sticks_from_the_region() -> None:
    # independent check with the exact law: states just outside the inner boundary (the
    # slowest to escape) and one far out
    structure, slider = _weak_case()
    kernel = _kernel(structure, slider)
    states = np.vstack([_ring_points(kernel, 1.002, [0.4, 3.0]),
                        _ring_points(kernel, 2.0, [1.5])])
    assert _certified(kernel, states).all()
    t_bound = kernel[3][ESCAPE_TIME]
    for z in states:
        # to its first switch (max_events=1): the belt speed reached, in time, and a stick
        result = friction_oracle_simulate(structure, slider, t_bound, InitialState(z[:1], z[1:]),
                                          max_step=0.05, rtol=1e-10, atol=1e-10, max_events=1)
        assert result.initial_mode != STICK
        assert list(result.event_modes) == [STICK]
        assert result.event_times[0] <= t_bound


@pytest.mark.parametrize("name, structure, slider", [
    # strong damping, weak weakening: every start decays, there is no unstable cycle
    # (C = 0.6 above the steepest weakening secant, lambda (1 - e^-5) = 0.497: k(v) > 0)
    ("monostable", rigid_base(0.3), Slider(0.5, friction=StribeckFriction(U_S, tolerance=1e-4))),
    # a weakening secant steeper than 2 sqrt(K M) - C: the motions may stop turning
    ("no rotation", rigid_base(ZETA), Slider(3.0, friction=StribeckFriction(U_S, tolerance=1e-4))),
    # one band (Coulomb) and two degrees of freedom: no region by construction
    ("coulomb", rigid_base(0.1), Slider(2.5, friction=CoulombFriction())),
    ("foundation", elastic_foundation(ZETA, Foundation(1.0, 1.0, 0.1)),
     Slider(LAM, friction=StribeckFriction(U_S, tolerance=1e-4))),
])
def test_the_region_is_refused_when_a_check_fails(name, structure, slider) -> None:  # type: ignore[no-untyped-def]
    prepared, r_in, r_hi, data = _kernel(structure, slider)
    assert r_in.size == 0 and r_hi.size == 0 and data[ESCAPE_R_MIN] == 0.0
    if structure.n_dof == 1:
        z_eq = prepared[15]
        rng = np.random.default_rng(5)
        states = np.column_stack([z_eq[0] + rng.uniform(-1.0, 1.0, 40), rng.uniform(-1.0, 0.99, 40)])
        assert not _certified((prepared, r_in, r_hi, data), states).any()
        (f_on, i_on), (f_off, i_off) = (_run_states(structure, slider, states, early)
                                        for early in (True, False))
        np.testing.assert_array_equal(i_on[:, engine.I_STATUS], i_off[:, engine.I_STATUS])
        sticks = i_on[:, engine.I_STATUS] == engine.STATUS_CYCLE
        np.testing.assert_array_equal(f_on[sticks], f_off[sticks])  # nothing certified early


def test_the_region_is_not_used_beyond_the_horizon(weak: dict) -> None:  # type: ignore[type-arg]
    # a horizon shorter than the region's time bound: a direct run might not certify its
    # cycle in time, so the region must not be used, and the runs are those without it
    structure, slider = weak["structure"], weak["slider"]
    t_max = 0.5 * weak["kernel"][3][ESCAPE_TIME]
    states = weak["states"][weak["escaped"]][:40]
    (f_on, i_on), (f_off, i_off) = (_run_states(structure, slider, states, early, t_max)
                                    for early in (True, False))
    np.testing.assert_array_equal(i_on, i_off)
    np.testing.assert_array_equal(f_on[:, engine.F_T_END], f_off[:, engine.F_T_END])
    assert np.all(f_on[:, engine.F_T_END] > 0.0)


@pytest.mark.parametrize("law, lam", [(StribeckFriction(U_S, tolerance=1e-4), LAM),
                                      (StribeckFriction(0.4, viscous=0.05, tolerance=1e-3), 1.0),
                                      (TableFriction((0.2, 0.7, 1.0, 1.5), (0.9, 0.4, 0.2, 0.5)), 0.8)])
def test_global_secant_range_and_power_bound_bracket_the_law(law, lam) -> None:  # type: ignore[no-untyped-def]
    # reference: the band table sampled densely over u in [0, 50] (beyond the last edge)
    table = law.bands(lam, 2.0)
    edges, intercepts, slopes = table
    u = np.linspace(0.0, 50.0, 400_001)
    u = u[np.abs(u - 1.0) > 1e-6]
    f_one = float(evaluate_bands(table, 1.0))
    f_u = evaluate_bands(table, u)
    sec = (f_u - f_one) / (u - 1.0)
    lo, hi = global_secant_range(edges, intercepts, slopes)
    tol = 1e-9 * max(1.0, abs(lo), abs(hi))
    assert lo <= sec.min() + tol and sec.max() <= hi + tol
    damping = 2.0 * ZETA
    v = 1.0 - u
    power = (f_u - f_one) * v - damping * v * v
    bound = power_bound(damping, edges, intercepts, slopes)
    assert power.max() <= bound + 1e-12
    assert bound - power.max() < 1e-3 * max(1.0, bound)  # attained up to the sampling


def test_states_above_the_belt_speed_stick_within_their_time_bound(weak: dict) -> None:  # type: ignore[type-arg]
    # slip_ii_stick_time: a state above the belt speed decelerated at a bounded rate; the
    # direct run (no early certificates) must stick by the bound, between xi_0 and the bound
    structure, slider = weak["structure"], weak["slider"]
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    f_lo = friction_floor(edges, intercepts, slopes)
    # the law's floor: lambda gamma (the Stribeck term decays to 0), up to the table's error
    assert f_lo == pytest.approx(slider.lam * slider.gamma, rel=1e-3)
    rng = np.random.default_rng(3)
    states = np.column_stack([rng.uniform(-0.7, 0.7, 80), rng.uniform(1.0 + 1e-9, 1.3, 80)])
    args = (structure.mass[0, 0], structure.damping[0, 0], structure.stiffness[0, 0], slider.lam,
            slider.gamma, f_lo)
    bounds = np.array([slip_ii_stick_time(np.array([z[0], z[1], 1.0]), *args) for z in states])
    assert np.isfinite(bounds).all()  # this box is far from the static limits
    for z, t_a in zip(states, bounds, strict=True):
        _, _, _, _, fsum, isum, z_end = _direct(structure, slider, z, OPTS.t_max, True)
        assert isum[engine.I_STATUS] == engine.STATUS_STUCK
        assert 0.0 < fsum[engine.F_T_END] <= t_a
        assert z[0] <= z_end[0] <= z[0] + z[1] * t_a
    # labels: the runs with these states certified equal those without
    (_, i_on), (_, i_off) = (_run_states(structure, slider, states, early) for early in (True, False))
    np.testing.assert_array_equal(i_on[:, engine.I_STATUS], i_off[:, engine.I_STATUS])
    # refused where the stick force could pass lambda at the arrival (a state pushed hard
    # forwards from far ahead) or the deceleration is not proven (far behind)
    assert slip_ii_stick_time(np.array([slider.lam, 3.0, 1.0]), *args) == np.inf
    assert slip_ii_stick_time(np.array([-20.0, 1.2, 1.0]), *args) == np.inf
    assert slip_ii_stick_time(np.array([0.0, 0.9, 1.0]), *args) == np.inf  # not above it
