"""How many threads the BLAS libraries may use while a computation of this layer runs.

The matrices of this package are small and its linear-algebra calls many; BLAS threads only
contend with each other and with numba's (on a loaded 2-core machine a 116 x 116
``scipy.linalg.eig`` took 2.4 s with OpenBLAS's default threads and 0.026 s on one thread,
measured 2026-11-25). :func:`blas_limited` holds a limit while any user needs it;
:func:`one_blas_thread` wraps a function in it.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, TypeVar

_F = TypeVar("_F", bound=Callable[..., Any])

_BLAS_LOCK = threading.Lock()
_blas_state: dict[str, Any] = {"users": 0, "limiter": None}


@contextmanager
def blas_limited(threads: int | None) -> Iterator[None]:
    """Hold the BLAS libraries at ``threads`` threads while any user runs (``None``: as they are).

    ``threadpoolctl`` sets a process-wide number, so computations running at once share one
    limit: the first to start sets it, the last to finish restores the process's own setting
    (a plain ``with threadpool_limits`` per computation would let the first to finish lift the
    limit under the others). The OpenBLAS that numpy and scipy ship ignores a limit set from a
    worker thread (measured: ``threadpool_info`` still reports the cores there), so a program
    that runs fits in a thread pool sets the limit around the pool, in its main thread:
    ``with threadpoolctl.threadpool_limits(1, user_api="blas"): ...``.

    Parameters
    ----------
    threads : int or None
        Threads allowed; None leaves the libraries as they are.

    Returns
    -------
    contextmanager
        A context in which the limit holds.
    """
    if threads is None:
        yield
        return
    from threadpoolctl import threadpool_limits

    with _BLAS_LOCK:
        if _blas_state["users"] == 0:
            _blas_state["limiter"] = threadpool_limits(limits=threads, user_api="blas")
        _blas_state["users"] += 1
    try:
        yield
    finally:
        with _BLAS_LOCK:
            _blas_state["users"] -= 1
            if _blas_state["users"] == 0:
                _blas_state["limiter"].restore_original_limits()
                _blas_state["limiter"] = None


def one_blas_thread(function: _F) -> _F:
    """Run ``function`` with BLAS on one thread (:func:`blas_limited`), then restore the setting.

    Parameters
    ----------
    function : callable
        The function to wrap.

    Returns
    -------
    callable
        The same function, run under a one-thread BLAS limit.
    """

    @functools.wraps(function)
    def wrapped(*args: Any, **kwargs: Any) -> Any:
        with blas_limited(1):
            return function(*args, **kwargs)

    return wrapped  # type: ignore[return-value]
