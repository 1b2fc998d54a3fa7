"""How a sweep runs: one options object for the backend, chunks, progress and resume store.

:class:`ExecutionOptions` is to a sweep what :class:`stickslip.analysis.simulation.EngineOptions`
is to each run: ``EngineOptions`` says *what* every run does (horizon, budgets, tolerances) and
changes the answer's fingerprint; ``ExecutionOptions`` says *how* the runs are carried out
(serially, on numba threads or on a Dask cluster, in which chunks, reporting progress to whom,
resuming from which store) and never changes an answer: the backends are bit-identical.

Every sweep (:func:`stickslip.occurrence_map`, :func:`stickslip.stick_slip_boundary`,
:func:`stickslip.sweep.basin.basin_stability`, :func:`stickslip.sweep.basin_maps.basin_map`)
takes ``execution=ExecutionOptions(...)``. The loose keywords they took before
(``backend=``, ``workers=``, ``scheduler=``, ``chunk_size=``, ``progress=``, ``store=``,
``overwrite=``) still work for one release, with a :class:`DeprecationWarning`
(:func:`execution_from_keywords`).
"""

from __future__ import annotations

import dataclasses
import os
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from stickslip.sweep.executors import Backend, check_backend, check_chunk_size

#: ``progress(done, total)``: called once at the start of a sweep and after every chunk.
Progress = Callable[[int, int], None]

#: The loose keywords that :class:`ExecutionOptions` replaces (kept one release, deprecated).
EXECUTION_KEYWORDS = ("backend", "workers", "scheduler", "chunk_size", "progress", "store", "overwrite")


@dataclass(frozen=True)
class ExecutionOptions:
    """How a sweep's runs are carried out; validated at construction.

    Parameters
    ----------
    backend : {"threads", "serial", "dask"}
        ``threads``: ``workers`` numba threads (all cores when None); ``serial``: one thread;
        ``dask``: a ``dask.distributed`` cluster at ``scheduler``, or a ``LocalCluster`` of
        ``workers`` single-threaded processes on 127.0.0.1. Results are bit-identical across
        backends.
    workers : int, optional
        Threads (``threads``) or worker processes (``dask`` without ``scheduler``); >= 1.
    scheduler : str, optional
        Address of a running Dask scheduler (``dask`` only; not with ``workers``).
    chunk_size : int, optional
        Cells (or states) per chunk: the unit of progress, of Dask tasks and of the resume
        store; >= 1, a default chosen by the sweep when None. An existing store keeps its own.
    progress : callable, optional
        ``progress(done, total)``, called once at the start and after every chunk.
    store : path, optional
        Resume store folder (:class:`stickslip.sweep.store.ChunkStore`): finished chunks are
        written there as they complete; a later sweep of the same configuration computes only
        the missing ones.
    overwrite : bool
        Discard a store of another configuration instead of raising ``StoreMismatch``.

    Raises
    ------
    ValueError
        An unknown backend, ``workers`` or ``chunk_size`` below 1 or not whole, a scheduler
        without the dask backend or together with ``workers``, or ``serial`` with more than one
        worker.
    """

    backend: Backend = "threads"
    workers: int | None = None
    scheduler: str | None = None
    chunk_size: int | None = None
    progress: Progress | None = None
    store: str | os.PathLike[str] | None = None
    overwrite: bool = False

    def __post_init__(self) -> None:
        check_backend(self.backend, self.workers, self.scheduler)
        check_chunk_size(self.chunk_size)
        if not isinstance(self.overwrite, bool):
            raise ValueError(f"overwrite={self.overwrite!r} must be True or False")
        if self.progress is not None and not callable(self.progress):
            raise ValueError(f"progress={self.progress!r} must be a callable progress(done, total)")

    def check_in_process(self, function: str, *, progress: bool = True) -> None:
        """Refuse what a sweep that runs only in this process cannot honour.

        :func:`stickslip.stick_slip_boundary` (bisection: each step depends on the last) and
        :func:`stickslip.sweep.basin_maps.basin_map` (one basin per cell) run on numba threads
        only, without chunks or a resume store; ``progress=False`` also refuses a callback.

        Raises
        ------
        ValueError
            The dask backend, a scheduler, a chunk size, a store, ``overwrite`` or (when
            refused) a progress callback.
        """
        refused = [f"backend={self.backend!r}"] if self.backend == "dask" else []
        refused += [f"{name}=..." for name in ("scheduler", "chunk_size", "store")
                    if getattr(self, name) is not None]
        refused += ["overwrite=True"] if self.overwrite else []
        refused += ["progress=..."] if self.progress is not None and not progress else []
        if refused:
            raise ValueError(f"{function} runs on numba threads in this process only; it does not "
                             f"take {', '.join(refused)}")

    @property
    def threads(self) -> int | None:
        """Numba threads of an in-process run: 1 for ``serial``, ``workers`` (None: all) otherwise."""
        return 1 if self.backend == "serial" else self.workers

    def replace(self, **changes: Any) -> ExecutionOptions:
        """A copy with ``changes`` applied (validated again)."""
        return dataclasses.replace(self, **changes)


def execution_from_keywords(execution: ExecutionOptions | None, legacy: Mapping[str, Any],
                            function: str) -> ExecutionOptions:
    """The execution options of a sweep called with ``execution=`` and/or the old keywords.

    The loose keywords (:data:`EXECUTION_KEYWORDS`) are deprecated: each use warns once per
    call with a :class:`DeprecationWarning` naming the replacement, and is applied on top of
    ``execution`` (or of the defaults).

    Parameters
    ----------
    execution : ExecutionOptions, optional
        What the caller passed as ``execution=``.
    legacy : mapping
        The other keyword arguments the sweep received (its ``**legacy``).
    function : str
        Name of the sweep, for the messages.

    Raises
    ------
    TypeError
        A keyword that is not one of :data:`EXECUTION_KEYWORDS`, or ``execution`` of the
        wrong type.
    ValueError
        Invalid values (:class:`ExecutionOptions`).
    """
    unknown = sorted(set(legacy) - set(EXECUTION_KEYWORDS))
    if unknown:
        raise TypeError(f"{function}() got an unexpected keyword argument {unknown[0]!r}")
    if execution is not None and not isinstance(execution, ExecutionOptions):
        raise TypeError(f"{function}(execution=...) takes an ExecutionOptions, "
                        f"not {type(execution).__name__}")
    base = execution if execution is not None else ExecutionOptions()
    if not legacy:
        return base
    names = ", ".join(f"{name}=" for name in legacy)
    warnings.warn(
        f"{function}({names}) is deprecated and will be removed in the next release: pass "
        f"execution=ExecutionOptions({', '.join(f'{name}=...' for name in legacy)}) instead",
        DeprecationWarning,
        stacklevel=3,
    )
    return base.replace(**legacy)
