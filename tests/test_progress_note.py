"""Long runs without a progress bar say so once on stderr (``--json`` or a pipe).

An audit found a ``[contact]`` basin's default 10,000 states silent for hours under
``--json`` (0.27 samples/s on the brake pad). The projection is the elapsed time per state
done, times the states left: with 1 state done in 20 s and 99 left, 1,980 s.
"""

from __future__ import annotations

import pytest

from stickslip.cli import progress
from stickslip.cli.progress import LONG_RUN, NOTE_AFTER, ProgressBar


def _run(monkeypatch: pytest.MonkeyPatch, times: list[float], calls: list[tuple[int, int]],
         shorten: str | None = "--samples sets fewer") -> None:
    clock = iter(times)
    monkeypatch.setattr(progress.time, "perf_counter", lambda: next(clock))
    bar = ProgressBar(False, "basin 100 starts", "samples", shorten=shorten)
    with bar:
        for done, total in calls:
            bar(done, total)


def test_a_long_run_without_a_bar_is_noted_once(monkeypatch: pytest.MonkeyPatch,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    _run(monkeypatch, [0.0, 20.0, 40.0, 60.0], [(0, 100), (1, 100), (2, 100), (3, 100)])
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert err[0].startswith("stickslip: note: basin 100 starts: about 0.55 h left at 0.05 "
                             "samples/s (1 of 100 done); --samples sets fewer")
    assert 99 * 20.0 > LONG_RUN and 20.0 >= NOTE_AFTER


def test_a_short_run_or_no_hint_is_quiet(monkeypatch: pytest.MonkeyPatch,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    _run(monkeypatch, [0.0, 20.0, 40.0], [(0, 100), (90, 100), (100, 100)])  # 2.2 s left
    _run(monkeypatch, [0.0, 20.0], [(0, 100), (1, 100)], shorten=None)
    assert capsys.readouterr().err == ""


def test_every_bar_notes_a_long_run_by_default(monkeypatch: pytest.MonkeyPatch,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit: a contact map of 10,000 runs (14-55 h) and a basin-map of 1e8 runs
    # ran silent in a pipe: a bar made without a hint of its own notes with the default one
    clock = iter([0.0, 20.0, 40.0])
    monkeypatch.setattr(progress.time, "perf_counter", lambda: next(clock))
    with ProgressBar(False, "contact map 100x100 (V, W)", "runs") as bar:
        for done in (0, 1, 2):
            bar(done, 10_000)
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("stickslip: note: contact map 100x100 (V, W): about")
    assert err[0].endswith(progress.DEFAULT_SHORTEN)
