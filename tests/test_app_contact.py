"""The machine page takes a machine with its contact: the numbers are the command line's.

The page builds the machine from the uploaded files (``stickslip.app.machine_contact``) as
``stickslip stability --config`` and ``stickslip simulate --config`` build it from disk; the
references here are those commands' ``--json`` answers on the same files, and for the
Jenkins element Eq. (34) of the paper (the period of the rigid contact, which a stiff damped
element gives back to 1e-3, as ``tests/test_cli_contact_simulate.py`` checks for the CLI).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from stickslip.app.machine_contact import (
    APPLIES,
    contact_machine,
    history_window,
    plain_title,
    simulate_in_worker,
    stability_in_worker,
)
from stickslip.app.machine_page import uploaded_machine_file
from tests.cli_helpers import run_cli

BRAKE_PAD = Path(__file__).resolve().parents[1] / "examples" / "brake_pad"
#: The paper's slider (m = 1 kg, k = 1 N/m, lambda = 0.5) on a stiff damped Jenkins element.
JENKINS = ('mu_s = 0.3\nmu_k = 0.2\nload = "1 N"\nspeed = "0.2 m/s"\nm = "1 kg"\nk = "1 N/m"\n'
           'c = "0 N*s/m"\n\n[contact]\ntangential_stiffness = "1e4 N/m"\n'
           'tangential_damping = "60 N*s/m"\n')


def _brake_pad_uploads() -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in BRAKE_PAD.iterdir()
            if p.suffix == ".csv" or p.name == "machine.toml"}


def test_the_brake_pads_analysis_is_stickslip_stabilitys(capsys: pytest.CaptureFixture[str]) -> None:
    cm = contact_machine(uploaded_machine_file(_brake_pad_uploads()))
    assert cm.normal_index == 1
    result, locus = stability_in_worker(cm)
    code, out, err = run_cli(["stability", "--config", str(BRAKE_PAD / "machine.toml"), "--json"],
                             capsys)
    assert code == 0, err
    cli = json.loads(out)
    page = result.to_dict()
    assert {key: page[key] for key in page} == {key: cli[key] for key in page}
    # docs/brake_squeal.md: critical mu 0.30291579, undamped 0.30833333 (closed form)
    assert f"{page['critical_mu']:.8g}" == "0.30291579"
    assert page["critical_mu_undamped"] == pytest.approx(0.308333333333, rel=1e-10)
    assert locus.critical_mu == pytest.approx(page["critical_mu"], rel=1e-12)


def test_a_jenkins_element_is_analysed_as_stickslip_stability_does(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = tmp_path / "jenkins.toml"
    config.write_text(JENKINS)
    code, out, err = run_cli(["stability", "--config", str(config), "--json"], capsys)
    assert code == 0, err
    cli = json.loads(out)
    result, _ = stability_in_worker(contact_machine(uploaded_machine_file(
        {"jenkins.toml": JENKINS.encode()})))
    # the undamped slider (c = 0) keeps its pair +-i on the axis: the element (no normal DOF,
    # Coulomb) decouples, k_t de + c_t de' = 0, and adds -k_t / c_t = -166.67 1/s
    assert result.verdict == cli["verdict"] == "marginal"
    assert [[v.real, v.imag] for v in result.eigenvalues] == cli["eigenvalues"]
    assert sorted(v.real for v in result.eigenvalues)[0] == pytest.approx(-1e4 / 60.0, rel=1e-9)
    assert sorted(abs(v.imag) for v in result.eigenvalues)[-1] == pytest.approx(1.0, rel=1e-12)


def test_the_jenkins_run_is_stickslip_simulates(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    config = tmp_path / "jenkins.toml"
    config.write_text(JENKINS)
    code, out, err = run_cli(["simulate", "--config", str(config), "--json"], capsys)
    assert code == 0, err
    cli = json.loads(out)
    run = simulate_in_worker(contact_machine(uploaded_machine_file(
        {"jenkins.toml": JENKINS.encode()})))
    assert {key: run.payload[key] for key in run.payload} == {key: cli[key] for key in run.payload}
    period = 2.0 * math.pi * (1.0 + (0.5 - math.atan(0.5)) / math.pi)  # Eq. (34), s
    assert run.payload["verdict"] == "stick-slip"
    assert run.payload["period_s"] == pytest.approx(period, rel=1e-3)
    t = run.history["t_s"]
    # the last four periods, ending where the run ended (this run is shorter: from its start)
    assert t[-1] == pytest.approx(cli["t_end_s"], rel=1e-12)
    assert cli["t_end_s"] < 4 * cli["period_s"] and t[0] == 0.0
    assert "stick" in run.history["mode"] and "normal_m" not in run.history


def test_the_window_without_a_period_is_natural_periods_and_starts_at_zero() -> None:
    assert history_window(None, 100.0, 2.0 * math.pi) == pytest.approx((96.0, 100.0))
    assert history_window(None, 1.0, 2.0 * math.pi) == (0.0, 1.0)
    assert history_window(0.5, 10.0, 1.0) == pytest.approx((8.0, 10.0))


def test_bad_contact_values_are_one_line_naming_the_upload() -> None:
    files = _brake_pad_uploads()
    files["machine.toml"] = files["machine.toml"].replace(b'"5e7 N/m"', b'"-5e7 N/m"')
    with pytest.raises(ValueError) as info:
        contact_machine(uploaded_machine_file(files))
    message = str(info.value)
    assert message.startswith("machine file 'machine.toml'") and "must be positive" in message
    assert len(message.splitlines()) == 1 and str(BRAKE_PAD) not in message


def test_a_refused_friction_table_of_a_flat_contact_machine_names_the_upload_once() -> None:
    # an audit: "machine file 'machine.toml': machine file 'machine.toml': [friction] table ..."
    files = {"machine.toml": (JENKINS + '[friction]\nlaw = "table"\ntable = "mu.csv"\n').encode(),
             "mu.csv": b"v,mu\n0,0.3\n0.1,x\n"}
    with pytest.raises(ValueError) as info:
        contact_machine(uploaded_machine_file(files))
    message = str(info.value)
    assert message.count("machine file 'machine.toml'") == 1 and "not two numbers" in message


def test_the_info_line_names_the_analyses_that_apply() -> None:
    for words in ("complex-eigenvalue analysis", "time history", "design", "absorbers",
                  "bifurcation diagram"):
        assert words in APPLIES


def test_a_machine_name_with_dollars_draws_as_typed() -> None:
    """A ``[structure] name`` is the user's text: Matplotlib must not read it as mathtext."""
    import io

    from stickslip.plot.contact.history import contact_history_plot

    name = r"pad $\frac$ x"  # as mathtext this fails to parse (checked: ParseSyntaxException)
    history = {"t_s": [0.0, 1.0], "tangential_m": [0.0, 1.0], "normal_force_N": [1.0, 0.0],
               "mode": ["stick", "separation"]}
    result = contact_history_plot(history, title=plain_title(name))
    result.figure.savefig(io.BytesIO(), format="png")
    assert result.figure.get_suptitle() == r"pad \$\frac\$ x"
