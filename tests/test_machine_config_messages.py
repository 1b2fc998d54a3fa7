"""A wrong unit in a machine file is named once (issue 32.7).

A load given in kg reported "--config 'x': --config 'x': load = '10 kg' has the wrong unit
...": the unit check names the file and key, and the command line named the file again.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.cli_helpers import run_cli

FLAT = """\
m = "0.538 kg"
k = "6957 N/m"
c = "5.746 N*s/m"
mu_s = 0.6
mu_k = 0.2
load = "10 kg"
speed = "0.1 m/s"
"""

STRUCTURE = """\
mu_s = 0.5
mu_k = 0.3
load = "10 kg"
speed = "1 cm/s"

[structure]
mass = [[2.0, 0.0], [0.0, 1.0]]
stiffness = [[3e4, -1e4], [-1e4, 2e4]]
rayleigh = [5.0, 1e-3]
contact_dof = 1
"""


@pytest.mark.parametrize("kind", ["flat", "structure"])
@pytest.mark.parametrize("command", [
    ["simulate"], ["cycles"], ["basin", "--samples", "10"], ["design"],
    ["map", "--speed", "0.01,0.02", "--load", "10,20", "--out", "vw.nc"],
])
def test_a_load_in_kg_is_refused_naming_the_file_once(command: list[str], kind: str, tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str],
                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    Path("m.toml").write_text(FLAT if kind == "flat" else STRUCTURE)
    code, out, err = run_cli([command[0], "--config", "m.toml", *command[1:]], capsys)
    assert code == 2 and out == ""
    assert err.strip() == ("stickslip: error: --config 'm.toml': load = '10 kg' has the wrong unit "
                           "for the normal load W: expected N (dimension [force]), got kg"), err
    assert not Path("vw.nc").exists()


@pytest.mark.parametrize("command", [["simulate"], ["stability"], ["cycles"], ["design"]])
def test_a_bad_friction_table_names_the_file_once(command: list[str], tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str],
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    # before: simulate and stability said "--config 'm.toml': --config 'm.toml': [friction]: ..."
    monkeypatch.chdir(tmp_path)
    Path("m.toml").write_text(FLAT.replace('"10 kg"', '"10 N"')
                              + '\n[friction]\nlaw = "stribeck"\nvs = 0.1\n')
    code, out, err = run_cli([command[0], "--config", "m.toml", *command[1:]], capsys)
    assert code == 2 and out == ""
    assert err.startswith("stickslip: error: --config 'm.toml': [friction]: unknown keys vs"), err
    assert err.count("--config 'm.toml'") == 1


@pytest.mark.parametrize("command", [["simulate"], ["stability"], ["cycles"], ["design"]])
def test_a_law_the_package_lacks_is_named(command: list[str], tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str],
                                         monkeypatch: pytest.MonkeyPatch) -> None:
    # a bad-input audit: law = "rate_state" (underscore) was reported as "lacks mu_s, mu_k"
    monkeypatch.chdir(tmp_path)
    Path("m.toml").write_text('load = "10 N"\nspeed = "1 mm/s"\nm = "1 kg"\nk = "8000 N/m"\n\n'
                              '[friction]\nlaw = "rate_state"\na = 0.01\n')
    code, out, err = run_cli([command[0], "--config", "m.toml", *command[1:]], capsys)
    assert code == 2 and out == ""
    assert err.strip() == ("stickslip: error: --config 'm.toml': [friction]: law = 'rate_state' is "
                           "not one of coulomb, linear, stribeck, table, rate-state, lugre"), err


def test_an_empty_value_is_said_empty(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                      monkeypatch: pytest.MonkeyPatch) -> None:
    # a bad-input audit: m = "" was reported as "lacks m"
    monkeypatch.chdir(tmp_path)
    Path("m.toml").write_text(FLAT.replace('"0.538 kg"', '""').replace('"10 kg"', '"10 N"'))
    code, out, err = run_cli(["simulate", "--config", "m.toml"], capsys)
    assert code == 2 and out == ""
    assert err.strip() == ("stickslip: error: --config 'm.toml': m = '' is empty; give a value "
                           "with its unit (e.g. m = \"2 kg\") or leave the key out"), err
