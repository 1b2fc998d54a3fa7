"""Friction laws where a user meets them: the command line, maps, boundaries, tuning, design.

Sources of the reference values:
* the rigid base with the linear law is Nakano's problem at ``zeta - delta``, so its exact
  boundary is Eq. (36) at ``zeta - delta`` (derivation in
  :func:`stickslip.analysis.theory.critical_lambda_linear`);
* steady sliding on the rigid base is stable iff ``zeta > delta`` (Routh-Hurwitz of
  ``s^2 + 2 (zeta - delta) s + 1``), so ``delta_crit = zeta``;
* for the foundation, the Routh-Hurwitz conditions of the quartic
  (:func:`stickslip.analysis.stability.routh_hurwitz_quartic`), independent of eigenvalues;
* ``delta = sigma W / (2 sqrt(m k))`` (DESIGN.md section 8) for the unit conversion.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from stickslip import (
    Foundation,
    Slider,
    elastic_foundation,
    occurrence_map,
    optimal_foundation_fit,
    rigid_base,
    simulate,
    stick_slip_boundary,
)
from stickslip.analysis.stability import critical_weakening, routh_hurwitz_2dof
from stickslip.analysis.stability_tuning import optimal_foundation_stability
from stickslip.analysis.theory import critical_lambda_linear
from stickslip.model.friction import CoulombFriction, LinearFriction, StribeckFriction, TableFriction
from stickslip.model.friction_input import parse_friction
from stickslip.model.physical import PhysicalSystem, physical_friction_from_config
from stickslip.sweep.execution import ExecutionOptions

from .cli_helpers import run_cli


@pytest.mark.parametrize(("text", "law"), [
    ("coulomb", CoulombFriction()),
    ("linear:0.05", LinearFriction(0.05)),
    ("linear:-0.1", LinearFriction(-0.1)),
    ("stribeck:vs=0.5,n=2,viscous=0.01,mu0=0.8,tol=1e-3",
     StribeckFriction(0.5, exponent=2.0, viscous=0.01, mu0_ratio=0.8, tolerance=1e-3)),
])
def test_friction_text_parses_to_the_law(text: str, law: object) -> None:
    assert parse_friction(text) == law


def test_friction_table_file_parses(tmp_path: Path) -> None:
    path = tmp_path / "curve.csv"
    path.write_text("v,f\n0,1\n0.5,0.2\n2,0\n")
    assert parse_friction(f"table:{path}") == TableFriction((0.0, 0.5, 2.0), (1.0, 0.2, 0.0))


@pytest.mark.parametrize("text", ["linear:x", "linear:nan", "stribeck:n=2", "stribeck:vs=0.5,q=1",
                                  "viscous", "table:/no/such/file.csv", "stribeck:vs=0.5,mu0=2"])
def test_bad_friction_is_one_line_exit_2(text: str, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["simulate", "--lam", "3", "--zeta", "0.1", "--friction", text], capsys)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_simulate_json_reports_the_law_and_its_stability(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["simulate", "--lam", "3", "--zeta", "0.1", "--friction", "linear:0.15",
                            "--json"], capsys)
    assert code == 0
    payload = json.loads(out)
    direct = simulate(rigid_base(0.1), Slider(3.0, friction=LinearFriction(0.15)), record=False)
    assert payload["verdict"] == direct.verdict.value
    assert payload["friction"]["law"] == "linear" and payload["friction"]["delta"] == 0.15
    # Routh-Hurwitz on the rigid base: unstable since delta = 0.15 > zeta = 0.1, growth 0.05
    assert payload["steady_sliding_stable"] is False
    assert payload["growth_rate"] == pytest.approx(0.05, rel=1e-9)


@pytest.mark.parametrize(("zeta", "delta"), [(0.1, 0.04), (0.2, -0.05)])
def test_boundary_with_the_linear_law_meets_its_closed_form(zeta: float, delta: float) -> None:
    result = stick_slip_boundary([zeta], "none", friction=LinearFriction(delta), rtol=1e-8)
    expected = critical_lambda_linear(zeta, delta)
    assert result.critical_lambda[0] == pytest.approx(expected, rel=1e-6)
    assert result.analytic()["eq36_linear"][0] == expected


def test_map_with_a_law_agrees_with_simulate_cell_by_cell() -> None:
    law = LinearFriction(0.03)
    lams, zetas = [0.5, 1.2, 3.0], [0.05, 0.2]
    result = occurrence_map(lams, zetas, "optimal", friction=law,
                            execution=ExecutionOptions(backend="serial"))
    for i, lam in enumerate(lams):
        for j, zeta in enumerate(zetas):
            run = simulate(elastic_foundation(zeta, optimal_foundation_fit(zeta)),
                           Slider(lam, friction=law), record=False)
            assert int(result.verdict[i, j]) == run.verdict.code
    assert "linear" in result.dataset.attrs["friction"]
    assert "friction" in result.configuration


def test_a_coulomb_map_keeps_its_configuration() -> None:
    # the fingerprint (resume stores) of a Coulomb map does not mention friction at all
    result = occurrence_map([1.0], [0.1], "none", execution=ExecutionOptions(backend="serial"))
    assert "friction" not in result.configuration


@pytest.mark.parametrize("zeta", [0.01, 0.1, 0.3])
def test_critical_weakening_of_the_rigid_base_is_zeta(zeta: float) -> None:
    assert critical_weakening(rigid_base(zeta)) == pytest.approx(zeta, rel=1e-9)


@pytest.mark.parametrize("zeta", [0.05, 0.2])
def test_critical_weakening_of_a_foundation_matches_routh_hurwitz(zeta: float) -> None:
    structure = elastic_foundation(zeta, optimal_foundation_fit(zeta))
    d_crit = critical_weakening(structure)
    assert routh_hurwitz_2dof(structure, -2.0 * d_crit * (1 - 1e-7))
    assert not routh_hurwitz_2dof(structure, -2.0 * d_crit * (1 + 1e-7))


def test_stability_tuning_beats_the_absorber_optimum(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["tune", "--zeta", "0.1", "--objective", "stability", "--json"], capsys)
    assert code == 0
    payload = json.loads(out)
    assert {"M", "K", "zeta_a", "delta_crit", "absorber_optimum"} <= set(payload)
    ref = payload["absorber_optimum"]
    assert ref["delta_crit"] == pytest.approx(
        critical_weakening(elastic_foundation(0.1, optimal_foundation_fit(0.1))), rel=1e-12)
    assert payload["delta_crit"] >= ref["delta_crit"] > 0.1  # the rigid base tolerates zeta
    assert payload["M"] <= optimal_foundation_fit(0.1).mass_ratio * (1 + 1e-12)
    found = Foundation(payload["M"], payload["K"], payload["zeta_a"])
    assert critical_weakening(elastic_foundation(0.1, found)) == pytest.approx(payload["delta_crit"])


def test_stability_tuning_respects_its_bounds() -> None:
    result = optimal_foundation_stability(0.05, mass_ratio_bounds=(0.5, 1.0),
                                          stiffness_ratio_bounds=(0.5, 2.0))
    assert 0.5 <= result.foundation.mass_ratio <= 1.0
    assert 0.5 <= result.foundation.stiffness_ratio <= 2.0


def test_physical_friction_converts_with_the_design_definitions(tmp_path: Path) -> None:
    # delta = sigma W / (2 sqrt(m k)); u = v / V; f = (mu - mu_k) / (mu_s - mu_k)
    base = {"mass": 2.0, "stiffness": 5e4, "damping": 20.0, "mu_s": 0.5, "mu_k": 0.3, "load": 150.0,
            "speed": 0.05}
    linear = physical_friction_from_config({"law": "linear", "slope": "0.02 s/m"})
    slider = PhysicalSystem(**base, friction=linear).slider()
    assert slider.friction == LinearFriction(0.02 * 150.0 / (2 * math.sqrt(2.0 * 5e4)))
    (tmp_path / "curve.csv").write_text("v,mu\n0,0.5\n0.05,0.4\n0.1,0.3\n")
    table = physical_friction_from_config({"law": "table", "table": "curve.csv"}, base_dir=tmp_path)
    law = PhysicalSystem(**base, friction=table).slider().friction
    assert isinstance(law, TableFriction)
    assert np.allclose(law.u, [0.0, 1.0, 2.0]) and np.allclose(law.f, [1.0, 0.5, 0.0])
    with pytest.raises(ValueError, match="slope"):
        physical_friction_from_config({"law": "linear", "slope": "2 kg"})


@pytest.mark.slow  # 12 s: out of the default run (kept under ten minutes)
def test_design_reports_the_stability_margin(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = tmp_path / "machine.toml"
    config.write_text(
        '[system]\nm = "2 kg"\nk = "50 kN/m"\nc = "20 N*s/m"\nmu_s = 0.5\nmu_k = 0.3\n'
        'load = "150 N"\nspeed = "0.05 m/s"\n\n[friction]\nlaw = "linear"\nslope = "0.1 s/m"\n'
    )
    code, out, _ = run_cli(["design", "--config", str(config), "--json"], capsys)
    assert code == 0
    stab = json.loads(out)["stability"]
    delta = 0.1 * 150.0 / (2 * math.sqrt(2.0 * 5e4))
    zeta = 20.0 / (2 * math.sqrt(2.0 * 5e4))
    assert stab["rigid"]["delta_local"] == pytest.approx(delta)
    assert stab["rigid"]["delta_crit"] == pytest.approx(zeta, rel=1e-9)
    assert stab["rigid"]["stable"] is (delta < zeta)
    assert stab["rigid"]["sigma_crit"] == pytest.approx(zeta * 2 * math.sqrt(2.0 * 5e4) / 150.0, rel=1e-9)
