"""The progress bar of long commands on a terminal (maps, basins, stability maps)."""

from __future__ import annotations

import time
from typing import Any

#: Without a bar (``--json``, or stderr not a terminal), a run projected to take longer than
#: this (s) after :data:`NOTE_AFTER` s says so once on stderr, with how to shorten it.
LONG_RUN = 600.0
NOTE_AFTER = 15.0
#: What a long run's note suggests when its command names nothing more precise.
DEFAULT_SHORTEN = "a smaller grid, fewer points or fewer samples run shorter (Ctrl-C stops it)"


class ProgressBar:
    """A rich progress bar on stderr with cells per second and time left.

    Without a bar, ``shorten`` (what makes the run shorter, e.g. ``"--samples sets fewer"``;
    :data:`DEFAULT_SHORTEN` unless given, None for no note) asks for one note on stderr when
    the run is projected to last beyond :data:`LONG_RUN`.
    """

    def __init__(self, enabled: bool, label: str, unit: str = "cells",
                 shorten: str | None = DEFAULT_SHORTEN) -> None:
        self._shorten = shorten
        self._note_from: tuple[int, float] | None = None
        self._unit = unit
        self._bar: Any = None
        self._task: Any = None
        self._label = label
        self._start_done = 0
        self._started = 0.0
        self.enabled = enabled

    def __enter__(self) -> ProgressBar:
        if self.enabled:
            from rich.console import Console
            from rich.progress import (
                BarColumn,
                MofNCompleteColumn,
                Progress,
                TextColumn,
                TimeRemainingColumn,
            )

            self._bar = Progress(
                TextColumn("{task.description}"),
                BarColumn(),
                MofNCompleteColumn(),
                TextColumn(f"{self._unit}  {{task.fields[rate]}} {self._unit}/s  left"),
                TimeRemainingColumn(),
                console=Console(stderr=True),
            )
            self._bar.__enter__()
        return self

    def __exit__(self, *exc: object) -> None:
        if self._bar is not None:
            self._bar.__exit__(*exc)

    def __call__(self, done: int, total: int) -> None:
        if self._bar is None:
            self._note_long(done, total)
            return
        now = time.perf_counter()
        if self._task is None:
            self._task = self._bar.add_task(self._label, total=total, completed=done, rate="-")
            self._start_done, self._started = done, now
            return
        rate = (done - self._start_done) / max(now - self._started, 1e-9)
        # the total may grow (a boundary search opens brackets as it goes)
        self._bar.update(self._task, completed=done, total=total,
                         rate=f"{rate:,.0f}" if rate >= 10.0 else f"{rate:.2g}")


    def _note_long(self, done: int, total: int) -> None:
        """One note on stderr when a run without a bar is projected to be long."""
        if self._shorten is None:
            return
        now = time.perf_counter()
        if self._note_from is None:
            self._note_from = (done, now)
            return
        self._start_done, self._started = self._note_from
        elapsed = now - self._started
        if elapsed < NOTE_AFTER or done <= self._start_done:
            return
        left = (total - done) * elapsed / (done - self._start_done)
        hint, self._shorten = self._shorten, None  # once
        if left > LONG_RUN:
            import sys

            rate = (done - self._start_done) / elapsed
            print(f"stickslip: note: {self._label}: about {left / 3600.0:.2g} h left at "
                  f"{rate:.3g} {self._unit}/s ({done} of {total} done); {hint}",
                  file=sys.stderr, flush=True)


class DesignProgress:
    """The design procedure's progress on stderr: its stage, the simulations made, the time spent
    (``label``: another open-ended search's, e.g. ``cycles``; ``counted=False``: without runs).

    Drawn with rich as the map command's bar is, and only on a terminal; the stage count is
    open-ended (each search stops when it has bracketed its onset), so it shows runs, not a
    fraction.
    """

    def __init__(self, enabled: bool, label: str = "design", counted: bool = True) -> None:
        self.enabled = enabled
        self._label = label
        self._counted = counted  # False: the work reports no runs, the spinner and time alone
        self._bar: Any = None
        self._task: Any = None

    def __enter__(self) -> DesignProgress:
        if self.enabled:
            from rich.console import Console
            from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

            runs = [TextColumn("{task.completed:.0f} runs")] if self._counted else []
            self._bar = Progress(SpinnerColumn(), TextColumn(f"{self._label}: {{task.description}}"),
                                 *runs, TimeElapsedColumn(),
                                 console=Console(stderr=True), transient=True)
            self._bar.__enter__()
            self._task = self._bar.add_task("starting", total=None)
        return self

    def __exit__(self, *exc: object) -> None:
        if self._bar is not None:
            self._bar.__exit__(*exc)

    def __call__(self, stage: str, runs: int) -> None:
        if self._bar is not None:
            self._bar.update(self._task, description=stage, completed=runs)
