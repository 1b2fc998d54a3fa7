"""Many runs of the contact engine, in a bounded pool of worker processes, summarised.

The engine (:func:`~stickslip.analysis.contact.engine.simulate_contact`) is pure Python and
holds the GIL, so independent runs go to worker processes
(:class:`~stickslip.analysis.contact.pool.WorkerPool`, the contact commands' one pool: its
workers ignore SIGINT, and a Ctrl-C in the parent ends them before the ``KeyboardInterrupt``
goes on; the command line prints one line, exit 130). Each run comes back as a small
picklable :class:`ContactOutcome` (not the whole run, whose mode cache is large).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.contact._modes import STICK, ContactSystem
from stickslip.analysis.contact.engine import ContactRun, simulate_contact
from stickslip.analysis.contact.pool import WorkerPool

FloatArray = NDArray[np.float64]

#: Most worker processes of one pool.
MAX_WORKERS = 64
#: A pool starts only when the runs left would take longer than this in this process, s
#: (starting worker processes costs a few seconds: each imports numpy, scipy and the engine).
POOL_THRESHOLD_S = 5.0


@dataclass(frozen=True)
class ContactOutcome:
    """What a run of the contact engine decided, in SI, with its orbit when periodic.

    ``final_state`` is the state at ``t_end``; ``orbit_events`` the ``(kind, state after the
    switch)`` of every event of the last period; ``orbit_point`` the state at the middle of the
    longest phase of that period (a point off every event surface, for the return map).
    """

    verdict: str
    certificate: str
    period_s: float | None
    amplitude_m: float | None
    separated: bool
    n_events: int
    t_end: float
    final_state: FloatArray = field(repr=False)
    repeat_kind: str | None = None
    event_counts: dict[str, int] = field(default_factory=dict)
    stick_phases: int = 0
    orbit_events: tuple[tuple[str, FloatArray], ...] = field(default=(), repr=False)
    orbit_point: FloatArray | None = field(default=None, repr=False)

    @property
    def periodic(self) -> bool:
        """True for ``stick-slip`` and ``slip-oscillation`` (observed, not proven)."""
        return self.period_s is not None


def summarise(run: ContactRun) -> ContactOutcome:
    """The :class:`ContactOutcome` of a run (its last period's events and a mid-phase point)."""
    final = run.state_at(np.array([run.t_end]))[0][0]
    common = {"verdict": run.verdict.value, "certificate": run.certificate,
              "period_s": run.period_s, "amplitude_m": run.amplitude_m,
              "separated": run.separated, "n_events": len(run.events), "t_end": run.t_end,
              "final_state": final}
    if run.period_s is None:
        return ContactOutcome(**common)
    start = run.t_end - run.period_s
    last = [i for i, e in enumerate(run.events) if e.t > start]
    counts: dict[str, int] = {}
    for i in last:
        counts[run.events[i].kind] = counts.get(run.events[i].kind, 0) + 1
    # segment i + 1 starts at event i (segment 0 is the start); the last closes at t_end
    orbit = tuple((run.events[i].kind, run.segment_states[i + 1].copy()) for i in last)
    times = np.append(run.segment_times, run.t_end)
    lengths = np.diff(times)
    first = last[0]  # the phase that starts at the event one period back
    seg = first + int(np.argmax(lengths[first:])) if lengths[first:].size else first
    middle = 0.5 * (float(times[seg]) + float(times[seg + 1]))
    point = run.state_at(np.array([middle]))[0][0]
    return ContactOutcome(**common, repeat_kind=run.events[-1].kind, event_counts=counts,
                          stick_phases=sum(run.events[i].after == STICK for i in last),
                          orbit_events=orbit, orbit_point=point)


def run_one(system: ContactSystem, initial: FloatArray | None, t_max: float | None,
            max_events: int) -> ContactOutcome:
    """One run from ``initial`` (None: the start-up state), summarised."""
    return summarise(simulate_contact(system, t_max=t_max, max_events=max_events,
                                      initial=initial))


def run_many(jobs: Sequence[tuple[ContactSystem, FloatArray | None]], *,
             t_max: float | None = None, max_events: int = 100_000, workers: int = 1,
             progress: Callable[[int, int], None] | None = None,
             pool_threshold: float = POOL_THRESHOLD_S) -> list[ContactOutcome]:
    """Run every ``(system, initial state)`` job; outcomes in the jobs' order.

    ``workers = 1`` runs in this process. With more, the first job runs here and is timed: when
    the others would take longer than ``pool_threshold`` seconds here, they go to the worker
    processes of :class:`~stickslip.analysis.contact.pool.WorkerPool` (at most one per job),
    else they run here too (cheap runs: a pool would cost more to start than it saves).
    ``progress(done, total)`` after each run.
    """
    if isinstance(workers, bool) or not 1 <= int(workers) <= MAX_WORKERS:
        raise ValueError(f"workers = {workers!r} must be from 1 to {MAX_WORKERS}")
    total = len(jobs)
    out: list[ContactOutcome] = []
    if progress is not None:
        progress(0, total)
    began = time.perf_counter()
    for i, (system, z) in enumerate(jobs):
        if i == 1 and int(workers) > 1 and (time.perf_counter() - began) * (total - 1) > pool_threshold:
            break
        out.append(run_one(system, z, t_max, max_events))
        if progress is not None:
            progress(i + 1, total)
    else:
        return out
    rest = [(system.at(), z, t_max, max_events) for system, z in jobs[1:]]  # no mode caches
    with WorkerPool(min(int(workers), len(rest))) as pool:
        return out + pool.map(run_one, rest, progress, done=1, total=total)
