"""The first engine command after an install says on stderr that numba compiles (issue 21, point 5)."""

from __future__ import annotations

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
