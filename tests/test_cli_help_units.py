"""Every command's rendered help shows its units and table names (issue 17, point 5).

Help used to go through Rich markup, which took bracketed text for style tags: ``basin
--config`` showed "(, )" for "([system], [friction])", ``design`` lost "[kg]" and "[m/s]" and
showed "slider mass ;". These tests render the help of every command as a user sees it (a
wide terminal) and look for the text the source gives, so anything swallowed fails.
"""

from __future__ import annotations

import click
import pytest
import typer

from stickslip.cli.design_command import UNIT_EXAMPLES, quantity_help
from stickslip.cli.main import app
from stickslip.model.units import QUANTITIES
from tests.cli_helpers import run_cli

ROOT = typer.main.get_command(app)
COMMANDS = sorted(ROOT.commands)  # type: ignore[attr-defined]


def _help(command: str, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> str:
    monkeypatch.setenv("COLUMNS", "200")
    code, out, err = run_cli([command, "--help"], capsys)
    assert code == 0, err
    return out


def _squeezed(text: str) -> str:
    """Text without any whitespace: the comparison ignores where the help was wrapped."""
    return "".join(text.split())


@pytest.mark.parametrize("command", COMMANDS)
def test_every_option_help_is_shown_whole(command: str, capsys: pytest.CaptureFixture[str],
                                          monkeypatch: pytest.MonkeyPatch) -> None:
    text = _help(command, capsys, monkeypatch)
    shown = _squeezed(text)
    cmd = ROOT.commands[command]  # type: ignore[attr-defined]
    for param in cmd.params:
        if isinstance(param, click.Option) and param.help:
            assert _squeezed(param.help) in shown, f"{command} {param.opts[0]}: {param.help!r}"
    for artefact in ("(,)", "[]", "()"):  # what was left of bracketed text
        assert artefact not in shown, f"{command} --help shows {artefact!r}"
    assert " ;" not in " ".join(text.split()), f"{command} --help lost the text before a ';'"


def test_design_help_names_every_unit(capsys: pytest.CaptureFixture[str],
                                      monkeypatch: pytest.MonkeyPatch) -> None:
    shown = _squeezed(_help("design", capsys, monkeypatch))
    for name, (_, unit, what) in QUANTITIES.items():  # what: the quantity named in the help
        text = quantity_help(name)
        assert text.startswith(what)
        assert _squeezed(text) in shown
        if unit:
            assert f"[{unit}]" in text and UNIT_EXAMPLES[unit] in text
        else:  # friction coefficients take a plain number, not "e.g. '2 kg'"
            assert "dimensionless" in text and "units allowed" not in text
    for unit in ("[kg]", "[N/m]", "[Ns/m]", "[N]", "[m/s]", "[system]", "[friction]"):
        assert unit in shown, unit
    masses = [name for name, (_, unit, _) in QUANTITIES.items() if unit == "kg"]
    assert shown.count("'2kg'") == len(masses) == 2  # the example in kg only where a mass is asked


def test_unit_examples_convert_to_their_quantity() -> None:
    """Each example of the help is a value of the right dimension (parsed by ``to_si``)."""
    from stickslip.model.units import to_si

    for name, (_, unit, _) in QUANTITIES.items():
        if unit:
            assert to_si(name, UNIT_EXAMPLES[unit]) > 0.0


@pytest.mark.parametrize("command", ["basin", "design"])
def test_config_help_names_the_toml_tables(command: str, capsys: pytest.CaptureFixture[str],
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    shown = _squeezed(_help(command, capsys, monkeypatch))
    assert "[system]" in shown and "[friction]" in shown
