"""``design`` says what degenerate inputs and undecided runs are (issue 29, items 5 and 6; issue 32.7).

An undamped slider (no ``--c``) is said to be one and gets the exact limits of Eq. (36); a
search that ends at a bound of its range says so instead of printing the bound; an
undetermined verdict says why and how to decide it (``--t-max``); the text has no "-0" and
no doubled foundation line; long runs report their progress.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from stickslip import PhysicalSystem
from stickslip.analysis.design import design_foundation
from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.theory import critical_lambda_exact, optimal_foundation_fit
from stickslip.cli.design_command import format_report
from tests.cli_helpers import run_cli

# the example of design --help before this fix: no --c, so c = 0
NO_C = ["--m", "2 kg", "--k", "50 kN/m", "--mu-s", "0.5", "--mu-k", "0.3", "--load", "500 N",
        "--speed", "5 cm/s", "--no-stick-slip-optimum"]
WITH_C = [*NO_C, "--c", "20 N*s/m"]


def test_help_example_gives_the_damping(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["design", "--help"], capsys)
    assert code == 0
    assert '--c "20 N*s/m"' in " ".join(out.split())


def test_undamped_slider_is_said_and_gets_the_exact_limits(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["design", *NO_C, "--json"], capsys)
    assert code == 0, err
    d = json.loads(out)
    assert d["system"]["c"] == 0.0 and d["damping_given"] is False
    # reference: Eq. (36) at zeta = 0 has the limit lambda_c = 0 (stick-slip at every V and W)
    assert critical_lambda_exact(0.0) == 0.0
    for row in ("rigid_exact", "rigid_simulation"):
        assert d["critical_lambda"][row] == 0.0
        assert d["critical_speed"][row] is None  # infinite: every speed
        assert d["critical_load"][row] == 0.0
    assert "lowest searched" in d["critical_note"]["rigid_simulation"]
    assert any(w.startswith("c = 0 (undamped") for w in d["warnings"])
    text = format_report(d)
    assert "c = 0 (undamped, zeta = 0): no --c given" in text
    # before: "rigid_simulation lambda_c=0.001 V_c=316.2 m/s W_c=0.07906 N" (the search's bound)
    assert "316.2" not in text and "0.07906" not in text
    assert "rigid_simulation         lambda_c=0: stick-slip at every belt speed" in text
    assert "tolerates no friction weakening at all" in text  # not "slope down to -0 s/m"


def test_text_has_no_negative_zero_and_one_foundation_line(capsys: pytest.CaptureFixture[str]) -> None:
    for args, zeta in ((NO_C, 0.0), (WITH_C, 20.0 / (2.0 * math.sqrt(1e5)))):
        code, out, _ = run_cli(["design", *args], capsys)
        assert code == 0
        assert not re.search(r"-0(?![.\d])", out), out  # "-0" alone, not "-0.5" or "-0.03"
        assert "1.4999999999999998" not in out
        # the recommended foundation, Eqs. (28)-(30) at this zeta (m = 2 kg): printed once
        assert out.count(f"m_a={optimal_foundation_fit(zeta).mass_ratio * 2.0:.4g} kg") == 1
    assert "slider damping" not in out  # c given: nothing to say


def test_a_search_ending_at_its_bound_says_so() -> None:
    # zeta = 0.0316, lambda_c = 0.69 (Eq. 36), but the search is told to stop at lambda = 0.04
    system = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05 * 632.5)  # lambda = 0.01
    d = design_foundation(system, lam_max=0.02).to_dict()
    assert critical_lambda_exact(system.zeta) > 0.04
    for row in ("rigid_simulation", "foundation_simulation"):
        assert d["critical_lambda"][row] is None and d["critical_speed"][row] is None
        assert "the search's upper bound" in d["critical_note"][row]
    # and the lower bound: zeta = 1e-8 has lambda_c = 3.5e-4 (Eq. 36), below the search's 1e-3
    tiny = PhysicalSystem(mass=2.0, stiffness=50e3, damping=2e-8 * math.sqrt(1e5), mu_s=0.5, mu_k=0.3,
                          load=500.0, speed=0.05)
    assert critical_lambda_exact(tiny.zeta) < 1e-3
    d = design_foundation(tiny).to_dict()
    assert d["critical_lambda"]["rigid_simulation"] is None
    assert "the search's lower bound" in d["critical_note"]["rigid_simulation"]
    assert "lambda_c=         -" in format_report(d)


def test_undetermined_verdict_says_why_and_how(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["design", *WITH_C, "--t-max", "1", "--json"], capsys)
    assert code == 0, err
    d = json.loads(out)
    assert d["verdict"]["rigid"]["simulation"] == "undetermined"
    assert d["verdict_status"]["rigid"]["status"] == "t-max" and d["t_max"] == 1.0
    why = [w for w in d["warnings"] if "on the rigid base is undetermined" in w]
    assert why and "time horizon" in why[0] and "--t-max" in why[0] and "try 10" in why[0]
    code, out, err = run_cli(["design", *WITH_C, "--t-max", "0"], capsys)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and "--t-max" in err


def test_progress_reports_stages_and_runs(capsys: pytest.CaptureFixture[str]) -> None:
    system = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05)
    calls: list[tuple[str, int]] = []
    design_foundation(system, progress=lambda stage, runs: calls.append((stage, runs)),
                      options=EngineOptions())
    stages = list(dict.fromkeys(stage for stage, _ in calls))
    assert stages[:3] == ["verdicts at the operating point", "critical speed and load, rigid base",
                          "critical speed and load, with foundation"]
    runs = [n for _, n in calls]
    assert runs == sorted(runs) and runs[-1] > 20  # every run counted, never backwards
    # not a terminal (the test's captured stderr): no progress drawn
    code, _, err = run_cli(["design", *WITH_C], capsys)
    assert code == 0 and err == ""


def test_machine_file_undetermined_verdict_says_why(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    from tests.test_cli_machine import write_structure_file

    machine = write_structure_file(tmp_path / "chain3.toml")
    code, out, err = run_cli(["design", "--config", str(machine), "--t-max", "1"], capsys)
    assert code == 0, err
    assert ": undetermined" in out
    assert "undetermined because: time horizon reached" in out and "--t-max 10 (now 1)" in out
    # past the speeds where steady sliding is proven within this horizon the runs are
    # undetermined: the critical speed is where the proof ends, and it says so (before: the
    # undetermined runs counted as steady, and the search's bound was reported)
    assert "steady sliding proven at the runs above V_c=" in out
    assert "the run just past it is undetermined, not proven stick-slip" in out
    assert "run(s) undetermined" in out and "V_c=0 m/s" not in out
    d = json.loads(run_cli(["design", "--config", str(machine), "--t-max", "1", "--json"], capsys)[1])
    assert d["status"] == "t-max" and d["t_max"] == 1.0


def test_flags_that_replace_file_values_are_named(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit: the flags of one machine and the file of another were merged key
    # by key without a word (m, k from the flags, c from the file: a damping ratio of neither)
    machine = tmp_path / "base.toml"
    machine.write_text('mu_s = 0.3\nmu_k = 0.2\nload = "1 N"\nspeed = "5 cm/s"\nm = "1 kg"\n'
                       'k = "1 N/m"\nc = "0.2 N*s/m"\n')
    code, out, err = run_cli(["design", "--m", "2 kg", "--k", "50 kN/m", "--config", str(machine),
                              "--no-stick-slip-optimum", "--json"], capsys)
    assert code == 0, err
    warnings = json.loads(out)["warnings"]
    assert any(w.startswith("--m, --k replace the values of --config") and "c, " in w
               for w in warnings), warnings
    # and on stderr, where every command warns (an audit found design's on stdout, after the
    # report, and with --json nowhere but in the JSON)
    assert "stickslip: warning: --m, --k replace the values of --config" in err
    code, out, err = run_cli(["design", "--m", "2 kg", "--k", "50 kN/m", "--config", str(machine),
                              "--no-stick-slip-optimum"], capsys)
    assert code == 0 and "warning" not in out and err.startswith("stickslip: warning: --m, --k")
    code, out, err = run_cli(["design", "--config", str(machine), "--no-stick-slip-optimum",
                              "--json"], capsys)
    assert code == 0, err
    assert not any("replace the values" in w for w in json.loads(out)["warnings"])
