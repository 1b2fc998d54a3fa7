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

if TYPE_CHECKING:
    import xarray as xr

    from stickslip.model.physical import PhysicalSystem

FloatArray = NDArray[np.float64]
Progress = Callable[[int, int], None]

#: Most samples of one basin computation (the summaries take about 150 bytes per sample).
MAX_SAMPLES = 50_000_000


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
    unknown = sorted(set(box) - set(names))
    if unknown:
        raise ValueError(f"box columns {', '.join(unknown)} are not among {', '.join(names)}")
    n = _count(n)
    states = np.tile(equilibrium_state(structure, slider), (n, 1))
    rng = np.random.default_rng(seed)
    for name, (lo, hi) in box.items():
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise ValueError(f"box {name}={lo!r}:{hi!r} must be a finite interval with lo <= hi")
        states[:, names.index(name)] = rng.uniform(lo, hi, n)
    return states


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
    """

    structure: Structure
    slider: Slider
    options: EngineOptions
    states: FloatArray
    verdict: NDArray[np.int8]
    float_summary: FloatArray = field(repr=False)
    int_summary: NDArray[np.int64] = field(repr=False)
    elapsed: float = 0.0

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
        """JSON-ready summary: ``n``, ``fractions``, ``standard_errors``, ``undetermined``, time."""
        return {
            "n": self.n,
            "fractions": self.fractions,
            "standard_errors": self.standard_errors,
            "undetermined": int(np.count_nonzero(self.verdict == Verdict.UNDETERMINED.code)),
            "elapsed_s": self.elapsed,
            "samples_per_second": self.samples_per_second,
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


def basin_stability(
    structure: Structure,
    slider: Slider,
    states: FloatArray,
    *,
    options: EngineOptions | None = None,
    workers: int | None = None,
    chunk_size: int = 4096,
    progress: Progress | None = None,
    store: str | Path | None = None,
    overwrite: bool = False,
) -> BasinResult:
    """Certified verdict for every initial state of one system, in parallel over numba threads.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (dimensionless); the friction law is ``slider.friction``.
    states : array_like, shape (n, 2 n_dof)
        Initial states in shifted dimensionless coordinates (:func:`sample_box`,
        :func:`states_from_physical`).
    options : EngineOptions, optional
        Horizon and budgets of every run.
    workers : int, optional
        Numba threads (all cores when None).
    chunk_size : int
        States per batch (unit of progress).
    progress : callable, optional
        ``progress(done, total)`` after every batch.
    store : path, optional
        Resume store folder (:class:`stickslip.sweep.store.ChunkStore`, as for maps): finished
        batches are written there as they complete, and a later call with the same system,
        options and states computes only the missing ones.
    overwrite : bool
        Discard a store of another configuration instead of raising ``StoreMismatch``.
    """
    from stickslip.kernel.batch import run_states
    from stickslip.sweep.executors import numba_threads

    opts = options or EngineOptions()
    z0s = np.ascontiguousarray(states, dtype=np.float64)
    n_dof = structure.n_dof
    if z0s.ndim != 2 or z0s.shape[1] != 2 * n_dof:
        raise ValueError(f"states need shape (n, {2 * n_dof}) for a {n_dof}-DOF structure, got {z0s.shape}")
    _count(z0s.shape[0])
    if not np.all(np.isfinite(z0s)):
        raise ValueError("initial states have NaN or infinite entries")
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    started = time.perf_counter()
    n = z0s.shape[0]
    fsum = np.empty((n, engine.N_FLOAT))
    isum = np.empty((n, engine.N_INT), dtype=np.int64)
    chunk_store = None
    if store is not None:
        from stickslip.sweep.store import ChunkStore

        configuration = _configuration(structure, slider, opts)
        configuration["states_sha256"] = hashlib.sha256(z0s.tobytes()).hexdigest()
        fingerprint = hashlib.sha256(json.dumps(configuration, sort_keys=True).encode()).hexdigest()
        chunk_store = ChunkStore(store, fingerprint, configuration, n, chunk_size, overwrite=overwrite)
        chunk_size = chunk_store.chunk_size
    done = 0
    if progress is not None:
        progress(0, n)
    with numba_threads(workers):
        for index, start in enumerate(range(0, n, chunk_size)):
            stop = min(n, start + chunk_size)
            stored = chunk_store.load(index, stop - start) if chunk_store is not None else None
            if stored is not None:
                fsum[start:stop], isum[start:stop] = stored
            else:
                fsum[start:stop], isum[start:stop] = run_states(
                    structure.mass, structure.damping, structure.stiffness, float(slider.lam),
                    float(slider.gamma), edges, intercepts, slopes, z0s[start:stop], float(opts.t_max),
                    int(opts.max_events), float(opts.cycle_tol), int(opts.max_period))
                if chunk_store is not None:
                    chunk_store.save(index, fsum[start:stop], isum[start:stop])
            done = stop
            if progress is not None:
                progress(done, n)
    return BasinResult(structure, slider, opts, z0s, verdict_codes(isum[:, engine.I_STATUS]), fsum,
                       isum, time.perf_counter() - started)


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

    ``dataset`` has coordinates ``lambda`` and ``zeta`` and the variables
    ``stick_slip_fraction`` (fraction of the fixed disturbance sample that ends in stick-slip),
    ``standard_error`` (binomial), ``undetermined_fraction`` and ``startup_verdict`` (the verdict
    from the start-up state, as in :func:`stickslip.occurrence_map`).
    """

    dataset: xr.Dataset
    elapsed: float = 0.0

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
    options: EngineOptions | None = None,
    workers: int | None = None,
    progress: Progress | None = None,
) -> BasinMap:
    """Basin stability over a ``(lambda, zeta)`` grid, next to the start-up verdict (issue 13).

    Every cell is disturbed by the same fixed sample of ``samples`` deviations from its own
    steady sliding, drawn uniformly in ``box`` (deviations of the slider's ``xi`` and ``v``;
    default ``xi`` in ``[-2, 2]``, ``v`` in ``[-2, 1]``, dimensionless) with ``seed``, so cells
    differ only by their dynamics. Each state gets a certified verdict.

    Parameters
    ----------
    lams, zetas : Axis, array_like or str
        The grid (axis specs as in :func:`stickslip.occurrence_map`).
    dva : DvaSpec or str
        The foundation at each ``zeta``.
    gamma : float
        ``mu_k / (mu_s - mu_k)``.
    samples, box, seed :
        The fixed disturbance sample.
    friction : FrictionLaw, optional
        Friction law of every cell.
    options : EngineOptions, optional
        Engine limits of every run.
    workers : int, optional
        Numba threads.
    progress : callable, optional
        ``progress(done_cells, total_cells)``.
    """
    import xarray as xr

    from stickslip.model.friction import CoulombFriction
    from stickslip.sweep.occurrence import MapConfig, occurrence_map

    started = time.perf_counter()
    law = friction or CoulombFriction()
    config = MapConfig.create(lams, zetas, dva, gamma, options=options, friction=law)
    n = _count(samples)
    box = dict(box or {"xi": (-2.0, 2.0), "v": (-2.0, 1.0)})
    rng = np.random.default_rng(seed)
    deviations = {name: rng.uniform(lo, hi, n) for name, (lo, hi) in box.items()}
    startup = occurrence_map(config.lam, config.zeta, config.dva, config.gamma, options=config.options,
                             friction=law, workers=workers)
    shape = config.shape
    fraction = np.empty(shape)
    undetermined = np.empty(shape)
    structures = config.structures
    total = config.n_cells
    done = 0
    if progress is not None:
        progress(0, total)
    for j in range(shape[1]):
        structure = Structure(structures.masses[j], structures.dampings[j], structures.stiffnesses[j])
        names = state_names(structure.n_dof)
        unknown = sorted(set(deviations) - set(names))
        if unknown:
            raise ValueError(f"box columns {', '.join(unknown)} are not among {', '.join(names)}")
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
    dims = ("lambda", "zeta")
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
        coords={"lambda": startup.dataset["lambda"], "zeta": startup.dataset["zeta"]},
        attrs=provenance_attributes(
            f"basin stability map, {config.dva.describe()}, gamma = {config.gamma:g}",
            {**config.to_dict(), "samples": n, "seed": seed,
             "box": {k: list(v) for k, v in box.items()}},
        ),
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
