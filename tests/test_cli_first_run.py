"""The first engine command after an install says on stderr that numba compiles (issue 21, point 5)."""

from __future__ import annotations

import os
import pickle
from pathlib import Path

import pytest

from stickslip.cli import main


@pytest.mark.parametrize("argv", [["simulate", "--lam", "3", "--json"], ["map", "--lam", "1"],
                                  ["basin-map", "--json"]])
def test_a_cold_cache_is_announced_on_stderr_only(argv: list[str], monkeypatch: pytest.MonkeyPatch,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(main, "engine_cache_is_cold", lambda: True)
    main._announce_compilation(argv)
    out, err = capsys.readouterr()
    assert out == ""  # --json keeps exactly one object on stdout
    assert err.startswith("stickslip: first run: compiling") and "minute" in err


@pytest.mark.parametrize("argv", [["simulate", "--help"], ["frf", "--zeta", "0.1"], ["--version"], []])
def test_no_notice_without_an_engine_run(argv: list[str], monkeypatch: pytest.MonkeyPatch,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(main, "engine_cache_is_cold", lambda: True)
    main._announce_compilation(argv)
    assert capsys.readouterr() == ("", "")


def test_no_notice_once_the_engine_is_cached() -> None:
    from stickslip import Slider, chain_structure, simulate

    simulate(chain_structure(0.1, ()), Slider(3.0))  # compiles, or loads the cache
    assert not main.engine_cache_is_cold()


def test_the_cache_is_warm_by_the_stamp_in_its_index_not_by_file_times(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # a checkout that rewrites identical kernel files gives them new times, and numba (which
    # compares the stamp of names and contents) keeps loading the cache: the notice must not
    # say "first run" then (it once did on every command, and refused input got two lines)
    from stickslip.kernel._stamp import kernel_source_stamp

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert main.engine_cache_is_cold()  # no index at all
    index = tmp_path / "stickslip" / "kernel" / "engine.run_prepared-294.py311.nbi"
    index.parent.mkdir(parents=True)
    index.write_bytes(pickle.dumps(1) + pickle.dumps(("0" * 64, {"a signature": "its file"})))
    assert main.engine_cache_is_cold()  # an index of other sources: numba recompiles
    index.write_bytes(pickle.dumps(1) + pickle.dumps((kernel_source_stamp(), {"a signature": "f"})))
    os.utime(index, (0.0, 0.0))  # older than every source file
    assert not main.engine_cache_is_cold()
