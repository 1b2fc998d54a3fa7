"""The app's frequency response and absorber tuning page (issue 31): ``stickslip tune`` in a browser.

Reference: the JSON of ``stickslip tune --zeta 0.05 --json`` (exact optimum and the paper's
fitted Eqs. 28-31, 33) and of ``stickslip frf --zeta 0.05 --dva optimal-exact --json`` (the
peak of the response with that foundation).
"""

from __future__ import annotations

import json
import re

import pytest

pytest.importorskip("streamlit", reason="the app extra (streamlit) is not installed")

from streamlit.testing.v1 import AppTest

from stickslip.app.figures import fmt
from stickslip.app.tuning_page import tuning
from stickslip.cli import app_command
from tests.cli_helpers import run_cli

PAGE = "frequency response and absorber tuning"


def test_the_page_shows_the_command_lines_optimum(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["tune", "--zeta", "0.05", "--json"], capsys)
    assert code == 0
    cli = json.loads(out)
    at = AppTest.from_file(str(app_command.APP_SCRIPT), default_timeout=180.0)
    at.session_state["page"] = PAGE
    at.run()
    assert not at.exception and not at.error
    (table,) = [d.value for d in at.dataframe]
    for row, key in (("M", "M"), ("K", "K"), ("ζ_a", "zeta_a"), ("H_max", "H_max")):
        assert table.loc[row, "exact"] == fmt(cli[key])
        assert table.loc[row, "paper fit"] == fmt(cli["fitted"][key])
    assert len(at.get("image")) == 1


def test_the_response_peak_is_the_frf_commands(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["frf", "--zeta", "0.05", "--dva", "optimal-exact", "--json"], capsys)
    assert code == 0
    _, curves = tuning("0.05", "")
    assert curves.peak.h_max == pytest.approx(json.loads(out)["H_max"], rel=1e-12)


@pytest.mark.parametrize("zeta,mass_ratio,word", [
    ("abc", "", "could not convert"), ("-0.1", "", "ζ"), ("5", "", "no tuning is defined"),
    ("0.05", "0", "Mass ratio M"), ("0.05", "[x](http://e.com)", "Mass ratio M"),
])
def test_bad_inputs_are_one_line(zeta: str, mass_ratio: str, word: str) -> None:
    at = AppTest.from_file(str(app_command.APP_SCRIPT), default_timeout=180.0)
    at.session_state["page"] = PAGE
    at.session_state["tuning_zeta"] = zeta
    at.session_state["tuning_mass_ratio"] = mass_ratio
    at.run()
    assert not at.exception and not at.dataframe
    (error,) = [re.sub(r"\\(.)", r"\1", str(e.value)).replace("\u2060", "") for e in at.error]
    assert word in error and "\n" not in error
