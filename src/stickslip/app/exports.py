"""The web app's downloads: the design report as JSON, the time histories and the bifurcation
diagrams as CSV."""

from __future__ import annotations

import csv
import io
import json
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from stickslip import Mode
from stickslip.analysis.continuation import ContinuationResult
from stickslip.analysis.simulation import SimulationResult
from stickslip.app.computations import LambdaAxis, length_scale_at, si_of_lambda
from stickslip.app.inputs import DEFAULTS, FRICTION_FIELDS, FRICTION_TABLE_NAME
from stickslip.io.netcdf import write_dataset
from stickslip.io.provenance import package_version, provenance_attributes
from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.model.physical import PhysicalSystem


def report_json(raw: Mapping[str, str], report: Mapping[str, Any],
                runs: Mapping[str, SimulationResult], optimum: Mapping[str, Any] | None) -> str:
    """The downloadable design report: inputs as typed, the design report, the two runs.

    The friction inputs are those of the chosen law (``friction_law`` and its fields, the
    uploaded table's file name).
    """
    summaries = {}
    for name, result in runs.items():
        summary = result.to_dict()
        summary.pop("events")  # thousands of entries; the CSV has the trajectory
        summaries[name] = summary
    payload = {
        "stickslip_version": package_version(),
        "inputs": {key: raw.get(key, "") for key in DEFAULTS} | friction_inputs(raw),
        "initial_condition": STARTUP_DESCRIPTION,
        "design": dict(report),
        "operating_point": summaries,
        "stick_slip_optimal_foundation": dict(optimum) if optimum is not None else None,
    }
    return json.dumps(payload, indent=2, allow_nan=False)


def friction_inputs(raw: Mapping[str, str]) -> dict[str, str]:
    """The friction inputs as typed: ``friction_law``, its fields and the uploaded table's name."""
    law = str(raw.get("friction_law", "coulomb") or "coulomb")
    out = {"friction_law": law} | {key: str(raw.get(key, "")) for key in FRICTION_FIELDS.get(law, ())}
    if law == "table":
        out[FRICTION_TABLE_NAME] = str(raw.get(FRICTION_TABLE_NAME, ""))
    return out


def history_csv(runs: Mapping[str, SimulationResult], system: PhysicalSystem,
                n_points: int = 2000) -> str:
    """The trajectories of the runs, dimensionless and in SI, one row per sample.

    Columns: ``structure``, ``tau``, ``t_s``, ``xi``, ``xi_dot``, ``xi_a``, ``xi_a_dot``
    (empty on the rigid base), ``x_m`` (slider displacement from its kinetic-friction
    equilibrium, m), ``v_m_s`` (slider velocity, m/s), ``mode``.
    """
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(["structure", "tau", "t_s", "xi", "xi_dot", "xi_a", "xi_a_dot", "x_m", "v_m_s",
                     "mode"])
    for name, result in runs.items():
        t, q, v, modes = result.time_history(n_points=n_points)
        has_foundation = q.shape[1] > 1
        for i in range(t.size):
            writer.writerow([
                name, repr(float(t[i])), repr(float(t[i] * system.time_scale)),
                repr(float(q[i, 0])), repr(float(v[i, 0])),
                repr(float(q[i, 1])) if has_foundation else "",
                repr(float(v[i, 1])) if has_foundation else "",
                repr(float(q[i, 0] * system.length_scale)), repr(float(v[i, 0] * system.speed)),
                Mode(int(modes[i])).label,
            ])
    return buffer.getvalue()


def bifurcation_csv(results: Mapping[str, ContinuationResult], system: PhysicalSystem,
                    axis: LambdaAxis | None) -> str:
    """The points of every continued branch, one row each, from the results' ``to_xarray``.

    Columns: ``structure``, ``branch`` (index in that diagram), ``kind`` (``stick-slip`` or
    ``slip-oscillation``), ``lam``, ``period`` (tau), ``period_s``, ``amplitude`` (V/omega_n),
    ``stick_ratio``, ``multiplier`` (largest Floquet multiplier modulus), ``stable`` (0/1), and
    when ``lambda`` stands for an SI quantity (``axis``) ``speed_m_s`` or ``load_n`` and
    ``amplitude_m`` (``V / omega_n`` of that point). Steady sliding and the events are in the
    page's table and in ``stickslip continue --out``.
    """
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    si_column = {"speed": ["speed_m_s"], "load": ["load_n"], None: []}[axis]
    amplitude_m = ["amplitude_m"] if axis is not None else []
    writer.writerow(["structure", "branch", "kind", "lam", *si_column, "period", "period_s", "amplitude",
                     *amplitude_m, "stick_ratio", "multiplier", "stable"])
    for name, result in results.items():
        ds = result.to_xarray()
        kinds = [b.kind for b in result.branches]
        for i in range(ds.sizes["point"]):
            lam = float(ds[result.param].values[i])
            amplitude = float(ds["amplitude"].values[i])
            period = float(ds["period"].values[i])
            si = [repr(si_of_lambda(system, axis, lam))] if axis is not None else []
            metres = [repr(amplitude * length_scale_at(system, axis, lam))] if axis is not None else []
            branch = int(ds["branch"].values[i])
            writer.writerow([name, branch, kinds[branch], repr(lam), *si, repr(period),
                             repr(period * system.time_scale), repr(amplitude), *metres,
                             repr(float(ds["stick_ratio"].values[i])),
                             repr(float(ds["multiplier"].values[i])), int(ds["stable"].values[i])])
    return buffer.getvalue()


def bifurcation_netcdf(results: Mapping[str, ContinuationResult]) -> bytes:
    """The diagrams as one netCDF-4 file: each result's ``to_xarray`` under a prefix.

    Every variable, dimension and attribute of the dataset of ``stickslip continue --out``
    (branch points, steady sliding and its growth rate, events) is prefixed with the
    machine's name (``rigid_base_``, ``with_foundation_``), with the provenance attributes
    and the continued systems as the configuration.
    """
    import xarray as xr

    parts = []
    config: dict[str, Any] = {}
    for name, result in results.items():
        prefix = name.replace(" ", "_") + "_"
        ds = result.to_xarray()
        ds = ds.rename({str(k): prefix + str(k) for k in [*ds.data_vars, *ds.dims]})
        ds.attrs = {prefix + k: v for k, v in ds.attrs.items()}
        parts.append(ds)
        summary = result.to_dict()
        config[name] = {k: summary[k] for k in ("param", "range", "system")}
    merged = xr.merge(parts, combine_attrs="no_conflicts")
    merged.attrs.update(provenance_attributes("continuation in lam, the web app's design point",
                                              config))
    with tempfile.TemporaryDirectory() as folder:
        return write_dataset(merged, Path(folder) / "bifurcation.nc").read_bytes()
