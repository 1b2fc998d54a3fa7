"""What ``--help`` shows is right and readable (issue 32, point 6).

Cases of the issue: every ``--config`` help cited a DESIGN.md that users do not have;
``--overwrite`` named a ``--csv`` that ``simulate`` and ``continue`` lack; the ``--initial``
syntax was not said; ``tune --help`` showed raw reStructuredText (````--mass-ratio````); the
friction option's ``stribeck:vs=...`` spec, one 56-character word, wrapped as "stribec" /
"k:vs=..."; and the command list cut "(paper Figs. 8 and 11)" to "(paper Figs.".
"""

from __future__ import annotations

import re

import pytest
import typer.main

from stickslip.cli.main import COMMAND_MODULES, build_app, first_sentence
from tests.cli_helpers import run_cli

COMMANDS = sorted(COMMAND_MODULES)
CITING_COMMANDS = COMMANDS


def _help(args: list[str], columns: int, capsys: pytest.CaptureFixture[str],
          monkeypatch: pytest.MonkeyPatch) -> str:
    monkeypatch.setenv("COLUMNS", str(columns))
    code, out, err = run_cli([*args, "--help"], capsys)
    assert code == 0, err
    return out


@pytest.mark.parametrize("command", CITING_COMMANDS)
def test_help_cites_no_internal_document_and_no_markup(command: str, capsys: pytest.CaptureFixture[str],
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    text = _help([command], 120, capsys, monkeypatch)
    assert "DESIGN" not in text
    assert "``" not in text and ":func:" not in text and ":data:" not in text


@pytest.mark.parametrize("columns", [80, 120])
@pytest.mark.parametrize("command", COMMANDS)
def test_no_word_of_an_option_help_is_broken(command: str, columns: int,
                                              capsys: pytest.CaptureFixture[str],
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    # every word of every option's help comes out whole (click breaks a word longer than its
    # column: "stribec" / "k:vs=V_S/V[,n=N]..." at 80 columns)
    text = _help([command], columns, capsys, monkeypatch)
    shown = set(re.sub(r"(?<=\w)-\n\s+", "-", text).split())  # a line may end at a hyphen
    click_command = typer.main.get_command(build_app(command)).commands[command]  # type: ignore[attr-defined]
    for param in click_command.params:
        for word in (getattr(param, "help", None) or "").split():
            assert word in shown, (param.name, word)


@pytest.mark.parametrize("command", ["simulate", "continue", "frf", "stability"])
def test_overwrite_names_no_option_the_command_lacks(command: str, capsys: pytest.CaptureFixture[str],
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    raw = _help([command], 120, capsys, monkeypatch)
    options = {line.split()[0] for line in raw.splitlines() if line.strip().startswith("--")
               for line in [line.strip()]}
    text = " ".join(raw.split())
    overwrite = text.split("--overwrite", 1)[1].split(" --", 1)[0]
    for named in re.findall(r"--[a-z][a-z-]*", overwrite):
        assert named in options, f"--overwrite's help names {named}, which {command} lacks"


def test_initial_says_its_syntax(capsys: pytest.CaptureFixture[str],
                                 monkeypatch: pytest.MonkeyPatch) -> None:
    text = " ".join(_help(["simulate"], 120, capsys, monkeypatch).split())
    initial = text.split("--initial TEXT", 1)[1].split(" --max-events", 1)[0]
    assert "comma-separated" in initial and "positions" in initial and "velocities" in initial
    assert "e.g. 0.5,0,0,0" in initial
    # the example it gives is accepted (2 DOF: slider and foundation)
    code, _, err = run_cli(["simulate", "--lam", "3", "--zeta", "0.1", "--dva", "optimal",
                            "--initial", "0.5,0,0,0", "--t-max", "50", "--json"], capsys)
    assert code == 0, err


def test_the_command_list_keeps_whole_sentences(capsys: pytest.CaptureFixture[str],
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    text = _help([], 120, capsys, monkeypatch)
    rows = {line.split()[0]: line.split(None, 1)[1] for line in
            text.split("Commands:", 1)[1].strip().splitlines()}
    assert rows["map"] == "Occurrence map over a (lambda, zeta) grid (paper Figs. 8 and 11); resumable."
    for command, summary in rows.items():
        # a summary ends a sentence or says it was shortened, never at an abbreviation
        assert summary.endswith((".", "...")), command
        assert not re.search(r"\b(Figs?|Eqs?)\.$", summary), (command, summary)


@pytest.mark.parametrize(("text", "sentence"), [
    ("Map over a grid (paper Figs. 8 and 11); resumable.\n\nMore.",
     "Map over a grid (paper Figs. 8 and 11); resumable."),
    ("One run. Another sentence.", "One run."),
    ("Bisected to --rtol (Fig. 11a).", "Bisected to --rtol (Fig. 11a)."),
    ("No period at all", "No period at all"),
])
def test_first_sentence(text: str, sentence: str) -> None:
    assert first_sentence(text) == sentence
