"""Many contact-engine runs of one machine at other operating points, in a bounded process pool.

The contact engine (:func:`stickslip.analysis.contact.engine.simulate_contact`) is pure Python
and holds the GIL, so its runs are spread over worker *processes* (:data:`START_METHOD`), each
running one operating point after another. A batch of one run, or a pool of one worker, runs
in this process instead. The workers ignore SIGINT:
a Ctrl-C reaches the parent alone, which ends every worker (``terminate``) before the
``KeyboardInterrupt`` goes on, so no worker prints a traceback or outlives the command. With
one worker the runs happen in this process, one after the other.

Each run starts from the machine's start-up state (:meth:`ContactSystem.startup_state`) at
``system.at(speed=V, load=W)`` and gives a :class:`ContactPoint`: verdict, period (s),
amplitude (m), separation.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import signal
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from stickslip.analysis.contact._modes import ContactSystem
from stickslip.analysis.verdict import Verdict
from stickslip.model.machine import Machine

#: Most runs of one call (each is a full contact-engine run).
MAX_POINTS = 100_000
#: Default number of worker processes.
DEFAULT_WORKERS = 2
#: How workers start: ``fork`` where there is one (a worker is ready in milliseconds and the
#: parent runs no threads of its own that the runs need), else ``spawn`` (each worker imports
#: the package first, 1.5 s or more).
START_METHOD = "fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn"


@dataclass(frozen=True)
class ContactPoint:
    """The answer of one run at an operating point (SI).

    Attributes
    ----------
    speed, load : float
        Belt speed ``V`` (m/s) and preload ``W`` (N) of the run.
    verdict : Verdict
        ``stick-slip``, ``slip-oscillation``, ``steady-sliding`` or ``undetermined``.
    period_s, amplitude_m : float
        Period (s) and half peak-to-peak displacement of the contact DOF (m); NaN without a
        repeating motion.
    separated : bool
        True when the contact lifted off at least once.
    certificate : str
        How the verdict was decided, or why there is none.
    n_events : int
        Mode switches of the run.
    """

    speed: float
    load: float
    verdict: Verdict
    period_s: float
    amplitude_m: float
    separated: bool
    certificate: str
    n_events: int


def run_point(system: ContactSystem, speed: float, load: float, t_max: float | None = None,
              max_events: int = 100_000) -> ContactPoint:
    """One run of ``system.at(speed=speed, load=load)`` from its start-up state.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).
    speed, load : float
        Belt speed (m/s) and preload (N), positive.
    t_max : float, optional
        Horizon in natural times ``1 / omega_ref`` of the contact DOF (default that of
        :func:`~stickslip.analysis.contact.engine.simulate_contact`, 5000).
    max_events : int
        Bound on mode switches.

    Returns
    -------
    ContactPoint
        The verdict, period (s), amplitude (m) and separation.
    """
    from stickslip.analysis.contact.engine import simulate_contact

    moved = system.at(speed=speed, load=load)
    horizon = None if t_max is None else t_max / moved.omega_ref
    run = simulate_contact(moved, t_max=horizon, max_events=max_events)
    return ContactPoint(float(speed), float(load), run.verdict,
                        math.nan if run.period_s is None else float(run.period_s),
                        math.nan if run.amplitude_m is None else float(run.amplitude_m),
                        bool(run.separated), run.certificate, len(run.events))


def run_machine_point(machine: Machine, speed: float, load: float, t_max: float | None = None,
                      max_events: int = 100_000) -> ContactPoint:
    """One exact-engine run of a machine without a contact model (no normal DOF, rigid contact).

    The run of :func:`~stickslip.analysis.simulation.simulate` on
    ``machine.with_operating_point(speed, load).to_dimensionless()`` from the start-up state:
    the same verdict (a proven cycle or the steady-sliding bound) as ``simulate --config`` at
    that point, so a machine of ``[structure]`` alone is searched like a contact machine.

    Parameters
    ----------
    machine : Machine
        The structure in SI.
    speed, load : float
        Belt speed (m/s) and normal load (N), positive.
    t_max : float, optional
        Horizon in natural times ``1 / omega_n`` of the contact DOF (default the engine's, 5000).
    max_events : int
        Bound on events of the run.

    Returns
    -------
    ContactPoint
        The verdict, period (s) and amplitude (m); ``separated`` is False (the contact is
        rigid) and ``n_events`` counts the stick phases and breakaways (the engine's band
        changes of a friction table are not counted).
    """
    from stickslip.analysis.engine_run import EngineOptions
    from stickslip.analysis.simulation import simulate

    moved = machine.with_operating_point(speed=speed, load=load)
    structure, slider = moved.to_dimensionless()
    options = EngineOptions(max_events=int(max_events)).with_t_max(t_max)
    run = simulate(structure, slider, options=options, record=False)
    ref = moved.reference_system()
    # NaN without a repeating motion, as the contact engine's
    return ContactPoint(float(speed), float(load), run.verdict, float(run.period) * ref.time_scale,
                        float(run.amplitude) * ref.length_scale, False, run.certificate,
                        int(run.n_stick + run.n_breakaway))


def _init_worker() -> None:
    """Pool initializer: Ctrl-C is the parent's to handle (it ends the workers).

    A forked worker also gets stdout and stderr objects of its own (on the same descriptors):
    the parent's may have been locked by another of its threads (a progress bar's refresh) at
    the fork, and a warning written through them would then wait forever.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in ("stdout", "stderr"):
        stream = getattr(sys, f"__{name}__", None)
        try:
            fd = stream.fileno() if stream is not None else None
        except (OSError, ValueError):
            fd = None
        if fd is not None:
            fresh = os.fdopen(os.dup(fd), "w", buffering=1, closefd=True)
            setattr(sys, name, fresh)


def _check_points(points: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    jobs = [(float(v), float(w)) for v, w in points]
    if len(jobs) > MAX_POINTS:
        raise ValueError(f"{len(jobs):,} runs is more than {MAX_POINTS:,}")
    if any(not (math.isfinite(v) and math.isfinite(w) and v > 0.0 and w > 0.0) for v, w in jobs):
        raise ValueError("every speed (m/s) and load (N) must be positive and finite")
    return jobs


class WorkerPool:
    """A bounded pool of worker processes for contact-engine jobs (a context manager).

    The processes start (:data:`START_METHOD`, :func:`_init_worker`) at the first batch of
    more than one job and serve every later batch; leaving the ``with`` block, normally or by
    an exception (a Ctrl-C), ends them (``terminate``). One worker, or a batch of one job, runs
    in this process. The one home of the contact commands' processes (maps, boundaries,
    cycles, basins, continuation).

    Parameters
    ----------
    workers : int
        Worker processes (1: every job in this process).
    """

    def __init__(self, workers: int = DEFAULT_WORKERS) -> None:
        if isinstance(workers, bool) or int(workers) != workers or workers < 1:
            raise ValueError(f"workers = {workers!r} must be a whole number >= 1")
        self.workers = int(workers)
        self._pool: Any = None

    def __enter__(self) -> WorkerPool:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """End the worker processes (a running job is stopped)."""
        if self._pool is not None:
            pool, self._pool = self._pool, None
            pool.terminate()
            pool.join()

    def map(self, function: Callable[..., Any], jobs: Sequence[tuple[Any, ...]],
            progress: Callable[[int, int], None] | None = None, done: int = 0,
            total: int | None = None) -> list[Any]:
        """``function(*job)`` for every job, in the jobs' order.

        Parameters
        ----------
        function : callable
            A module-level function (picklable), run in the workers.
        jobs : sequence of tuple
            Its arguments, one tuple per job (picklable).
        progress : callable, optional
            ``progress(done + finished, total)`` after each finished job.
        done, total : int
            Jobs finished before this batch and in all (default: this batch's count).

        Returns
        -------
        list
            The results.
        """
        count = len(jobs)
        total = done + count if total is None else total
        out: list[Any] = [None] * count
        if self.workers == 1 or count <= 1:
            for i, job in enumerate(jobs):
                out[i] = function(*job)
                if progress is not None:
                    progress(done + i + 1, total)
            return out
        if self._pool is None:
            self._pool = multiprocessing.get_context(START_METHOD).Pool(
                self.workers, initializer=_init_worker)
        tasks = [(i, function, job) for i, job in enumerate(jobs)]
        for finished, (i, value) in enumerate(self._pool.imap_unordered(_call_indexed, tasks),
                                              start=1):
            out[i] = value
            if progress is not None:
                progress(done + finished, total)
        return out


def _call_indexed(task: tuple[int, Callable[..., Any], tuple[Any, ...]]) -> tuple[int, Any]:
    index, function, job = task
    return index, function(*job)


class ContactPool:
    """Worker processes that run one machine at many operating points (a context manager).

    The processes start at the first batch of more than one run and serve every later batch;
    leaving the ``with`` block, normally or by an exception (a Ctrl-C), ends them.

    Parameters
    ----------
    system : ContactSystem or Machine
        The machine (SI): with its contact (the contact engine, :func:`run_point`), or a
        structure alone (the exact engine, :func:`run_machine_point`).
    workers : int
        Worker processes (1: every run in this process).
    t_max : float, optional
        Horizon of each run in natural times of the contact DOF.
    max_events : int
        Bound on mode switches of each run.
    """

    def __init__(self, system: ContactSystem | Machine, *, workers: int = DEFAULT_WORKERS,
                 t_max: float | None = None, max_events: int = 100_000) -> None:
        # without the caller's mode cache: small to send
        self.system: ContactSystem | Machine = (system if isinstance(system, Machine)
                                                else system.at())
        self._run_one: Callable[..., ContactPoint] = (run_machine_point if isinstance(
            system, Machine) else run_point)
        self.t_max = t_max
        self.max_events = max_events
        self._workers = WorkerPool(workers)

    @property
    def workers(self) -> int:
        """Worker processes."""
        return self._workers.workers

    def __enter__(self) -> ContactPool:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """End the worker processes (a running run is stopped)."""
        self._workers.close()

    def run(self, points: Sequence[tuple[float, float]],
            progress: Callable[[int, int], None] | None = None) -> list[ContactPoint]:
        """Run the machine at every ``(speed, load)`` of ``points`` (m/s, N).

        Parameters
        ----------
        points : sequence of (float, float)
            Belt speeds (m/s) and preloads (N), each positive and finite.
        progress : callable, optional
            ``progress(done, total)`` after each finished run.

        Returns
        -------
        list of ContactPoint
            In the order of ``points``.
        """
        jobs = [(self.system, v, w, self.t_max, self.max_events) for v, w in _check_points(points)]
        if progress is not None:
            progress(0, len(jobs))
        return self._workers.map(self._run_one, jobs, progress)


def run_points(system: ContactSystem, points: Sequence[tuple[float, float]], *,
               workers: int = DEFAULT_WORKERS, t_max: float | None = None,
               max_events: int = 100_000,
               progress: Callable[[int, int], None] | None = None) -> list[ContactPoint]:
    """Run the machine at every ``(speed, load)`` of ``points``, ``workers`` runs at a time.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).
    points : sequence of (float, float)
        Belt speeds (m/s) and preloads (N), each positive and finite.
    workers : int
        Worker processes (1: in this process); see :class:`ContactPool`.
    t_max : float, optional
        Horizon of each run in natural times of the contact DOF.
    max_events : int
        Bound on mode switches of each run.
    progress : callable, optional
        ``progress(done, total)`` after each finished run.

    Returns
    -------
    list of ContactPoint
        In the order of ``points``.

    Raises
    ------
    ValueError
        Too many points, a speed or load that is not positive and finite, ``workers < 1``.
    """
    jobs = _check_points(points)
    with ContactPool(system, workers=min(int(workers), max(1, len(jobs))), t_max=t_max,
                     max_events=max_events) as pool:
        return pool.run(jobs, progress)


__all__ = ["DEFAULT_WORKERS", "MAX_POINTS", "START_METHOD", "ContactPoint", "ContactPool",
           "WorkerPool", "run_point", "run_points"]
