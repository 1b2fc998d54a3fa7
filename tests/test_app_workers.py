"""The app's worker pool (issue 31, quick): heavy work off the page thread, bounded, shared.

Checked with cheap stand-ins for the design (``time.sleep``, ``operator.add`` and a function
here that reports a stage): a job runs in another process, the same key shares one job, the
waiting room is bounded (one job more is refused with :class:`Busy`), finished results are
kept for every session, and a worker's stage reaches the server process.
"""

from __future__ import annotations

import operator
import os
import time

import pytest

from stickslip.app import workers

#: Bound of every wait here, s (a spawned worker imports numpy and the package first).
DEADLINE = 120.0


def _pid() -> int:
    return os.getpid()


def _staged(value: int) -> int:
    """A job that reports a stage, then waits a little for the test to see it."""
    workers.report("stage one", 7)
    time.sleep(2.0)
    return value


def _until(condition: object, what: str) -> None:
    deadline = time.monotonic() + DEADLINE
    while not condition():  # type: ignore[operator]
        assert time.monotonic() < deadline, f"{what} within {DEADLINE:.0f} s"
        time.sleep(0.05)


def test_a_job_runs_in_another_process_and_its_result_is_kept() -> None:
    future = workers.submit(("test", "pid"), _pid)
    assert future.result(timeout=DEADLINE) != os.getpid()
    key = ("test", "add", 2, 3)
    assert workers.submit(key, operator.add, 2, 3).result(timeout=DEADLINE) == 5
    _until(lambda: workers.result(key) == 5, "the result kept")


def test_the_same_key_shares_one_job_and_a_full_pool_refuses_politely() -> None:
    _until(lambda: workers.waiting_jobs() == 0, "an idle pool")
    futures = [workers.submit(("test", "sleep", i), time.sleep, 1.0)
               for i in range(workers.MAX_WORKERS + workers.MAX_WAITING)]
    assert workers.submit(("test", "sleep", 0), time.sleep, 1.0) is futures[0]
    with pytest.raises(workers.Busy, match=r"busy .* try again in a minute"):
        workers.submit(("test", "one too many"), time.sleep, 1.0)
    for future in futures:
        future.result(timeout=DEADLINE)
    _until(lambda: workers.waiting_jobs() == 0, "the jobs to finish")
    assert workers.submit(("test", "after"), operator.add, 1, 1).result(timeout=DEADLINE) == 2


def test_a_workers_stage_reaches_the_page() -> None:
    key = ("test", "staged")
    future = workers.submit(key, _staged, 11)
    _until(lambda: workers.progress(key) == ("stage one", 7) or future.done(), "the stage")
    assert workers.progress(key) == ("stage one", 7)
    assert future.result(timeout=DEADLINE) == 11


def test_the_progress_listener_keeps_running_jobs_only_and_ends_on_request() -> None:
    """A report for a finished job is dropped (the table cannot grow without end) and the
    listener returns when told to (its loop is bounded by the pool's life)."""
    import queue

    reports: queue.Queue[object] = queue.Queue()
    running = ("listener-test", "running")
    with workers._lock:
        workers._jobs[running] = None  # type: ignore[assignment]
    try:
        reports.put((running, "stage", 3))
        reports.put((("listener-test", "finished"), "late", 9))
        reports.put(None)
        workers._listen(reports)  # returns: the sentinel ended it
        assert workers.progress(running) == ("stage", 3)
        assert workers.progress(("listener-test", "finished")) is None
    finally:
        with workers._lock:
            workers._jobs.pop(running, None)
            workers._progress.pop(running, None)
