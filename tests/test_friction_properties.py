"""Properties of the engine with random friction laws (hypothesis).

* events strictly increase in time and every run ends with a reported status;
* in every slip phase the sliding speed ``u = |1 - xi'|`` stays inside the phase's friction
  band (a missed band-edge event would show up here), and the friction magnitude there,
  ``F = a_b + s_b u``, is the law's (exactly for linear and table laws, within the stated
  tolerance for Stribeck), never negative and at most the static level at ``u = 0+``;
* in stick ``xi' = 1`` and the stick force stays within Eq. (20);
* the verdict matches the status.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from stickslip import (
    EngineOptions,
    Foundation,
    Mode,
    RunStatus,
    Slider,
    Verdict,
    chain_structure,
    simulate,
)
from stickslip.kernel.system import mode_kind_band
from stickslip.model.friction import LinearFriction, StribeckFriction, TableFriction

foundations = st.builds(
    Foundation,
    mass_ratio=st.floats(0.1, 5.0),
    stiffness_ratio=st.floats(0.2, 4.0),
    damping_ratio=st.floats(0.0, 1.5),
)

linear_laws = st.builds(LinearFriction, st.floats(-0.5, 0.5))
stribeck_laws = st.builds(
    StribeckFriction,
    velocity_ratio=st.floats(0.05, 2.0),
    exponent=st.floats(0.5, 4.0),
    viscous=st.floats(-0.1, 0.5),
    mu0_ratio=st.floats(-0.5, 1.0),
    tolerance=st.sampled_from([1e-3, 1e-4]),
)


@st.composite
def table_laws(draw):  # type: ignore[no-untyped-def]
    n = draw(st.integers(1, 6))
    steps = draw(st.lists(st.floats(0.05, 1.0), min_size=n, max_size=n))
    u = np.cumsum(steps) - steps[0] * draw(st.sampled_from([0.0, 1.0]))
    f = draw(st.lists(st.floats(-1.0, 1.0), min_size=n, max_size=n))
    return TableFriction(tuple(float(x) for x in u), tuple(f))


@st.composite
def systems(draw):  # type: ignore[no-untyped-def]
    zeta = draw(st.floats(0.0, 0.6))
    stages = draw(st.lists(foundations, min_size=0, max_size=1))
    law = draw(st.one_of(linear_laws, stribeck_laws, table_laws()))
    gamma = draw(st.floats(1.0, 4.0))
    return chain_structure(zeta, stages), Slider(draw(st.floats(0.05, 20.0)), gamma=gamma, friction=law)


@settings(max_examples=60, deadline=None)
@given(systems())
def test_phases_stay_in_their_bands_and_friction_in_its_bounds(system) -> None:  # type: ignore[no-untyped-def]
    structure, slider = system
    result = simulate(structure, slider, options=EngineOptions(t_max=100.0, max_events=3000))
    assert isinstance(result.status, RunStatus)
    assert np.all(np.diff(result.segment_times) > 0.0)
    lam, gamma = slider.lam, slider.gamma
    edges, intercepts, slopes = result.friction_bands
    tol = getattr(slider.friction, "tolerance", 0.0) * lam
    bounds = np.append(result.segment_times, result.t_end)
    for i, code in enumerate(result.segment_modes):
        t0, t1 = bounds[i], bounds[i + 1]
        if t1 <= t0:
            continue
        t = np.linspace(t0, t1, 12)[1:-1]
        if t.size == 0:
            continue
        q, v, modes = result.state_at(t)
        scale = 1e-9 * max(1.0, float(np.abs(q).max()), float(np.abs(v).max()))
        kind, band = mode_kind_band(int(code))
        assert np.all(modes == kind)
        if kind == Mode.STICK:
            assert np.all(v[:, 0] == 1.0)
            s = v @ structure.damping[0] + q @ structure.stiffness[0]
            assert np.all(s <= lam + scale * max(1.0, lam))
            assert np.all(s >= -lam * (1 + 2 * gamma) - scale * max(1.0, lam))
            continue
        u = (1.0 - v[:, 0]) if kind == Mode.SLIP_I else (v[:, 0] - 1.0)
        assert np.all(u >= edges[band] - scale)
        assert np.all(u <= edges[band + 1] + scale)
        force = intercepts[band] + slopes[band] * u
        exact = slider.friction.value(np.maximum(u, 0.0), lam, gamma)
        assert np.all(force >= -scale * max(1.0, lam))
        assert np.all(np.abs(force - exact) <= tol * 1.01 + 1e-9 * max(1.0, lam))
    assert float(intercepts[0]) <= (1.0 + gamma) * lam * (1 + 1e-12) + tol


@settings(max_examples=60, deadline=None)
@given(systems())
def test_verdict_matches_status(system) -> None:  # type: ignore[no-untyped-def]
    structure, slider = system
    result = simulate(structure, slider, options=EngineOptions(t_max=200.0, max_events=5000), record=False)
    expected = {
        RunStatus.CERTIFIED_STEADY: Verdict.STEADY_SLIDING,
        RunStatus.CERTIFIED_CYCLE: Verdict.STICK_SLIP,
        RunStatus.CERTIFIED_OSCILLATION: Verdict.SLIP_OSCILLATION,
        RunStatus.T_MAX: Verdict.UNDETERMINED,
        RunStatus.MAX_EVENTS: Verdict.UNDETERMINED,
        RunStatus.MAX_STEPS: Verdict.UNDETERMINED,
    }
    assert result.verdict is expected[result.status]
    assert result.t_end <= 200.0
    if result.verdict is Verdict.STICK_SLIP:
        assert result.period > 0.0 and 0.0 < result.stick_ratio < 1.0
    if result.verdict is Verdict.SLIP_OSCILLATION:
        assert result.period > 0.0 and result.stick_ratio == 0.0
