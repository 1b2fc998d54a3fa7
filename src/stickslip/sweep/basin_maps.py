"""Basin stability maps: the disturbed-start fraction over a parameter grid.

:func:`basin_map` puts one system's basin stability (:func:`stickslip.sweep.basin.basin_stability`)
on every cell of a ``(lambda, zeta)`` or ``(lambda, delta)`` grid, next to the start-up verdict of
the occurrence map on the same grid: every cell is disturbed by the same fixed sample of
deviations from its own steady sliding, so cells differ only by their dynamics.
"""

from __future__ import annotations

import json
import time
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.verdict import VERDICTS, Verdict
from stickslip.io.provenance import provenance_attributes
from stickslip.model._validate import random_seed
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure
from stickslip.sweep.basin import (
    basin_stability,
    check_box,
    check_map_work,
    equilibrium_state,
    sample_count,
    state_names,
)
from stickslip.sweep.execution import ExecutionOptions, execution_from_keywords
from stickslip.sweep.map_config import DELTA_LAW, MapConfig
from stickslip.sweep.occurrence import occurrence_map
from stickslip.sweep.renamed import warn_renamed

if TYPE_CHECKING:
    import xarray as xr

#: The disturbance box of :func:`basin_map` when none is given: deviations of the slider's
#: ``xi`` and ``xi'`` from steady sliding (dimensionless, ``V / omega_n`` and ``V``).
DEFAULT_MAP_BOX: dict[str, tuple[float, float]] = {"xi": (-2.0, 2.0), "v": (-2.0, 1.0)}


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
    def second_axis_name(self) -> str:
        """Name of the grid's second axis: ``"zeta"`` or ``"delta"``."""
        return str(self.dataset["stick_slip_fraction"].dims[1])

    @property
    def second(self) -> str:
        """Deprecated name of :attr:`second_axis_name` (removed in the next release)."""
        warn_renamed("BasinMap.second", "BasinMap.second_axis_name")
        return self.second_axis_name

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
        second: dict[str, Any] = {f"n_{self.second_axis_name}": int(ds[self.second_axis_name].size)}
        if self.second_axis_name == "delta":
            second["zeta"] = float(ds.attrs["zeta"])
        disturbable = (startup == Verdict.STEADY_SLIDING.code) & (fraction > 0.0)
        return {
            "axes": ["lambda", self.second_axis_name],
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
    execution: ExecutionOptions | None = None,
    **legacy: Any,
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
    execution : ExecutionOptions, optional
        ``workers`` (numba threads, all cores when None; ``serial`` is one) and ``progress``
        (``progress(done_cells, total_cells)``); the map runs in this process, so the dask
        backend, chunk size and store are refused.
    **legacy
        ``workers=``, ``progress=``: deprecated spellings of the fields of ``execution``.
    """

    from stickslip.model.friction import LinearFriction

    started = time.perf_counter()
    config = MapConfig.create(lams, zetas, dva, gamma, options=options, friction=friction, deltas=deltas)
    run = execution_from_keywords(execution, legacy, "basin_map")
    run.check_in_process("basin_map")
    workers, progress = run.threads, run.progress
    n = sample_count(samples)
    check_map_work(config.n_cells, n)
    box = dict(DEFAULT_MAP_BOX if box is None else box)
    structures = config.structures
    names = state_names(structures.n_dof)
    check_box(box, names)
    rng = np.random.default_rng(random_seed(seed))  # columns in the order of state_names, whatever box's
    deviations = {name: rng.uniform(*box[name], n) for name in names if name in box}
    by_delta = config.delta is not None
    startup = occurrence_map(config.lam, config.zeta, config.dva, config.gamma, options=config.options,
                             friction=None if by_delta else config.friction, deltas=config.delta,
                             execution=ExecutionOptions(workers=workers))
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
            result = basin_stability(structure, slider, states, options=config.options,
                                     execution=ExecutionOptions(workers=workers))
            fraction[i, j] = result.fractions[Verdict.STICK_SLIP.value]
            undetermined[i, j] = result.fractions[Verdict.UNDETERMINED.value]
            done += 1
            if progress is not None:
                progress(done, total)
    ds = _basin_map_dataset(config, fraction, undetermined, startup.dataset, n, seed, box)
    return BasinMap(ds, time.perf_counter() - started)


def _basin_map_dataset(config: MapConfig, fraction: NDArray[np.float64],
                       undetermined: NDArray[np.float64], startup: xr.Dataset, n: int, seed: int,
                       box: Mapping[str, tuple[float, float]]) -> xr.Dataset:
    """The dataset of :class:`BasinMap`: the fractions, their binomial standard error
    ``sqrt(p (1 - p) / n)``, the start-up verdict of the same grid and the provenance."""
    import xarray as xr

    by_delta = config.delta is not None
    dims = ("lambda", config.second_axis_name)
    title = f"basin stability map, {config.dva.describe()}, gamma = {config.gamma:g}"
    extra: dict[str, Any] = {}
    if by_delta:
        fixed = float(config.zeta.values[0])
        title += f", over (lambda, delta) at zeta = {fixed:g}, friction {DELTA_LAW}"
        extra = {"zeta": fixed}
    law_text = DELTA_LAW if by_delta else config.friction.describe()
    return xr.Dataset(
        {
            "stick_slip_fraction": (dims, fraction, {
                "long_name": "fraction of the fixed disturbance sample ending in stick-slip", "units": "1"}),
            "standard_error": (dims, np.sqrt(fraction * (1.0 - fraction) / n), {
                "long_name": "binomial standard error of stick_slip_fraction", "units": "1"}),
            "undetermined_fraction": (dims, undetermined, {
                "long_name": "fraction of the sample without a certified verdict", "units": "1"}),
            "startup_verdict": startup["verdict"],
        },
        coords={name: startup[name] for name in dims},
        attrs={
            **provenance_attributes(title, {**config.to_dict(), "samples": n, "seed": seed,
                                            "box": {k: list(v) for k, v in box.items()}}),
            "dva": config.dva.describe(),
            "friction": law_text,
            **extra,
        },
    )
