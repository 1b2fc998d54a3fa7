"""Occurrence maps: where in the (lambda, zeta) plane does the system stick-slip?

The paper's Figs. 8 and 11 classify a grid of ``(lambda, zeta)`` by simulation, for the
rigid base and for a foundation that depends on ``zeta`` (the fitted optimum of Eqs. 28-30,
possibly with ``K`` scaled). Here each cell is a certified simulation from the startup
state, so a cell is ``stick-slip``, ``steady-sliding`` or, when
neither could be certified before the time horizon, explicitly ``undetermined``.

The result is an ``xarray.Dataset`` laid out as the results format asks (coordinates
``lambda`` and ``zeta``, CF flag attributes for the integer codes, provenance in the
attributes) inside an :class:`OccurrenceMap`.

A map may instead run over ``(lambda, delta)`` at one fixed ``zeta`` (issue 10, point 5):
``delta = sigma W / (2 sqrt(m k))`` is the dimensionless slope of the linear friction law
(:class:`~stickslip.model.friction.LinearFriction`), and each cell has the law
``LinearFriction(delta_j)``. Everything else (chunks, backends, resume store, dataset
layout) is shared: the second axis of the grid is ``zeta`` or ``delta``.
"""

from __future__ import annotations

import json
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.verdict import (
    VERDICTS,
    Verdict,
)
from stickslip.kernel import engine
from stickslip.model.dva import DvaSpec
from stickslip.model.friction import CoulombFriction, FrictionLaw
from stickslip.sweep.cycle_check import prove_map_cycles, withhold_interpolant_steady
from stickslip.sweep.execution import ExecutionOptions, execution_from_keywords
from stickslip.sweep.executors import (
    CellBatch,
    Chunk,
    default_chunk_size,
    execute,
    load_stored,
    make_chunks,
)
from stickslip.sweep.grid import Axis
from stickslip.sweep.map_config import DELTA_LAW, MapConfig, dva_from_config
from stickslip.sweep.map_data import map_axes, map_dataset, stored_foundations
from stickslip.sweep.renamed import warn_renamed
from stickslip.sweep.store import ChunkStore

if TYPE_CHECKING:
    import xarray as xr


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
        ``max_velocity``, ``t_end`` (the layout of the user guide's maps page, ``docs/maps.md``).
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
    def second_axis_name(self) -> str:
        """Name of the second axis: ``"zeta"``, or ``"delta"`` for a (lambda, delta) map."""
        return map_axes(self.dataset)[1]

    @property
    def second(self) -> str:
        """Deprecated name of :attr:`second_axis_name` (removed in the next release)."""
        warn_renamed("OccurrenceMap.second", "OccurrenceMap.second_axis_name")
        return self.second_axis_name

    @property
    def second_values(self) -> NDArray[np.float64]:
        """Values of the second axis (:attr:`zeta` or :attr:`delta`)."""
        return np.asarray(self.dataset[self.second_axis_name].values)

    @property
    def lam(self) -> NDArray[np.float64]:
        """The ``lambda`` axis (dimensionless)."""
        return np.asarray(self.dataset["lambda"].values)

    @property
    def zeta(self) -> NDArray[np.float64]:
        """The ``zeta`` axis (dimensionless); one value, the fixed one, for a (lambda, delta) map."""
        if self.second_axis_name == "delta":
            return np.array([float(self.dataset.attrs["zeta"])])
        return np.asarray(self.dataset["zeta"].values)

    @property
    def delta(self) -> NDArray[np.float64] | None:
        """The ``delta`` axis of a (lambda, delta) map (dimensionless); ``None`` otherwise."""
        return np.asarray(self.dataset["delta"].values) if self.second_axis_name == "delta" else None

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
        if self.second_axis_name == "zeta":
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
    execution: ExecutionOptions | None = None,
    **legacy: Any,
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
    execution : ExecutionOptions, optional
        How the cells run: backend (``threads``, ``serial`` or ``dask``; bit-identical
        results), workers, scheduler, chunk size (the unit of progress, of Dask tasks and of
        the resume store; an existing store keeps its own), progress callback, resume store
        and overwrite (:class:`stickslip.sweep.execution.ExecutionOptions`).
    **legacy
        ``backend=``, ``workers=``, ``scheduler=``, ``chunk_size=``, ``progress=``,
        ``store=``, ``overwrite=``: deprecated spellings of the fields of ``execution``
        (a :class:`DeprecationWarning`; removed in the next release).

    Returns
    -------
    OccurrenceMap
    """
    run = execution_from_keywords(execution, legacy, "occurrence_map")
    config = MapConfig.create(lams, zetas, dva, gamma, options=options, t_max=t_max,
                              friction=friction, deltas=deltas)
    backend, chunk_size, store, progress = run.backend, run.chunk_size, run.store, run.progress
    started = time.perf_counter()
    n_cells = config.n_cells
    size = int(chunk_size) if chunk_size is not None else default_chunk_size(n_cells, backend)
    fingerprint = config.fingerprint()
    chunk_store = None
    if store is not None:
        chunk_store = ChunkStore(store, fingerprint, config.to_dict(), n_cells, size,
                                 overwrite=run.overwrite)
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
                                           backend=backend, workers=run.workers, scheduler=run.scheduler):
        float_summary[chunk.start:chunk.stop] = f_chunk
        int_summary[chunk.start:chunk.stop] = i_chunk
        if chunk_store is not None:
            chunk_store.save(chunk.index, f_chunk, i_chunk)
        done += chunk.size
        if progress is not None:
            progress(done, n_cells)
    # multi-phase candidates of N-DOF cells: the minimal, proven cycle (none in the paper's maps)
    prove_map_cycles(config.structures, config.batch(Chunk(0, 0, n_cells)), float_summary,
                     int_summary, config.options)
    withhold_interpolant_steady(config.structures, config.batch(Chunk(0, 0, n_cells)), int_summary)
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



#: Kept importable from here (the modules this one was split into in issue 17).
__all__ = [
    "DELTA_LAW",
    "VERDICTS",
    "MapConfig",
    "OccurrenceMap",
    "dva_from_config",
    "map_axes",
    "map_dataset",
    "occurrence_map",
    "stored_foundations",
]
