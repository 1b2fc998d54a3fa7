"""Occurrence maps: where in the (lambda, zeta) plane does the system stick-slip?

The paper's Figs. 8 and 11 classify a grid of ``(lambda, zeta)`` by simulation, for the
rigid base and for a foundation that depends on ``zeta`` (the fitted optimum of Eqs. 28-30,
possibly with ``K`` scaled). Here each cell is a certified simulation from the startup
state (DESIGN.md section 2), so a cell is ``stick-slip``, ``steady-sliding`` or, when
neither could be certified before the time horizon, explicitly ``undetermined``.

The result is an ``xarray.Dataset`` laid out as DESIGN.md section 6 asks (coordinates
``lambda`` and ``zeta``, CF flag attributes for the integer codes, provenance in the
attributes) inside an :class:`OccurrenceMap`.

A map may instead run over ``(lambda, delta)`` at one fixed ``zeta`` (issue 10, point 5):
``delta = sigma W / (2 sqrt(m k))`` is the dimensionless slope of the linear friction law
(:class:`~stickslip.model.friction.LinearFriction`), and each cell has the law
``LinearFriction(delta_j)``. Everything else (chunks, backends, resume store, dataset
layout) is shared: the second axis of the grid is ``zeta`` or ``delta``.
"""

from __future__ import annotations

import functools
import hashlib
import json
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.verdict import (
    VERDICTS,
    Verdict,
    status_flag_attributes,
    verdict_codes,
    verdict_flag_attributes,
)
from stickslip.io.provenance import package_version, provenance_attributes
from stickslip.kernel import engine
from stickslip.model._validate import non_negative, positive
from stickslip.model.dva import DvaSpec
from stickslip.model.friction import CoulombFriction, FrictionLaw, LinearFriction
from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.model.parameters import Foundation
from stickslip.sweep.executors import (
    Backend,
    CellBatch,
    Chunk,
    StructureSet,
    check_backend,
    check_chunk_size,
    default_chunk_size,
    execute,
    load_stored,
    make_chunks,
)
from stickslip.sweep.grid import Axis, as_axis
from stickslip.sweep.store import ChunkStore

if TYPE_CHECKING:
    import xarray as xr

Progress = Callable[[int, int], None]

_NAN_COMMENT = "NaN (the _FillValue) where no stick-slip cycle was certified (verdict is not stick-slip)"
_FLOAT_VARIABLES: dict[str, tuple[int, dict[str, str]]] = {
    "period": (engine.F_PERIOD, {
        "long_name": "period of the certified stick-slip cycle",
        "units": "1 (dimensionless time tau = omega_n t)",
        "comment": _NAN_COMMENT,
    }),
    "amplitude": (engine.F_AMPLITUDE, {
        "long_name": "half the peak-to-peak of xi over the certified cycle",
        "units": "1 (V / omega_n)",
        "comment": _NAN_COMMENT,
    }),
    "stick_ratio": (engine.F_STICK_RATIO, {
        "long_name": "fraction of the cycle period spent stuck",
        "units": "1",
        "comment": _NAN_COMMENT,
    }),
    "max_velocity": (engine.F_MAX_VELOCITY, {
        "long_name": "largest slider velocity xi' reached in the run",
        "units": "1 (belt speed V)",
    }),
    "t_end": (engine.F_T_END, {
        "long_name": "dimensionless time at which the run stopped (certificate or horizon)",
        "units": "1 (dimensionless time tau)",
    }),
}


@dataclass(frozen=True)
class MapConfig:
    """Everything that determines an occurrence map (its fingerprint is a hash of it).

    Parameters
    ----------
    lam, zeta : Axis
        Grid axes, dimensionless (``lambda > 0``, ``zeta >= 0``).
    dva : DvaSpec
        The foundation, resolved at each ``zeta`` (``none`` is the rigid base).
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless (the paper uses 2).
    options : EngineOptions
        Engine limits of every cell.
    friction : FrictionLaw
        The friction law of every cell (default: the paper's Coulomb law).
    delta : Axis, optional
        Slopes ``delta`` of the linear friction law (dimensionless, finite): the grid is then
        ``(lambda, delta)`` at the one value of ``zeta``, cell ``(i, j)`` has the law
        ``LinearFriction(delta[j])`` and ``friction`` stays the Coulomb default.
    """

    lam: Axis
    zeta: Axis
    dva: DvaSpec = field(default_factory=DvaSpec)
    gamma: float = 2.0
    options: EngineOptions = field(default_factory=EngineOptions)
    friction: FrictionLaw = field(default_factory=CoulombFriction)
    delta: Axis | None = None

    def __post_init__(self) -> None:
        for value in self.lam.values.tolist():
            positive("lambda", value)
        for value in self.zeta.values.tolist():
            non_negative("zeta", value)
        object.__setattr__(self, "gamma", non_negative("gamma", self.gamma))
        if self.delta is not None:
            if len(self.zeta) != 1:
                raise ValueError(f"a (lambda, delta) map is at one fixed zeta; got {len(self.zeta)} "
                                 "zeta values")
            if not isinstance(self.friction, CoulombFriction):
                raise ValueError("a (lambda, delta) map sets the linear law LinearFriction(delta) "
                                 f"in every cell; it cannot also take the friction law "
                                 f"{self.friction.describe()!r}")
            for value in self.delta.values.tolist():
                LinearFriction(value)  # finite, or a one-line ValueError

    @classmethod
    def create(
        cls,
        lams: Axis | ArrayLike,
        zetas: Axis | ArrayLike,
        dva: DvaSpec | str = "none",
        gamma: float = 2.0,
        *,
        options: EngineOptions | None = None,
        t_max: float | None = None,
        friction: FrictionLaw | None = None,
        deltas: Axis | ArrayLike | None = None,
    ) -> MapConfig:
        """The configuration of :func:`occurrence_map` for these arguments (same parsing rules).

        Lets a caller know the map's :meth:`fingerprint` before computing it (the command line
        uses it to recognise an output file that already holds this map).
        """
        spec = DvaSpec.parse(dva) if isinstance(dva, str) else dva
        engine_options = (options or EngineOptions()).with_t_max(t_max)
        if deltas is not None and friction is not None:
            raise ValueError("deltas and friction exclude each other: a (lambda, delta) map has "
                             "the linear law LinearFriction(delta) in every cell")
        return cls(as_axis(lams, "lambda"), as_axis(zetas, "zeta"), spec, gamma, engine_options,
                   friction or CoulombFriction(),
                   None if deltas is None else as_axis(deltas, "delta"))

    @property
    def second(self) -> str:
        """Name of the grid's second axis: ``"zeta"``, or ``"delta"`` for a (lambda, delta) map."""
        return "zeta" if self.delta is None else "delta"

    @property
    def second_axis(self) -> Axis:
        """The grid's second axis (:attr:`zeta` or :attr:`delta`)."""
        return self.zeta if self.delta is None else self.delta

    @functools.cached_property
    def structures(self) -> StructureSet:
        """The structure at every ``zeta`` of the grid."""
        return StructureSet.resolve(self.dva, self.zeta.values)

    @property
    def shape(self) -> tuple[int, int]:
        """``(n_lambda, n_zeta)``, or ``(n_lambda, n_delta)``."""
        return len(self.lam), len(self.second_axis)

    @property
    def n_cells(self) -> int:
        """Number of grid cells."""
        return len(self.lam) * len(self.second_axis)

    def to_dict(self) -> dict[str, Any]:
        """The full resolved configuration, JSON-ready (floats kept to full precision).

        The friction law appears only when it is not the paper's Coulomb law, and the
        ``delta`` axis only for a (lambda, delta) map, so that the configuration (and
        fingerprint) of a Coulomb map is what it was before friction laws.
        """
        friction: dict[str, Any] = {} if isinstance(self.friction, CoulombFriction) else {
            "friction": {**self.friction.to_dict(), "description": self.friction.describe()}}
        if self.delta is not None:
            friction = {
                "friction": {"law": "linear", "delta": "per cell: the delta axis",
                             "description": _DELTA_LAW},
                "delta": _axis_dict(self.delta),
                "axes": ["lambda", "delta"],
            }
        return {
            **friction,
            "lambda": _axis_dict(self.lam),
            "zeta": _axis_dict(self.zeta),
            "dva": {
                "text": self.dva.as_text(),
                "kind": self.dva.kind,
                "k_scale": self.dva.k_scale,
                "description": self.dva.describe(),
            },
            "foundations": [
                None if f is None else [f.mass_ratio, f.stiffness_ratio, f.damping_ratio]
                for f in self.structures.foundations
            ],
            "gamma": self.gamma,
            "engine": self.options.to_dict(),
            "initial_condition": STARTUP_DESCRIPTION,
            "package_version": package_version(),
        }

    def fingerprint(self) -> str:
        """SHA-256 of the resolved configuration: grids, foundations, gamma, engine, version."""
        text = json.dumps(self.to_dict(), sort_keys=True, allow_nan=False)
        return hashlib.sha256(text.encode()).hexdigest()

    def batch(self, chunk: Chunk) -> CellBatch:
        """The cells of ``chunk``: flat index ``c = i_lambda * n_second + j``.

        A (lambda, zeta) map indexes the structure of ``zeta_j``; a (lambda, delta) map has
        one structure and the law ``LinearFriction(delta_j)`` per cell.
        """
        cells = np.arange(chunk.start, chunk.stop, dtype=np.int64)
        n_second = self.shape[1]
        lams = np.array(self.lam.values[cells // n_second])
        if self.delta is None:
            return CellBatch(structure_index=cells % n_second, lams=lams, gamma=self.gamma,
                             friction=self.friction)
        deltas = self.delta.values[cells % n_second]
        return CellBatch(structure_index=np.zeros(cells.size, dtype=np.int64), lams=lams,
                         gamma=self.gamma, laws=tuple(LinearFriction(float(d)) for d in deltas))


#: How the cells of a (lambda, delta) map are computed (``describe()`` of their laws).
_DELTA_LAW = "linear, delta per cell (the delta axis), exact (floored at zero)"


def _axis_dict(axis: Axis) -> dict[str, Any]:
    return {"spec": axis.spec, "spacing": axis.spacing, "values": [float(v) for v in axis.values]}


def stored_foundations(dataset: xr.Dataset) -> list[Foundation | None]:
    """The foundation at each ``zeta`` of a map dataset (``None`` everywhere for the rigid base).

    A (lambda, delta) map has one ``zeta``, hence one foundation.
    """
    n_zeta = int(dataset.sizes["zeta"]) if "zeta" in dataset.dims else 1
    if "foundation_mass_ratio" not in dataset:
        return [None] * n_zeta
    return [
        Foundation(float(m), float(k), float(c))
        for m, k, c in zip(np.atleast_1d(dataset["foundation_mass_ratio"].values),
                           np.atleast_1d(dataset["foundation_stiffness_ratio"].values),
                           np.atleast_1d(dataset["foundation_damping_ratio"].values), strict=True)
    ]


def map_axes(dataset: xr.Dataset) -> tuple[str, str]:
    """``("lambda", "zeta")`` or ``("lambda", "delta")``: the dimensions of a map dataset."""
    return ("lambda", "delta") if "delta" in dataset.dims else ("lambda", "zeta")


def dva_from_config(configuration: dict[str, Any]) -> DvaSpec:
    """The :class:`DvaSpec` recorded in a map's configuration (``MapConfig.to_dict``)."""
    dva = configuration["dva"]
    return DvaSpec.parse(str(dva["text"]), float(dva["k_scale"]))


@dataclass
class OccurrenceMap:
    """Result of :func:`occurrence_map`: the dataset and how it was computed.

    Unpacks as ``lam, zeta, verdict = result`` (``verdict`` has shape
    ``(n_lambda, n_zeta)`` and holds :attr:`Verdict.code` values); a (lambda, delta) map
    unpacks as ``lam, delta, verdict = result``.

    Attributes
    ----------
    dataset : xarray.Dataset
        Coordinates ``lambda`` and ``zeta`` (or ``lambda`` and ``delta``, the fixed ``zeta``
        in the attribute ``zeta``); variables ``verdict``, ``certificate``,
        ``n_stick``, ``cycle_k``, ``period``, ``amplitude``, ``stick_ratio``,
        ``max_velocity``, ``t_end`` (DESIGN.md section 6).
    chunks_total, chunks_loaded, chunks_computed : int
        Chunks of the grid, those read from the resume store and those simulated now.
    cells_computed : int
        Cells simulated now (not read from the store).
    elapsed : float
        Wall-clock seconds spent loading and computing the cells (the assembly of the
        dataset excluded).
    backend : str
        The backend that computed the missing chunks.
    """

    dataset: xr.Dataset
    chunks_total: int = 0
    chunks_loaded: int = 0
    chunks_computed: int = 0
    cells_computed: int = 0
    elapsed: float = 0.0
    backend: str = ""

    def __iter__(self) -> Iterator[NDArray[Any]]:
        return iter((self.lam, self.second_values, self.verdict))

    @property
    def second(self) -> str:
        """Name of the second axis: ``"zeta"``, or ``"delta"`` for a (lambda, delta) map."""
        return map_axes(self.dataset)[1]

    @property
    def second_values(self) -> NDArray[np.float64]:
        """Values of the second axis (:attr:`zeta` or :attr:`delta`)."""
        return np.asarray(self.dataset[self.second].values)

    @property
    def lam(self) -> NDArray[np.float64]:
        """The ``lambda`` axis (dimensionless)."""
        return np.asarray(self.dataset["lambda"].values)

    @property
    def zeta(self) -> NDArray[np.float64]:
        """The ``zeta`` axis (dimensionless); one value, the fixed one, for a (lambda, delta) map."""
        if self.second == "delta":
            return np.array([float(self.dataset.attrs["zeta"])])
        return np.asarray(self.dataset["zeta"].values)

    @property
    def delta(self) -> NDArray[np.float64] | None:
        """The ``delta`` axis of a (lambda, delta) map (dimensionless); ``None`` otherwise."""
        return np.asarray(self.dataset["delta"].values) if self.second == "delta" else None

    @property
    def verdict(self) -> NDArray[np.int8]:
        """Verdict codes, shape ``(n_lambda, n_zeta)`` or ``(n_lambda, n_delta)``:
        0 steady, 1 stick-slip, 2 undetermined, 3 slip-oscillation."""
        return np.asarray(self.dataset["verdict"].values)

    @property
    def configuration(self) -> dict[str, Any]:
        """The resolved configuration recorded in the dataset."""
        return dict(json.loads(self.dataset.attrs["configuration"]))

    @property
    def fingerprint(self) -> str:
        """Hash of the configuration (equal for maps of the same configuration)."""
        return str(self.dataset.attrs["config_fingerprint"])

    @property
    def dva(self) -> DvaSpec:
        """The foundation choice of the map."""
        return dva_from_config(self.configuration)

    @property
    def cells_per_second(self) -> float | None:
        """Throughput of the cells simulated in this call (None when none was)."""
        if self.cells_computed == 0 or self.elapsed <= 0.0:
            return None
        return self.cells_computed / self.elapsed

    @property
    def counts(self) -> dict[str, int]:
        """Number of cells of each verdict."""
        codes = self.verdict
        return {v.value: int(np.count_nonzero(codes == v.code)) for v in VERDICTS}

    @property
    def stick_slip_fraction(self) -> float:
        """Fraction of all cells that stick-slip (undetermined cells count as not)."""
        return self.counts[Verdict.STICK_SLIP.value] / max(1, self.verdict.size)

    @property
    def undetermined_fraction(self) -> float:
        """Fraction of cells without a certified verdict (increase ``t_max`` if large)."""
        return self.counts[Verdict.UNDETERMINED.value] / max(1, self.verdict.size)

    def verdict_at(self, lam: float, zeta: float | None = None, *,
                   delta: float | None = None) -> Verdict:
        """Verdict of the grid cell nearest to ``(lam, zeta)``, or to ``(lam, delta)``.

        A (lambda, zeta) map takes ``zeta``; a (lambda, delta) map takes ``delta=`` (and
        ``zeta`` only when it is the map's fixed value, or omitted).
        """
        i = int(np.argmin(np.abs(self.lam - lam)))
        if self.second == "zeta":
            if zeta is None or delta is not None:
                raise ValueError("this map is over (lambda, zeta): give lam and zeta, not delta")
            value = zeta
        else:
            fixed = float(self.zeta[0])
            if delta is None:
                raise ValueError(f"this map is over (lambda, delta) at zeta = {fixed:g}: "
                                 "give lam and delta=")
            if zeta is not None and not np.isclose(zeta, fixed, rtol=1e-12, atol=0.0):
                raise ValueError(f"this map is at zeta = {fixed:g}, not {zeta:g}")
            value = delta
        j = int(np.argmin(np.abs(self.second_values - value)))
        return VERDICTS[int(self.verdict[i, j])]

    def to_netcdf(self, path: str | Path, *, overwrite: bool = True) -> Path:
        """Write the dataset to netCDF-4 atomically; see :func:`stickslip.io.netcdf.write_dataset`."""
        from stickslip.io.netcdf import write_dataset

        return write_dataset(self.dataset, path, overwrite=overwrite)

    def to_csv(self, path: str | Path) -> Path:
        """One row per cell for spreadsheets; see :func:`stickslip.io.csv.write_map_csv`."""
        from stickslip.io.csv import write_map_csv

        return write_map_csv(self.dataset, path)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (counts, fractions, grid shape and axes, chunks, fingerprint).

        ``axes`` names the grid's dimensions; a (lambda, delta) map adds ``n_delta`` and the
        fixed ``zeta``.
        """
        delta: dict[str, Any] = {}
        if self.delta is not None:
            delta = {"n_delta": int(self.delta.size), "zeta": float(self.zeta[0])}
        return {
            "axes": list(map_axes(self.dataset)),
            "n_lambda": int(self.lam.size),
            "n_zeta": int(self.zeta.size),
            **delta,
            "n_cells": int(self.verdict.size),
            "counts": self.counts,
            "stick_slip_fraction": self.stick_slip_fraction,
            "undetermined_fraction": self.undetermined_fraction,
            "chunks": {
                "total": self.chunks_total,
                "loaded": self.chunks_loaded,
                "computed": self.chunks_computed,
            },
            "backend": self.backend,
            "elapsed_s": self.elapsed,
            "cells_computed": self.cells_computed,
            "cells_per_second": self.cells_per_second,
            "fingerprint": self.fingerprint,
            "dva": self.dva.describe(),
            "friction": self.dataset.attrs.get("friction", CoulombFriction().describe()),
            "gamma": self.configuration["gamma"],
            "t_max": self.configuration["engine"]["t_max"],
        }

    def plot(self, **kwargs: Any) -> Any:
        """Draw the map, a ``PlotResult``; see :func:`stickslip.plot.maps.occurrence_map_plot`."""
        from stickslip.plot.maps import occurrence_map_plot

        return occurrence_map_plot(self, **kwargs)

    @classmethod
    def from_netcdf(cls, path: str | Path) -> OccurrenceMap:
        """Read a map written by :meth:`to_netcdf` (loaded into memory)."""
        from stickslip.io.netcdf import read_dataset

        return cls(read_dataset(path))


def occurrence_map(
    lams: Axis | ArrayLike,
    zetas: Axis | ArrayLike,
    dva: DvaSpec | str = "none",
    gamma: float = 2.0,
    *,
    t_max: float | None = None,
    options: EngineOptions | None = None,
    friction: FrictionLaw | None = None,
    deltas: Axis | ArrayLike | None = None,
    backend: Backend = "threads",
    workers: int | None = None,
    scheduler: str | None = None,
    chunk_size: int | None = None,
    progress: Progress | None = None,
    store: str | Path | None = None,
    overwrite: bool = False,
) -> OccurrenceMap:
    """Classify every ``(lambda, zeta)`` cell of a grid by certified simulation (Figs. 8, 11).

    With ``deltas`` the grid is ``(lambda, delta)`` at one ``zeta`` instead, each cell with
    the linear friction law of its ``delta`` (issue 10, point 5).

    Parameters
    ----------
    lams : Axis or array_like or str
        ``lambda`` values (dimensionless, > 0), or an axis spec such as
        ``"log:0.1:50:200"`` (see :mod:`stickslip.sweep.grid`).
    zetas : Axis or array_like or str
        ``zeta`` values (dimensionless damping ratio, >= 0).
    dva : DvaSpec or str
        Foundation: ``"none"`` (rigid base, 1DOF), ``"optimal"`` (Eqs. 28-30 at each
        ``zeta``), ``"optimal-exact"``, ``"M,K,ZETA_A"`` or a :class:`DvaSpec` (which
        carries ``k_scale``).
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless, default 2 as in the paper.
    t_max : float, optional
        Time horizon of each cell (dimensionless ``tau``); overrides ``options.t_max``.
    options : EngineOptions, optional
        Engine limits (defaults of :class:`EngineOptions`).
    friction : FrictionLaw, optional
        Friction law of every cell (:mod:`stickslip.model.friction`); the paper's Coulomb law
        by default. Cells may then also end in ``slip-oscillation``. Not with ``deltas``.
    deltas : Axis or array_like or str, optional
        Slopes ``delta = sigma W / (2 sqrt(m k))`` of the linear law (dimensionless, > 0
        velocity weakening), e.g. ``"-0.1:0.3:41"``: the map is then over ``(lambda, delta)``
        with the law ``LinearFriction(delta)`` in each cell; ``zetas`` must hold exactly one
        value (the fixed primary damping) and ``friction`` must be left out.
    backend : {"threads", "serial", "dask"}
        ``threads``: numba threads (``workers`` of them, all cores when None);
        ``serial``: one thread; ``dask``: a ``dask.distributed`` cluster at ``scheduler``
        or a ``LocalCluster`` of ``workers`` processes on 127.0.0.1. The results are
        bit-identical across backends.
    workers : int, optional
        Threads (``threads``) or worker processes (``dask`` without ``scheduler``).
    scheduler : str, optional
        Address of a running Dask scheduler (``dask`` backend only).
    chunk_size : int, optional
        Cells per chunk (unit of progress, of Dask tasks and of the resume store). An
        existing store keeps its own chunk size.
    progress : callable, optional
        ``progress(done_cells, total_cells)``, called once at the start and after every chunk.
    store : path, optional
        Resume store folder: finished chunks are written there as they complete, and a
        later call with the same configuration computes only the missing ones.
    overwrite : bool
        Discard a store of another configuration instead of raising ``StoreMismatch``.

    Returns
    -------
    OccurrenceMap
    """
    config = MapConfig.create(lams, zetas, dva, gamma, options=options, t_max=t_max,
                              friction=friction, deltas=deltas)
    backend = check_backend(backend, workers, scheduler)
    check_chunk_size(chunk_size)
    started = time.perf_counter()
    n_cells = config.n_cells
    size = int(chunk_size) if chunk_size is not None else default_chunk_size(n_cells, backend)
    fingerprint = config.fingerprint()
    chunk_store = None
    if store is not None:
        chunk_store = ChunkStore(store, fingerprint, config.to_dict(), n_cells, size,
                                 overwrite=overwrite)
        size = chunk_store.chunk_size
    chunks = make_chunks(n_cells, size)
    float_summary = np.full((n_cells, engine.N_FLOAT), np.nan)
    int_summary = np.zeros((n_cells, engine.N_INT), dtype=np.int64)
    missing = load_stored(chunk_store, chunks, float_summary, int_summary)
    done = n_cells - sum(c.size for c in missing)
    if progress is not None:
        progress(done, n_cells)
    batches: Sequence[tuple[Chunk, CellBatch]] = [(c, config.batch(c)) for c in missing]
    for chunk, f_chunk, i_chunk in execute(config.structures, batches, config.options,
                                           backend=backend, workers=workers, scheduler=scheduler):
        float_summary[chunk.start:chunk.stop] = f_chunk
        int_summary[chunk.start:chunk.stop] = i_chunk
        if chunk_store is not None:
            chunk_store.save(chunk.index, f_chunk, i_chunk)
        done += chunk.size
        if progress is not None:
            progress(done, n_cells)
    elapsed = time.perf_counter() - started
    if chunk_store is not None:
        chunk_store.record_run(len(chunks) - len(missing), len(missing), backend)
    dataset = map_dataset(config, float_summary, int_summary, fingerprint)
    return OccurrenceMap(
        dataset,
        chunks_total=len(chunks),
        chunks_loaded=len(chunks) - len(missing),
        chunks_computed=len(missing),
        cells_computed=sum(c.size for c in missing),
        elapsed=elapsed,
        backend=backend,
    )


def map_dataset(
    config: MapConfig, float_summary: NDArray[np.float64], int_summary: NDArray[np.int64], fingerprint: str
) -> xr.Dataset:
    """Assemble the dataset of DESIGN.md section 6 from the engine's per-cell summaries.

    Parameters
    ----------
    config : MapConfig
    float_summary, int_summary : ndarray, shapes ``(n_cells, N_FLOAT)`` and ``(n_cells, N_INT)``
        Summaries in flat lambda-major order (``c = i_lambda * n_zeta + j_zeta``).
    fingerprint : str
        :meth:`MapConfig.fingerprint`, stored in the attributes.
    """
    import xarray as xr

    shape = config.shape
    dims = ("lambda", config.second)
    status = int_summary[:, engine.I_STATUS].reshape(shape)
    data_vars: dict[str, Any] = {
        "verdict": (dims, verdict_codes(status), {
            "long_name": "certified stick-slip verdict from the startup state",
            **verdict_flag_attributes(),
            "comment": "undetermined: no certificate before t_max or max_events (see certificate)",
        }),
        "certificate": (dims, status.astype(np.int8), {
            "long_name": "how the run ended: the certificate of the verdict, or why there is none",
            **status_flag_attributes(),
        }),
        "n_stick": (dims, int_summary[:, engine.I_N_STICK].reshape(shape).astype(np.int32), {
            "long_name": "number of stick phases in the run, the initial one included",
            "units": "1",
        }),
        "cycle_k": (dims, int_summary[:, engine.I_CYCLE_K].reshape(shape).astype(np.int16), {
            "long_name": "stick phases per certified cycle (period-k cycle); 0 without a cycle",
            "units": "1",
        }),
    }
    for name, (column, var_attrs) in _FLOAT_VARIABLES.items():
        data_vars[name] = (dims, float_summary[:, column].reshape(shape).astype(np.float64), var_attrs)
    foundations = config.structures.foundations
    if foundations and foundations[0] is not None:
        for name, attr, long_name in (
            ("foundation_mass_ratio", "mass_ratio", "foundation mass ratio M = m_a / m"),
            ("foundation_stiffness_ratio", "stiffness_ratio", "foundation stiffness ratio K = sqrt(k_a/k)"),
            ("foundation_damping_ratio", "damping_ratio", "foundation damping zeta_a = c_a / (2 sqrt(m k))"),
        ):
            values = np.array([getattr(f, attr) for f in foundations], dtype=np.float64)
            if config.delta is None:
                data_vars[name] = (("zeta",), values, {"long_name": long_name, "units": "1"})
            else:  # the one foundation of the fixed zeta
                data_vars[name] = ((), values[0], {"long_name": long_name, "units": "1"})
    coords = {
        "lambda": ("lambda", np.array(config.lam.values), {
            "long_name": "lambda = (mu_s - mu_k) W / (V sqrt(m k))",
            "units": "1",
            "spacing": config.lam.spacing,
        }),
    }
    if config.delta is None:
        coords["zeta"] = ("zeta", np.array(config.zeta.values), {
            "long_name": "damping ratio zeta = c / (2 sqrt(m k))",
            "units": "1",
            "spacing": config.zeta.spacing,
        })
    else:
        coords["delta"] = ("delta", np.array(config.delta.values), {
            "long_name": "friction slope delta = sigma W / (2 sqrt(m k)), > 0 velocity weakening",
            "units": "1",
            "spacing": config.delta.spacing,
        })
    law = "" if isinstance(config.friction, CoulombFriction) else f", friction {config.friction.describe()}"
    description = config.friction.describe()
    if config.delta is not None:
        zeta = float(config.zeta.values[0])
        law = f", over (lambda, delta) at zeta = {zeta:g}, friction {_DELTA_LAW}"
        description = _DELTA_LAW
    attrs: dict[str, Any] = provenance_attributes(
        f"stick-slip occurrence map, {config.dva.describe()}, gamma = {config.gamma:g}{law}",
        config.to_dict(),
    )
    attrs.update({
        "source": f"stickslip {package_version()}: exact piecewise-linear engine, certified verdicts",
        "references": "Discussion of Stick-Slip Dynamics of 2DOF Sliding Systems Based on Dynamic "
                      "Vibration Absorbers Analysis (Figs. 8 and 11)",
        "initial_condition": STARTUP_DESCRIPTION,
        "t_max": config.options.t_max,
        "gamma": config.gamma,
        "dva": config.dva.describe(),
        "friction": description,
        "config_fingerprint": fingerprint,
    })
    if config.delta is not None:
        attrs["zeta"] = float(config.zeta.values[0])
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)

