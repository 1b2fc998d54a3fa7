"""The slip trap region (issue 21, point 2): early certificates of steady sliding, 1 DOF.

``stickslip.kernel.certificate`` builds, once per system, a positively invariant region of
the slip plane bounded by one turn of a decaying motion (argument in its docstring); a state
inside it is certified steady sliding at once. References here:

* the engine without the region (``prepare_bands``, the certificates before this work) run to
  ten times the default horizon: a certified state must end in steady sliding there too, with
  no stick phase;
* the independent solve_ivp oracle of tests/friction_oracle.py (the exact Stribeck law, not
  the band table) for a few states just inside the region's boundary;
* the Coulomb law and two degrees of freedom build no region: ``prepare_certified`` is then
  ``prepare_bands`` bit for bit.

The bistable case is issue 21's: zeta = 0.05, exponential Stribeck law (n = 1) with
``v_s/V = 0.2`` and ``lambda = 0.05 * 0.2 * e^5``, so that the law's slope at the belt speed,
``F'(1) = -lambda exp(-1/u_s) / u_s``, is ``-zeta`` (half the net damping ``2 zeta``).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from stickslip import Foundation, InitialState, Slider, elastic_foundation, rigid_base
from stickslip.analysis.simulation import EngineOptions
from stickslip.kernel import engine
from stickslip.kernel.batch import run_states
from stickslip.kernel.certificate import prepare_certified
from stickslip.kernel.system import (
    TRAP_ENERGY_RADIUS,
    TRAP_RHO0,
    TRAP_SQRT_K,
    TRAP_SQRT_M,
    TRAP_V_BOUND,
    prepare_bands,
    secant_range,
    trap_certifies,
)
from stickslip.model.friction import CoulombFriction, StribeckFriction, TableFriction
from tests.friction_oracle import friction_oracle_simulate

ZETA = 0.05
U_S = 0.2
LAM = ZETA * U_S * float(np.exp(1.0 / U_S))
OPTS = EngineOptions()
STICK = 2


def _tables(slider: Slider) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return slider.friction.bands(slider.lam, slider.gamma)


def _prepared(structure, slider, certified: bool):  # type: ignore[no-untyped-def]
    edges, intercepts, slopes = _tables(slider)
    prep = prepare_certified if certified else prepare_bands
    return prep(structure.mass, structure.damping, structure.stiffness, slider.lam, slider.gamma,
                edges, intercepts, slopes)


def _run_states(structure, slider, states, early: bool, t_max: float = OPTS.t_max):  # type: ignore[no-untyped-def]
    edges, intercepts, slopes = _tables(slider)
    return run_states(structure.mass, structure.damping, structure.stiffness, slider.lam,
                      slider.gamma, edges, intercepts, slopes, states, t_max, OPTS.max_events,
                      OPTS.cycle_tol, OPTS.max_period, True, early)


def _long_direct_run(structure, slider, z0):  # type: ignore[no-untyped-def]
    """The engine without the region, from ``z0``, to ten times the default horizon."""
    edges, intercepts, slopes = _tables(slider)
    return engine.run(structure.mass, structure.damping, structure.stiffness, slider.lam,
                      slider.gamma, edges, intercepts, slopes, np.asarray(z0, dtype=np.float64),
                      10.0 * OPTS.t_max, 100 * OPTS.max_events, OPTS.cycle_tol, OPTS.max_period,
                      False, False)


def _weak_case() -> tuple:  # type: ignore[type-arg]
    return rigid_base(ZETA), Slider(LAM, friction=StribeckFriction(U_S, tolerance=1e-4))


def _inside_points(prepared, fractions, angles) -> np.ndarray:  # type: ignore[no-untyped-def]
    """States at ``fraction`` of the stored region radius at clockwise angles ``angles``."""
    radius, data, z_eq = prepared[21], prepared[22], prepared[15]
    nbin = radius.shape[0]
    out = []
    for f, phi in zip(fractions, angles, strict=True):
        r = f * radius[min(int(phi / (2 * np.pi) * nbin), nbin - 1)]
        x, y = r * np.cos(phi), -r * np.sin(phi)
        out.append([z_eq[0] + x / data[TRAP_SQRT_K], y / data[TRAP_SQRT_M]])
    return np.array(out)


def test_the_region_reaches_beyond_the_energy_disk() -> None:
    structure, slider = _weak_case()
    slope_at_one = slider.friction.slope_at(1.0, slider.lam, slider.gamma)
    assert slope_at_one == pytest.approx(-ZETA, rel=1e-12)  # the case, by construction
    prepared = _prepared(structure, slider, True)
    radius, data = prepared[21], prepared[22]
    assert radius.shape[0] > 0
    # the energy disk certifies |xi'| below its band margin only; the region is much larger
    assert data[TRAP_RHO0] > 1.5 * data[TRAP_ENERGY_RADIUS]
    assert radius.min() > data[TRAP_ENERGY_RADIUS]
    assert 0.0 < data[TRAP_V_BOUND] < 1.0  # never reaches the belt speed
    # every stored state of the region is certified, one just outside a bin's bound is not
    z_eq = prepared[15]
    inside = _inside_points(prepared, [0.999] * 8, np.linspace(0.1, 6.2, 8))
    for z in inside:
        assert trap_certifies(np.array([z[0], z[1], 1.0]), z_eq, radius, data)
    outside = _inside_points(prepared, [1.001] * 8, np.linspace(0.1, 6.2, 8))
    for z in outside:
        assert not trap_certifies(np.array([z[0], z[1], 1.0]), z_eq, radius, data)


def test_one_band_and_two_dof_build_no_region() -> None:
    # Coulomb: one band, the energy disk is the whole certificate; 2 DOF: not planar
    cases = [
        (rigid_base(0.1), Slider(2.5, friction=CoulombFriction())),
        (elastic_foundation(ZETA, Foundation(1.0, 1.0, 0.1)),
         Slider(LAM, friction=StribeckFriction(U_S, tolerance=1e-4))),
    ]
    for structure, slider in cases:
        old = _prepared(structure, slider, False)
        new = _prepared(structure, slider, True)
        assert new[21].shape == (0,)
        assert len(old) == len(new)
        for a, b in zip(old, new, strict=True):
            np.testing.assert_array_equal(a, b)


@pytest.fixture(scope="module")
def weak_runs() -> dict[str, np.ndarray]:
    structure, slider = _weak_case()
    rng = np.random.default_rng(7)
    z_eq = _prepared(structure, slider, False)[15]
    states = np.column_stack([z_eq[0] + rng.uniform(-0.7, 0.7, 200), rng.uniform(-0.7, 1.3, 200)])
    f_new, i_new = _run_states(structure, slider, states, True)
    f_old, i_old = _run_states(structure, slider, states, False)
    return {"states": states, "f_new": f_new, "i_new": i_new, "f_old": f_old, "i_old": i_old}


def test_verdicts_are_unchanged_and_certified_earlier(weak_runs: dict[str, np.ndarray]) -> None:
    s_new = weak_runs["i_new"][:, engine.I_STATUS]
    s_old = weak_runs["i_old"][:, engine.I_STATUS]
    steady = s_new == engine.STATUS_STEADY
    # both sides of the bistability are present (about a third slides)
    assert 0.15 < steady.mean() < 0.6
    np.testing.assert_array_equal(s_new, s_old)
    t_new = weak_runs["f_new"][steady, engine.F_T_CERTIFIED]
    t_old = weak_runs["f_old"][steady, engine.F_T_CERTIFIED]
    assert np.all(t_new <= t_old)
    # measured: most sliding states start inside the region (t = 0); the old median is
    # tens of periods
    assert np.median(t_new) < 0.1 * np.median(t_old)
    # the stick-slip states: the same cycle; either untouched (same certificate time) or
    # certified at once by the slip escape region (tests/test_escape_certificate.py)
    f_new, f_old = weak_runs["f_new"][~steady], weak_runs["f_old"][~steady]
    escaped = f_new[:, engine.F_T_END] == 0.0
    assert escaped.mean() > 0.5  # measured: all but the thin ring about the unstable cycle
    np.testing.assert_array_equal(f_new[~escaped, engine.F_T_CERTIFIED],
                                  f_old[~escaped, engine.F_T_CERTIFIED])
    np.testing.assert_array_equal(f_new[escaped, engine.F_T_CERTIFIED], 0.0)
    for column in (engine.F_PERIOD, engine.F_AMPLITUDE, engine.F_STICK_RATIO):
        np.testing.assert_allclose(f_new[:, column], f_old[:, column], rtol=1e-9)


def test_certified_states_slide_for_ever_in_long_direct_runs(weak_runs: dict[str, np.ndarray]) -> None:
    structure, slider = _weak_case()
    steady = weak_runs["i_new"][:, engine.I_STATUS] == engine.STATUS_STEADY
    early = steady & (weak_runs["f_new"][:, engine.F_T_CERTIFIED]
                      < weak_runs["f_old"][:, engine.F_T_CERTIFIED])
    assert early.sum() >= 20
    for z in weak_runs["states"][early][:30]:
        _, _, _, _, _, isum, _ = _long_direct_run(structure, slider, z)
        assert isum[engine.I_STATUS] == engine.STATUS_STEADY
        assert isum[engine.I_N_STICK] == 0


@pytest.mark.slow  # 11 s: out of the default run (kept under ten minutes)
def test_the_oracle_never_sticks_from_the_region_boundary() -> None:
    # independent check with the exact law: states at 98 % of the region's radius
    structure, slider = _weak_case()
    prepared = _prepared(structure, slider, True)
    for z in _inside_points(prepared, [0.98] * 3, [0.3, 2.4, 4.5]):
        result = friction_oracle_simulate(structure, slider, 150.0, InitialState(z[:1], z[1:]),
                                          max_step=0.05, rtol=1e-10, atol=1e-10)
        assert result.initial_mode != STICK
        assert not np.any(np.asarray(result.event_modes) == STICK)
        # and it has decayed well inside: the final velocity is small
        y_end = result.pieces[-1].sol(result.t_end)
        assert abs(y_end[1]) < 0.2


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(zeta=st.floats(0.03, 0.12), u_s=st.floats(0.15, 0.4), weakening=st.floats(0.2, 0.8),
       data=st.data())
def test_any_region_state_slides_in_a_long_direct_run(zeta: float, u_s: float, weakening: float,
                                                      data: st.DataObject) -> None:
    # the law's slope at u = 1 removes the fraction `weakening` of the net damping 2 zeta
    lam = weakening * 2.0 * zeta * u_s * float(np.exp(1.0 / u_s))
    structure = rigid_base(zeta)
    slider = Slider(lam, friction=StribeckFriction(u_s, tolerance=1e-4))
    prepared = _prepared(structure, slider, True)
    if prepared[21].shape[0] == 0:
        return  # no region for this law: nothing certified early
    fractions = data.draw(st.lists(st.floats(0.0, 0.995), min_size=3, max_size=3))
    angles = data.draw(st.lists(st.floats(0.0, 6.283), min_size=3, max_size=3))
    for z in _inside_points(prepared, fractions, angles):
        _, _, _, _, fsum, isum, _ = _long_direct_run(structure, slider, z)
        assert isum[engine.I_STATUS] == engine.STATUS_STEADY
        assert isum[engine.I_N_STICK] == 0
        assert fsum[engine.F_MAX_VELOCITY] <= prepared[22][TRAP_V_BOUND]


@pytest.mark.parametrize("u_lo, u_hi", [(0.0, 2.0), (0.3, 0.9), (1.0, 1.7), (0.05, 1.0)])
def test_secant_range_brackets_every_secant(u_lo: float, u_hi: float) -> None:
    # reference: the secant (F(u) - F(1)) / (u - 1) of the band table sampled densely
    from stickslip.model.friction import evaluate_bands

    for law, lam in [(StribeckFriction(U_S, tolerance=1e-4), LAM),
                     (TableFriction((0.2, 0.7, 1.0, 1.5), (0.9, 0.4, 0.2, 0.5)), 0.8)]:
        table = law.bands(lam, 2.0)
        u = np.linspace(u_lo, u_hi, 20001)
        u = u[np.abs(u - 1.0) > 1e-6]
        sec = (evaluate_bands(table, u) - evaluate_bands(table, 1.0)) / (u - 1.0)
        lo, hi = secant_range(*table, u_lo, u_hi)
        tol = 1e-9 * max(1.0, abs(lo), abs(hi))
        assert lo <= sec.min() + tol and sec.max() <= hi + tol
        # and the range is tight: attained up to the sampling (or at the limit u -> 1)
        assert sec.min() - lo < 1e-3 * max(1.0, abs(lo)) + 1e-3
        assert hi - sec.max() < 1e-3 * max(1.0, abs(hi)) + 1e-3
