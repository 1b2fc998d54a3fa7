"""``stickslip stability`` and the machine-file contract of normal-load coupling (issue 34).

The brake pad of examples/brake_pad is the minimal model of Hoffmann et al. (2002): its
undamped flutter boundary is the closed form ((k11 - k22 - k_n)^2 + 4 k12^2) / (-4 k12 k_n)
of stickslip.analysis.contact.squeal_minimal_model, evaluated here from the file's own numbers.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from stickslip.io.machine_file import read_machine_file
from tests.cli_helpers import STRIBECK_SLIDER, run_cli, stribeck_slider_file

ROOT = Path(__file__).resolve().parents[1]
BRAKE_PAD = ROOT / "examples" / "brake_pad"
#: examples/brake_pad/K.csv and machine.toml: k11 = 8e7, k12 = -1.5e7, k22 = 2.5e7, k_n = 5e7 N/m
K11, K12, K22, KN = 8.0e7, -1.5e7, 2.5e7, 5.0e7
CLOSED_FORM = ((K11 - K22 - KN) ** 2 + 4 * K12**2) / (-4 * K12 * KN)


def test_stability_json_gives_the_contract_keys(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["stability", "--config", str(BRAKE_PAD / "machine.toml"), "--json"],
                             capsys)
    assert code == 0, err
    p = json.loads(out)
    assert len(p["eigenvalues"]) == 4 and all(len(pair) == 2 for pair in p["eigenvalues"])
    assert p["stable"] is False and p["verdict"] == "unstable"  # mu_k = 0.4 above both boundaries
    assert p["critical_mu_undamped"] == pytest.approx(CLOSED_FORM, rel=1e-11)
    # unequal damping (40 and 4 N s/m) lowers the boundary below the undamped one
    assert p["critical_mu"] < p["critical_mu_undamped"]
    assert p["critical"]["kind"] == "flutter" and p["critical_undamped"]["modes"] == [1, 2]
    growing = [pair for pair in p["eigenvalues"] if pair[0] > 0]
    assert len(growing) == 2 and growing[0][1] == pytest.approx(-growing[1][1])
    # Coulomb law: speed and load do not change the eigenvalues, unstable over both grids
    ranges = p["operating_ranges"]
    assert ranges["unstable_speeds_m_per_s"] == [[0.5, 50.0]]
    assert ranges["unstable_loads_N"] == [[pytest.approx(100.0), pytest.approx(10000.0)]]


def test_stability_text_and_root_locus(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    locus = tmp_path / "locus.png"
    code, out, err = run_cli(["stability", "--config", str(BRAKE_PAD / "machine.toml"),
                              "--plot", str(locus)], capsys)
    assert code == 0, err
    assert "verdict     UNSTABLE" in out and "critical mu 0.3029" in out
    assert f"undamped    {CLOSED_FORM:.8g}" in out and "modes 1 and 2" in out
    assert f"figure      {locus}" in out and locus.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_stability_map_figure(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    grid = tmp_path / "map.png"
    code, out, err = run_cli(["stability", "--config", str(BRAKE_PAD / "machine.toml"),
                              "--map", str(grid)], capsys)
    assert code == 0, err
    assert f"figure      {grid}" in out and grid.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _copy(tmp_path: Path, replace: dict[str, str] | None = None, extra: str = "") -> Path:
    for name in ("M.csv", "K.csv", "C.csv"):
        shutil.copy(BRAKE_PAD / name, tmp_path / name)
    text = (BRAKE_PAD / "machine.toml").read_text()
    for old, new in (replace or {}).items():
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "machine.toml"
    path.write_text(text + extra)
    return path


@pytest.mark.parametrize("replace, extra, why", [
    ({"normal_dof = 1 ": "normal_dof = 0 "}, "", "normal_dof = 0 is the contact_dof"),
    ({"normal_dof = 1 ": "normal_dof = 2 "}, "", "normal_dof = 2 is beyond the 2 DOF"),
    ({"normal_dof = 1 ": "normal_dof = -1 "}, "", "normal_dof = -1 must be a whole number"),
    ({'normal_stiffness = "5e7 N/m"': 'normal_stiffness = "-5e7 N/m"'}, "", "must be positive"),
    ({'normal_stiffness = "5e7 N/m"': 'normal_stiffness = "5 kg"'}, "", "normal_stiffness"),
    ({'normal_stiffness = "5e7 N/m"': 'normal_stiffnes = "5e7 N/m"'}, "", "unknown keys normal_stiffnes"),
    ({'normal_stiffness = "5e7 N/m"': ""}, "", "normal_dof = 1 needs [contact] normal_stiffness"),
    ({}, 'normal_damping = "-1 N*s/m"\n', "normal_damping = -1.0 must not be negative"),
    # a constant coefficient (Hoffmann et al. 2002 use one): the analysis needs mu_k alone
    ({"mu_k = 0.4": "mu_k = 0.5"}, "", "mu_s = mu_k = 0.5: the model needs static friction "
     "above kinetic friction; the eigenvalues of steady sliding depend on mu_k alone"),
])
def test_bad_contact_is_refused_in_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                            replace: dict[str, str], extra: str, why: str) -> None:
    path = _copy(tmp_path, replace, extra)
    code, out, err = run_cli(["stability", "--config", str(path), "--json"], capsys)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and why in err, err
    assert str(path) in err


# every command but the absorber tuning runs a contact machine (tests/test_contact_*.py)
def test_tune_refuses_normal_coupling(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _copy(tmp_path, extra="")
    text = path.read_text()
    path.write_text(text.replace("[contact]", '[absorber]\nmass = "0.01 kg"\nattach_dof = 0\n\n'
                                 "[contact]"))
    code, out, err = run_cli(["tune", "--config", str(path)], capsys)
    assert code == 2, (out, err)
    assert err.count("\n") == 1
    assert "assumes a rigid contact" in err and "`design`, `map`, `boundary`" in err


def test_a_file_without_contact_reads_as_before_and_a_contact_table_alone_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    slideway = read_machine_file(ROOT / "examples" / "slideway" / "machine.toml")
    assert not slideway.has_contact and slideway.contact() is None and slideway.contact_table is None
    flat = tmp_path / "flat.toml"
    flat.write_text('mu_s = 0.5\nmu_k = 0.4\nload = "1 kN"\nspeed = "1 m/s"\nm = "1 kg"\n'
                    'k = "1e6 N/m"\nc = "40 N*s/m"\n\n[contact]\ntangential_stiffness = "1e8 N/m"\n')
    code, _, err = run_cli(["tune", "--config", str(flat)], capsys)
    assert code == 2 and "assumes a rigid contact" in err


def test_flat_machine_without_contact_has_no_coupling(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    # the paper's slider, no normal DOF: mu enters nowhere (Coulomb), so no critical mu; the
    # 1 DOF eigenvalues are -zeta w +- i w sqrt(1 - zeta^2) with w = 1000 rad/s, zeta = 0.02
    flat = tmp_path / "flat.toml"
    flat.write_text('mu_s = 0.5\nmu_k = 0.4\nload = "1 kN"\nspeed = "1 m/s"\nm = "1 kg"\n'
                    'k = "1e6 N/m"\nc = "40 N*s/m"\n')
    code, out, err = run_cli(["stability", "--config", str(flat), "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["stable"] is True and p["critical_mu"] is None and p["critical_mu_undamped"] is None
    (re1, im1), (re2, im2) = p["eigenvalues"]
    assert re1 == pytest.approx(-20.0, rel=1e-12) and re2 == pytest.approx(-20.0, rel=1e-12)
    assert im2 == pytest.approx(1000.0 * (1 - 0.02**2) ** 0.5, rel=1e-12) and im1 == pytest.approx(-im2)


def test_stability_refuses_bad_flags_before_work(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = str(BRAKE_PAD / "machine.toml")
    code, _, err = run_cli(["stability", "--config", config, "--mu-max", "0"], capsys)
    assert code == 2 and "--mu-max 0.0 must be above 0" in err
    existing = tmp_path / "locus.png"
    existing.write_bytes(b"keep")
    code, _, err = run_cli(["stability", "--config", config, "--plot", str(existing)], capsys)
    assert code == 2 and "exists" in err and existing.read_bytes() == b"keep"
    code, _, err = run_cli(["stability", "--config", config, "--plot", str(tmp_path / "a.txt")], capsys)
    assert code == 2 and "must end in one of" in err


def test_the_apps_machine_builder_refuses_normal_coupling_too() -> None:
    # the web app builds machines through machine_from_file, not through load_machine_file
    from stickslip.io.machine_file import machine_from_file

    machine_file = read_machine_file(BRAKE_PAD / "machine.toml")
    values = {"mu_s": 0.5, "mu_k": 0.4, "load": 1000.0, "speed": 5.0}
    with pytest.raises(ValueError, match="assumes a rigid contact"):
        machine_from_file(machine_file, values)
    machine, reduction = machine_from_file(machine_file, values, normal_coupling=True)
    assert machine.n_dof == 2 and reduction is None
    assert machine_file.contact().normal_stiffness == 5e7 and machine_file.contact().normal_dof == 1


def test_a_search_below_the_operating_mu_says_so(capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit: "UNSTABLE" at mu = 0.4 beside "critical mu none up to mu = 0.1",
    # with no word that the search never reached the operating point
    code, out, err = run_cli(["stability", "--config", str(BRAKE_PAD / "machine.toml"), "--mu-max", "0.1"],
                             capsys)
    assert code == 0, err
    line = next(x for x in out.splitlines() if x.startswith("critical mu"))
    assert "none up to mu = 0.1" in line
    assert "the operating mu = 0.4 lies above the searched range: raise --mu-max" in line


def test_the_unstable_ranges_end_at_the_closed_form_boundaries(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # one DOF (m = 1 kg, k = 1e4 N/m, c = 20 N s/m) with the exponential Stribeck law
    # mu = mu_k + (mu_s - mu_k) exp(-v / v_s): steady sliding loses stability where the net
    # damping c + W mu'(V) vanishes, mu'(V) = -(mu_s - mu_k) / v_s exp(-V / v_s). Closed forms:
    # V_H = v_s ln(W (mu_s - mu_k) / (v_s c)) at W = 100 N, W_H = c v_s exp(V / v_s) /
    # (mu_s - mu_k) at V = 0.1 m/s. Before, the ranges ended at grid points (0.1496 for
    # 0.1498 m/s, 37.6 for 36.9 N; an independent audit found a 2-DOF pad 10 % off in load).
    import math

    mu_s, mu_k, v_s, c, w, v = (STRIBECK_SLIDER[k] for k in ("mu_s", "mu_k", "v_s", "c", "w", "v"))
    config = stribeck_slider_file(tmp_path / "slider.toml")
    code, out, err = run_cli(["stability", "--config", str(config), "--json"], capsys)
    assert code == 0, err
    ranges = json.loads(out)["operating_ranges"]
    v_h = v_s * math.log(w * (mu_s - mu_k) / (v_s * c))
    w_h = c * v_s * math.exp(v / v_s) / (mu_s - mu_k)
    (speeds,) = ranges["unstable_speeds_m_per_s"]
    assert speeds[0] == pytest.approx(0.01) and speeds[1] == pytest.approx(v_h, rel=1e-8)
    (loads,) = ranges["unstable_loads_N"]
    assert loads[0] == pytest.approx(w_h, rel=1e-8) and loads[1] == pytest.approx(1000.0)


def test_a_law_unstable_by_its_slope_alone_has_no_critical_mu(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit: "critical mu 0 (unstable at mu = 0)" for a Stribeck pad whose
    # structure alone is stable; the slope mu'(V) N is negative damping at the contact, which
    # no friction coefficient of mode coupling describes. Reference: one DOF, net damping
    # c + W mu'(V) = 20 - 100 * 4 exp(-2) < 0 (the closed form of the test above)
    config = stribeck_slider_file(tmp_path / "slider.toml")
    code, out, err = run_cli(["stability", "--config", str(config)], capsys)
    assert code == 0, err
    line = next(x for x in out.splitlines() if x.startswith("critical mu"))
    assert line.startswith("critical mu - (unstable at mu = 0")
    assert "the friction law's slope (-0.541341 s/m at V" in line  # -4 exp(-2)
    assert "the structure alone is stable" in line
