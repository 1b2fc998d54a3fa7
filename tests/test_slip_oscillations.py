"""Slip oscillations found at a point without a Hopf point (issue 30, point 1).

The published bistable case: rigid base, ``lambda = 1/3``, ``zeta = 0.05``, ``gamma = 1``, the
exponential Stribeck law with ``v_s / V = 1/3`` (``n = 1``). Steady sliding is linearly stable
there (its Hopf point, ``lambda_H = 2 zeta u_s e^(1/u_s)``, is about 0.67) and an unstable slip
oscillation separates its basin from that of the stable stick-slip cycle.

Sources of the reference values:

* an independent event-driven ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-12) integration,
  **backwards in time**, of the smooth law written here in shifted coordinates: the unstable
  cycle of a planar system is a stable cycle backwards in time, so the backward run converges
  to it from either side; its period is the time between two velocity zeros of one sign and
  its amplitude half the peak-to-peak of ``xi``;
* two seeds of the search that share nothing (the section scan with backward iteration of the
  engine's map, and the basin code's slip trap and escape regions) must give the same cycle.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from stickslip.analysis.cycles import find_cycles
from stickslip.analysis.slip_oscillations import find_slip_oscillations
from stickslip.model.friction import CoulombFriction, StribeckFriction
from stickslip.model.parameters import Slider
from stickslip.model.structure import rigid_base
from tests.cli_helpers import run_cli

LAM, ZETA, GAMMA, US = 1.0 / 3.0, 0.05, 1.0, 0.3333


def backward_cycle(lam: float, zeta: float = ZETA, us: float = US, start: float = 0.5
                   ) -> tuple[float, float]:
    """Period and amplitude of the cycle reached backwards in time by ``solve_ivp``.

    ``xi'' + 2 zeta xi' + xi = F(1 - xi') - gamma lam`` with ``F(u) = lam (gamma + e^(-u/u_s))``
    (``mu_0 = mu_s``), i.e. ``xi'' + 2 zeta xi' + xi = lam e^(-(1 - xi') / u_s)`` in slip-I.
    """

    def rhs(_t: float, z: np.ndarray) -> list[float]:
        return [z[1], -2.0 * zeta * z[1] - z[0] + lam * math.exp(-(1.0 - z[1]) / us)]

    def turn(_t: float, z: np.ndarray) -> float:
        return float(z[1])

    x_s = lam * math.exp(-1.0 / us)  # steady sliding
    sol = solve_ivp(rhs, (0.0, -1500.0), [x_s + start, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-13, events=turn)
    assert sol.status == 0
    assert float(np.max(sol.y[1])) < 1.0  # never reaches the belt speed: a slip oscillation
    t_ev, x_ev = sol.t_events[0], sol.y_events[0][:, 0]
    top, bottom = x_ev[x_ev > x_s], x_ev[x_ev < x_s]
    assert abs(top[-1] - top[-2]) < 1e-10 and abs(bottom[-1] - bottom[-2]) < 1e-10  # converged
    t_top = t_ev[x_ev > x_s]
    return float(abs(t_top[-1] - t_top[-2])), 0.5 * float(top[-1] - bottom[-1])


def test_the_published_unstable_slip_oscillation_matches_backward_time_solve_ivp() -> None:
    # law interpolated to 1e-6 lambda: the engine's cycle is the smooth law's to about that
    slider = Slider(LAM, gamma=GAMMA, friction=StribeckFriction(US, tolerance=1e-6))
    (osc,) = find_slip_oscillations(rigid_base(ZETA), slider)
    period, amplitude = backward_cycle(LAM)
    assert not osc.stable and osc.multiplier > 1.0
    assert osc.amplitude == pytest.approx(amplitude, abs=1e-6)
    assert osc.period == pytest.approx(period, abs=1e-6)
    assert 0.0 < osc.peak_velocity < 1.0
    # two independent seeds arrive at it: the engine's section scan and the trap certificate
    assert {"section scan", "trap certificate"} <= set(osc.found_by)


def test_both_sides_of_the_backward_run_reach_the_same_cycle() -> None:
    # the oracle itself: from inside and from outside the cycle, one answer
    inside, outside = backward_cycle(LAM, start=0.3), backward_cycle(LAM, start=0.8)
    assert inside == pytest.approx(outside, abs=1e-9)


@pytest.mark.slow  # 15 s: out of the default run (kept under ten minutes)
def test_cycles_lists_the_stick_slip_cycle_and_the_unstable_slip_oscillation(
        capsys: pytest.CaptureFixture[str]) -> None:
    code, text, _ = run_cli(["cycles", "--lam", repr(LAM), "--zeta", "0.05", "--gamma", "1", "--dva", "none",
                             "--friction", "stribeck:vs=0.3333,n=1", "--json"], capsys)
    assert code == 0
    payload = json.loads(text)
    (cycle,) = payload["cycles"]
    assert cycle["stable"] and cycle["stick_ratio"] > 0.0
    (osc,) = payload["slip_oscillations"]
    assert osc["kind"] == "slip-oscillation" and osc["stable"] is False
    assert osc["multipliers"][0]["abs"] > 1.0
    period, amplitude = backward_cycle(LAM)
    # the default law tolerance 1e-4 lambda: the cycle to about that
    assert osc["amplitude"] == pytest.approx(amplitude, rel=1e-4)
    assert osc["period"] == pytest.approx(period, rel=1e-5)
    # the unstable cycle lies between steady sliding and the stick-slip cycle
    assert osc["amplitude"] < cycle["amplitude"]
    code, text, _ = run_cli(["cycles", "--lam", repr(LAM), "--zeta", "0.05", "--gamma", "1",
                             "--friction", "stribeck:vs=0.3333,n=1"], capsys)
    assert code == 0 and "UNSTABLE" in text and "slip osc." in text


def test_no_search_without_velocity_dependence() -> None:
    # Coulomb: slip-I is a damped linear oscillator, no isolated periodic motion without stick
    assert find_slip_oscillations(rigid_base(ZETA), Slider(2.0, friction=CoulombFriction())) == ()
    search = find_cycles(rigid_base(0.1), Slider(2.0), slip_oscillations=True)
    assert search.slip_oscillations == () and search.to_dict()["slip_oscillations"] == []


@pytest.mark.slow
def test_continue_traces_the_unstable_slip_oscillation_over_the_published_range(
        capsys: pytest.CaptureFixture[str]) -> None:
    # no Hopf point in the range: the branch comes from the search at points of the range
    code, text, _ = run_cli(["continue", "--param", "lam", "--range", "0.3:0.3667", "--zeta", "0.05",
                             "--gamma", "1", "--dva", "none", "--friction", "stribeck:vs=0.3333,n=1",
                             "--json"], capsys)
    assert code == 0
    payload = json.loads(text)
    assert not [e for e in payload["events"] if e["type"] == "hopf"]
    kinds = sorted(b["kind"] for b in payload["branches"])
    assert kinds == ["slip-oscillation", "stick-slip"]
    slip = next(b for b in payload["branches"] if b["kind"] == "slip-oscillation")
    lams = [p["lam"] for p in slip["points"]]
    assert min(lams) == pytest.approx(0.3, abs=1e-12) and max(lams) == pytest.approx(0.3667, abs=1e-12)
    assert all(not p["stable"] and p["multiplier"] > 1.0 for p in slip["points"])
    for lam in (0.3, 0.3667):
        point = next(p for p in slip["points"] if abs(p["lam"] - lam) < 1e-12)
        period, amplitude = backward_cycle(lam)
        assert point["amplitude"] == pytest.approx(amplitude, rel=1e-4)
        assert point["period"] == pytest.approx(period, rel=1e-5)


def test_two_dof_unstable_slip_oscillation_separates_the_basins() -> None:
    # a foundation (M, K, zeta_a) = (1, 10, 0.5) under the published slider: the search's modal
    # starts find the unstable cycle (no backward runs in 4 dimensions). Independent check by
    # direct runs of the exact engine: the cycle returns to its state after its period, and
    # starts just inside it slide steadily while starts just outside it stick-slip
    from stickslip.analysis.simulation import EngineOptions, simulate
    from stickslip.analysis.verdict import Verdict
    from stickslip.model.initial import InitialState
    from stickslip.model.parameters import Foundation
    from stickslip.model.structure import elastic_foundation

    structure = elastic_foundation(ZETA, Foundation(1.0, 10.0, 0.5))
    slider = Slider(LAM, gamma=GAMMA, friction=StribeckFriction(US))
    found = find_slip_oscillations(structure, slider)
    unstable = [c for c in found if not c.stable]
    assert len(unstable) == 1
    osc = unstable[0]
    assert osc.multipliers.size == 3 and osc.multiplier > 1.0  # 2 n - 1 of the section map
    n = structure.n_dof
    run = simulate(structure, slider, initial=InitialState(osc.state[:n], osc.state[n:]),
                   options=EngineOptions(t_max=2.0 * osc.period), record=True, run_to_t_max=True)
    q, v, _ = run.state_at([osc.period])
    assert np.max(np.abs(np.concatenate([q[0], v[0]]) - osc.state)) < 1e-7
    # steady sliding: K q = f with the law's force at the belt speed (shifted coordinates)
    force = np.zeros(n)
    force[0] = float(slider.friction.value(1.0, slider.lam, slider.gamma)) - slider.gamma * slider.lam
    z_eq = np.concatenate([np.linalg.solve(structure.stiffness, force), np.zeros(n)])
    for factor, verdict in ((0.97, Verdict.STEADY_SLIDING), (1.03, Verdict.STICK_SLIP)):
        z = z_eq + factor * (osc.state - z_eq)
        assert simulate(structure, slider, initial=InitialState(z[:n], z[n:]),
                        record=False).verdict is verdict


def test_a_slip_oscillations_amplitude_is_its_own_cycles_after_a_larger_transient() -> None:
    # fitted foundation (zeta = 0.1), lambda = 0.5, linear law delta = 0.4: a certified slip
    # oscillation of period 6.721768577. Its amplitude was 0.854312: the step's interior
    # extrema were located only when they could beat the range since the last breakaway,
    # which (no breakaway in a slip oscillation) held the start's larger transient. References:
    # an independent solve_ivp (DOP853, rtol 1e-12, extrema where xi' = 0: xi from -2.07167 to
    # -0.35912, amplitude 0.856271; an audit, rounded to 6 digits), and the run's own record
    # sampled at 200,001 points over its last period
    from stickslip import simulate
    from stickslip.analysis.theory import optimal_foundation_fit
    from stickslip.model.friction import LinearFriction
    from stickslip.model.structure import elastic_foundation

    run = simulate(elastic_foundation(0.1, optimal_foundation_fit(0.1)),
                   Slider(0.5, friction=LinearFriction(0.4)))
    assert run.verdict.value == "slip-oscillation"
    assert run.period == pytest.approx(6.721768577, abs=1e-9)
    t = np.linspace(run.t_end - run.period, run.t_end, 200_001)
    xi = run.state_at(t)[0][:, 0]
    assert run.amplitude == pytest.approx((xi.max() - xi.min()) / 2.0, rel=1e-9)
    assert run.amplitude == pytest.approx(0.856271, abs=1e-6)
    # the search finds it too: the linear law's floor at zero friction (its second band) is
    # the nonlinearity that bounds it (before, a linear law was never searched)
    structure = elastic_foundation(0.1, optimal_foundation_fit(0.1))
    (found,) = find_slip_oscillations(structure, Slider(0.5, friction=LinearFriction(0.4)))
    assert found.stable and found.period == pytest.approx(run.period, rel=1e-9)
    assert found.amplitude == pytest.approx(0.856271, abs=1e-6)
    assert find_slip_oscillations(structure, Slider(0.5, friction=LinearFriction(-0.2))) == ()


def test_small_cycles_near_the_hopf_point_are_found_two_to_a_cell() -> None:
    # Near the Hopf point (lambda_H about 0.67 here) the same law has three slip oscillations
    # at lambda = 0.668, all of amplitude below 0.05: the first below the old scan's first grid
    # point (0.02475) and the other two inside one of its cells (0.02475-0.0495), where their
    # sign changes cancelled: `cycles` listed none (independent audit; `continue` of the same
    # law traces them through folds at lambda 0.6665-0.6698). Each found cycle is checked here
    # as a fixed point of the engine's own section map, independently of the scan's seeds,
    # and their stabilities alternate as fixed points of an increasing map of the line must.
    from stickslip.analysis.simulation import EngineOptions
    from stickslip.analysis.slip_oscillations import slip_section

    slider = Slider(0.668, gamma=GAMMA, friction=StribeckFriction(US))
    found = find_slip_oscillations(rigid_base(ZETA), slider)
    assert len(found) == 3
    amplitudes = [osc.amplitude for osc in found]
    assert amplitudes == sorted(amplitudes) and amplitudes[-1] < 0.05
    assert amplitudes[0] < 0.02475 and 0.02475 < amplitudes[1] < amplitudes[2] < 0.0495
    assert [osc.stable for osc in found] == [False, True, False]
    section = slip_section(rigid_base(ZETA), slider, EngineOptions())
    for osc in found:
        y = np.array([osc.peak_velocity])
        back = section.step(y)
        assert back is not None and abs(float(back[0]) - osc.peak_velocity) < 1e-9
        assert osc.period == pytest.approx(2.0 * math.pi, rel=1e-4)  # small: the linear period


@pytest.mark.slow
def test_the_cycle_near_the_hopf_point_matches_smooth_law_shooting() -> None:
    # An independent audit's Newton shooting of the smooth law (solve_ivp, rtol 1e-12) at
    # lambda = 0.668: the outer unstable cycle has amplitude 0.046860 and multiplier 1.00155;
    # the law interpolated to 1e-6 lambda must give it to the interpolant's effect (1e-3 here,
    # the cycle's amplitude being set by the law's weak cubic term near the Hopf point).
    slider = Slider(0.668, gamma=GAMMA, friction=StribeckFriction(US, tolerance=1e-6))
    found = find_slip_oscillations(rigid_base(ZETA), slider)
    outer = max(found, key=lambda osc: osc.amplitude)
    assert not outer.stable
    assert outer.amplitude == pytest.approx(0.046860, rel=1e-3)
    assert outer.multiplier == pytest.approx(1.00155, abs=2e-4)
