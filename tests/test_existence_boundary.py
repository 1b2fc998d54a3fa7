"""``boundary --criterion existence``: lambda_exist(zeta), where a stick-slip cycle first exists.

Sources: on the rigid base the breakaway state is unique, so a cycle exists exactly where the
start-up run stick-slips, above the root of Eq. (36); in general a start-up run that
stick-slips lands on a cycle, so ``lambda_exist <= lambda_startup`` (the gap is the bistable
band where only a disturbance leads to stick-slip).
"""

from __future__ import annotations

import json

import pytest

from stickslip import critical_lambda_exact, stick_slip_boundary

from .cli_helpers import run_cli


def test_rigid_base_existence_boundary_is_eq36() -> None:
    result = stick_slip_boundary([0.05, 0.2], "none", criterion="existence", n_scan=12, rtol=1e-6,
                                 existence_seeds=2)
    for j, zeta in enumerate((0.05, 0.2)):
        assert result.critical_lambda[j] == pytest.approx(critical_lambda_exact(zeta), rel=2e-6)


def test_existence_comes_no_later_than_the_startup_onset() -> None:
    startup = stick_slip_boundary([0.1], "optimal", n_scan=8, rtol=1e-4)
    exist = stick_slip_boundary([0.1], "optimal", criterion="existence", n_scan=8, rtol=1e-4,
                                existence_seeds=4)
    assert exist.critical_lambda[0] <= startup.critical_lambda[0] * (1 + 2e-4)


def test_existence_boundary_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["boundary", "--zeta", "0.1", "--criterion", "existence", "--scan", "8",
                              "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["criterion"] == "existence"
    assert payload["rows"][0]["critical_lambda"] == pytest.approx(critical_lambda_exact(0.1), rel=1e-5)
    code, out, err = run_cli(["boundary", "--zeta", "0.1", "--criterion", "nope"], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1
