"""Ctrl-C while a compiled kernel runs: recorded, then raised once the kernel has returned.

A numba kernel holds the GIL and cannot be interrupted. Python's SIGINT handler runs only when
the kernel returns, inside numba's dispatcher, and its ``KeyboardInterrupt`` then surfaces as
``SystemError: CPUDispatcher(...) returned a result with an exception set`` (a 59-line
traceback); during the first compile it can land in a finalizer and be lost ("Exception
ignored in ...") while the run goes on. :func:`deferred_sigint` replaces the handler for the
duration of a kernel call (and its compile) by one that only records the signal; the caller
keeps the kernel's finished result and raises ``KeyboardInterrupt`` at its next safe point
(:meth:`Sigint.raise_if_caught`), e.g. once the chunk is in the resume store.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType


class Sigint:
    """What :func:`deferred_sigint` recorded: whether SIGINT arrived inside its block."""

    def __init__(self) -> None:
        self.caught = False

    def __call__(self, signum: int, frame: FrameType | None) -> None:
        self.caught = True

    def raise_if_caught(self) -> None:
        """Raise ``KeyboardInterrupt`` if SIGINT arrived inside the block (once)."""
        if self.caught:
            self.caught = False
            raise KeyboardInterrupt


@contextmanager
def deferred_sigint() -> Iterator[Sigint]:
    """Record SIGINT instead of raising it inside the block; yields the :class:`Sigint` record.

    Only in the main thread, and only where Python handles SIGINT itself (not where it is
    ignored, e.g. a background job); elsewhere the block runs unchanged and nothing is
    recorded. The previous handler is restored on exit.
    """
    record = Sigint()
    main = threading.current_thread() is threading.main_thread()
    previous = signal.getsignal(signal.SIGINT) if main else None
    if not callable(previous):  # another thread, SIG_IGN, SIG_DFL or a handler set from C
        yield record
        return
    signal.signal(signal.SIGINT, record)
    try:
        yield record
    finally:
        signal.signal(signal.SIGINT, previous)
