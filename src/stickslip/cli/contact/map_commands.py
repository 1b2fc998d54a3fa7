"""``map --config`` and ``boundary --config`` for a machine with its contact.

(``cycles``, ``basin`` and ``continue`` with a contact: :mod:`stickslip.cli.contact.commands`.)

A machine file with a ``[structure] normal_dof`` and ``[contact]`` table, or a ``[contact]
tangential_stiffness`` (a Jenkins element), runs on the exact contact engine
(:mod:`stickslip.analysis.contact.engine`), one run per operating point from the start-up
state, in worker processes (``--workers``, default 2; Ctrl-C ends them). ``map`` gives each
(speed, load) cell its verdict, period, amplitude and separation
(:mod:`stickslip.sweep.contact.maps`); ``boundary`` finds the speeds or loads where the
start-up verdict changes (:mod:`stickslip.analysis.contact.boundary`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import typer

from stickslip.cli.console import (
    BadInput,
    print_json,
    show_progress,
    typed_options,
)
from stickslip.cli.options import check_map_outputs
from stickslip.io.machine_file import MachineFile

#: Default scan points and tolerance of ``boundary --config``.
CONTACT_SCAN = 12
CONTACT_RTOL = 1e-3


def _workers(workers: int | None) -> int:
    """``--workers``: default 2, at most the machine's cores; one line if not a whole number >= 1."""
    from stickslip.analysis.contact.pool import DEFAULT_WORKERS
    from stickslip.sweep.executors import capped_workers

    if workers is None:
        return min(DEFAULT_WORKERS, capped_workers(None))
    if workers < 1:
        raise BadInput(f"--workers {workers} must be at least 1")
    return capped_workers(workers)


def _where(workers: int) -> str:
    return "in this process" if workers == 1 else f"on {workers} worker processes"


def _t_max(t_max: float | None) -> float | None:
    if t_max is not None and not (math.isfinite(t_max) and t_max > 0.0):
        raise BadInput(f"--t-max {t_max!r} must be a positive number of natural times of the "
                       "contact DOF (1 / omega_ref)")
    return t_max


def contact_system_of(config: Path, machine_file: MachineFile) -> tuple[Any, Any]:
    """The file's :class:`~stickslip.analysis.contact.engine.ContactSystem` and machine (one line
    if the file is wrong or pairs the contact with a friction law with memory)."""
    from stickslip.cli.contact.simulation import contact_run_system
    from stickslip.cli.machine_config import refuse_contact_with_memory

    refuse_contact_with_memory(machine_file)
    return contact_run_system(config, machine_file)


def _machine_description(machine: Any, system: Any) -> dict[str, Any]:
    from stickslip.cli.contact.simulation import _contact_summary

    return {"name": machine.name, "n_dof": system.n_dof, "contact_dof": system.tangential_dof,
            "normal_dof": system.normal_dof, "mu_s": system.mu_s, "mu_k": system.mu_k,
            "load_N": system.load, "speed_m_per_s": system.speed,
            "contact": _contact_summary(system)}


def _rigid_description(machine: Any, has_absorber: bool) -> dict[str, Any]:
    """:func:`_machine_description` of a machine without a contact model (rigid contact)."""
    contact = "rigid (no [contact] table): the exact engine's start-up verdicts"
    if has_absorber:
        contact += "; the bare machine (the [absorber] table is design's, not mounted)"
    return {"name": machine.name, "n_dof": machine.n_dof, "contact_dof": machine.contact_dof,
            "normal_dof": None, "mu_s": machine.mu_s, "mu_k": machine.mu_k,
            "load_N": machine.load, "speed_m_per_s": machine.speed, "contact": contact}


def contact_map_command(ctx: typer.Context, config: Path, machine_file: MachineFile,
                        speed: str | None, load: str | None, *, out: Path, t_max: float | None,
                        csv: Path | None, plot: Path | None, overwrite: bool, json: bool,
                        workers: int | None) -> None:
    """``map --config`` for a contact machine: one start-up run per (speed, load) cell.

    Every input is checked before the first run and before any file is made; the map is
    written to ``out`` (netCDF) at the end, with ``csv`` and ``plot`` when asked.
    """
    import numpy as np

    from stickslip.io.lock import output_lock
    from stickslip.sweep.contact.maps import MAX_CONTACT_CELLS, contact_map

    typed = typed_options(ctx, ("backend", "scheduler", "chunk_size", "scheduler_timeout"))
    if typed:
        raise BadInput(f"{', '.join(typed)} cannot be given for a [contact] machine: its cells "
                       "are contact-engine runs in worker processes on this machine (--workers N)")
    from stickslip.cli.options import operating_axes

    axes = [np.asarray(a.values, dtype=np.float64)
            for a in operating_axes(speed, load, "--speed log:1e-3:1:20 --load 10:1000:10")]
    n_cells = axes[0].size * axes[1].size
    if n_cells > MAX_CONTACT_CELLS:
        raise BadInput(f"--speed x --load is {n_cells:,} operating points, more than "
                       f"{MAX_CONTACT_CELLS:,} (each is a full contact-engine run); use fewer")
    n_workers, horizon = _workers(workers), _t_max(t_max)
    system, machine = contact_system_of(config, machine_file)
    check_map_outputs(out, csv, plot, overwrite)
    from stickslip.cli.progress import ProgressBar

    enabled = show_progress()
    out.parent.mkdir(parents=True, exist_ok=True)  # every check passed: writing starts
    with output_lock(out):
        with ProgressBar(enabled, f"contact map {axes[0].size}x{axes[1].size} (V, W)",
                         "runs") as bar:
            result = contact_map(system, axes[0], axes[1], workers=n_workers, t_max=horizon,
                                 machine=_machine_description(machine, system), progress=bar)
        result.to_netcdf(out, overwrite=True)
        payload = result.to_dict()
        payload.update({"config": str(config), "dataset": str(out), "workers": n_workers,
                        "csv": None, "plot": None})
        if csv is not None:
            payload["csv"] = str(result.to_csv(csv))
        if plot is not None:
            payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    typer.echo(result.summary() + f" {_where(n_workers)}")
    typer.echo(f"dataset     {out}" + "".join(f"\n{key:<11} {payload[key]}" for key in ("csv", "plot")
                                             if payload[key]))


def decade_range(text: str | None, param: str, value: float) -> tuple[float, float]:
    """``--range A:B`` with units (a bare number is SI); default a decade either side of
    ``value``."""
    from stickslip.cli.options import parse_range

    if text is None:
        return value / 10.0, value * 10.0
    return parse_range(text, param, positive=True)


def contact_boundary_command(ctx: typer.Context, config: Path, *, param: str | None,
                             range_text: str | None, scan: int, rtol: float, t_max: float | None,
                             workers: int | None, json: bool) -> None:
    """``boundary --config`` for a contact machine: the speeds or loads where the start-up
    verdict changes, each crossing bisected to ``--rtol`` with its bracket."""
    from stickslip.analysis.contact.boundary import MAX_SCAN, PARAMS, contact_boundary
    from stickslip.cli.machine_config import load_machine_file

    machine_file = load_machine_file(config, normal_coupling=True)
    typed = typed_options(ctx, ("out", "plot"))
    if typed:
        what = "a [contact] machine" if machine_file.has_contact else "--config"
        raise BadInput(f"{', '.join(typed)} cannot be given with {what}: boundary --config "
                       "prints its crossings (--json for the numbers)")
    param = "speed" if param is None else param
    if param not in PARAMS:
        raise BadInput(f"--param {param!r} must be speed or load")
    if not typed_options(ctx, ("scan",)):
        scan = CONTACT_SCAN
    if not typed_options(ctx, ("rtol",)):
        rtol = CONTACT_RTOL
    if not 2 <= scan <= MAX_SCAN:
        raise BadInput(f"--scan {scan} must be from 2 to {MAX_SCAN}")
    if not (math.isfinite(rtol) and 0.0 < rtol < 1.0):
        raise BadInput(f"--rtol {rtol!r} must be between 0 and 1")
    n_workers, horizon = _workers(workers), _t_max(t_max)
    if machine_file.has_contact:
        system, machine = contact_system_of(config, machine_file)
        description = _machine_description(machine, system)
    else:  # a structure alone (or the paper's slider): the exact engine at each point
        from stickslip.cli.machine_config import config_machine

        system = machine = config_machine(config)[0]
        description = _rigid_description(machine, machine_file.absorber() is not None)
    lo, hi = decade_range(range_text, param, system.speed if param == "speed" else system.load)
    from stickslip.cli.progress import ProgressBar

    enabled = show_progress()
    with ProgressBar(enabled, f"contact boundary along {param}", "runs") as bar:
        result = contact_boundary(system, param, lo, hi, n_scan=scan, rtol=rtol,
                                  workers=n_workers, t_max=horizon, progress=bar)
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": description, "workers": n_workers,
                    "engine": "contact-engine" if machine_file.has_contact else "exact-engine"})
    if json:
        print_json(payload)
        return
    typer.echo(_boundary_table(payload))


def _boundary_table(p: dict[str, Any]) -> str:
    unit, other = p["unit"], ("load" if p["param"] == "speed" else "speed")
    held = f"{other} {p[other + '_SI']:.6g} {'N' if other == 'load' else 'm/s'} held"
    lines = [f"boundary    {p['machine']['name']}: start-up verdict along {p['param']} [{unit}] "
             f"in [{p['range_SI'][0]:.6g}, {p['range_SI'][1]:.6g}], {held}; {p['n_scan']} scan "
             f"points, rtol {p['rtol']:g}",
             f"{'crossing':<11} {'value':>12}  {'bracket':<27} {'below':<17} above"]
    for c in p["crossings"]:
        value = "-" if c["value_SI"] is None else f"{c['value_SI']:.7g}"
        bracket = f"[{c['bracket'][0]:.7g}, {c['bracket'][1]:.7g}]"
        note = ("  (undetermined: not a boundary)" if c["kind"] == "undetermined"
                else "" if c["converged"] else "  (not converged)")
        lines.append(f"{c['kind']:<11} {value:>12}  {bracket:<27} {c['below']:<17} {c['above']}"
                     + note)
    if not p["crossings"]:
        verdicts = sorted({s["verdict"] for s in p["scan"]})
        lines.append(f"none        the start-up verdict is {' / '.join(verdicts)} at every scan "
                     "point (a change narrower than a scan step is not seen)")
    lines.append(f"runs        {p['n_runs']} {p['engine']} runs in {p['elapsed_s']:.2f} s "
                 f"({p['n_runs'] / max(p['elapsed_s'], 1e-9):.3g} runs/s {_where(p['workers'])})")
    return "\n".join(lines)
