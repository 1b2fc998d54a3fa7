"""``design`` answers with the machine's own friction law (issue 32, item 1).

The critical belt speed ``V_c`` and load ``W_c`` of a law whose dimensionless form moves with
``V`` or ``W`` come from one exact onset search along each
(:func:`stickslip.analysis.critical.speed_and_load_onsets`); the paper's Coulomb closed forms
stay beside them, labelled as such.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from stickslip import PhysicalSystem
from stickslip.analysis.critical import lowest_onset, speed_and_load_onsets
from stickslip.analysis.design import COULOMB_LAW, design_foundation
from stickslip.analysis.simulation import simulate
from stickslip.analysis.theory import critical_lambda_linear, optimal_foundation_fit
from stickslip.analysis.verdict import Verdict
from stickslip.cli.design_command import format_report
from stickslip.model.physical import PhysicalFriction
from stickslip.model.structure import elastic_foundation, rigid_base
from tests.cli_helpers import STRIBECK_SLIDER, run_cli, stribeck_slider_file

# issue 32 item 1: the Stribeck machine whose design printed V_c = 0.0747 m/s (the Coulomb
# value) on every rigid-base row; the issue gives its true limit as 0.2718 m/s
STRIBECK = PhysicalSystem(mass=0.538, stiffness=6957.0, damping=5.746, mu_s=0.6, mu_k=0.2, load=10.0,
                          speed=0.19, friction=PhysicalFriction("stribeck", stribeck_velocity=0.1,
                                                                viscous=0.02))
STRIBECK_TOML = """m = "0.538 kg"
k = "6957 N/m"
c = "5.746 N*s/m"
mu_s = 0.6
mu_k = 0.2
load = "10 N"
speed = "0.19 m/s"

[friction]
law = "stribeck"
stribeck_velocity = "0.1 m/s"
viscous = "0.02 s/m"
"""


def _bisect_speed(system: PhysicalSystem, slow: float, fast: float, rtol: float) -> float:
    """The stick-slip limit in belt speed by bisection of direct ``simulate`` runs (rigid base).

    Independent of the onset search: the machine is rebuilt at each speed from its SI values
    (``PhysicalSystem.slider()``: lambda and the law's ``v_s / V`` and viscous term), midpoints
    are arithmetic in ``V``, and nothing of :mod:`stickslip.analysis.critical` is used.
    """
    def stick_slips(speed: float) -> bool:
        at = dataclasses.replace(system, speed=speed)
        verdict = simulate(rigid_base(at.zeta), at.slider(), record=False).verdict
        assert verdict is not Verdict.UNDETERMINED, f"V={speed}: undetermined"
        return verdict is Verdict.STICK_SLIP

    assert stick_slips(slow) and not stick_slips(fast)
    for _ in range(60):  # bounded: 60 halvings are far below rtol
        if fast - slow <= rtol * slow:
            break
        mid = 0.5 * (slow + fast)
        slow, fast = (mid, fast) if stick_slips(mid) else (slow, mid)
    return 0.5 * (slow + fast)


def test_stribeck_machine_critical_speed_is_its_own_laws() -> None:
    onsets = speed_and_load_onsets(rigid_base(STRIBECK.zeta), STRIBECK, lam_min=1e-3, lam_max=200.0)
    assert onsets.own_law and onsets.speed.converged and onsets.speed.n_undetermined == 0
    v_c = STRIBECK.speed_for_lambda(onsets.speed.lam)
    # reference 1: issue 32 item 1 states the true limit, 0.2718 m/s (4 digits)
    assert round(v_c, 4) == 0.2718
    # reference 2: bisection in V with direct simulate runs (independent of the search);
    # issue 32: the machine stick-slips at 0.25 m/s; 0.30 m/s is above the stated limit
    assert v_c == pytest.approx(_bisect_speed(STRIBECK, 0.25, 0.30, 1e-7), rel=2e-6)
    # the paper's Coulomb value is 3.6x lower (issue 32): the answer the command gave before
    coulomb = lowest_onset(rigid_base(STRIBECK.zeta), gamma=STRIBECK.slider().gamma, lam_min=1e-3)
    assert STRIBECK.speed_for_lambda(coulomb) == pytest.approx(0.0747, abs=5e-5)
    # along the load the law's viscous term moves too: another onset, below the operating
    # load of 10 N, where the machine stick-slips (its own simulated verdict at 0.19 m/s)
    w_c = STRIBECK.load_for_lambda(onsets.load.lam)
    assert onsets.load.lam != onsets.speed.lam and w_c < STRIBECK.load
    assert simulate(rigid_base(STRIBECK.zeta), STRIBECK.slider(), record=False).verdict is Verdict.STICK_SLIP


def test_linear_law_critical_speed_and_load_are_eq_36_at_the_effective_damping() -> None:
    # a linear law mu = mu_k - sigma v_r: delta = sigma W / (2 sqrt(m k)) moves with the load only
    sigma = 0.01
    system = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05, friction=PhysicalFriction("linear", slope=sigma))
    d = design_foundation(system).to_dict()
    root_mk = math.sqrt(2.0 * 50e3)
    # reference: critical_lambda_linear, Eq. (36) at zeta - delta (derivation in its docstring)
    along_speed = critical_lambda_linear(system.zeta, sigma * 500.0 / (2.0 * root_mk))
    # along the load delta = sigma V lambda / (2 (mu_s - mu_k)): the fixed point of the same form
    along_load = brentq(lambda lam: lam - critical_lambda_linear(system.zeta, sigma * 0.05 * lam / 0.4),
                        1e-3, 50.0, xtol=1e-14)
    assert d["critical_lambda"]["rigid_simulation"] == pytest.approx(along_speed, rel=1e-6)
    assert d["critical_lambda_load"]["rigid_simulation"] == pytest.approx(along_load, rel=1e-6)
    assert d["critical_speed"]["rigid_simulation"] == pytest.approx(
        system.speed_for_lambda(along_speed), rel=1e-6)
    assert d["critical_load"]["rigid_simulation"] == pytest.approx(
        system.load_for_lambda(along_load), rel=1e-6)
    # the Coulomb procedure is stated beside it, labelled
    assert d["critical_law"]["rigid_exact"] == COULOMB_LAW
    assert d["critical_law"]["rigid_simulation"].startswith("linear")
    assert any("Coulomb law" in w and "machine's friction law" in w for w in d["warnings"])


def test_coulomb_search_is_todays_onset_bit_for_bit() -> None:
    # the paper's law: one search, the same float as lowest_onset (tests/test_coulomb_bit_identity)
    system = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05)
    structure = elastic_foundation(system.zeta, optimal_foundation_fit(system.zeta))
    onsets = speed_and_load_onsets(structure, system, lam_min=1e-3, lam_max=200.0)
    assert not onsets.own_law and onsets.speed is onsets.load
    assert onsets.speed.lam == lowest_onset(structure, gamma=system.slider().gamma, lam_min=1e-3,
                                            lam_max=200.0)


@pytest.mark.slow
def test_stribeck_design_command_states_both_laws(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cfg = tmp_path / "machine.toml"
    cfg.write_text(STRIBECK_TOML)
    code, out, err = run_cli(["design", "--config", str(cfg), "--no-stick-slip-optimum", "--json"], capsys)
    assert code == 0, err
    d = json.loads(out)
    # reference: issue 32 item 1, 0.2718 m/s (checked by bisection above)
    assert round(d["critical_speed"]["rigid_simulation"], 4) == 0.2718
    assert d["critical_speed"]["rigid_exact"] == pytest.approx(0.0747, abs=5e-5)
    assert d["critical_law"]["rigid_simulation"].startswith("stribeck")
    text = format_report(d)  # the command's text output of this very report
    assert "the paper's procedure, for its Coulomb law" in text
    assert "the machine's friction law (stribeck" in text
    assert "V_c=  0.2718 m/s" in text


def test_hopf_boundaries_are_the_closed_forms_on_the_rigid_base() -> None:
    # Derivation: mu(v) = mu_k + (mu_0 - mu_k) exp(-v/v_s) + sigma_v v (docs/friction.md), so
    # steady sliding on the rigid base is stable while c + W mu'(V) > 0 (the net damping, the
    # Routh-Hurwitz condition of one DOF), mu'(V) = -(mu_0 - mu_k) exp(-V/v_s)/v_s + sigma_v:
    # along the speed V_H = v_s ln(W (mu_0 - mu_k) / (v_s (c + W sigma_v))), unstable below;
    # along the load W_H = c / ((mu_0 - mu_k) exp(-V/v_s)/v_s - sigma_v), unstable above
    from stickslip.analysis.stability_boundaries import stability_boundaries

    c, w, v, dmu, v_s, sigma_v = 5.746, 10.0, 0.19, 0.4, 0.1, 0.02
    bounds = stability_boundaries(STRIBECK, rigid_base(STRIBECK.zeta))
    v_h = v_s * math.log(w * dmu / (v_s * (c + w * sigma_v)))
    w_h = c / (dmu * math.exp(-v / v_s) / v_s - sigma_v)
    assert bounds.speeds == (pytest.approx(v_h, rel=1e-9),)
    assert bounds.unstable_speeds == ((bounds.scan[0], pytest.approx(v_h, rel=1e-9)),)
    assert bounds.load == pytest.approx(w_h, rel=1e-12)
    assert "unstable at belt speeds below 0.1" in bounds.sentence()
    # the law's slope stays at -dmu/v_s + sigma_v as v -> 0: unstable down to where the law's
    # scaling ends, and the sentence names that speed instead of claiming every lower speed
    assert bounds.scan[0] < v / 1e3
    assert f"and down to at least {bounds.scan[0]:.3g} m/s" in bounds.sentence()


def test_a_gaussian_stribeck_law_is_stable_again_far_below_the_belt_speed() -> None:
    # Derivation: with mu = mu_k + dmu exp(-(v/v_s)^2) the slope mu'(v) = -2 dmu v/v_s^2
    # exp(-(v/v_s)^2) vanishes as v -> 0, so the rigid-base net damping c + W mu'(v) (one DOF,
    # Routh-Hurwitz) is positive again below the lower root of c = 2 W dmu v/v_s^2
    # exp(-(v/v_s)^2), about c v_s^2/(2 W dmu) = 7.2e-6 m/s at W = 10 kN: 26 times below the
    # scan's first decades (V/1000 = 1.9e-4 m/s), where the old sentence said "below" the
    # upper root alone (an audit of design on a Stribeck machine)
    from stickslip.analysis.stability_boundaries import stability_boundaries

    gauss = dataclasses.replace(STRIBECK, load=1e4, friction=dataclasses.replace(
        STRIBECK.friction, exponent=2.0, viscous=0.0))
    c, w, dmu, v_s = gauss.damping, gauss.load, gauss.mu_s - gauss.mu_k, 0.1

    def net_damping(v: float) -> float:
        return c - w * dmu * 2.0 * v / v_s**2 * math.exp(-((v / v_s) ** 2))

    peak = v_s / math.sqrt(2.0)  # where the slope is steepest
    low = brentq(net_damping, 1e-12, peak, xtol=1e-300, rtol=1e-14)
    high = brentq(net_damping, peak, 100.0 * v_s, rtol=1e-14)
    assert low < gauss.speed / 1e3
    bounds = stability_boundaries(gauss, rigid_base(gauss.zeta))
    assert bounds.speeds == (pytest.approx(low, rel=1e-9), pytest.approx(high, rel=1e-9))
    assert bounds.unstable_speeds == ((bounds.speeds[0], bounds.speeds[1]),)
    assert f"unstable at belt speeds {low:.4g} to {high:.4g} m/s" in bounds.sentence()


def test_hopf_boundaries_keep_a_foundations_window_of_stability() -> None:
    # The foundation (M, K, zeta_a) = (1.17013, 0.109102, 0.69939) at zeta = 0.1 (docs/
    # continuation.md) is stable for delta < 0.61488, unstable to 0.62413, stable again to
    # 0.68562 and unstable beyond (stability_intervals). Derivation: with mu = mu_k + dmu
    # exp(-v/v_s), delta_local(V) = W dmu exp(-V/v_s) / (2 v_s sqrt(m k)) = exp(-V/v_s) here
    # (W = 5 N, dmu = 0.4, v_s = 0.01 m/s, m k = 1e4 kg N/m), so the speed boundaries are
    # V_i = v_s ln(1/c_i) at the three weakenings c_i where the verdict changes, and along the
    # load W_i = W c_i / delta_local(V). The scan once took delta_crit - delta_local alone and
    # reported "unstable below 0.004863 m/s" across the window 0.003774-0.004714 m/s.
    from stickslip.analysis.stability import stability_intervals, steady_sliding_stability
    from stickslip.analysis.stability_boundaries import stability_boundaries
    from stickslip.model.structure import Foundation

    structure = elastic_foundation(0.1, Foundation(1.17013, 0.109102, 0.69939))
    system = PhysicalSystem(mass=1.0, stiffness=1e4, damping=20.0, mu_s=0.6, mu_k=0.2, load=5.0,
                            speed=0.02, friction=PhysicalFriction(law="stribeck",
                                                                  stribeck_velocity=0.01))
    intervals = stability_intervals(structure)
    assert [stable for *_, stable in intervals] == [True, False, True, False]
    changes = [hi for _, hi, _ in intervals[:-1]]
    bounds = stability_boundaries(system, structure)
    assert bounds.speeds == tuple(pytest.approx(0.01 * math.log(1.0 / c), rel=1e-9)
                                  for c in reversed(changes))
    v1, v2, v3 = bounds.speeds
    assert bounds.unstable_speeds == ((bounds.scan[0], v1), (v2, v3))

    def growth(v: float) -> float:
        return steady_sliding_stability(structure, dataclasses.replace(system, speed=v).slider()
                                        ).growth_rate

    assert growth(0.5 * (v1 + v2)) < 0.0 < growth(0.5 * (v2 + v3))  # the window, the eigenvalues
    local = math.exp(-2.0)  # delta_local at V = 0.02 m/s
    (a1, b1), (a2, b2) = bounds.unstable_loads
    assert (a1, b1, a2) == tuple(pytest.approx(5.0 * c / local, rel=1e-12) for c in changes)
    assert math.isinf(b2) and bounds.load == a1
    assert "unstable at loads 22.72 to 23.06 N, above 25.33 N" in bounds.sentence()


def test_unstable_load_ranges_are_one_where_a_second_pair_crosses() -> None:
    # a 3-DOF chain whose second and third Hopf weakenings add unstable pairs to an already
    # unstable motion: the verdict changes once, so the loads give one range (an audit found
    # "unstable at loads 5.828 to 23.32 N, 23.32 to 47.13 N, ..." on a 4-DOF machine), and the
    # growth rate (eigenvalues) is positive on both sides of the inner weakenings
    from stickslip.analysis.stability import growth_rate, stability_intervals
    from stickslip.analysis.stability_boundaries import stability_boundaries
    from stickslip.model.structure import Structure

    rng = np.random.default_rng(3)
    mass = np.diag(np.r_[1.0, rng.uniform(0.2, 3.0, 2)])
    springs = rng.uniform(0.2, 3.0, 3)
    stiffness = np.zeros((3, 3))
    stiffness[0, 0] = springs[0]
    for i in (1, 2):  # ground - k0 - x0 - k1 - x1 - k2 - x2
        stiffness[i - 1:i + 1, i - 1:i + 1] += springs[i] * np.array([[1.0, -1.0], [-1.0, 1.0]])
    stiffness /= stiffness[0, 0]
    damping = rng.uniform(0.01, 0.2) * stiffness + rng.uniform(0.0, 0.1) * mass
    structure = Structure(mass, damping, stiffness)
    intervals = stability_intervals(structure)
    assert [stable for *_, stable in intervals] == [True, False, False, False]
    for _, hi, _ in intervals[1:-1]:
        assert growth_rate(structure, hi * (1.0 - 1e-6)) > 0.0 < growth_rate(structure, hi * (1.0 + 1e-6))
    bounds = stability_boundaries(STRIBECK, structure)
    local = intervals[0][1] * STRIBECK.load / bounds.load  # delta_local at the operating point
    assert bounds.unstable_loads == ((pytest.approx(STRIBECK.load * intervals[0][1] / local),
                                      math.inf),)
    assert f"unstable at loads above {bounds.load:.4g} N" in bounds.sentence()
    assert len(bounds.hopf_frequencies) == 1


def test_the_onset_frequency_of_one_dof_is_its_natural_frequency() -> None:
    # one DOF at the Hopf weakening delta = zeta: s^2 + 2 (zeta - delta) s + 1 = s^2 + 1, so the
    # onset is at omega = 1 per unit tau, f_H = sqrt(k/m) / (2 pi)
    from stickslip.analysis.stability_boundaries import stability_boundaries

    bounds = stability_boundaries(STRIBECK, rigid_base(STRIBECK.zeta))
    f_h = math.sqrt(STRIBECK.stiffness / STRIBECK.mass) / (2.0 * math.pi)
    assert bounds.hopf_frequencies == (pytest.approx(f_h, rel=1e-12),)
    assert f"onset frequency {f_h:.4g} Hz" in bounds.sentence()


def test_hopf_boundary_with_a_foundation_is_where_the_growth_rate_changes_sign() -> None:
    # the boundary of the 2-DOF machine against the eigenvalues of its linearisation (the
    # growth rate of steady sliding) just on either side of it, rebuilt at each speed and load
    from stickslip.analysis.stability import steady_sliding_stability
    from stickslip.analysis.stability_boundaries import stability_boundaries

    found = optimal_foundation_fit(STRIBECK.zeta)
    system = dataclasses.replace(STRIBECK, speed=0.05)
    structure = elastic_foundation(system.zeta, found)
    bounds = stability_boundaries(system, structure)
    assert bounds.speeds, bounds

    def growth(at: PhysicalSystem) -> float:
        return steady_sliding_stability(structure, at.slider()).growth_rate

    for v_h in bounds.speeds:
        below = growth(dataclasses.replace(system, speed=v_h * (1.0 - 1e-6)))
        above = growth(dataclasses.replace(system, speed=v_h * (1.0 + 1e-6)))
        assert below * above < 0.0, (v_h, below, above)
    assert bounds.load is not None  # the law weakens at 0.05 m/s: a load makes it unstable
    lighter = growth(dataclasses.replace(system, load=bounds.load * (1.0 - 1e-6)))
    heavier = growth(dataclasses.replace(system, load=bounds.load * (1.0 + 1e-6)))
    assert lighter < 0.0 < heavier


def test_design_of_a_structure_with_a_stribeck_law_gives_its_stability_and_boundaries(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # design --config of a [structure] machine said nothing of steady sliding's stability
    # (an independent audit: a 4-DOF machine unstable at +3.49 1/s, Hopf at 0.0308 m/s and
    # 15.7 N). Reference: one DOF (m = 1 kg, k = 1e4 N/m, c = 20 N s/m, W = 100 N, V = 0.1 m/s)
    # with mu = mu_k + (mu_s - mu_k) exp(-v / v_s): the linearisation is m s^2 + (c + W mu'(V))
    # s + k, mu'(V) = -(mu_s - mu_k) / v_s exp(-V / v_s), so the growth rate is
    # -(c + W mu'(V)) / (2 m) (underdamped), stable down to mu' = -c / W, and the Hopf
    # boundaries are V_H = v_s ln(W (mu_s - mu_k) / (v_s c)) and W_H = -c / mu'(V)
    mu_s, mu_k, v_s, c, w, v = (STRIBECK_SLIDER[k] for k in ("mu_s", "mu_k", "v_s", "c", "w", "v"))
    config = stribeck_slider_file(tmp_path / "slider.toml")
    code, out, err = run_cli(["design", "--config", str(config), "--json", "--no-stick-slip-optimum"],
                             capsys)
    assert code == 0, err
    s = json.loads(out)["stability"]
    slope = -(mu_s - mu_k) / v_s * math.exp(-v / v_s)
    assert s["stable"] is False
    assert s["growth_rate"] == pytest.approx(-(c + w * slope) / 2.0, rel=1e-9)
    assert s["sigma_local"] == pytest.approx(-slope, rel=1e-12)
    assert s["sigma_crit"] == pytest.approx(c / w, rel=1e-9)
    b = s["boundaries"]
    assert b["critical_speeds_m_s"] == [pytest.approx(v_s * math.log(w * (mu_s - mu_k) / (v_s * c)),
                                                      rel=1e-9)]
    assert b["critical_load_N"] == pytest.approx(-c / slope, rel=1e-9)
    code, out, err = run_cli(["design", "--config", str(config), "--no-stick-slip-optimum"], capsys)
    assert code == 0, err
    assert "steady sliding with the friction law (stribeck): UNSTABLE, growth rate 17.07 1/s" in out
    assert "unstable at belt speeds below 0.1498 m/s and down to at least" in out


def test_the_stability_optimum_as_printed_is_checked() -> None:
    # An independent audit (eigenvalues of the linearised 2-DOF steady sliding, slider damping
    # 2 (zeta - delta)): for this machine the stability-optimal foundation's delta_crit is
    # 0.5312 to full precision, but the foundation built from design's printed m_a, k_a, c_a
    # (4 digits) is unstable for delta in 0.486-0.496: the optimum sits on the edge of a window
    # of instability. design must give the printed foundation's own limit and say so.
    from stickslip.analysis.design import stability_optimum
    from stickslip.analysis.stability import slip_matrix
    from stickslip.model.parameters import Foundation

    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05)
    best = stability_optimum(system)
    assert best["delta_crit"] == pytest.approx(0.5312, abs=1e-4)
    assert best["delta_crit_as_printed"] == pytest.approx(0.486, abs=1e-3)
    m, k = system.mass, system.stiffness
    printed = [float(f"{best[key]:.4g}") for key in ("m_a", "k_a", "c_a")]
    built = Foundation(printed[0] / m, math.sqrt(printed[1] / k), printed[2] / (2 * math.sqrt(m * k)))
    exact = Foundation(best["M"], best["K"], best["zeta_a"])
    delta = 0.49  # inside the audit's window: the printed foundation grows, the optimum does not

    def growth(foundation: Foundation) -> float:
        return float(np.max(np.linalg.eigvals(
            slip_matrix(elastic_foundation(system.zeta, foundation), -2.0 * delta)).real))

    assert growth(built) > 0.0 > growth(exact)
    payload = design_foundation(system).to_dict()
    payload["stability_optimal_foundation"] = best  # as design --config gives it for such a law
    report = format_report(payload)
    assert "the optimum sits on the edge of a window of instability" in report
    assert "delta_crit=0.486" in report
