"""Design procedure (Fig. 16) in physical units: units parsing, critical speed and load."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from stickslip import PhysicalSystem
from stickslip.analysis.critical import lowest_onset
from stickslip.analysis.design import design_foundation
from stickslip.analysis.theory import (
    critical_lambda_approx,
    critical_lambda_exact,
    equivalent_damping_fit,
    optimal_foundation_fit,
)
from stickslip.model import rigid_base
from stickslip.model.units import to_si
from tests.cli_helpers import run_cli as _cli

# a 2 kg slider on 50 kN/m with 20 N s/m, mu_s = 0.5, mu_k = 0.3, 500 N, 5 cm/s
SYSTEM = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0, speed=0.05)


@pytest.mark.parametrize(
    ("name", "text", "si"),
    [("m", "2 kg", 2.0), ("m", "500 g", 0.5), ("k", "50 kN/m", 5e4), ("k", "5 N/mm", 5e3),
     ("speed", "5 cm/s", 0.05), ("speed", "0.5", 0.5), ("load", "1 kN", 1e3),
     ("c", "20 N*s/m", 20.0), ("mu_s", "0.4", 0.4)],
)
def test_units_are_converted_to_si(name: str, text: str, si: float) -> None:
    assert to_si(name, text) == pytest.approx(si)


@pytest.mark.parametrize(
    ("name", "text", "needle"),
    [("k", "5 kg", "wrong unit for the slider stiffness"), ("m", "3 m/s", "wrong unit"),
     ("speed", "fast", "not a quantity"), ("mu_s", "2 kg", "dimensionless"),
     ("load", "nan", "finite")],
)
def test_wrong_units_are_rejected(name: str, text: str, needle: str) -> None:
    with pytest.raises(ValueError, match=needle):
        to_si(name, text)


def test_design_report_matches_closed_forms_and_simulation() -> None:
    report = design_foundation(SYSTEM)
    d = report.to_dict()
    # closed forms: Eq. (39), Eq. (36), Eq. (33) with Eq. (37)
    assert d["critical_lambda"]["rigid_theory"] == pytest.approx(critical_lambda_approx(SYSTEM.zeta))
    assert d["critical_lambda"]["rigid_exact"] == pytest.approx(critical_lambda_exact(SYSTEM.zeta))
    assert d["zeta_eq"] == pytest.approx(equivalent_damping_fit(SYSTEM.zeta))
    zeta_eq = equivalent_damping_fit(SYSTEM.zeta)
    assert d["critical_lambda"]["foundation_theory"] == pytest.approx(critical_lambda_approx(zeta_eq))
    # simulation of the rigid base agrees with the exact Eq. (36)
    assert d["critical_lambda"]["rigid_simulation"] == pytest.approx(
        critical_lambda_exact(SYSTEM.zeta), rel=2e-6)
    # lambda = (mu_s - mu_k) W / (V sqrt(mk)): critical speed and load invert it
    lam_c = d["critical_lambda"]["rigid_exact"]
    root_mk = math.sqrt(2.0 * 50e3)
    assert d["critical_speed"]["rigid_exact"] == pytest.approx(0.2 * 500.0 / (lam_c * root_mk))
    assert d["critical_load"]["rigid_exact"] == pytest.approx(lam_c * 0.05 * root_mk / 0.2)
    # the recommended foundation is Eqs. (28)-(30) in SI units
    fit = optimal_foundation_fit(SYSTEM.zeta)
    assert d["foundation"]["m_a"] == pytest.approx(fit.mass_ratio * 2.0)
    assert d["foundation"]["k_a"] == pytest.approx(fit.stiffness_ratio**2 * 50e3)
    assert d["foundation"]["c_a"] == pytest.approx(2 * fit.damping_ratio * root_mk)
    # lambda = 6.3 is above every critical value here: stick-slip everywhere
    assert d["verdict"]["rigid"] == {"theory": "stick-slip", "exact": "stick-slip",
                                     "simulation": "stick-slip"}


def test_lowest_onset_of_rigid_base_is_eq_36() -> None:
    # reference: root of Eq. (36)
    found = lowest_onset(rigid_base(0.2), rtol=1e-8)
    assert found == pytest.approx(critical_lambda_exact(0.2), rel=1e-7)




ARGS = ["--m", "2 kg", "--k", "50 kN/m", "--c", "20 N*s/m", "--mu-s", "0.5", "--mu-k", "0.3",
        "--load", "500 N", "--speed", "5 cm/s"]


def test_design_cli_json_keys(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _cli(["design", *ARGS, "--json"], capsys)
    assert code == 0
    d = json.loads(out)
    for key in ("lambda", "zeta", "gamma", "zeta_eq", "verdict", "critical_speed",
                "critical_load", "foundation"):
        assert key in d
    for key in ("rigid_theory", "rigid_simulation", "foundation_theory", "foundation_simulation"):
        assert d["critical_speed"][key] > 0 and d["critical_load"][key] > 0
    assert set(d["foundation"]) >= {"m_a", "k_a", "c_a"}
    best = d["stick_slip_optimal_foundation"]
    assert set(best) >= {"m_a", "k_a", "c_a", "lambda_crit"}
    # bounded by the recommended (absorber-optimal) mass, Eq. (28)
    assert best["m_a"] <= d["recommended_foundation"]["m_a"] * (1 + 1e-12)


@pytest.mark.slow  # 15 s: out of the default run (kept under ten minutes)
def test_design_cli_reads_toml(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cfg = tmp_path / "machine.toml"
    cfg.write_text('m = "2 kg"\nk = "50 kN/m"\nc = 20\nmu_s = 0.5\nmu_k = 0.3\n'
                   'load = "500 N"\nspeed = "5 cm/s"\n')
    code, out, _ = _cli(["design", "--config", str(cfg), "--json"], capsys)
    _, ref, _ = _cli(["design", *ARGS, "--json"], capsys)
    assert code == 0
    assert json.loads(out)["critical_lambda"] == json.loads(ref)["critical_lambda"]


@pytest.mark.parametrize(
    ("extra", "needle"),
    [(["--k", "5 kg"], "wrong unit"), (["--m", "-2 kg"], "m=-2.0 must be positive"),
     (["--mu-k", "0.6"], "mu_k=0.6 must be smaller than mu_s=0.5"),
     (["--m-a", "1 kg"], "needs all of --m-a, --k-a and --c-a"),
     (["--speed", "0 m/s"], "must be positive")],
)
def test_design_cli_bad_input(extra: list[str], needle: str,
                              capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = _cli(["design", *ARGS, *extra], capsys)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and needle in err


def test_design_refuses_an_overdamped_slider(capsys: pytest.CaptureFixture[str]) -> None:
    # k = 1e-3 N/m with c = 20 N s/m gives zeta = 224: Eqs. (28)-(33) do not apply
    code, out, err = _cli(["design", *ARGS, "--k", "1e-3 N/m"], capsys)
    assert code == 2 and out == ""
    assert "is above 0.9" in err and len(err.strip().splitlines()) == 1


def test_design_warns_outside_the_fitted_range() -> None:
    # zeta = 0.6 lies outside 0 <= zeta <= 0.4, where Eqs. (28)-(33) were fitted
    system = PhysicalSystem(mass=2.0, stiffness=50e3, damping=2 * 0.6 * math.sqrt(2.0 * 50e3), mu_s=0.5,
                            mu_k=0.3, load=500.0, speed=0.05)
    report = design_foundation(system)
    assert report.warnings and "outside the range" in report.warnings[0]


def test_step_budget_is_a_reported_status() -> None:
    from stickslip import Foundation, RunStatus, Slider, elastic_foundation, simulate

    # zeta_a = 1000 forces steps of ~2.5e-4: the budget ends the run, it never hangs
    result = simulate(elastic_foundation(0.1, Foundation(1.0, 1.0, 1000.0)), Slider(3.0))
    assert result.status is RunStatus.MAX_STEPS
    assert result.verdict.value == "undetermined"
