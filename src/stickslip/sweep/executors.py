"""Running the cells of a sweep: serially, over numba threads, or on a Dask cluster.

Every cell is one certified simulation from the startup state (``run_cells`` of
:mod:`stickslip.kernel.batch`). Cells are independent and the engine is deterministic, so
the float and integer summaries of a cell do not depend on the backend, the number of
threads or the chunking: the backends return bit-identical arrays.

Basin stability (:func:`stickslip.sweep.basin.basin_stability`) runs through the same
machinery with its own per-chunk task (many initial states of one system, ``execute(...,
task=...)``): the same backends, chunks, progress and resume store.

The grid is cut into chunks of consecutive cells. A backend yields each chunk as soon as
it is finished (in completion order for Dask), which is what lets the caller report
progress and write the chunk to a resume store.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, TypeVar, cast

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.dva import resolve_dva
from stickslip.analysis.simulation import EngineOptions
from stickslip.kernel.interrupt import deferred_sigint
from stickslip.model._validate import non_negative, whole_number
from stickslip.model.dva import DvaSpec
from stickslip.model.friction import CoulombFriction, FrictionLaw
from stickslip.model.parameters import Foundation
from stickslip.model.structure import chain_structure

if TYPE_CHECKING:
    from stickslip.sweep.store import ChunkStore

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
Backend = Literal["serial", "threads", "dask"]
BACKENDS: tuple[Backend, ...] = ("serial", "threads", "dask")
S = TypeVar("S")
B = TypeVar("B")
#: The work of one chunk: ``task(shared, batch, options, n_threads) -> (float_summary,
#: int_summary)`` (see :func:`execute`).
ChunkTask: TypeAlias = Callable[[S, B, EngineOptions, int | None], tuple[FloatArray, IntArray]]

#: Cells handed to one numba thread at a time: the cost of a cell varies by orders of
#: magnitude (a certified steady state can come after one phase, a cycle near the boundary
#: after thousands), so threads take small batches instead of one fixed slice each.
THREAD_BATCH = 4


@dataclass(frozen=True)
class StructureSet:
    """The structure of every ``zeta`` of a sweep, stacked for the kernel.

    ``masses[j]``, ``dampings[j]`` and ``stiffnesses[j]`` are the dimensionless matrices at
    ``zetas[j]``; ``foundations[j]`` the resolved foundation (``None`` for the rigid base).
    """

    zetas: FloatArray
    foundations: tuple[Foundation | None, ...]
    masses: FloatArray
    dampings: FloatArray
    stiffnesses: FloatArray

    @classmethod
    def resolve(cls, dva: DvaSpec, zetas: Sequence[float] | FloatArray) -> StructureSet:
        """Resolve ``dva`` at each ``zeta`` and build the chain structure."""
        z = np.asarray(zetas, dtype=np.float64).reshape(-1)
        for value in z.tolist():
            non_negative("zeta", value)
        try:
            foundations = tuple(resolve_dva(dva, float(value)) for value in z)
        except ImportError as exc:
            raise ValueError(f"--dva {dva.as_text()} is not available in this build: {exc}") from None
        structures = [
            chain_structure(float(value), () if f is None else (f,))
            for value, f in zip(z, foundations, strict=True)
        ]
        return cls(
            zetas=z,
            foundations=foundations,
            masses=np.stack([s.mass for s in structures]),
            dampings=np.stack([s.damping for s in structures]),
            stiffnesses=np.stack([s.stiffness for s in structures]),
        )

    @property
    def n_dof(self) -> int:
        """Degrees of freedom of every structure (1 rigid base, 2 with a foundation)."""
        return int(self.masses.shape[1])

    @functools.cached_property
    def kernel_data(self) -> tuple[Any, ...]:
        """The kernel's per-structure data, computed once per set (the first time it is asked).

        :func:`stickslip.kernel.system.structure_data_stack`: what does not depend on the
        cell's ``lambda``, ``gamma`` or friction law (the stick and Coulomb slip-I
        exponentials, the Lyapunov solve), shared by every batch of a sweep.
        """
        from stickslip.kernel.system import structure_data_stack

        return tuple(structure_data_stack(self.masses, self.dampings, self.stiffnesses))


@dataclass(frozen=True)
class CellBatch:
    """Cells to run: structure index and ``lambda`` of each, ``gamma`` and the friction law.

    ``laws``, when given, holds one friction law per cell (a (lambda, delta) map) and takes
    the place of ``friction``.
    """

    structure_index: IntArray
    lams: FloatArray
    gamma: float
    friction: FrictionLaw = field(default_factory=CoulombFriction)
    laws: tuple[FrictionLaw, ...] | None = None


def band_tables(lams: FloatArray, gamma: float, friction: FrictionLaw | Sequence[FrictionLaw]
                ) -> tuple[FloatArray, FloatArray, FloatArray, IntArray]:
    """Padded per-cell band tables ``(edges, intercepts, slopes, n_bands)`` for ``run_cells``.

    ``friction`` is the law of every cell, or a sequence of one law per cell. The Coulomb law
    (of every cell) takes the kernel's own fast path; otherwise each distinct pair
    ``(lambda, law)`` is tabulated once (cells sharing it share their table).
    """
    from stickslip.kernel.batch import coulomb_tables

    gammas = np.full(lams.shape, float(gamma))
    if isinstance(friction, CoulombFriction):
        return coulomb_tables(lams, gammas)
    per_cell = [friction] * lams.size if not isinstance(friction, Sequence) else list(friction)
    if len(per_cell) != lams.size:
        raise ValueError(f"{len(per_cell)} friction laws for {lams.size} cells")
    index: dict[tuple[float, FrictionLaw], int] = {}
    inverse = np.array([index.setdefault((float(lam), law), len(index))
                        for lam, law in zip(lams.tolist(), per_cell, strict=True)], dtype=np.int64)
    tables = [law.bands(lam, float(gamma)) for lam, law in index]
    width = max((len(t[1]) for t in tables), default=1)
    n_unique = len(tables)
    edges = np.full((n_unique, width + 1), np.inf)
    intercepts = np.zeros((n_unique, width))
    slopes = np.zeros((n_unique, width))
    n_bands = np.empty(n_unique, dtype=np.int64)
    for i, (e, a, sl) in enumerate(tables):
        n_bands[i] = len(a)
        edges[i, : len(e)] = e
        intercepts[i, : len(a)] = a
        slopes[i, : len(sl)] = sl
    return edges[inverse], intercepts[inverse], slopes[inverse], n_bands[inverse]


def run_batch(
    structures: StructureSet, batch: CellBatch, options: EngineOptions, n_threads: int | None = None
) -> tuple[FloatArray, IntArray]:
    """Run ``batch`` on ``n_threads`` numba threads (all when None): ``run_cells`` of
    :mod:`stickslip.kernel.batch`, with the structures' own data computed once per set.

    Returns the float and integer summaries, shapes ``(n, N_FLOAT)`` and ``(n, N_INT)``,
    with the layouts ``F_*`` and ``I_*`` of :mod:`stickslip.kernel.engine`. This is also the
    task that Dask workers run, so it only takes plain, picklable data.
    """
    from stickslip.kernel.batch import run_prepared_cells

    gammas = np.full(batch.lams.shape, float(batch.gamma))
    lams = np.ascontiguousarray(batch.lams, dtype=np.float64)
    laws = batch.friction if batch.laws is None else batch.laws
    edges, intercepts, slopes, n_bands = band_tables(lams, batch.gamma, laws)
    shared = structures.kernel_data
    with numba_threads(n_threads):
        float_summary, int_summary = run_prepared_cells(
            shared,
            structures.masses,
            structures.dampings,
            structures.stiffnesses,
            np.ascontiguousarray(batch.structure_index, dtype=np.int64),
            lams,
            gammas,
            edges,
            intercepts,
            slopes,
            n_bands,
            float(options.t_max),
            int(options.max_events),
            float(options.cycle_tol),
            int(options.max_period),
        )
    return float_summary, int_summary


@contextmanager
def numba_threads(n_threads: int | None) -> Iterator[int]:
    """Run the enclosed parallel kernels on ``n_threads`` threads (all when None), then restore."""
    import numba

    available = int(numba.config.NUMBA_NUM_THREADS)  # type: ignore[attr-defined]
    n = available if n_threads is None else max(1, min(int(n_threads), available))
    previous = numba.get_num_threads()
    previous_chunk = numba.get_parallel_chunksize()
    numba.set_num_threads(n)
    numba.set_parallel_chunksize(THREAD_BATCH)
    try:
        yield n
    finally:
        numba.set_num_threads(previous)
        numba.set_parallel_chunksize(previous_chunk)


def machine_cores() -> int:
    """Cores this process may run on (its CPU affinity where known, else ``os.cpu_count``)."""
    import os

    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def capped_workers(workers: int | None) -> int:
    """Worker processes of a local Dask cluster: ``workers`` capped at :func:`machine_cores`
    (all of them when None). More processes than cores only add memory (each holds an
    interpreter and the compiled engine, ~100 MB): ``--workers 1000`` started 304 processes and
    took 10 GiB before it was killed. Numba threads are capped the same way
    (:func:`numba_threads`)."""
    cores = machine_cores()
    return cores if workers is None else max(1, min(int(workers), cores))


def max_threads() -> int:
    """Number of numba threads available in this process (all cores by default)."""
    import numba

    return int(numba.config.NUMBA_NUM_THREADS)  # type: ignore[attr-defined]


@dataclass(frozen=True)
class Chunk:
    """Cells ``start`` to ``stop - 1`` (flat, lambda-major order) of a sweep; ``index`` numbers it."""

    index: int
    start: int
    stop: int

    @property
    def size(self) -> int:
        """Number of cells."""
        return self.stop - self.start


def check_chunk_size(chunk_size: Any) -> None:
    """Refuse a ``chunk_size`` that is not a whole number of at least 1 (None is the default)."""
    if chunk_size is not None:
        whole_number("chunk_size", chunk_size)  # not a boolean (numpy's neither), not a fraction


def load_stored(store: ChunkStore | None, chunks: Sequence[Chunk], float_summary: FloatArray,
                int_summary: IntArray) -> list[Chunk]:
    """Fill the rows of the chunks a resume store holds; return the chunks still to compute.

    Without a store every chunk is still to compute.
    """
    missing: list[Chunk] = []
    for chunk in chunks:
        stored = store.load(chunk.index, chunk.size) if store is not None else None
        if stored is None:
            missing.append(chunk)
        else:
            float_summary[chunk.start:chunk.stop], int_summary[chunk.start:chunk.stop] = stored
    return missing


def make_chunks(n_cells: int, chunk_size: int) -> list[Chunk]:
    """Consecutive chunks of ``chunk_size`` cells (the last one may be smaller)."""
    if chunk_size < 1:
        raise ValueError(f"chunk_size={chunk_size!r} must be at least 1")
    n_chunks = math.ceil(n_cells / chunk_size)
    return [
        Chunk(k, k * chunk_size, min(n_cells, (k + 1) * chunk_size)) for k in range(n_chunks)
    ]


def default_chunk_size(n_cells: int, backend: Backend = "threads") -> int:
    """Cells per chunk when none is given: progress, resume and task granularity.

    In-process backends: about a hundred chunks of 64 to 16384 cells; at tens of thousands of
    cells per second a chunk takes well under a second, which keeps the progress bar live
    and loses little work when a run is killed (each chunk costs some Python and a store
    write: 245 writes of 4096 cells took 2.8 s of wall time, 62 of 16384 cells 1.5 s).
    Dask: about 32 chunks of 256 to 8192 cells,
    since every task costs the scheduler a few milliseconds (measured on 2 cores: 100 tasks
    of 100 cells ran 1.3x faster on 2 workers than on 1, 20 tasks of 500 cells 1.4x).
    """
    if backend == "dask":
        size = min(8192, max(256, math.ceil(n_cells / 32)))
    else:
        size = min(16384, max(64, math.ceil(n_cells / 100)))
    return int(min(size, max(1, n_cells)))


def check_backend(backend: str, workers: int | None, scheduler: str | None) -> Backend:
    """Validate the backend choice; ``scheduler`` needs ``dask`` and excludes ``workers``."""
    if backend not in BACKENDS:
        raise ValueError(f"backend {backend!r} is not one of {', '.join(BACKENDS)}")
    if workers is not None:
        whole_number("workers", workers)
    if scheduler is not None and not scheduler.strip():
        raise ValueError("--scheduler '' is empty: give the scheduler's address, e.g. "
                         "tcp://10.0.0.5:8786")
    if scheduler is not None and backend != "dask":
        raise ValueError(f"a scheduler address needs the dask backend, not {backend!r}")
    if scheduler is not None and workers is not None:
        raise ValueError("give either a scheduler address or a number of workers, not both")
    if backend == "serial" and workers not in (None, 1):
        raise ValueError(f"the serial backend runs on one thread; workers={workers!r}")
    return backend


def execute(
    structures: S,
    batches: Sequence[tuple[Chunk, B]],
    options: EngineOptions,
    *,
    backend: Backend = "threads",
    workers: int | None = None,
    scheduler: str | None = None,
    task: ChunkTask[S, B] | None = None,
) -> Iterator[tuple[Chunk, FloatArray, IntArray]]:
    """Run every batch and yield ``(chunk, float_summary, int_summary)`` as each one finishes.

    Parameters
    ----------
    structures : StructureSet, or what ``task`` takes
        The data every batch shares (sent once to every Dask worker).
    batches : sequence of (Chunk, CellBatch), or of (Chunk, what ``task`` takes)
        The work, one batch per chunk.
    options : EngineOptions
        Engine limits.
    backend : {"serial", "threads", "dask"}
        ``serial``: one numba thread. ``threads``: ``workers`` numba threads (all cores
        when None). ``dask``: a ``dask.distributed`` client connected to ``scheduler``, or a
        ``LocalCluster`` of ``workers`` single-threaded worker processes on 127.0.0.1.
    workers : int, optional
        Numba threads (``threads``) or worker processes (``dask`` without ``scheduler``).
    scheduler : str, optional
        Address of a running Dask scheduler (``dask`` only).
    task : callable, optional
        The work of one chunk, ``task(structures, batch, options, n_threads) ->
        (float_summary, int_summary)``, run on ``n_threads`` numba threads (1 on a Dask
        worker); a module-level function, so that Dask can send it. Default
        :func:`run_batch`, the cells of a map (``structures`` a :class:`StructureSet`, each
        batch a :class:`CellBatch`); basin stability passes its own (many initial states of
        one system).
    """
    run = task if task is not None else cast("ChunkTask[S, B]", run_batch)
    if not batches:
        return
    if backend == "dask":
        yield from _execute_dask(structures, batches, options, workers, scheduler, run)
        return
    n_threads = 1 if backend == "serial" else workers
    for chunk, batch in batches:
        with deferred_sigint() as sigint:  # Ctrl-C in the kernel (or its compile): after it
            float_summary, int_summary = run(structures, batch, options, n_threads)
        yield chunk, float_summary, int_summary  # the caller keeps it (resume store) ...
        sigint.raise_if_caught()  # ... then Ctrl-C stops the run


def _execute_dask(
    structures: S,
    batches: Sequence[tuple[Chunk, B]],
    options: EngineOptions,
    workers: int | None,
    scheduler: str | None,
    task: ChunkTask[S, B],
) -> Iterator[tuple[Chunk, FloatArray, IntArray]]:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise ValueError(
            "the dask backend needs dask.distributed: pip install 'stickslip[dask]'"
        ) from None
    with _dask_client(Client, LocalCluster, workers, scheduler) as client:
        [shared] = client.scatter([structures], broadcast=True)
        futures: dict[Any, Chunk] = {}
        for chunk, batch in batches:
            future = client.submit(task, shared, batch, options, 1, pure=False)
            futures[future] = chunk
        try:
            for future in as_completed(futures):
                float_summary, int_summary = future.result()
                yield futures[future], float_summary, int_summary
        finally:
            client.cancel(list(futures))


#: Default bound, in seconds, on reaching a Dask scheduler: TCP connection, its handshake and
#: the client's registration. Set ``stickslip.scheduler-timeout`` in the Dask configuration
#: (``dask.config.set``, or the environment variable ``DASK_STICKSLIP__SCHEDULER_TIMEOUT``)
#: to change it; ``--scheduler-timeout`` of ``stickslip map`` and ``stickslip basin`` does.
SCHEDULER_TIMEOUT_S = 10.0

#: Address schemes of a Dask scheduler that can be reached from another process.
_SCHEMES = ("tcp", "tls", "ws", "wss")

#: Longest first message accepted from a scheduler: its handshake is under a hundred bytes.
_MAX_HANDSHAKE_BYTES = 1 << 16


def scheduler_timeout() -> float:
    """Seconds allowed to reach a scheduler: the Dask config key or :data:`SCHEDULER_TIMEOUT_S`."""
    try:
        import dask

        value = dask.config.get("stickslip.scheduler-timeout", default=None)
    except ImportError:  # pragma: no cover - dask is an optional extra
        value = None
    if value is None:
        return SCHEDULER_TIMEOUT_S
    seconds = float(value)
    if not (seconds > 0.0 and math.isfinite(seconds)):
        raise ValueError(f"scheduler timeout {value!r} must be a positive number of seconds")
    return seconds


@contextmanager
def _dask_client(client_cls: Any, cluster_cls: Any, workers: int | None,
                 scheduler: str | None) -> Iterator[Any]:
    if scheduler is not None:
        timeout = scheduler_timeout()
        _probe_tcp(scheduler, timeout)
        try:
            client = client_cls(scheduler, timeout=f"{timeout}s")
        except Exception as exc:  # a wrong peer can fail in many ways; all mean "not reached"
            reason = " ".join(str(exc).split()) or type(exc).__name__
            raise ValueError(f"cannot reach the dask scheduler at {scheduler!r} within "
                             f"{timeout:g} s: {reason}") from None
        with client:
            yield client
        return
    n_workers = capped_workers(workers)
    with (
        cluster_cls(
            n_workers=n_workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            # loopback and a free port: the scheduler's HTTP server runs even without a
            # dashboard, and the default port 8787 may belong to another cluster
            dashboard_address="127.0.0.1:0",
        ) as cluster,
        client_cls(cluster) as client,
    ):
        yield client


def _probe_tcp(address: str, timeout: float | None = None) -> None:
    """Check within ``timeout`` seconds that a ``tcp://`` address is a Dask scheduler.

    A scheduler sends its handshake (a small framed msgpack message naming ``python`` and
    ``pickle-protocol``) as soon as a connection is accepted. A refused port fails at once;
    a silent listener fails after ``timeout``; a peer that answers with anything else (an
    HTTP server, a worker of another protocol) fails as "not a Dask scheduler" -- before the
    Dask client could misread its bytes as a frame length (a 3 EiB allocation) or retry for
    minutes. ``tls://``, ``ws://`` and ``wss://`` addresses must accept a TCP connection (their
    handshake is left to the client); ``inproc://`` (a scheduler inside another process's
    memory) and other schemes are refused -- all before a resume store is made.
    """
    import socket
    import time

    from distributed.comm import parse_address, parse_host_port

    timeout = scheduler_timeout() if timeout is None else float(timeout)
    deadline = time.monotonic() + timeout

    def fail(reason: str) -> ValueError:
        return ValueError(f"cannot reach the dask scheduler at {address!r}: {reason}")

    try:
        protocol, location = parse_address(address)
        if protocol == "inproc":
            raise fail("an inproc:// scheduler lives inside the memory of another process and "
                       "cannot be reached from this one; give its tcp:// address")
        if protocol not in _SCHEMES:
            raise fail(f"the scheme {protocol!r} is not one of {', '.join(_SCHEMES)}")
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise (exc if str(exc).startswith("cannot reach") else fail(reason)) from None
    if protocol != "tcp":
        try:
            socket.create_connection((host, port), timeout=timeout).close()
        except TimeoutError:
            raise fail(f"no answer within {timeout:g} s (see --scheduler-timeout)") from None
        except OSError as exc:
            raise fail(" ".join(str(exc).split()) or type(exc).__name__) from None
        return
    try:
        with socket.create_connection((host, port), timeout=timeout) as sock:
            data = b""
            need = 8
            while len(data) < need:
                left = deadline - time.monotonic()
                if left <= 0.0:
                    raise TimeoutError
                sock.settimeout(left)
                chunk = sock.recv(4096)
                if not chunk:
                    raise fail("the peer closed the connection without a Dask handshake "
                               "(not a Dask scheduler)")
                data += chunk
                if len(data) >= 8:
                    length = int.from_bytes(data[:8], "little")
                    if not 0 < length <= _MAX_HANDSHAKE_BYTES:
                        raise fail("the peer answered with something that is not a Dask "
                                   "handshake (not a Dask scheduler)")
                    need = 8 + length
    except TimeoutError:
        raise fail(f"no Dask handshake within {timeout:g} s (a silent peer, or not a Dask "
                   "scheduler; see --scheduler-timeout)") from None
    except OSError as exc:
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise fail(reason) from None
    if b"pickle-protocol" not in data and b"python" not in data:
        raise fail("the peer's first message is not a Dask handshake (not a Dask scheduler)")
