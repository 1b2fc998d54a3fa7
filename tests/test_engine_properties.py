"""Properties of the engine on random inputs (hypothesis).

* events strictly increase in time;
* in every phase the trajectory obeys that phase's definition (Eqs. 19-27), checked on a
  dense sample of the exact trajectory: xi' < 1 in slip-I, xi' > 1 in slip-II, xi' = 1 and
  the stick force within [-lambda (1 + 2 gamma), lambda] in stick (Eq. 20). A missed
  event (a graze) would show up as a slip-I sample above the belt speed;
* the run ends, with a reported status, on every input the model accepts.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from stickslip import (
    EngineOptions,
    Foundation,
    Mode,
    RunStatus,
    Slider,
    Verdict,
    chain_structure,
    rigid_base,
    simulate,
)

foundations = st.builds(
    Foundation,
    mass_ratio=st.floats(0.05, 10.0),
    stiffness_ratio=st.floats(0.1, 8.0),
    damping_ratio=st.floats(0.0, 2.0),
)


@st.composite
def systems(draw):  # type: ignore[no-untyped-def]
    zeta = draw(st.floats(0.0, 0.8))
    stages = draw(st.lists(foundations, min_size=0, max_size=2))
    slider = Slider(draw(st.floats(0.01, 40.0)), gamma=draw(st.floats(0.0, 5.0)))
    return chain_structure(zeta, stages), slider


def _stick_force(structure, q, v):  # type: ignore[no-untyped-def]
    # Eq. (20) generalised: S = (C q' + K q)_0 for a lumped (diagonal) mass matrix
    return v @ structure.damping[0] + q @ structure.stiffness[0]


@given(systems())
def test_phases_obey_their_definitions(system) -> None:  # type: ignore[no-untyped-def]
    structure, slider = system
    result = simulate(structure, slider, options=EngineOptions(t_max=150.0, max_events=400))
    assert np.all(np.diff(result.segment_times) > 0.0)
    assert isinstance(result.status, RunStatus)
    t = np.linspace(0.0, result.t_end, 2500)
    q, v, modes = result.state_at(t)
    scale = 1e-9 * max(1.0, float(np.abs(q).max()), float(np.abs(v).max()))
    slip1 = modes == Mode.SLIP_I
    slip2 = modes == Mode.SLIP_II
    stick = modes == Mode.STICK
    assert np.all(v[slip1, 0] <= 1.0 + scale)
    assert np.all(v[slip2, 0] >= 1.0 - scale)
    assert np.all(v[stick, 0] == 1.0)
    force = _stick_force(structure, q[stick], v[stick])
    lam, gamma = slider.lam, slider.gamma
    assert np.all(force <= lam + scale * max(1.0, lam))
    assert np.all(force >= -lam * (1 + 2 * gamma) - scale * max(1.0, lam))


@given(systems())
def test_verdict_matches_status(system) -> None:  # type: ignore[no-untyped-def]
    structure, slider = system
    result = simulate(structure, slider, options=EngineOptions(t_max=300.0, max_events=1000), record=False)
    expected = {
        RunStatus.CERTIFIED_STEADY: Verdict.STEADY_SLIDING,
        RunStatus.CERTIFIED_CYCLE: Verdict.STICK_SLIP,
        RunStatus.T_MAX: Verdict.UNDETERMINED,
        RunStatus.MAX_EVENTS: Verdict.UNDETERMINED,
        # the step budget runs out before t_max when ||A||_inf is large against the horizon
        # (hypothesis found mass 0.05 next to stiffness 52: h = 0.5 / ||A||_inf = 2.9e-4)
        RunStatus.MAX_STEPS: Verdict.UNDETERMINED,
        # a repeat that no divisor proves (hypothesis found an undamped third DOF, lambda 8,
        # gamma 0: a multiplier on the unit circle, so no ball contracts)
        RunStatus.UNPROVEN_CYCLE: Verdict.UNDETERMINED,
        # a 1-DOF cycle whose stick phases all last no time (hypothesis found zeta 0, gamma 0:
        # touches of the belt speed): a slip oscillation
        RunStatus.CERTIFIED_OSCILLATION: Verdict.SLIP_OSCILLATION,
    }
    assert result.verdict is expected[result.status]
    assert result.t_end <= 300.0
    if result.verdict is Verdict.STICK_SLIP:
        assert result.period > 0.0 and result.amplitude > 0.0
        assert 0.0 < result.stick_ratio < 1.0
    if result.verdict is Verdict.STEADY_SLIDING:
        assert result.lyapunov_bound < 1.0


def test_max_events_is_a_reported_status() -> None:
    # a 2DOF stick-slip case needs 5 switches before its breakaway state repeats
    structure = chain_structure(0.1, (Foundation(2.8, 1.09, 1.5),))
    result = simulate(structure, Slider(15.0), options=EngineOptions(max_events=3))
    assert result.status is RunStatus.MAX_EVENTS
    assert result.verdict is Verdict.UNDETERMINED
    assert "increase max_events" in result.status.message


def test_t_max_is_a_reported_status() -> None:
    structure = chain_structure(0.05, ())
    result = simulate(structure, Slider(3.0), options=EngineOptions(t_max=2.0))
    assert result.status is RunStatus.T_MAX
    assert result.t_end == 2.0
    assert result.certificate == ""


def test_touching_the_belt_speed_without_sticking_is_a_slip_oscillation() -> None:
    # hypothesis's example: undamped, no kinetic friction (gamma = 0). After the start-up stick
    # phase the slider only touches the belt speed (stick phases of zero duration) and crosses
    # it between slip-I and slip-II: periodic, but with no stick phase, so not stick-slip
    result = simulate(rigid_base(0.0), Slider(0.9466785280815826, gamma=0.0),
                      options=EngineOptions(t_max=300.0, max_events=1000))
    assert result.verdict is Verdict.SLIP_OSCILLATION
    times, modes = result.segment_times, result.segment_modes
    ends = np.append(times[1:], result.t_end)
    later_stick = (modes == Mode.STICK) & (times > 0.0)
    assert np.all(ends[later_stick] == times[later_stick])  # no stick phase after start-up
    assert np.any(modes == Mode.SLIP_II)

