"""The progress bar of long commands on a terminal (maps, basins, stability maps)."""

from __future__ import annotations

import time
from typing import Any


class ProgressBar:
    """A rich progress bar on stderr with cells per second and time left."""

    def __init__(self, enabled: bool, label: str, unit: str = "cells") -> None:
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


class DesignProgress:
    """The design procedure's progress on stderr: its stage, the simulations made, the time spent.

    Drawn with rich as the map command's bar is, and only on a terminal; the stage count is
    open-ended (each search stops when it has bracketed its onset), so it shows runs, not a
    fraction.
    """

    def __init__(self, enabled: bool) -> None:
        self.enabled = enabled
        self._bar: Any = None
        self._task: Any = None

    def __enter__(self) -> DesignProgress:
        if self.enabled:
            from rich.console import Console
            from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

            self._bar = Progress(SpinnerColumn(), TextColumn("design: {task.description}"),
                                 TextColumn("{task.completed:.0f} runs"), TimeElapsedColumn(),
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
