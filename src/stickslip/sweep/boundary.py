"""Critical lambda as a function of zeta, every verdict change included (paper Fig. 11a).

For the rigid base stick-slip occurs above one critical value, the root of Eq. (36). With a
detuned foundation the stick-slip set along ``lambda`` need not be an interval, so a single
bisection would find only part of the boundary. Here, for every ``zeta``:

1. ``lambda`` is scanned on a log grid of ``n_scan`` points in ``[lam_min, lam_max]``;
2. each pair of consecutive certified scan points with different verdicts brackets a
   crossing (undetermined scan points are skipped, their neighbours bracket across them);
3. each bracket is bisected (geometric midpoints) on the certified verdict until
   ``hi - lo <= rtol * lo``; the crossing is reported at ``sqrt(lo hi)``, within ``rtol / 2``
   relative. A bisection run that ends undetermined stops its bracket, which is then
   reported as not converged rather than guessed.

All scan points of all ``zeta`` run as one parallel batch, and each bisection round runs the
midpoints of every open bracket as one batch. Features narrower than the scan spacing can
be missed (two crossings inside one scan interval cancel); refine with a larger ``n_scan``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.analysis.analytic_boundary import analytic_boundaries
from stickslip.analysis.critical import Crossing, bisect_crossings, checked_rtol, scan_brackets
from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.theory import critical_lambda_linear
from stickslip.analysis.verdict import Verdict, verdict_codes, verdict_flag_attributes
from stickslip.io.provenance import package_version, provenance_attributes
from stickslip.kernel import engine
from stickslip.model._validate import at_most, non_negative, positive
from stickslip.model.dva import DvaSpec
from stickslip.model.friction import CoulombFriction, FrictionLaw, LinearFriction
from stickslip.model.parameters import Foundation
from stickslip.sweep.cycle_check import withhold_interpolant_steady
from stickslip.sweep.execution import ExecutionOptions, execution_from_keywords
from stickslip.sweep.executors import CellBatch, StructureSet, run_batch
from stickslip.sweep.grid import Axis, as_axis

if TYPE_CHECKING:
    import xarray as xr

FloatArray = NDArray[np.float64]

#: Largest number of scan runs (scan points times zeta values): each is one simulation whose
#: summaries (``N_FLOAT + N_INT`` numbers, 144 bytes) are held at once, so 1e7 runs already
#: take 1.4 GB and hours; ``--scan 1e12`` used to attempt a 7 TiB allocation.
MAX_SCAN_RUNS = 10_000_000



@dataclass(frozen=True)
class BoundaryResult:
    """Result of :func:`stick_slip_boundary`.

    Attributes
    ----------
    zeta : Axis
        The damping ratios (dimensionless).
    dva : DvaSpec
        The foundation choice.
    gamma, lam_min, lam_max, rtol : float
    n_scan : int
    options : EngineOptions
    scan_lambda : ndarray, shape (n_scan,)
        The log-spaced scan points.
    scan_verdict : ndarray, shape (n_zeta, n_scan)
        Verdict codes at the scan points (0 steady, 1 stick-slip, 2 undetermined).
    crossings : tuple of tuple of Crossing
        Per ``zeta``, every verdict change found, sorted by ``lambda``.
    foundations : tuple of Foundation or None
        ``dva`` resolved at each ``zeta`` (``None`` for the rigid base).
    n_runs : int
        Simulations run in total.
    elapsed : float
        Wall-clock seconds.
    """

    zeta: Axis
    dva: DvaSpec
    gamma: float
    lam_min: float
    lam_max: float
    n_scan: int
    rtol: float
    options: EngineOptions
    scan_lambda: FloatArray = field(repr=False)
    scan_verdict: NDArray[np.int8] = field(repr=False)
    crossings: tuple[tuple[Crossing, ...], ...] = field(repr=False)
    foundations: tuple[Foundation | None, ...] = field(default=(), repr=False)
    friction: FrictionLaw = field(default_factory=CoulombFriction)
    criterion: str = "startup"
    n_runs: int = 0
    elapsed: float = 0.0

    @property
    def critical_lambda(self) -> FloatArray:
        """Lowest ``lambda`` at which stick-slip starts, per ``zeta`` (the design value).

        NaN when the lowest certified scan point already stick-slips (the critical value is
        below ``lam_min``) or no scan point was certified; ``inf`` when no stick-slip was
        found in the range. Equals the root of Eq. (36) for the rigid base.
        """
        out = np.full(len(self.zeta), np.nan)
        for j, row in enumerate(self.scan_verdict):
            known = row[row != Verdict.UNDETERMINED.code]
            if known.size == 0 or known[0] == Verdict.STICK_SLIP.code:
                continue
            onsets = [c.lam for c in self.crossings[j] if c.onset]
            out[j] = onsets[0] if onsets else math.inf
        return out

    def notes(self) -> list[str]:
        """Per ``zeta``, why :attr:`critical_lambda` is not a plain number (else ``""``)."""
        out = []
        for j, row in enumerate(self.scan_verdict):
            known = row[row != Verdict.UNDETERMINED.code]
            if known.size == 0:
                out.append("every scan run was undetermined; increase t_max")
            elif known[0] == Verdict.STICK_SLIP.code:
                out.append(f"stick-slip already at lam_min={self.lam_min:g}")
            elif not any(c.onset for c in self.crossings[j]):
                out.append(f"no stick-slip in [{self.lam_min:g}, {self.lam_max:g}]")
            elif not all(c.converged for c in self.crossings[j]):
                out.append("a bisection stopped on an undetermined run")
            else:
                out.append("")
        return out

    def analytic(self) -> dict[str, FloatArray]:
        """Closed-form critical lambda at each ``zeta``: ``eq36``/``eq39`` or ``eq37``.

        With a friction law other than Coulomb the paper's closed forms do not apply; on the
        rigid base the linear law has its own exact boundary, Eq. (36) at ``zeta - delta``
        (:func:`stickslip.analysis.theory.critical_lambda_linear`), under the key
        ``eq36_linear``; other laws have none.
        """
        if isinstance(self.friction, LinearFriction) and self.dva.kind == "none":
            delta = self.friction.delta
            return {"eq36_linear": np.array([critical_lambda_linear(z, delta) for z in self.zeta.values])}
        if not isinstance(self.friction, CoulombFriction):
            return {}
        found = self.foundations if len(self.foundations) == len(self.zeta) else None
        return {c.key: c.lam for c in analytic_boundaries(self.dva, self.zeta.values, found)}

    def configuration(self) -> dict[str, Any]:
        """The resolved configuration, JSON-ready (the friction law only when not Coulomb)."""
        friction = {} if isinstance(self.friction, CoulombFriction) else {
            "friction": {**self.friction.to_dict(), "description": self.friction.describe()}}
        existence = {} if self.criterion == "startup" else {"criterion": self.criterion}
        return {
            **friction,
            **existence,
            "zeta": {"spec": self.zeta.spec, "spacing": self.zeta.spacing,
                     "values": [float(v) for v in self.zeta.values]},
            "dva": {"text": self.dva.as_text(), "kind": self.dva.kind,
                    "k_scale": self.dva.k_scale, "description": self.dva.describe()},
            "gamma": self.gamma,
            "lam_min": self.lam_min,
            "lam_max": self.lam_max,
            "n_scan": self.n_scan,
            "rtol": self.rtol,
            "engine": self.options.to_dict(),
            "package_version": package_version(),
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: one row per ``zeta`` with all crossings and the analytic values."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        analytic = {key: [num(v) for v in values] for key, values in self.analytic().items()}
        critical = self.critical_lambda
        notes = self.notes()
        rows = []
        for j, z in enumerate(self.zeta.values):
            row: dict[str, Any] = {
                "zeta": float(z),
                "critical_lambda": num(critical[j]),
                "note": notes[j],
                "crossings": [c.to_dict() for c in self.crossings[j]],
                "undetermined_scan_points": [
                    float(v) for v, code in zip(self.scan_lambda, self.scan_verdict[j], strict=True)
                    if code == Verdict.UNDETERMINED.code
                ],
            }
            row.update({key: values[j] for key, values in analytic.items()})
            rows.append(row)
        return {
            "dva": self.dva.describe(),
            "criterion": self.criterion,
            "friction": self.friction.describe(),
            "gamma": self.gamma,
            "lam_min": self.lam_min,
            "lam_max": self.lam_max,
            "n_scan": self.n_scan,
            "rtol": self.rtol,
            "t_max": self.options.t_max,
            "n_runs": self.n_runs,
            "elapsed_s": self.elapsed,
            "rows": rows,
        }

    def to_xarray(self) -> xr.Dataset:
        """As an ``xarray.Dataset`` over ``zeta`` (CF flag attributes, provenance)."""
        import xarray as xr

        n_cross = max([len(c) for c in self.crossings] + [1])
        shape = (len(self.zeta), n_cross)
        lam = np.full(shape, np.nan)
        lo = np.full(shape, np.nan)
        hi = np.full(shape, np.nan)
        kind = np.full(shape, -1, dtype=np.int8)
        converged = np.zeros(shape, dtype=np.int8)
        for j, row in enumerate(self.crossings):
            for k, c in enumerate(row):
                lam[j, k], lo[j, k], hi[j, k] = c.lam, c.lam_below, c.lam_above
                kind[j, k] = 1 if c.onset else 0
                converged[j, k] = int(c.converged)
        nan_note = "NaN (the _FillValue) where this zeta has fewer crossings"
        data: dict[str, Any] = {
            "critical_lambda": (("zeta",), self.critical_lambda, {
                "long_name": "lowest lambda at which stick-slip starts (simulated)",
                "units": "1",
                "comment": "NaN: stick-slip already at lam_min or no certified scan point; "
                           "inf: no stick-slip in the scanned range",
            }),
            "crossing_lambda": (("zeta", "crossing"), lam, {
                "long_name": "lambda of each verdict change", "units": "1", "comment": nan_note}),
            "crossing_lo": (("zeta", "crossing"), lo, {"long_name": "lower end of the final bracket",
                                                       "units": "1", "comment": nan_note}),
            "crossing_hi": (("zeta", "crossing"), hi, {"long_name": "upper end of the final bracket",
                                                       "units": "1", "comment": nan_note}),
            "crossing_kind": (("zeta", "crossing"), kind, {
                "long_name": "direction of the verdict change with increasing lambda",
                "flag_values": np.array([-1, 0, 1], dtype=np.int8),
                "flag_meanings": "none end-of-stick-slip onset-of-stick-slip",
            }),
            "crossing_converged": (("zeta", "crossing"), converged, {
                "long_name": "1 when the bracket reached rtol, 0 when an undetermined run stopped it",
                "flag_values": np.array([0, 1], dtype=np.int8),
                "flag_meanings": "not-converged converged",
            }),
            "scan_verdict": (("zeta", "scan_lambda"), self.scan_verdict, {
                "long_name": "certified verdict at the scan points",
                **verdict_flag_attributes(),
            }),
        }
        for key, values in self.analytic().items():
            data[f"critical_lambda_{key}"] = (("zeta",), values, {
                "long_name": f"critical lambda of the closed form {key.replace('eq', 'Eq. ')}",
                "units": "1",
            })
        attrs = provenance_attributes(
            f"critical lambda against zeta, {self.dva.describe()}, gamma = {self.gamma:g}",
            self.configuration(),
        )
        attrs.update({"rtol": self.rtol, "t_max": self.options.t_max})
        return xr.Dataset(
            data,
            coords={
                "zeta": ("zeta", np.array(self.zeta.values), {"long_name": "damping ratio", "units": "1"}),
                "crossing": ("crossing", np.arange(n_cross)),
                "scan_lambda": ("scan_lambda", self.scan_lambda, {"units": "1"}),
            },
            attrs=attrs,
        )

    def to_netcdf(self, path: str | Path, *, overwrite: bool = True) -> Path:
        """Write :meth:`to_xarray` to netCDF-4 atomically; see :func:`stickslip.io.netcdf.write_dataset`."""
        from stickslip.io.netcdf import write_dataset

        return write_dataset(self.to_xarray(), path, overwrite=overwrite)

    def plot(self, **kwargs: Any) -> Any:
        """Draw the boundary, a ``PlotResult``; see :func:`stickslip.plot.maps.boundary_plot`."""
        from stickslip.plot.maps import boundary_plot

        return boundary_plot(self, **kwargs)


def _checked_scan(lam_min: float, lam_max: float, n_scan: int, rtol: float,
                  n_zeta: int) -> tuple[float, float, float]:
    """``(lam_min, lam_max, rtol)`` of a boundary scan, checked; a one-line ValueError otherwise.

    ``0 < lam_min < lam_max`` finite, ``n_scan`` a whole number >= 2 with ``n_scan * n_zeta`` at
    most :data:`MAX_SCAN_RUNS` (the scan's results are held in memory at once), ``0 < rtol < 1``.
    """
    lam_min = at_most("lam_min", positive("lam_min", lam_min))
    lam_max = at_most("lam_max", positive("lam_max", lam_max))
    if lam_max <= lam_min:
        raise ValueError(f"lam_max={lam_max!r} must exceed lam_min={lam_min!r}")
    if isinstance(n_scan, bool) or int(n_scan) != n_scan or n_scan < 2:
        raise ValueError(f"n_scan={n_scan!r} must be a whole number of at least 2")
    if n_scan * n_zeta > MAX_SCAN_RUNS:
        raise ValueError(
            f"n_scan={n_scan!r} at {n_zeta} zeta values is {n_scan * n_zeta:,} scan runs, "
            f"above the limit of {MAX_SCAN_RUNS:,} (their results are held in memory at once)"
        )
    return lam_min, lam_max, checked_rtol(rtol)


def stick_slip_boundary(
    zetas: Axis | ArrayLike,
    dva: DvaSpec | str = "none",
    gamma: float = 2.0,
    *,
    lam_min: float = 0.01,
    lam_max: float = 100.0,
    n_scan: int = 48,
    rtol: float = 1e-6,
    t_max: float | None = None,
    options: EngineOptions | None = None,
    friction: FrictionLaw | None = None,
    criterion: str = "startup",
    existence_seeds: int = 8,
    execution: ExecutionOptions | None = None,
    **legacy: Any,
) -> BoundaryResult:
    """Every critical ``lambda`` in ``[lam_min, lam_max]`` at each ``zeta``, by scan and bisection.

    Parameters
    ----------
    zetas : Axis or array_like or str
        Primary damping ratios (dimensionless, >= 0), or an axis spec (``"0.01:0.4:20"``).
    dva : DvaSpec or str
        Foundation (``none`` = rigid base, ``optimal``, ``optimal-exact``, ``M,K,ZETA_A``).
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless.
    lam_min, lam_max : float
        Scan range of ``lambda`` (dimensionless), ``0 < lam_min < lam_max``.
    n_scan : int
        Log-spaced scan points (at least 2).
    rtol : float
        Relative width of the final brackets, ``0 < rtol < 1`` (default ``1e-6``).
    t_max : float, optional
        Time horizon of each simulation (dimensionless); overrides ``options.t_max``.
    options : EngineOptions, optional
        Engine limits (defaults of :class:`EngineOptions`).
    friction : FrictionLaw, optional
        Friction law of every run (the paper's Coulomb law by default).
    criterion : {"startup", "existence"}
        ``startup``: the verdict of the run from the startup state (the paper's question).
        ``existence``: whether the cycle search finds a stick-slip cycle, whatever the start
        (:func:`stickslip.analysis.cycles.find_cycles`, seeded from ``existence_seeds`` random
        starts: a search, not a proof of absence): the boundary ``lambda_exist(zeta)`` above
        which a disturbance can lead to lasting stick-slip. Runs one cycle search per point,
        serially (seconds each with a foundation).
    existence_seeds : int
        Random starts of each cycle search (``existence`` only).
    execution : ExecutionOptions, optional
        ``workers``: numba threads (all cores when None; ``serial`` is one). The bisection runs
        in this process, so the dask backend, chunk size, store and progress are refused.
    **legacy
        ``workers=``: deprecated spelling of ``execution=ExecutionOptions(workers=...)``.

    Returns
    -------
    BoundaryResult
    """
    run = execution_from_keywords(execution, legacy, "stick_slip_boundary")
    run.check_in_process("stick_slip_boundary", progress=False)
    workers = run.threads
    started = time.perf_counter()
    spec = DvaSpec.parse(dva) if isinstance(dva, str) else dva
    axis = as_axis(zetas, "zeta")
    for value in axis.values.tolist():
        non_negative("zeta", value)
    gamma = at_most("gamma", non_negative("gamma", gamma))
    lam_min, lam_max, rtol = _checked_scan(lam_min, lam_max, n_scan, rtol, len(axis))
    engine_options = (options or EngineOptions()).with_t_max(t_max)
    law = friction or CoulombFriction()
    structures = StructureSet.resolve(spec, axis.values)
    n_zeta = len(axis)

    if criterion not in ("startup", "existence"):
        raise ValueError(f"criterion={criterion!r} must be 'startup' or 'existence'")

    def verdicts(index: NDArray[np.int64], lams: FloatArray) -> NDArray[np.int8]:
        if index.size == 0:
            return np.zeros(0, dtype=np.int8)
        if criterion == "existence":
            return _cycle_codes(structures, index, lams, gamma, law, engine_options, existence_seeds)
        batch = CellBatch(index, lams, gamma, law)
        _, int_summary = run_batch(structures, batch, engine_options, workers)
        withhold_interpolant_steady(structures, batch, int_summary)
        return verdict_codes(int_summary[:, engine.I_STATUS])

    scan = np.geomspace(lam_min, lam_max, int(n_scan))
    scan[0], scan[-1] = lam_min, lam_max
    index = np.repeat(np.arange(n_zeta, dtype=np.int64), scan.size)
    scan_verdict = verdicts(index, np.tile(scan, n_zeta)).reshape(n_zeta, scan.size)
    n_runs = index.size

    brackets = [(j, lo, hi, v_lo) for j in range(n_zeta)
                for lo, hi, v_lo in scan_brackets(scan, scan_verdict[j])]
    found, n_bisect = bisect_crossings(verdicts, brackets, rtol)
    n_runs += n_bisect
    per_zeta: list[list[Crossing]] = [[] for _ in range(n_zeta)]
    for j, crossing in found:
        per_zeta[j].append(crossing)
    return BoundaryResult(
        zeta=axis,
        dva=spec,
        gamma=gamma,
        lam_min=lam_min,
        lam_max=lam_max,
        n_scan=int(n_scan),
        rtol=rtol,
        options=engine_options,
        scan_lambda=scan,
        scan_verdict=scan_verdict,
        crossings=tuple(tuple(sorted(c, key=lambda x: x.lam)) for c in per_zeta),
        foundations=structures.foundations,
        friction=law,
        criterion=criterion,
        n_runs=n_runs,
        elapsed=time.perf_counter() - started,
    )


def _cycle_codes(structures: StructureSet, index: NDArray[np.int64], lams: FloatArray, gamma: float,
                 law: FrictionLaw, options: EngineOptions, seeds: int) -> NDArray[np.int8]:
    """Stick-slip code where a stick-slip cycle exists (whatever the start), steady code where none.

    A point where the search finds only candidates (fixed points of the return map no proof
    makes cycles, :attr:`stickslip.analysis.cycles.CycleSearch.candidates`) is undetermined.
    """
    from stickslip.analysis.cycles import find_cycles
    from stickslip.model.parameters import Slider
    from stickslip.model.structure import Structure

    codes = np.empty(index.size, dtype=np.int8)
    for c, (j, lam) in enumerate(zip(index, lams, strict=True)):
        structure = Structure(structures.masses[j], structures.dampings[j], structures.stiffnesses[j])
        found = find_cycles(structure, Slider(float(lam), gamma=gamma, friction=law), seeds=seeds,
                            options=options)
        codes[c] = (Verdict.STICK_SLIP.code if found.cycles else Verdict.UNDETERMINED.code
                    if found.candidates else Verdict.STEADY_SLIDING.code)
    return codes
