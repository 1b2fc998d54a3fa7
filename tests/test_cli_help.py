"""``--version``, shell completion and an example in every ``--help`` (issue 11, point 6)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest
import typer

from stickslip.cli.main import app
from tests.cli_helpers import run_cli

ROOT = Path(__file__).resolve().parents[1]
VERSION = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
COMMANDS = sorted(typer.main.get_command(app).commands)  # type: ignore[attr-defined]


def test_every_command_is_registered() -> None:
    assert set(COMMANDS) >= {"simulate", "frf", "tune", "map", "boundary", "design", "reproduce", "app"}


@pytest.mark.parametrize("command", COMMANDS)
def test_command_help_has_an_example(command: str, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli([command, "--help"], capsys)
    assert code == 0, err
    assert "Example: stickslip " + command in " ".join(out.split())


def test_main_help_has_an_example_and_completion(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["--help"], capsys)
    assert code == 0
    assert "Example: stickslip simulate" in out
    assert "--install-completion" in out and "--show-completion" in out


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    assert run_cli(["--version"], capsys) == (0, f"stickslip {VERSION}\n", "")


@pytest.fixture
def shell_given(monkeypatch: pytest.MonkeyPatch) -> None:
    """Name the shell on the command line instead of detecting the parent process's."""
    monkeypatch.setenv("_TYPER_COMPLETE_TEST_DISABLE_SHELL_DETECTION", "1")


@pytest.mark.usefixtures("shell_given")
@pytest.mark.parametrize(("shell", "marker"), [
    ("bash", "complete -o default -F _stickslip_completion stickslip"),
    ("zsh", "#compdef stickslip"),
    ("fish", "complete --command stickslip"),
])
def test_show_completion_prints_a_script(shell: str, marker: str, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["--show-completion", shell], capsys)
    assert code == 0
    assert marker in out
    assert f"_STICKSLIP_COMPLETE=complete_{shell}" in out


@pytest.mark.usefixtures("shell_given")
def test_install_completion_writes_to_the_home_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setenv("HOME", str(tmp_path))
    code, out, _ = run_cli(["--install-completion", "bash"], capsys)
    assert code == 0, out
    script = tmp_path / ".bash_completions" / "stickslip.sh"
    assert "_STICKSLIP_COMPLETE=complete_bash" in script.read_text()
    assert str(script) in (tmp_path / ".bashrc").read_text()


@pytest.mark.parametrize(("words", "expected"), [("stickslip si", "simulate"),
                                                 ("stickslip simulate --ze", "--zeta"),
                                                 ("stickslip tune --obj", "--objective")])
def test_completion_completes(words: str, expected: str, monkeypatch: pytest.MonkeyPatch,
                              capsys: pytest.CaptureFixture[str]) -> None:
    """What bash's completion function asks the command (the script's COMP_WORDS protocol)."""
    monkeypatch.setenv("_STICKSLIP_COMPLETE", "complete_bash")
    monkeypatch.setenv("COMP_WORDS", words)
    monkeypatch.setenv("COMP_CWORD", str(len(words.split()) - 1))
    code, out, _ = run_cli([], capsys)
    assert code == 0
    assert expected in out.split()


@pytest.mark.slow  # 24 s: out of the default run (kept under ten minutes)
def test_compile_runs_every_warm_up_case(tmp_path: Path) -> None:
    # stickslip compile (cli/compile_command.py): each warm-up case is a valid command line
    # (it exits 0 with the cache warm, as after `make`), so none of them silently compiles nothing
    from stickslip.cli.compile_command import compile_kernels

    assert compile_kernels(jobs=2) == 0
