"""Run the ``stickslip`` command in-process and capture what it prints."""

from __future__ import annotations

import pytest

from stickslip.cli.main import run


def run_cli(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """Exit code, stdout and stderr of ``stickslip ARGS``."""
    try:
        run(args)
        code = 0
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err
