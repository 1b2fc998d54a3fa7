"""``basin`` says why samples ended undetermined and which ``--t-max`` may decide them (issue 29.6)."""

from __future__ import annotations

import json

import pytest

from stickslip.analysis.theory import stick_slip_period
from tests.cli_helpers import run_cli

ARGS = ["basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "60", "--seed", "1"]


def test_undetermined_samples_are_counted_by_reason(capsys: pytest.CaptureFixture[str]) -> None:
    # tau = 3 is shorter than one stick-slip period (Eq. 34, undamped: 8.9 at lambda = 2.5):
    # no stick-slip cycle can be certified this soon
    assert stick_slip_period(2.5) > 3.0
    code, out, err = run_cli([*ARGS, "--t-max", "3", "--json"], capsys)
    assert code == 0, err
    d = json.loads(out)
    assert d["undetermined"] > 0 and d["fractions"]["stick-slip"] == 0.0
    assert sum(d["undetermined_by"].values()) == d["undetermined"]
    assert set(d["undetermined_by"]) <= {"t-max", "max-events", "max-steps", "unproven-cycle"}
    code, out, _ = run_cli([*ARGS, "--t-max", "3"], capsys)
    assert code == 0
    line = next(x for x in out.splitlines() if x.startswith("undetermined "))
    assert f"undetermined {d['undetermined']}:" in line
    assert "time horizon reached" in line and "--t-max 30 (now 3)" in line


def test_no_line_when_every_sample_is_decided(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli([*ARGS, "--json"], capsys)
    assert code == 0, err
    d = json.loads(out)
    assert d["undetermined"] == 0 and d["undetermined_by"] == {}
    code, out, _ = run_cli(ARGS, capsys)
    assert code == 0 and "undetermined " not in out
