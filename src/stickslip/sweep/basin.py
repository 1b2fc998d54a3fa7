"""Basin stability: certified verdicts for many initial states of one system (DESIGN.md section 9).

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
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.verdict import VERDICTS, Verdict, verdict_codes, verdict_flag_attributes
from stickslip.io.provenance import provenance_attributes
from stickslip.kernel import engine
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure
from stickslip.sweep.executors import (
    Backend,
    check_backend,
    check_chunk_size,
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
Progress = Callable[[int, int], None]

#: Most samples of one basin computation (the summaries take about 150 bytes per sample).
MAX_SAMPLES = 50_000_000

#: States per chunk of the in-process backends when none is given (the unit of progress and
#: of the resume store); the Dask backend cuts about 32 chunks (``default_chunk_size``).
THREADS_CHUNK = 4096

#: The disturbance box of :func:`basin_map` when none is given: deviations of the slider's
#: ``xi`` and ``xi'`` from steady sliding (dimensionless, ``V / omega_n`` and ``V``).
DEFAULT_MAP_BOX: dict[str, tuple[float, float]] = {"xi": (-2.0, 2.0), "v": (-2.0, 1.0)}


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
    """``n`` states uniform in a box around steady sliding (dimensionless, shifted).

    ``box`` maps column names of :func:`state_names` to ``(lo, hi)`` intervals; columns not
    named keep their steady-sliding value. Reproducible for a given ``seed``.
    """
    names = state_names(structure.n_dof)
    check_box(box, names)
    n = _count(n)
    states = np.tile(equilibrium_state(structure, slider), (n, 1))
    rng = np.random.default_rng(seed)
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


def _count(n: int) -> int:
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
        configuration = _configuration(self.structure, self.slider, self.options)
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
    table of the friction law at them (:meth:`FrictionLaw.bands`), tabulated once.
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    lam: float
    gamma: float
    edges: FloatArray
    intercepts: FloatArray
    slopes: FloatArray

    @classmethod
    def prepare(cls, structure: Structure, slider: Slider) -> BasinSystem:
        """The arrays of ``structure`` and the band table of ``slider.friction``."""
        if structure.contact_dof != 0:  # states and box columns are in the contact-first order
            raise ValueError(f"basin sampling needs the contact on DOF 0 (this structure has it on "
                             f"DOF {structure.contact_dof}): pass structure.contact_first()[0] and "
                             "states in that order")
        edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
        return cls(structure.mass, structure.damping, structure.stiffness, float(slider.lam),
                   float(slider.gamma), edges, intercepts, slopes)


def run_state_batch(system: BasinSystem, states: FloatArray, options: EngineOptions,
                    n_threads: int | None = None) -> tuple[FloatArray, IntArray]:
    """Run ``system`` from every row of ``states`` on ``n_threads`` numba threads (all when None).

    The per-chunk task of :func:`basin_stability` (for
    :func:`stickslip.sweep.executors.execute`, on every backend): ``run_states`` of
    :mod:`stickslip.kernel.batch`. Returns the float and integer summaries, shapes
    ``(n, N_FLOAT)`` and ``(n, N_INT)``.
    """
    from stickslip.kernel.batch import run_states

    with numba_threads(n_threads):
        float_summary, int_summary = run_states(
            system.mass, system.damping, system.stiffness, system.lam, system.gamma, system.edges,
            system.intercepts, system.slopes, states, float(options.t_max), int(options.max_events),
            float(options.cycle_tol), int(options.max_period))
    return float_summary, int_summary


def basin_stability(
    structure: Structure,
    slider: Slider,
    states: FloatArray,
    *,
    options: EngineOptions | None = None,
    backend: Backend = "threads",
    workers: int | None = None,
    scheduler: str | None = None,
    chunk_size: int | None = None,
    progress: Progress | None = None,
    store: str | Path | None = None,
    overwrite: bool = False,
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
    backend : {"threads", "serial", "dask"}
        As for maps (:func:`stickslip.occurrence_map`, :func:`stickslip.sweep.executors.execute`):
        ``threads``: ``workers`` numba threads (all cores when None); ``serial``: one thread;
        ``dask``: a ``dask.distributed`` cluster at ``scheduler``, or a ``LocalCluster`` of
        ``workers`` single-threaded processes on 127.0.0.1. The labels are identical across
        backends (every state is an independent, deterministic run).
    workers : int, optional
        Threads (``threads``) or worker processes (``dask`` without ``scheduler``); >= 1.
    scheduler : str, optional
        Address of a running Dask scheduler (``dask`` only).
    chunk_size : int, optional
        States per chunk (unit of progress, of Dask tasks and of the resume store); default
        :data:`THREADS_CHUNK` in process, about 32 chunks with Dask. An existing store keeps
        its own chunk size.
    progress : callable, optional
        ``progress(done, total)`` at the start and after every chunk (in completion order).
    store : path, optional
        Resume store folder (:class:`stickslip.sweep.store.ChunkStore`, as for maps): finished
        chunks are written there as they complete, and a later call with the same system,
        options and states computes only the missing ones, on any backend.
    overwrite : bool
        Discard a store of another configuration instead of raising ``StoreMismatch``.
    """
    opts = options or EngineOptions()
    backend = check_backend(backend, workers, scheduler)
    z0s = np.ascontiguousarray(states, dtype=np.float64)
    n_dof = structure.n_dof
    if z0s.ndim != 2 or z0s.shape[1] != 2 * n_dof:
        raise ValueError(f"states need shape (n, {2 * n_dof}) for a {n_dof}-DOF structure, got {z0s.shape}")
    _count(z0s.shape[0])
    if not np.all(np.isfinite(z0s)):
        raise ValueError("initial states have NaN or infinite entries")
    check_chunk_size(chunk_size)
    system = BasinSystem.prepare(structure, slider)
    started = time.perf_counter()
    n = z0s.shape[0]
    if chunk_size is None:
        chunk_size = default_chunk_size(n, backend) if backend == "dask" else THREADS_CHUNK
    fsum = np.empty((n, engine.N_FLOAT))
    isum = np.empty((n, engine.N_INT), dtype=np.int64)
    chunk_store = None
    if store is not None:
        from stickslip.sweep.store import ChunkStore

        configuration = _configuration(structure, slider, opts)
        configuration["states_sha256"] = hashlib.sha256(z0s.tobytes()).hexdigest()
        fingerprint = hashlib.sha256(json.dumps(configuration, sort_keys=True).encode()).hexdigest()
        chunk_store = ChunkStore(store, fingerprint, configuration, n, int(chunk_size), overwrite=overwrite)
        chunk_size = chunk_store.chunk_size
    chunks = make_chunks(n, int(chunk_size))
    missing = load_stored(chunk_store, chunks, fsum, isum)
    done = n - sum(c.size for c in missing)
    if progress is not None:
        progress(done, n)
    batches = [(c, z0s[c.start:c.stop]) for c in missing]
    for chunk, f_chunk, i_chunk in execute(system, batches, opts, backend=backend, workers=workers,
                                           scheduler=scheduler, task=run_state_batch):
        fsum[chunk.start:chunk.stop], isum[chunk.start:chunk.stop] = f_chunk, i_chunk
        if chunk_store is not None:
            chunk_store.save(chunk.index, f_chunk, i_chunk)
        done += chunk.size
        if progress is not None:
            progress(done, n)
    if chunk_store is not None:
        chunk_store.record_run(len(chunks) - len(missing), len(missing), backend)
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


@dataclass
class BasinMap:
    """Result of :func:`basin_map`: the dataset and how long it took.

    ``dataset`` has coordinates ``lambda`` and ``zeta`` (or ``lambda`` and ``delta`` for a map
    over the slope of the linear friction law at one ``zeta``, kept in ``attrs["zeta"]``) and
    the variables ``stick_slip_fraction`` (fraction of the fixed disturbance sample that ends
    in stick-slip), ``standard_error`` (binomial), ``undetermined_fraction`` and
    ``startup_verdict`` (the verdict from the start-up state, as in
    :func:`stickslip.occurrence_map` on the same grid).
    """

    dataset: xr.Dataset
    elapsed: float = 0.0

    @property
    def second(self) -> str:
        """Name of the grid's second axis: ``"zeta"`` or ``"delta"``."""
        return str(self.dataset["stick_slip_fraction"].dims[1])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary of the map.

        Keys: ``axes``, ``n_lambda``, ``n_zeta`` or ``n_delta`` (and the fixed ``zeta``),
        ``n_cells``, ``samples``, ``seed``, ``box``, ``startup_counts`` (cells per start-up
        verdict), ``mean_stick_slip_fraction``, ``max_stick_slip_fraction``,
        ``max_undetermined_fraction``, ``disturbable_cells`` (cells whose start-up ends in
        steady sliding although part of the disturbance sample ends in stick-slip: bistable
        cells that the start-up verdict calls safe), ``elapsed_s``, ``samples_per_second``,
        ``dva``, ``gamma``, ``friction``, ``t_max``.
        """
        ds = self.dataset
        fraction = np.asarray(ds["stick_slip_fraction"].values)
        startup = np.asarray(ds["startup_verdict"].values)
        configuration = json.loads(ds.attrs["configuration"])
        n_cells = int(fraction.size)
        samples = int(configuration["samples"])
        second: dict[str, Any] = {f"n_{self.second}": int(ds[self.second].size)}
        if self.second == "delta":
            second["zeta"] = float(ds.attrs["zeta"])
        disturbable = (startup == Verdict.STEADY_SLIDING.code) & (fraction > 0.0)
        return {
            "axes": ["lambda", self.second],
            "n_lambda": int(ds["lambda"].size),
            **second,
            "n_cells": n_cells,
            "samples": samples,
            "seed": configuration["seed"],
            "box": configuration["box"],
            "startup_counts": {v.value: int(np.count_nonzero(startup == v.code)) for v in VERDICTS},
            "mean_stick_slip_fraction": float(fraction.mean()),
            "max_stick_slip_fraction": float(fraction.max()),
            "max_undetermined_fraction": float(np.asarray(ds["undetermined_fraction"].values).max()),
            "disturbable_cells": int(np.count_nonzero(disturbable)),
            "elapsed_s": self.elapsed,
            "samples_per_second": n_cells * samples / self.elapsed if self.elapsed > 0 else None,
            "dva": ds.attrs["dva"],
            "gamma": configuration["gamma"],
            "friction": ds.attrs["friction"],
            "t_max": configuration["engine"]["t_max"],
        }

    def to_netcdf(self, path: str | Path, *, overwrite: bool = True) -> Path:
        """Write the dataset atomically; see :func:`stickslip.io.netcdf.write_dataset`."""
        from stickslip.io.netcdf import write_dataset

        return write_dataset(self.dataset, path, overwrite=overwrite)

    def plot(self, **kwargs: Any) -> Any:
        """The fractions with the start-up boundary, a ``PlotResult``; see
        :func:`stickslip.plot.basin.basin_map_plot`."""
        from stickslip.plot.basin import basin_map_plot

        return basin_map_plot(self, **kwargs)


def basin_map(
    lams: Any,
    zetas: Any,
    dva: Any = "none",
    gamma: float = 2.0,
    *,
    samples: int = 500,
    box: Mapping[str, tuple[float, float]] | None = None,
    seed: int = 0,
    friction: Any = None,
    deltas: Any = None,
    options: EngineOptions | None = None,
    workers: int | None = None,
    progress: Progress | None = None,
) -> BasinMap:
    """Basin stability over a ``(lambda, zeta)`` or ``(lambda, delta)`` grid, next to the
    start-up verdict (issue 13, point 2).

    Every cell is disturbed by the same fixed sample of ``samples`` deviations from its own
    steady sliding, drawn uniformly in ``box`` with ``seed``, so cells differ only by their
    dynamics. Each state gets a certified verdict (:func:`basin_stability`).

    Parameters
    ----------
    lams, zetas : Axis, array_like or str
        The grid (axis specs as in :func:`stickslip.occurrence_map`): ``lambda > 0`` and
        damping ratios ``zeta >= 0``, dimensionless. With ``deltas``, ``zetas`` holds the one
        fixed ``zeta``.
    dva : DvaSpec or str
        The foundation at each ``zeta``.
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless.
    samples : int
        Disturbances per cell (1 to :data:`MAX_SAMPLES`).
    box : mapping of str to (float, float), optional
        Intervals of the deviations from steady sliding, by column of :func:`state_names`
        (``xi``, ``v``, ``xi_a``, ``v_a``; positions in ``V / omega_n``, velocities in ``V``);
        unnamed columns are not disturbed. Default :data:`DEFAULT_MAP_BOX`.
    seed : int
        Seed of the disturbance sample (drawn column after column, in the order of
        :func:`state_names`: ``xi`` before ``v``).
    friction : FrictionLaw, optional
        Friction law of every cell (the paper's Coulomb law by default); not with ``deltas``.
    deltas : Axis, array_like or str, optional
        Slopes ``delta = sigma W / (2 sqrt(m k))`` of the linear law (dimensionless, > 0
        velocity weakening): the map is then over ``(lambda, delta)`` at the one ``zeta``,
        cell ``(i, j)`` with the law ``LinearFriction(delta_j)``, as in
        :func:`stickslip.occurrence_map`.
    options : EngineOptions, optional
        Engine limits of every run.
    workers : int, optional
        Numba threads (all cores when None).
    progress : callable, optional
        ``progress(done_cells, total_cells)``.
    """
    import xarray as xr

    from stickslip.model.friction import LinearFriction
    from stickslip.sweep.occurrence import _DELTA_LAW, MapConfig, occurrence_map

    started = time.perf_counter()
    config = MapConfig.create(lams, zetas, dva, gamma, options=options, friction=friction, deltas=deltas)
    check_backend("threads", workers, None)
    n = _count(samples)
    box = dict(DEFAULT_MAP_BOX if box is None else box)
    structures = config.structures
    names = state_names(structures.n_dof)
    check_box(box, names)
    rng = np.random.default_rng(seed)  # columns drawn in the order of state_names, whatever box's
    deviations = {name: rng.uniform(*box[name], n) for name in names if name in box}
    by_delta = config.delta is not None
    startup = occurrence_map(config.lam, config.zeta, config.dva, config.gamma, options=config.options,
                             friction=None if by_delta else config.friction, deltas=config.delta,
                             workers=workers)
    shape = config.shape
    fraction = np.empty(shape)
    undetermined = np.empty(shape)
    total = config.n_cells
    done = 0
    if progress is not None:
        progress(0, total)
    for j in range(shape[1]):
        # a (lambda, zeta) map: the structure of zeta_j and one law; (lambda, delta): the one
        # structure and the linear law of delta_j
        at = 0 if by_delta else j
        law = LinearFriction(float(config.second_axis.values[j])) if by_delta else config.friction
        structure = Structure(structures.masses[at], structures.dampings[at], structures.stiffnesses[at])
        for i, lam in enumerate(config.lam.values):
            slider = Slider(float(lam), gamma=config.gamma, friction=law)
            states = np.tile(equilibrium_state(structure, slider), (n, 1))
            for name, values in deviations.items():
                states[:, names.index(name)] += values
            result = basin_stability(structure, slider, states, options=config.options, workers=workers)
            fraction[i, j] = result.fractions[Verdict.STICK_SLIP.value]
            undetermined[i, j] = result.fractions[Verdict.UNDETERMINED.value]
            done += 1
            if progress is not None:
                progress(done, total)
    dims = ("lambda", config.second)
    title = f"basin stability map, {config.dva.describe()}, gamma = {config.gamma:g}"
    extra: dict[str, Any] = {}
    if by_delta:
        fixed = float(config.zeta.values[0])
        title += f", over (lambda, delta) at zeta = {fixed:g}, friction {_DELTA_LAW}"
        extra = {"zeta": fixed}
    law_text = _DELTA_LAW if by_delta else config.friction.describe()
    ds = xr.Dataset(
        {
            "stick_slip_fraction": (dims, fraction, {
                "long_name": "fraction of the fixed disturbance sample ending in stick-slip", "units": "1"}),
            "standard_error": (dims, np.sqrt(fraction * (1.0 - fraction) / n), {
                "long_name": "binomial standard error of stick_slip_fraction", "units": "1"}),
            "undetermined_fraction": (dims, undetermined, {
                "long_name": "fraction of the sample without a certified verdict", "units": "1"}),
            "startup_verdict": startup.dataset["verdict"],
        },
        coords={name: startup.dataset[name] for name in dims},
        attrs={
            **provenance_attributes(title, {**config.to_dict(), "samples": n, "seed": seed,
                                            "box": {k: list(v) for k, v in box.items()}}),
            "dva": config.dva.describe(),
            "friction": law_text,
            **extra,
        },
    )
    return BasinMap(ds, time.perf_counter() - started)


def _configuration(structure: Structure, slider: Slider, options: EngineOptions) -> dict[str, Any]:
    """The resolved configuration of a basin computation, JSON-ready (datasets, resume stores)."""
    return {
        "lambda": slider.lam, "gamma": slider.gamma, "zeta": structure.zeta,
        "structure": structure.name, "mass": structure.mass.tolist(),
        "damping": structure.damping.tolist(), "stiffness": structure.stiffness.tolist(),
        "friction": slider.friction.to_dict(), "engine": options.to_dict(),
    }
