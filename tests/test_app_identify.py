"""The app's identification page (issue 31): ``stickslip identify`` on an uploaded record.

References: the JSON of ``stickslip identify examples/rig_record.csv --mass "1 kg" --load
"100 N" --speed "5 cm/s" --json`` (the command line on the same file: the page must give the
same fit), and the truth written in that record's header by ``tests/make_identify_example.py``
(k 10 kN/m, c 5 N s/m, mu_s 0.6, mu_k 0.4).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from stickslip.app.identify_page import KNOWN_INPUTS, identify_upload, slider_inputs
from tests.cli_helpers import run_cli

RECORD = Path(__file__).resolve().parents[1] / "examples" / "rig_record.csv"
KNOWN = {key: default for key, (_, default) in KNOWN_INPUTS.items()}


def test_an_uploaded_record_gives_the_command_lines_fit(capsys: pytest.CaptureFixture[str]) -> None:
    result = identify_upload(RECORD.read_bytes(), "rig_record.csv", KNOWN, "coulomb", "")
    code, out, _ = run_cli(["identify", str(RECORD), "--mass", "1 kg", "--load", "100 N",
                            "--speed", "5 cm/s", "--json"], capsys)
    assert code == 0
    cli = json.loads(out)["parameters"]
    for name in ("k", "c", "mu_s", "mu_k"):
        assert result.parameters[name].value == cli[name]["value"]
        assert result.parameters[name].stderr == cli[name]["stderr"]
    # the record's truth lies within four standard errors
    for name, truth in (("k", 1e4), ("c", 5.0), ("mu_s", 0.6), ("mu_k", 0.4)):
        p = result.parameters[name]
        assert abs(p.value - truth) < 4.0 * p.stderr, (name, p.value, p.stderr)
    # the machine file the page downloads is --write-config's, read back
    import tomllib

    config = tomllib.loads(result.to_config())
    assert config["system"]["k"] == f"{result.parameters['k'].value!r} N/m"


def test_the_fit_fills_the_slider_page_with_valid_inputs() -> None:
    from stickslip.app.inputs import parse_inputs

    result = identify_upload(RECORD.read_bytes(), "rig_record.csv", KNOWN, "linear", "")
    fields = slider_inputs(result)
    system, errors = parse_inputs(fields)
    assert system is not None and not errors, errors
    assert system.stiffness == result.parameters["k"].value
    assert system.mass == 1.0 and system.load == 100.0 and system.speed == pytest.approx(0.05)
    assert fields["friction_law"] == "linear"
    assert system.friction.slope == result.parameters["slope"].value


@pytest.mark.parametrize("content,known,law,columns,word", [
    (b"t,x\n0,hunter2\n", KNOWN, "coulomb", "", "data row 2: not all numbers"),
    (b"\xff\xfe", KNOWN, "coulomb", "", "not UTF-8"),
    (None, KNOWN | {"m": "-1 kg"}, "coulomb", "", "must be positive"),
    (None, KNOWN | {"speed": "5 kg"}, "coulomb", "", "wrong unit"),
    (None, KNOWN, "quadratic", "", "is not one of"),
    (None, KNOWN, "coulomb", "t=nothing", "has no column 'nothing'"),
])
def test_bad_uploads_and_inputs_are_one_line_without_contents(
        content: bytes | None, known: dict[str, str], law: str, columns: str, word: str) -> None:
    with pytest.raises(ValueError) as info:
        identify_upload(RECORD.read_bytes() if content is None else content, "/srv/x/rec.csv",
                        known, law, columns)
    message = str(info.value)
    assert word in message and len(message.splitlines()) == 1
    assert "hunter2" not in message and "/srv" not in message
