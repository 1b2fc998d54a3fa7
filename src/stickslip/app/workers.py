"""Heavy computations off the page's thread: one worker process for every session, bounded.

A page's script runs in a thread of the Streamlit server, and the engine's compiled kernels
hold Python's lock while they run: a 30-second design on one page froze every other page for
as long. Heavy work (the machine page's design and absorber searches) therefore runs in a
separate process, :data:`MAX_WORKERS` of them for the whole server, with at most
:data:`MAX_WAITING` jobs waiting behind them; beyond that a page is told politely that the
server is busy, instead of queueing without end. Finished results are kept
(:data:`MAX_RESULTS`, shared by all sessions), so returning to an input costs nothing.

The pages wait for their job with :func:`wait_for`, which shows the stage the worker
reports (``progress(stage, runs)`` of :func:`~stickslip.analysis.machine_absorber.design_machine`)
and the time elapsed, and gives up after :data:`MAX_WAIT_S`.
"""

from __future__ import annotations

import atexit
import collections
import concurrent.futures
import multiprocessing
import threading
import time
from collections.abc import Callable, Hashable
from typing import Any

#: Worker processes for the whole server (the machine this was written on has 2 cores).
MAX_WORKERS = 1
#: Jobs that may wait for a worker; one more is refused (:class:`Busy`).
MAX_WAITING = 2
#: Finished results kept for every session, the oldest dropped first.
MAX_RESULTS = 32
#: Longest a page waits for its job, s (the job goes on; the page can be reloaded).
MAX_WAIT_S = 900.0
#: How often a waiting page looks again, s.
POLL_S = 0.25

_lock = threading.Lock()
_pool: concurrent.futures.ProcessPoolExecutor | None = None
_progress_queue: Any = None
_progress: dict[Hashable, tuple[str, int]] = {}
_jobs: dict[Hashable, concurrent.futures.Future[Any]] = {}
_results: collections.OrderedDict[Hashable, Any] = collections.OrderedDict()
_worker_key: Hashable | None = None  # in a worker process: the job it runs
_listener_queue: list[Any] = []  # the queue _listen reads (to send it the end)


class Busy(RuntimeError):
    """Every worker is taken and :data:`MAX_WAITING` jobs already wait."""

    def __init__(self) -> None:
        super().__init__(f"the server is busy with {MAX_WORKERS + MAX_WAITING} heavy computations "
                         "of other pages; try again in a minute (nothing was started)")


def _init_worker(progress_queue: Any) -> None:
    global _progress_queue
    _progress_queue = progress_queue


def report(stage: str, runs: int) -> None:
    """In a worker: tell the waiting page which stage its job is at (a ``progress`` callback)."""
    if _progress_queue is not None and _worker_key is not None:
        _progress_queue.put((_worker_key, stage, runs))


def _run(key: Hashable, function: Callable[..., Any], args: tuple[Any, ...]) -> Any:
    global _worker_key
    _worker_key = key
    try:
        return function(*args)
    finally:
        _worker_key = None


def _listen(progress_queue: Any) -> None:
    """Thread of the server process: copy the workers' reports into :data:`_progress`.

    It lives as long as the pool: :func:`_stop` sends ``None`` to end it. A report that arrives
    after its job finished is dropped (the table holds running jobs only).
    """
    while True:
        try:
            item = progress_queue.get()
        except (EOFError, OSError, ValueError, TypeError):  # the queue closed: the server exits
            return
        if item is None:
            return
        key, stage, runs = item
        with _lock:
            if key in _jobs:
                _progress[key] = (stage, runs)


def _executor() -> concurrent.futures.ProcessPoolExecutor:
    global _pool
    if _pool is None:
        context = multiprocessing.get_context("spawn")  # no fork of a threaded server
        progress_queue = context.Queue()
        _listener_queue.append(progress_queue)
        threading.Thread(target=_listen, args=(progress_queue,), daemon=True,
                         name="stickslip-progress").start()
        _pool = concurrent.futures.ProcessPoolExecutor(
            MAX_WORKERS, mp_context=context, initializer=_init_worker, initargs=(progress_queue,))
        atexit.register(_stop)
    return _pool


def _stop() -> None:
    """At the server's exit: drop waiting jobs and stop the workers (a search may run for
    minutes), before the interpreter tears down the modules the pool's threads use."""
    if _pool is None:
        return
    for queue in _listener_queue:
        queue.put(None)
    processes = list(getattr(_pool, "_processes", {}).values())
    _pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        process.terminate()
        process.join(timeout=10)


def result(key: Hashable) -> Any | None:
    """The finished result of ``key``, or None."""
    with _lock:
        if key in _results:
            _results.move_to_end(key)
            return _results[key]
    return None


def submit(key: Hashable, function: Callable[..., Any], *args: Any) -> concurrent.futures.Future[Any]:
    """Start ``function(*args)`` in a worker, once per ``key`` (a running job is shared).

    ``function`` must be importable by name (a module-level function) and its arguments and
    result picklable. Raises :class:`Busy` when the workers and the waiting room are full.
    """
    with _lock:
        running = _jobs.get(key)
        if running is not None:
            return running
        if len(_jobs) >= MAX_WORKERS + MAX_WAITING:
            raise Busy()
        future = _executor().submit(_run, key, function, args)
        _jobs[key] = future

    def finished(done: concurrent.futures.Future[Any]) -> None:
        with _lock:
            _jobs.pop(key, None)
            _progress.pop(key, None)
            if not done.cancelled() and done.exception() is None:
                _results[key] = done.result()
                while len(_results) > MAX_RESULTS:
                    _results.popitem(last=False)

    future.add_done_callback(finished)
    return future


def progress(key: Hashable) -> tuple[str, int] | None:
    """The last stage and run count the job of ``key`` reported, or None."""
    with _lock:
        return _progress.get(key)


def wait_for(key: Hashable, function: Callable[..., Any], *args: Any, what: str) -> Any:
    """``function(*args)`` computed in a worker (or kept from before), with progress shown.

    Raises :class:`Busy`, the job's own exception, or ``TimeoutError`` after
    :data:`MAX_WAIT_S`.
    """
    import streamlit as st

    kept = result(key)
    if kept is not None:
        return kept
    future = submit(key, function, *args)
    start = time.monotonic()
    box = st.empty()
    try:
        while not future.done():
            elapsed = time.monotonic() - start
            if elapsed > MAX_WAIT_S:
                raise TimeoutError(f"{what} took over {MAX_WAIT_S:.0f} s; it goes on in the "
                                   "background: reload the page later to see it")
            stage = progress(key)
            box.info(f"{what}: {stage[0] if stage else 'waiting for a worker'}"
                     + (f", {stage[1]} runs" if stage and stage[1] else "")
                     + f" ({elapsed:.0f} s)")
            time.sleep(POLL_S)
    finally:
        box.empty()
    return future.result()


def waiting_jobs() -> int:
    """Jobs running or waiting now."""
    with _lock:
        return len(_jobs)


