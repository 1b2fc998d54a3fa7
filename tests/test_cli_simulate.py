"""The ``simulate`` command: JSON contract, figures, one-line errors with exit code 2."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from stickslip.analysis.theory import stick_slip_period
from tests.cli_helpers import run_cli as _run

JSON_KEYS = {"verdict", "certificate", "n_stick", "period", "amplitude", "max_velocity", "t_end",
             "status"}




def test_json_is_one_object_with_the_contract_keys(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run(["simulate", "--lam", "1", "--zeta", "0", "--json"], capsys)
    assert code == 0
    payload = json.loads(out)  # exactly one JSON document on stdout
    assert JSON_KEYS <= payload.keys()
    assert payload["verdict"] == "stick-slip"
    # reference: paper Eq. (34) for the undamped rigid base
    assert payload["period"] == pytest.approx(stick_slip_period(1.0), rel=1e-9)


def test_json_with_foundation(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run(
        ["simulate", "--lam", "3", "--zeta", "0.1", "--dva", "optimal", "--json"], capsys
    )
    payload = json.loads(out)
    assert code == 0 and payload["verdict"] == "steady-sliding"
    assert payload["period"] is None and payload["amplitude"] is None
    assert payload["foundation"]["M"] == pytest.approx(2.824)  # Eq. (28) at zeta = 0.1


def test_k_scale_and_explicit_foundation_agree(capsys: pytest.CaptureFixture[str]) -> None:
    _, a, _ = _run(["simulate", "--lam", "5", "--zeta", "0.1", "--dva", "2,1,1", "--k-scale",
                    "2", "--json"], capsys)
    _, b, _ = _run(["simulate", "--lam", "5", "--zeta", "0.1", "--dva", "2,2,1", "--json"], capsys)
    pa, pb = json.loads(a), json.loads(b)
    assert pa["verdict"] == pb["verdict"] and pa["t_end"] == pb["t_end"]


def test_plot_is_written(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    target = tmp_path / "sub" / "run.png"
    code, out, _ = _run(["simulate", "--lam", "15", "--zeta", "0.1", "--dva", "optimal",
                         "--plot", str(target)], capsys)
    assert code == 0
    assert target.stat().st_size > 10_000
    assert "stick-slip" in out


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--lam", "-1", "--zeta", "0.1"], "lambda=-1.0 must be positive"),
        (["--lam", "0", "--zeta", "0.1"], "lambda=0.0 must be positive"),
        (["--lam", "nan", "--zeta", "0.1"], "must be finite"),
        (["--lam", "inf", "--zeta", "0.1"], "must be finite"),
        (["--lam", "abc", "--zeta", "0.1"], "--lam"),
        (["--lam", "1", "--zeta", "-0.2"], "zeta=-0.2 must not be negative"),
        (["--lam", "1", "--zeta", "0.1", "--gamma", "-1"], "gamma"),
        (["--lam", "1", "--zeta", "0.1", "--dva", "1,2"], "--dva '1,2'"),
        (["--lam", "1", "--zeta", "0.1", "--dva", "a,b,c"], "must be numbers"),
        (["--lam", "1", "--zeta", "0.1", "--dva", "0,1,1"], "M=0.0 must be positive"),
        (["--lam", "1", "--zeta", "0.1", "--dva", "1,-1,1"], "K=-1.0 must be positive"),
        (["--lam", "1", "--zeta", "0.1", "--dva", "1,1,-1"], "zeta_a=-1.0"),
        (["--lam", "1", "--zeta", "0.1", "--k-scale", "2"], "needs a foundation"),
        (["--lam", "1", "--zeta", "0.1", "--t-max", "0"], "t_max"),
        (["--lam", "1"], "Missing option '--zeta'"),
    ],
)
def test_bad_input_is_one_line_exit_2(args: list[str], needle: str,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = _run(["simulate", *args], capsys)
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert needle in lines[0]


def test_bad_input_writes_no_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    target = tmp_path / "keep.png"
    target.write_bytes(b"precious")
    code, _, _ = _run(["simulate", "--lam", "-1", "--zeta", "0.1", "--plot", str(target)], capsys)
    assert code == 2
    assert target.read_bytes() == b"precious"


def test_console_script_has_no_traceback() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "stickslip.cli.main", "simulate", "--lam", "x", "--zeta", "1"],
        capture_output=True, text=True, check=False,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
