"""Basin stability: certified verdicts for many initial states of one system.

Above the stick-slip boundary the sliding system is usually bistable: steady sliding and a
stick-slip cycle side by side, and which one a disturbed start ends in depends on the start.
The basin-stability literature integrates thousands of random initial states with a smoothed
friction law; here every state gets the engine's certified verdict (exact propagation,
graze-proof events, Lyapunov or cycle certificate), so the fraction ending in stick-slip is
an estimate with binomial standard error ``sqrt(p (1 - p) / n)`` and no integration error.

States are in the engine's shifted dimensionless coordinates (Eqs. 15-16): positions
``xi, xi_a, ...`` from the kinetic-friction equilibrium in units of ``V / omega_n``, velocities
``xi', xi_a', ...`` in units of the belt speed, ground frame. :func:`states_from_physical`
converts positions measured from where the springs are relaxed (m) and velocities (m/s).
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.interpolant_margin import interpolant_mismatch
from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.verdict import (
    VERDICTS,
    RunStatus,
    Verdict,
    verdict_codes,
    verdict_flag_attributes,
)
from stickslip.io.provenance import provenance_attributes
from stickslip.kernel import engine
from stickslip.kernel.interrupt import deferred_sigint
from stickslip.model._validate import random_seed
from stickslip.model.initial import MAX_STATE
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure
from stickslip.sweep.basin_cycles import ProvenBalls, pilot_balls
from stickslip.sweep.execution import ExecutionOptions, execution_from_keywords
from stickslip.sweep.executors import (
    default_chunk_size,
    execute,
    load_stored,
    make_chunks,
    numba_threads,
)

if TYPE_CHECKING:
    import xarray as xr

    from stickslip.model.physical import PhysicalSystem

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Most samples of one basin computation (the summaries take about 150 bytes per sample).
MAX_SAMPLES = 50_000_000

#: Most runs of one basin map (cells x samples per cell), checked before anything starts as
#: ``boundary`` bounds its scan: 1e8 certified runs take one to two hours at the 25,000
#: samples/s measured on two cores (bench_basin); a larger map is split into several.
MAX_MAP_RUNS = 100_000_000

#: Fewest states of a basin for which the slip escape region is built
#: (:mod:`stickslip.kernel.outer_certificate`): measured on issue 21's weak-net-damping case,
#: the region takes about 0.1 s to build, the time of about 400 runs it spares (bench_basin).
ESCAPE_MIN_STATES = 1000

#: States per chunk of the in-process backends when none is given (the unit of progress and
#: of the resume store); the Dask backend cuts about 32 chunks (``default_chunk_size``).
THREADS_CHUNK = 4096



def state_names(n_dof: int) -> list[str]:
    """Column names of dimensionless states: ``xi, v`` (slider), ``xi_a, v_a`` (foundation), ..."""
    suffix = [""] + ["_a"] + [f"_a{i}" for i in range(2, n_dof)]
    return [f"xi{suffix[i]}" for i in range(n_dof)] + [f"v{suffix[i]}" for i in range(n_dof)]


def physical_names(n_dof: int) -> list[str]:
    """Column names of physical states: ``x, v`` [m, m/s] (slider), ``x_a, v_a`` (foundation), ..."""
    suffix = [""] + ["_a"] + [f"_a{i}" for i in range(2, n_dof)]
    return [f"x{suffix[i]}" for i in range(n_dof)] + [f"v{suffix[i]}" for i in range(n_dof)]


def equilibrium_state(structure: Structure, slider: Slider) -> FloatArray:
    """Steady sliding in shifted coordinates: ``K q = (F(1) - gamma lambda) e_0``, ``v = 0``."""
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    b = int(np.searchsorted(edges, 1.0, side="right") - 1)
    force = float(intercepts[b] + slopes[b]) - slider.gamma * slider.lam
    n = structure.n_dof
    if force == 0.0:  # the Coulomb law: the origin, exactly
        return np.zeros(2 * n)
    q = np.linalg.solve(structure.stiffness, force * np.eye(n)[0])
    return np.concatenate([q, np.zeros(n)])


def sample_box(structure: Structure, slider: Slider, n: int, box: Mapping[str, tuple[float, float]],
               seed: int = 0) -> FloatArray:
    """``n`` states uniform in a box (dimensionless, the shifted coordinates of Eqs. 15-16).

    ``box`` maps column names of :func:`state_names` to ``(lo, hi)`` intervals of those
    coordinates, whose origin is steady sliding under the Coulomb law (under a law that varies
    with speed, steady sliding sits at its own ``xi``: :func:`equilibrium_state`); columns not
    named keep their steady-sliding value. Reproducible for a given ``seed``.
    """
    names = state_names(structure.n_dof)
    check_box(box, names)
    n = sample_count(n)
    states = np.tile(equilibrium_state(structure, slider), (n, 1))
    rng = np.random.default_rng(random_seed(seed))
    for name, (lo, hi) in box.items():
        states[:, names.index(name)] = rng.uniform(lo, hi, n)
    return states


def check_box(box: Mapping[str, tuple[float, float]], names: Sequence[str]) -> None:
    """Raise ``ValueError`` unless every column of ``box`` is in ``names`` and every interval
    ``(lo, hi)`` is finite with ``lo <= hi``."""
    unknown = sorted(set(box) - set(names))
    if unknown:
        raise ValueError(f"box columns {', '.join(unknown)} are not among {', '.join(names)}")
    for name, (lo, hi) in box.items():
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise ValueError(f"box {name}={lo!r}:{hi!r} must be a finite interval with lo <= hi")
        if max(abs(lo), abs(hi)) > MAX_STATE:
            raise ValueError(f"box {name}={lo!r}:{hi!r} reaches beyond the supported magnitude "
                             f"{MAX_STATE:g} of a state (its energy would overflow)")


def check_states(states: FloatArray, names: Sequence[str]) -> None:
    """Raise ``ValueError`` unless every entry of ``states`` (rows of ``names``) is finite and
    at most :data:`~stickslip.model.initial.MAX_STATE` in magnitude, the bound of
    ``simulate --initial``; the message names the first bad row (from 1) and column."""
    bad = ~np.isfinite(states) | (np.abs(np.nan_to_num(states, nan=0.0)) > MAX_STATE)
    if np.any(bad):
        row, col = (int(i) for i in np.argwhere(bad)[0])
        raise ValueError(f"initial state {row + 1}: {names[col]}={float(states[row, col])!r} must be finite "
                         f"and at most {MAX_STATE:g} in magnitude (its energy would overflow)")


def check_map_work(n_cells: int, samples: int) -> None:
    """Refuse a basin map of more than :data:`MAX_MAP_RUNS` runs (cells x samples) before it starts."""
    n = sample_count(samples)
    if int(n_cells) * n > MAX_MAP_RUNS:
        raise ValueError(f"a basin map of {int(n_cells):,} cells x {n:,} samples is {int(n_cells) * n:,} "
                         f"runs, above the limit of {MAX_MAP_RUNS:,} (hours of computing); use fewer "
                         "cells or samples, or split the map")


def sample_count(n: int) -> int:
    """``n`` as a sample count: a whole number from 1 to :data:`MAX_SAMPLES`, else ValueError."""
    if isinstance(n, bool) or int(n) != n or not 1 <= int(n) <= MAX_SAMPLES:
        raise ValueError(f"samples={n!r} must be a whole number from 1 to {MAX_SAMPLES:,}")
    return int(n)


def states_from_physical(system: PhysicalSystem, physical: FloatArray) -> FloatArray:
    """Physical states ``(x, x_a, ..., v, v_a, ...)`` [m, m/s] to shifted dimensionless states.

    Positions are measured from where every spring is relaxed (ground frame), velocities are
    ground-frame velocities. ``xi = x / (V / omega_n) - gamma lambda K^-1 e_0`` (the shift of
    Eqs. 15-16; at rest with relaxed springs this is the startup position), ``xi' = v / V``.
    """
    structure = system.structure()
    slider = system.slider()
    n = structure.n_dof
    physical = np.asarray(physical, dtype=np.float64)
    if physical.ndim != 2 or physical.shape[1] != 2 * n:
        raise ValueError(f"physical states need {2 * n} columns ({', '.join(physical_names(n))})")
    shift = slider.gamma * slider.lam * structure.kinetic_equilibrium_offset()
    out = np.empty_like(physical)
    out[:, :n] = physical[:, :n] / system.length_scale - shift
    out[:, n:] = physical[:, n:] / system.speed
    return out


@dataclass
class BasinResult:
    """Outcome of :func:`basin_stability`: one certified verdict per initial state.

    Attributes
    ----------
    states : ndarray, shape (n, 2 n_dof)
        The initial states (dimensionless, shifted; see :func:`state_names`).
    verdict : ndarray of int8, shape (n,)
        Verdict codes (:class:`~stickslip.analysis.verdict.Verdict`).
    float_summary, int_summary : ndarray
        The engine's per-run summaries (layouts of :mod:`stickslip.kernel.engine`).
    elapsed : float
        Wall-clock seconds of the call.
    backend : str
        The backend that ran it (``serial``, ``threads`` or ``dask``).
    chunks_total, chunks_loaded : int
        Chunks of the run, and how many of them were read from a resume store.
    """

    structure: Structure
    slider: Slider
    options: EngineOptions
    states: FloatArray
    verdict: NDArray[np.int8]
    float_summary: FloatArray = field(repr=False)
    int_summary: NDArray[np.int64] = field(repr=False)
    elapsed: float = 0.0
    backend: str = "threads"
    chunks_total: int = 0
    chunks_loaded: int = 0

    @property
    def n(self) -> int:
        """Number of samples."""
        return int(self.verdict.size)

    @property
    def fractions(self) -> dict[str, float]:
        """Fraction of samples per verdict."""
        return {v.value: float(np.count_nonzero(self.verdict == v.code)) / max(1, self.n) for v in VERDICTS}

    @property
    def standard_errors(self) -> dict[str, float]:
        """Binomial standard error of each fraction, ``sqrt(p (1 - p) / n)``."""
        return {k: math.sqrt(p * (1.0 - p) / max(1, self.n)) for k, p in self.fractions.items()}

    @property
    def samples_per_second(self) -> float | None:
        """Throughput of this computation."""
        return self.n / self.elapsed if self.elapsed > 0 else None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: ``n``, ``fractions``, ``standard_errors``, ``undetermined``, time,
        backend and chunks (``total``, ``loaded`` from a resume store, ``computed``)."""
        return {
            "n": self.n,
            "fractions": self.fractions,
            "standard_errors": self.standard_errors,
            "undetermined": int(np.count_nonzero(self.verdict == Verdict.UNDETERMINED.code)),
            "elapsed_s": self.elapsed,
            "samples_per_second": self.samples_per_second,
            "backend": self.backend,
            "chunks": {"total": self.chunks_total, "loaded": self.chunks_loaded,
                       "computed": self.chunks_total - self.chunks_loaded},
            "lambda": self.slider.lam,
            "zeta": self.structure.zeta,
            "gamma": self.slider.gamma,
            "structure": self.structure.name,
            "friction": self.slider.friction.describe(),
            "t_max": self.options.t_max,
        }

    def to_xarray(self) -> xr.Dataset:
        """As an ``xarray.Dataset`` over ``sample`` (CF flags, provenance)."""
        import xarray as xr

        names = state_names(self.structure.n_dof)
        data: dict[str, Any] = {
            name: (("sample",), self.states[:, i], {"long_name": f"initial {name} (shifted, dimensionless)",
                                                    "units": "1"})
            for i, name in enumerate(names)
        }
        data["verdict"] = (("sample",), self.verdict, {
            "long_name": "certified verdict from this initial state", **verdict_flag_attributes()})
        data["t_end"] = (("sample",), self.float_summary[:, engine.F_T_END], {
            "long_name": "dimensionless time at which the run stopped", "units": "1"})
        configuration = basin_configuration(self.structure, self.slider, self.options)
        attrs = provenance_attributes(f"basin stability, {self.structure.name}, lambda = "
                                      f"{self.slider.lam:g}", configuration)
        return xr.Dataset(data, coords={"sample": np.arange(self.n)}, attrs=attrs)

    def plot(self, **kwargs: Any) -> Any:
        """The basin in the slider's phase plane, a ``PlotResult``; see
        :func:`stickslip.plot.basin.basin_plot`."""
        from stickslip.plot.basin import basin_plot

        return basin_plot(self, **kwargs)


@dataclass(frozen=True)
class BasinSystem:
    """One system made ready for :func:`run_state_batch`: plain arrays, so Dask can send it.

    ``mass``, ``damping``, ``stiffness`` are the dimensionless matrices of the structure,
    ``lam`` and ``gamma`` the paper's ratios, ``edges``, ``intercepts``, ``slopes`` the band
    table of the friction law at them (:meth:`FrictionLaw.bands`), tabulated once, and
    ``kernel`` the per-system data of :func:`stickslip.kernel.batch.prepare_states` (matrix
    exponentials, certificates, the slip trap and escape regions), computed once for every
    chunk of a basin (empty: each chunk prepares its own).
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    lam: float
    gamma: float
    edges: FloatArray
    intercepts: FloatArray
    slopes: FloatArray
    kernel: tuple[Any, ...] = field(default=(), repr=False, compare=False)

    @classmethod
    def prepare(cls, structure: Structure, slider: Slider, n_states: int | None = None) -> BasinSystem:
        """The arrays of ``structure``, the band table of ``slider.friction`` and the kernel's
        per-system data; the slip escape region only for ``n_states`` of at least
        :data:`ESCAPE_MIN_STATES` (or None): it costs about as much as running a few hundred
        states, and the labels are the same without it."""
        from stickslip.kernel.batch import prepare_states

        if structure.contact_dof != 0:  # states and box columns are in the contact-first order
            raise ValueError(f"basin sampling needs the contact on DOF 0 (this structure has it on "
                             f"DOF {structure.contact_dof}): pass structure.contact_first()[0] and "
                             "states in that order")
        edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
        lam, gamma = float(slider.lam), float(slider.gamma)
        escape = n_states is None or n_states >= ESCAPE_MIN_STATES
        kernel = prepare_states(structure.mass, structure.damping, structure.stiffness, lam, gamma,
                                edges, intercepts, slopes, True, escape)
        return cls(structure.mass, structure.damping, structure.stiffness, lam, gamma, edges,
                   intercepts, slopes, kernel)


    def with_balls(self, balls: ProvenBalls) -> BasinSystem:
        """This system with the proven contraction balls of ``balls`` in its kernel data
        (:mod:`stickslip.sweep.basin_cycles`); itself when there are none."""
        if not len(balls):
            return self
        from stickslip.kernel.cycle_balls import with_balls

        prepared, r_in, r_hi, escape_data = self.kernel
        return replace(self, kernel=(with_balls(prepared, balls.data, balls.norm), r_in, r_hi,
                                     escape_data))


def run_state_batch(system: BasinSystem, states: FloatArray, options: EngineOptions,
                    n_threads: int | None = None) -> tuple[FloatArray, IntArray]:
    """Run ``system`` from every row of ``states`` on ``n_threads`` numba threads (all when None).

    The per-chunk task of :func:`basin_stability` (for
    :func:`stickslip.sweep.executors.execute`, on every backend): ``run_prepared_states`` of
    :mod:`stickslip.kernel.batch` on the system's data prepared once (``run_states`` when
    there is none). Returns the float and integer summaries, shapes
    ``(n, N_FLOAT)`` and ``(n, N_INT)``.
    """
    from stickslip.kernel.batch import run_prepared_states, run_states

    limits = (float(options.t_max), int(options.max_events), float(options.cycle_tol),
              int(options.max_period))
    with numba_threads(n_threads):
        if system.kernel:
            prepared, r_in, r_hi, escape_data = system.kernel
            float_summary, int_summary = run_prepared_states(
                system.mass, system.stiffness, system.lam, system.gamma, system.edges, prepared,
                r_in, r_hi, escape_data, states, *limits, True)
        else:
            float_summary, int_summary = run_states(
                system.mass, system.damping, system.stiffness, system.lam, system.gamma,
                system.edges, system.intercepts, system.slopes, states, *limits)
    return float_summary, int_summary


def basin_stability(
    structure: Structure,
    slider: Slider,
    states: FloatArray,
    *,
    options: EngineOptions | None = None,
    execution: ExecutionOptions | None = None,
    **legacy: Any,
) -> BasinResult:
    """Certified verdict for every initial state of one system, on numba threads or Dask.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (dimensionless); the friction law is ``slider.friction``.
    states : array_like, shape (n, 2 n_dof)
        Initial states in shifted dimensionless coordinates (:func:`sample_box`,
        :func:`states_from_physical`).
    options : EngineOptions, optional
        Horizon and budgets of every run.
    execution : ExecutionOptions, optional
        How the runs are carried out, as for maps (:class:`stickslip.sweep.execution.ExecutionOptions`):
        backend (the labels are identical across backends: every state is an independent,
        deterministic run), workers, scheduler, chunk size (states per chunk; default
        :data:`THREADS_CHUNK` in process, about 32 chunks with Dask; an existing store keeps
        its own), progress ``progress(done, total)`` (in completion order), resume store (a
        later call with the same system, options and states computes only the missing
        chunks, on any backend) and overwrite.
    **legacy
        ``backend=``, ``workers=``, ``scheduler=``, ``chunk_size=``, ``progress=``,
        ``store=``, ``overwrite=``: deprecated spellings of the fields of ``execution``.
    """
    run = execution_from_keywords(execution, legacy, "basin_stability")
    backend, chunk_size, store, progress = run.backend, run.chunk_size, run.store, run.progress
    opts = options or EngineOptions()
    z0s = np.ascontiguousarray(states, dtype=np.float64)
    n_dof = structure.n_dof
    if z0s.ndim != 2 or z0s.shape[1] != 2 * n_dof:
        raise ValueError(f"states need shape (n, {2 * n_dof}) for a {n_dof}-DOF structure, got {z0s.shape}")
    sample_count(z0s.shape[0])
    check_states(z0s, state_names(n_dof))
    started = time.perf_counter()
    # Ctrl-C while the system's data is prepared (and its kernels compile) is held, as inside a
    # chunk (kernel.interrupt): it stops the run once the first chunk is kept
    with deferred_sigint() as sigint:
        system = BasinSystem.prepare(structure, slider, z0s.shape[0])
        # N DOF: the stable cycles' proven balls, from the first states (basin_cycles)
        balls = pilot_balls(structure, slider, z0s, opts)
        system = system.with_balls(balls)
    n = z0s.shape[0]
    if chunk_size is None:
        chunk_size = default_chunk_size(n, backend) if backend == "dask" else THREADS_CHUNK
    fsum = np.empty((n, engine.N_FLOAT))
    isum = np.empty((n, engine.N_INT), dtype=np.int64)
    chunk_store = None
    if store is not None:
        from stickslip.sweep.store import ChunkStore

        configuration = basin_configuration(structure, slider, opts)
        configuration["states_sha256"] = hashlib.sha256(z0s.tobytes()).hexdigest()
        fingerprint = hashlib.sha256(json.dumps(configuration, sort_keys=True).encode()).hexdigest()
        chunk_store = ChunkStore(store, fingerprint, configuration, n, int(chunk_size),
                                 overwrite=run.overwrite)
        chunk_size = chunk_store.chunk_size
    chunks = make_chunks(n, int(chunk_size))
    missing = load_stored(chunk_store, chunks, fsum, isum)
    done = n - sum(c.size for c in missing)
    if progress is not None:
        progress(done, n)
    batches = [(c, z0s[c.start:c.stop]) for c in missing]
    for chunk, f_chunk, i_chunk in execute(system, batches, opts, backend=backend, workers=run.workers,
                                           scheduler=run.scheduler, task=run_state_batch):
        if structure.n_dof > 1:  # every label proven: the candidates a ball did not hold
            balls.prove_candidates(z0s[chunk.start:chunk.stop], f_chunk, i_chunk)
        fsum[chunk.start:chunk.stop], isum[chunk.start:chunk.stop] = f_chunk, i_chunk
        if chunk_store is not None:
            chunk_store.save(chunk.index, f_chunk, i_chunk)
        done += chunk.size
        if progress is not None:
            progress(done, n)
        sigint.raise_if_caught()
    sigint.raise_if_caught()  # every chunk was stored already
    if chunk_store is not None:
        chunk_store.record_run(len(chunks) - len(missing), len(missing), backend)
    mismatch = interpolant_mismatch(structure, slider)
    if mismatch is not None:  # a certificate of the interpolant that does not hold for the law
        kernel, withheld = ((engine.STATUS_STEADY, RunStatus.INTERPOLANT_STEADY)
                            if mismatch[0] == "steady"
                            else (engine.STATUS_OSCILLATION, RunStatus.INTERPOLANT_OSCILLATION))
        isum[isum[:, engine.I_STATUS] == kernel, engine.I_STATUS] = withheld.code
    return BasinResult(structure, slider, opts, z0s, verdict_codes(isum[:, engine.I_STATUS]), fsum,
                       isum, time.perf_counter() - started, backend, len(chunks),
                       len(chunks) - len(missing))


def write_labels(result: BasinResult, path: str | Path, rows: Sequence[Mapping[str, Any]] | None = None,
                 columns: Sequence[str] | None = None) -> Path:
    """``labels.csv``: the input rows in their order (or the dimensionless states) plus ``verdict``."""
    import csv
    import io

    from stickslip.io.atomic import atomic_write_text

    if rows is None:
        columns = state_names(result.structure.n_dof)
        rows = [dict(zip(columns, (repr(float(x)) for x in state), strict=True)) for state in result.states]
    assert columns is not None
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow([*columns, "verdict"])
    for row, code in zip(rows, result.verdict, strict=True):
        writer.writerow([row[c] for c in columns] + [VERDICTS[int(code)].value])
    atomic_write_text(path, buffer.getvalue())
    return Path(path)


def basin_configuration(structure: Structure, slider: Slider, options: EngineOptions) -> dict[str, Any]:
    """The resolved configuration of a basin computation, JSON-ready (datasets, resume stores).

    With two or more degrees of freedom it says that stick-slip labels are proven
    (:mod:`stickslip.sweep.basin_cycles`), so a store written when they were observed is not
    resumed into a run that proves them.
    """
    configuration = {
        "lambda": slider.lam, "gamma": slider.gamma, "zeta": structure.zeta,
        "structure": structure.name, "mass": structure.mass.tolist(),
        "damping": structure.damping.tolist(), "stiffness": structure.stiffness.tolist(),
        "friction": slider.friction.to_dict(), "engine": options.to_dict(),
    }
    if structure.n_dof > 1:
        configuration["stick_slip_labels"] = "proven cycles"
    return configuration


#: Names that moved to :mod:`stickslip.sweep.basin_maps` (one system's basin here, maps there);
#: still importable from here for one release, with a DeprecationWarning.
_MOVED_TO_BASIN_MAP = ("BasinMap", "DEFAULT_MAP_BOX", "basin_map")


def __getattr__(name: str) -> Any:
    """A name moved to :mod:`stickslip.sweep.basin_maps`, with a ``DeprecationWarning`` (PEP 562).

    Loaded by name, as ``stickslip.analysis.tuning`` does for its moved names: the shim is the
    old path only, not an import of the layer's structure (basin_maps builds on this module).
    """
    if name in _MOVED_TO_BASIN_MAP:
        import importlib
        import warnings

        module = importlib.import_module("stickslip.sweep.basin_maps")

        warnings.warn(f"stickslip.sweep.basin.{name} moved to stickslip.sweep.basin_maps.{name}; the old "
                      "path will be removed in the next release", DeprecationWarning, stacklevel=2)
        return getattr(module, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
