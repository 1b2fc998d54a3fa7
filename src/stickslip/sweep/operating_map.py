"""A machine's occurrence map over its operating point: belt speed ``V`` and normal load ``W``.

The structure of a machine does not depend on where it runs; the contact does. At belt speed
``V`` [m/s] and normal load ``W`` [N] the contact's groups are (:mod:`stickslip.model.machine`,
``m_ref = M[c, c]``, ``k_ref = K[c, c]``)

    lambda(V, W) = (mu_s - mu_k) W / (V sqrt(m_ref k_ref)),    gamma = mu_k / (mu_s - mu_k),

and ``zeta`` and the dimensionless structure stay fixed. For the paper's Coulomb law that is
all: each cell is one ``lambda``. A velocity-dependent law also changes its *shape* with the
operating point: the Stribeck law's ``v_s / V``, the linear law's slope
``delta = sigma W / (2 sqrt(m_ref k_ref))``, a measured table's speeds ``v_i / V``, the viscous
term ``sigma_v W / (2 sqrt(m k))``. Each cell therefore gets its own dimensionless law, built by
:meth:`Machine.with_operating_point(speed=V, load=W).slider() <stickslip.model.machine.Machine>`
from the SI law: the map is correct for every law, not only for Coulomb.

Every cell is one certified run of the exact engine from the start-up state, with the verdict,
period [s] and amplitude [m] of its cycle. The cells run like those of the dimensionless map
(:func:`stickslip.sweep.occurrence.occurrence_map`): through
:func:`stickslip.sweep.executors.execute` with an
:class:`~stickslip.sweep.execution.ExecutionOptions` (serially, on numba threads or on a Dask
cluster, bit-identical), in chunks that a resume store keeps as they finish. Each cell is the
kernel's ``run_cells`` on the contact-first twin of the structure (what
:func:`stickslip.analysis.simulation.simulate` runs), with the cell's ``lambda`` and band table.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.verdict import VERDICTS, RunStatus
from stickslip.io.netcdf import FINGERPRINT_ATTR, read_dataset
from stickslip.io.provenance import package_version
from stickslip.kernel import engine
from stickslip.model._validate import friction_range
from stickslip.model.friction import CoulombFriction, FrictionLaw
from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.sweep.cycle_check import prove_map_cycles, withhold_interpolant_steady
from stickslip.sweep.execution import ExecutionOptions
from stickslip.sweep.executors import (
    CellBatch,
    Chunk,
    StructureSet,
    default_chunk_size,
    execute,
    load_stored,
    make_chunks,
)
from stickslip.sweep.grid import Axis
from stickslip.sweep.store import ChunkStore

if TYPE_CHECKING:
    import xarray as xr

    from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]

#: Largest number of cells of one operating map: each cell is a full certified run (about 10
#: ms for a 6-DOF machine), so 250,000 cells is about 40 minutes on one core.
MAX_CELLS = 250_000


@dataclass(frozen=True)
class OperatingMap:
    """Verdicts of a machine over belt speed and normal load (:func:`operating_map`).

    Attributes
    ----------
    speed : ndarray, shape (n_speed,)
        Belt speeds ``V``, m/s.
    load : ndarray, shape (n_load,)
        Normal loads ``W``, N.
    lam : ndarray, shape (n_speed, n_load)
        ``lambda`` of each cell.
    verdict : ndarray of str, shape (n_speed, n_load)
        Certified verdict of each cell (:data:`stickslip.analysis.verdict.VERDICTS`).
    period_s, amplitude_m, stick_ratio : ndarray, shape (n_speed, n_load)
        Of the certified cycle (s, m, -); NaN without a cycle.
    machine : dict
        The machine (:meth:`Machine.to_dict`), at its file's operating point.
    zeta, gamma : float
        The fixed groups of the contact.
    friction : str
        The SI law.
    fingerprint : str
        :func:`operating_fingerprint` of what determined the map (stored in the file: a later
        ``map --config`` of the same configuration reuses the file instead of running again).
    status, n_stick, cycle_k : ndarray of int, shape (n_speed, n_load), optional
        How each run ended (:class:`~stickslip.analysis.verdict.RunStatus` code: the
        certificate, or why there is none), its stick phases, and the stick phases of its
        certified cycle (0 without one).
    configuration : dict, optional
        :func:`operating_configuration`: everything that determined the answers (the SI law's
        fields, grid, engine options, start, version), stored with the file's provenance.
    """

    speed: FloatArray
    load: FloatArray
    lam: FloatArray
    verdict: NDArray[np.str_]
    period_s: FloatArray
    amplitude_m: FloatArray
    stick_ratio: FloatArray
    machine: dict[str, Any]
    zeta: float
    gamma: float
    friction: str
    fingerprint: str = ""
    status: NDArray[np.int64] | None = None
    n_stick: NDArray[np.int64] | None = None
    cycle_k: NDArray[np.int64] | None = None
    configuration: dict[str, Any] | None = None

    def fractions(self) -> dict[str, float]:
        """Fraction of cells with each verdict."""
        n = self.verdict.size
        return {v: float(np.count_nonzero(self.verdict == v)) / n for v in VERDICTS}

    def to_xarray(self) -> xr.Dataset:
        """Dataset with coordinates ``speed`` [m/s] and ``load`` [N] and one variable per answer.

        Self-describing as the dimensionless map's: the verdict and the certificate as integer
        codes with CF ``flag_values`` and ``flag_meanings``, the stick phases, and the
        provenance (version, date, the full configuration as JSON, the start, ``t_max``).
        """
        import xarray as xr

        from stickslip.analysis.verdict import Verdict, status_flag_attributes, verdict_flag_attributes
        from stickslip.io.provenance import provenance_attributes

        dims = ("speed", "load")
        codes = np.vectorize(lambda v: Verdict(v).code, otypes=[np.int8])(self.verdict)
        data_vars: dict[str, Any] = {
            "verdict": (dims, codes.astype(np.int8), {
                "long_name": "certified stick-slip verdict from the startup state",
                **verdict_flag_attributes(),
                "comment": "undetermined: no certificate before t_max or max_events (see certificate)"}),
            "lambda": (dims, self.lam, {"long_name": "(mu_s - mu_k) W / (V sqrt(m_ref k_ref))"}),
            "period": (dims, self.period_s, {"units": "s"}),
            "amplitude": (dims, self.amplitude_m, {"units": "m",
                                                  "long_name": "half peak-to-peak contact displacement"}),
            "stick_ratio": (dims, self.stick_ratio, {"units": "1"})}
        if self.status is not None:
            data_vars["certificate"] = (dims, self.status.astype(np.int8), {
                "long_name": "how the run ended: the certificate of the verdict, or why there is none",
                **status_flag_attributes()})
        for name, values, long_name in (
                ("n_stick", self.n_stick, "number of stick phases in the run, the initial one included"),
                ("cycle_k", self.cycle_k, "stick phases per certified cycle; 0 without a cycle")):
            if values is not None:
                data_vars[name] = (dims, values.astype(np.int32), {"long_name": long_name, "units": "1"})
        configuration = self.configuration or {}
        attrs = provenance_attributes(f"stick-slip over belt speed and normal load, "
                                      f"{self.machine.get('name')}", configuration)
        attrs.update({"machine": str(self.machine.get("name")), "n_dof": int(self.machine["n_dof"]),
                      "contact_dof": int(self.machine["contact_dof"]), "zeta": self.zeta,
                      "gamma": self.gamma, "friction": self.friction,
                      "machine_json": json.dumps(self.machine, sort_keys=True),
                      FINGERPRINT_ATTR: self.fingerprint})
        if configuration:
            attrs.update({"initial_condition": configuration["initial_condition"],
                          "t_max": float(configuration["engine"]["t_max"]),
                          "friction_json": json.dumps(configuration["friction"], sort_keys=True)})
        return xr.Dataset(
            data_vars,
            coords={"speed": ("speed", self.speed, {"units": "m/s", "long_name": "belt speed V"}),
                    "load": ("load", self.load, {"units": "N", "long_name": "normal load W"})},
            attrs=attrs)

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> OperatingMap:
        """The map back from :meth:`to_xarray` (every array bit for bit: netCDF keeps float64)."""
        try:
            attrs = dataset.attrs
            verdict = np.asarray(dataset["verdict"].values)
            if np.issubdtype(verdict.dtype, np.integer):  # codes with their flag meanings
                meanings = str(dataset["verdict"].attrs["flag_meanings"]).split()
                values = [int(x) for x in np.atleast_1d(dataset["verdict"].attrs["flag_values"])]
                verdict = np.vectorize(dict(zip(values, meanings, strict=True)).__getitem__,
                                       otypes=[object])(verdict)
            optional = {name: (np.asarray(dataset[name].values, dtype=np.int64)
                               if name in dataset else None)
                        for name in ("certificate", "n_stick", "cycle_k")}
            configuration = (json.loads(str(attrs["configuration"]))
                             if attrs.get("configuration") else None)
            return cls(np.asarray(dataset["speed"].values, dtype=np.float64),
                       np.asarray(dataset["load"].values, dtype=np.float64),
                       np.asarray(dataset["lambda"].values, dtype=np.float64),
                       np.asarray(verdict).astype(str),
                       np.asarray(dataset["period"].values, dtype=np.float64),
                       np.asarray(dataset["amplitude"].values, dtype=np.float64),
                       np.asarray(dataset["stick_ratio"].values, dtype=np.float64),
                       json.loads(str(attrs["machine_json"])), float(attrs["zeta"]),
                       float(attrs["gamma"]), str(attrs["friction"]),
                       str(attrs.get(FINGERPRINT_ATTR, "")), optional["certificate"],
                       optional["n_stick"], optional["cycle_k"], configuration)
        except (KeyError, ValueError) as exc:
            raise ValueError(f"not an operating map written by this version of stickslip ({exc})") from None

    @classmethod
    def from_netcdf(cls, path: str | os.PathLike[str]) -> OperatingMap:
        """Read a map written by ``map --config`` (:func:`stickslip.io.netcdf.write_dataset`)."""
        return cls.from_xarray(read_dataset(path))

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """One row per operating point (speed [m/s], load [N] and each answer), atomically.

        Written to a temporary file that replaces ``path`` once complete
        (:func:`stickslip.io.atomic.atomic_output`): an interrupted or failed write leaves
        the old file, or none.
        """
        from stickslip.io.atomic import atomic_output

        target = Path(path)
        with atomic_output(target) as tmp:
            table = self.to_xarray().to_dataframe().reset_index()
            table["verdict"] = self.verdict.reshape(-1)  # the words, as in the text output
            table.to_csv(tmp, index=False)
        return target

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: axes, fractions and the groups (no per-cell arrays)."""
        return {"n_speed": int(self.speed.size), "n_load": int(self.load.size),
                "speed_range_m_per_s": [float(self.speed.min()), float(self.speed.max())],
                "load_range_N": [float(self.load.min()), float(self.load.max())],
                "lambda_range": [float(self.lam.min()), float(self.lam.max())],
                "fractions": self.fractions(), "zeta": self.zeta, "gamma": self.gamma,
                "friction": self.friction, "machine": self.machine}

    def summary(self) -> str:
        """One paragraph: the grid and the share of each verdict."""
        parts = ", ".join(f"{k} {v:.1%}" for k, v in self.fractions().items() if v > 0)
        return (f"{self.machine.get('name')}: {self.speed.size} x {self.load.size} operating points, "
                f"V {self.speed.min():.4g} to {self.speed.max():.4g} m/s, W {self.load.min():.4g} "
                f"to {self.load.max():.4g} N (lambda {self.lam.min():.4g} to {self.lam.max():.4g}, "
                f"zeta={self.zeta:.4g}, gamma={self.gamma:.4g}, {self.friction}): {parts}")

    def plot(self, **kwargs: Any) -> Any:
        """The verdict map over speed and load, a ``PlotResult``.

        Drawn by :func:`stickslip.plot.operating.operating_map_plot` (keywords passed on).
        """
        from stickslip.plot.operating import operating_map_plot

        return operating_map_plot(self, **kwargs)


@dataclass(frozen=True)
class OperatingCells:
    """The cells of an operating map, flat (``c = i_speed * n_load + j_load``), ready to run.

    ``lam``, ``laws`` (the dimensionless law of each cell, built from the SI law at its
    ``(V, W)``), ``time_scale`` and ``length_scale`` (s and m per unit of ``tau`` and of the
    dimensionless displacement) per cell; ``structures`` the machine's contact-first
    dimensionless structure (one, whatever ``V`` and ``W``); ``gamma``, ``zeta``.
    """

    structures: StructureSet
    lam: FloatArray
    laws: tuple[FrictionLaw, ...]
    coulomb: bool
    time_scale: FloatArray
    length_scale: FloatArray
    gamma: float
    zeta: float

    @classmethod
    def of(cls, machine: Machine, speeds: FloatArray, loads: FloatArray) -> OperatingCells:
        """Each cell's groups from :meth:`Machine.with_operating_point` (as one run of it would)."""
        structure, _ = machine.to_dimensionless()  # independent of V and W
        inner, _ = structure.contact_first()
        n = speeds.size * loads.size
        lam = np.empty(n)
        time_scale = np.empty(n)
        length_scale = np.empty(n)
        laws: list[FrictionLaw] = []
        gamma = float("nan")
        for i, speed in enumerate(speeds.tolist()):
            for j, load in enumerate(loads.tolist()):
                point = machine.with_operating_point(speed=speed, load=load)
                slider = point.slider()  # lambda and the law's own shape at (V, W)
                reference = point.reference_system()
                c = i * loads.size + j
                try:  # as simulate refuses it
                    friction_range(slider.lam, slider.gamma)
                except ValueError as exc:
                    raise ValueError(f"at V = {speed:g} m/s and W = {load:g} N: {exc}; narrow "
                                     "the speed or load range") from None
                lam[c] = slider.lam
                laws.append(slider.friction)
                time_scale[c] = reference.time_scale
                length_scale[c] = reference.length_scale
                gamma = slider.gamma
        # writable stacks, as StructureSet.resolve's np.stack makes for `map`: a read-only view
        # of the structure's matrices is another numba signature of the cell kernels, which
        # the first `map --config` after `stickslip compile` compiled for a minute (issue 32.5)
        structures = StructureSet(zetas=np.array([inner.zeta]), foundations=(None,),
                                  masses=np.stack([inner.mass]), dampings=np.stack([inner.damping]),
                                  stiffnesses=np.stack([inner.stiffness]))
        coulomb = all(isinstance(law, CoulombFriction) for law in laws)
        return cls(structures, lam, tuple(laws), coulomb, time_scale, length_scale, float(gamma),
                   float(structure.zeta))

    def batch(self, chunk: Chunk) -> CellBatch:
        """The cells of ``chunk`` for the kernel's ``run_cells``."""
        lams = self.lam[chunk.start:chunk.stop]
        index = np.zeros(chunk.size, dtype=np.int64)
        if self.coulomb:
            return CellBatch(index, lams, self.gamma)
        return CellBatch(index, lams, self.gamma, laws=self.laws[chunk.start:chunk.stop])


def operating_configuration(machine: Machine, speeds: FloatArray, loads: FloatArray,
                            options: EngineOptions) -> dict[str, Any]:
    """What determines an operating map's answers (its resume store's fingerprint is its hash).

    The structure enters through a SHA-256 of its SI matrices (full precision), the law through
    every field of the SI ``[friction]`` table.
    """
    digest = hashlib.sha256()
    for matrix in (machine.mass, machine.damping, machine.stiffness):
        digest.update(np.ascontiguousarray(matrix, dtype=np.float64).tobytes())
    return {"kind": "operating-map", "machine": str(machine.name), "n_dof": machine.n_dof,
            "contact_dof": machine.contact_dof, "matrices_sha256": digest.hexdigest(),
            "mu_s": machine.mu_s, "mu_k": machine.mu_k,
            "friction": dataclasses.asdict(machine.friction),
            "speed_m_per_s": speeds.tolist(), "load_N": loads.tolist(),
            "engine": options.to_dict(), "initial_condition": STARTUP_DESCRIPTION,
            "package_version": package_version()}


def operating_fingerprint(machine: Machine, speeds: FloatArray, loads: FloatArray,
                          options: EngineOptions) -> str:
    """SHA-256 of :func:`operating_configuration`: the resume store's tag and the file's.

    Two maps with the same fingerprint have the same answers (same structure to the bit, law,
    grid, engine options, start and package version), so the command line reuses a file that
    holds it instead of running the map again.
    """
    configuration = operating_configuration(machine, np.asarray(speeds, dtype=np.float64),
                                            np.asarray(loads, dtype=np.float64), options)
    return hashlib.sha256(json.dumps(configuration, sort_keys=True).encode()).hexdigest()


# Over 60 lines: the docstring states every parameter; the body is the occurrence map's chunk
# loop (load the stored chunks, run the missing ones, save each as it finishes).
def operating_map(machine: Machine, speeds: Axis, loads: Axis, *,
                  options: EngineOptions | None = None,
                  execution: ExecutionOptions | None = None,
                  progress: Callable[[int], None] | None = None) -> OperatingMap:
    """Certified verdict of ``machine`` at every belt speed and normal load of the grid.

    Parameters
    ----------
    machine : Machine
        The structure, contact and friction law in SI (its own speed and load are replaced).
    speeds : Axis
        Belt speeds ``V``, m/s (> 0).
    loads : Axis
        Normal loads ``W``, N (> 0).
    options : EngineOptions, optional
        Horizon and budgets of each run (dimensionless time).
    execution : ExecutionOptions, optional
        How the cells run (backend ``threads``, ``serial`` or ``dask``: bit-identical results;
        workers, scheduler, chunk size, ``progress(done, total)``, resume store, overwrite), as
        for :func:`stickslip.sweep.occurrence.occurrence_map`. Default: numba threads on every
        core.
    progress : callable, optional
        Deprecated (one release): ``progress(done)``; pass ``execution=ExecutionOptions(
        progress=...)``, called as ``progress(done, total)``.

    Returns
    -------
    OperatingMap
        Verdict, ``lambda``, period [s], amplitude [m] and stick ratio per cell.

    Raises
    ------
    ValueError
        A speed or load that is not positive and finite, or more than :data:`MAX_CELLS` cells.
    stickslip.sweep.store.StoreMismatch
        The resume store holds another configuration (and ``execution.overwrite`` is false).
    """
    v = np.asarray(speeds.values, dtype=np.float64)
    w = np.asarray(loads.values, dtype=np.float64)
    for name, values, unit in (("speed", v, "m/s"), ("load", w, "N")):
        if not (np.all(np.isfinite(values)) and np.all(values > 0.0)):
            raise ValueError(f"every {name} must be positive and finite [{unit}]")
    if v.size * w.size > MAX_CELLS:
        raise ValueError(f"{v.size} x {w.size} = {v.size * w.size:,} operating points exceed "
                         f"{MAX_CELLS:,} (each is a full certified run); use fewer points")
    run = execution if execution is not None else ExecutionOptions()
    if progress is not None:
        warnings.warn("operating_map(progress=f) is deprecated: pass "
                      "execution=ExecutionOptions(progress=...), called as progress(done, total)",
                      DeprecationWarning, stacklevel=2)
        old = progress
        run = run.replace(progress=lambda done, _total: old(done))
    opts = options or EngineOptions()
    cells = OperatingCells.of(machine, v, w)
    n_cells = v.size * w.size
    size = int(run.chunk_size) if run.chunk_size is not None else default_chunk_size(n_cells, run.backend)
    chunk_store = None
    fingerprint = operating_fingerprint(machine, v, w, opts)
    if run.store is not None:
        chunk_store = ChunkStore(run.store, fingerprint, operating_configuration(machine, v, w, opts),
                                 n_cells, size, overwrite=run.overwrite)
        size = chunk_store.chunk_size
    chunks = make_chunks(n_cells, size)
    fsum = np.full((n_cells, engine.N_FLOAT), np.nan)
    isum = np.zeros((n_cells, engine.N_INT), dtype=np.int64)
    missing = load_stored(chunk_store, chunks, fsum, isum)
    done = n_cells - sum(c.size for c in missing)
    if run.progress is not None:
        run.progress(done, n_cells)
    batches = [(c, cells.batch(c)) for c in missing]
    for chunk, f_chunk, i_chunk in execute(cells.structures, batches, opts, backend=run.backend,
                                           workers=run.workers, scheduler=run.scheduler):
        fsum[chunk.start:chunk.stop] = f_chunk
        isum[chunk.start:chunk.stop] = i_chunk
        if chunk_store is not None:
            chunk_store.save(chunk.index, f_chunk, i_chunk)
        done += chunk.size
        if run.progress is not None:
            run.progress(done, n_cells)
    if chunk_store is not None:
        chunk_store.record_run(len(chunks) - len(missing), len(missing), run.backend)
    # multi-phase candidates: the minimal, proven cycle that simulate reports
    prove_map_cycles(cells.structures, cells.batch(Chunk(0, 0, n_cells)), fsum, isum, opts)
    withhold_interpolant_steady(cells.structures, cells.batch(Chunk(0, 0, n_cells)), isum)
    verdicts = {code: RunStatus.from_code(int(code)).verdict.value
                for code in np.unique(isum[:, engine.I_STATUS])}
    shape = (v.size, w.size)
    verdict = np.array([verdicts[code] for code in isum[:, engine.I_STATUS]], dtype=str)
    return OperatingMap(v, w, cells.lam.reshape(shape), verdict.reshape(shape),
                        (fsum[:, engine.F_PERIOD] * cells.time_scale).reshape(shape),
                        (fsum[:, engine.F_AMPLITUDE] * cells.length_scale).reshape(shape),
                        fsum[:, engine.F_STICK_RATIO].reshape(shape), machine.to_dict(),
                        cells.zeta, cells.gamma, machine.friction.law, fingerprint,
                        isum[:, engine.I_STATUS].reshape(shape), isum[:, engine.I_N_STICK].reshape(shape),
                        isum[:, engine.I_CYCLE_K].reshape(shape),
                        json.loads(json.dumps(operating_configuration(machine, v, w, opts))))
