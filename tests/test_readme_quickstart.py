"""The README's Quick start prints what its command prints, and writes nothing in the repository.

Issue 17, point 6: the sample output sat under a ``--json`` command and showed half of the text
form, and the command left ``run.png`` in the repository root. Here the last ``stickslip
simulate`` line of the Quick start is run as a user would (in a fresh folder) and its output
compared line by line with the ``text`` block that follows it.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from tests.cli_helpers import run_cli

ROOT = Path(__file__).resolve().parents[1]


def _quick_start() -> tuple[list[str], list[str]]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    commands = re.findall(r"^\.venv/bin/stickslip (simulate [^#\n]*)", section, flags=re.M)
    sample = re.search(r"```text\n(.*?)```", section, flags=re.S)
    assert commands and sample, "the Quick start has a simulate command and a text sample"
    return shlex.split(commands[-1]), sample.group(1).rstrip("\n").splitlines()


def test_quick_start_sample_is_the_commands_output(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    args, sample = _quick_start()
    assert "--json" not in args  # the sample is the text form
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli(args, capsys)
    assert code == 0, err
    assert out.rstrip("\n").splitlines() == sample
    plots = [args[i + 1] for i, a in enumerate(args) if a == "--plot"]
    for plot in plots:  # written where it says, under results/ (ignored by git), not the root
        assert (tmp_path / plot).is_file() and Path(plot).parts[0] == "results"
