"""``stability --config`` and ``map --config`` for a machine whose friction has memory.

Both judge steady sliding by its linearisation, structure and state variable together
(:mod:`stickslip.analysis.memory.stability`): ``stability`` at the file's operating point
(eigenvalues with round-off bounds, the verdict, the critical stiffness and the critical
speeds), ``map`` over a grid of drive speeds and normal loads (the growth rate of every cell).
No simulation runs, so neither takes a horizon.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import typer

from stickslip.cli.console import BadInput, print_json, show_progress
from stickslip.cli.options import check_map_outputs
from stickslip.io.machine_file import MachineFile


def memory_system(machine_file: MachineFile) -> Any:
    """The file's :class:`~stickslip.model.state_friction.MemorySystem`; a bad file is one line."""
    from stickslip.cli.machine_config import refuse_contact_with_memory

    refuse_contact_with_memory(machine_file)
    try:
        return machine_file.memory_system()
    except ValueError as exc:
        message = str(exc)
        raise BadInput(message if message.startswith(machine_file.label)
                       else f"{machine_file.label}: {message}") from None


def memory_stability_command(machine_file: MachineFile, config: Path, map_plot: Path | None,
                             json: bool) -> None:
    """``stability --config`` for a law with memory: the verdict at the operating point.

    ``map_plot`` draws the growth rate over a decade of drive speed and normal load either side
    of the operating point (:func:`~stickslip.analysis.memory.stability.memory_stability_map`).
    """
    import numpy as np

    from stickslip.analysis.memory.stability import memory_stability
    from stickslip.sweep.memory.maps import memory_stability_map

    system = memory_system(machine_file)
    result = memory_stability(system)
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": machine_file.label, "map": None})
    if map_plot is not None:
        speeds = result.speed * np.logspace(-1.0, 1.0, 61)
        loads = system.load * np.logspace(-1.0, 1.0, 41)
        data = memory_stability_map(system, speeds, loads)
        payload["map"] = str(data.plot().savefig(map_plot))
    if json:
        print_json(payload)
        return
    typer.echo(f"stability   {machine_file.label}: {system.n_dof} DOF, contact_dof "
               f"{system.contact_dof}, load {system.load:.6g} N\n" + result.summary()
               + (f"\nfigure      {payload['map']}" if payload["map"] else ""))


def memory_map_command(machine_file: Any, config: Path, speeds: Any, loads: Any, *,
                       out: Path, csv: Path | None, plot: Path | None, overwrite: bool,
                       json: bool) -> None:
    """``map --config`` for a law with memory: the growth rate over ``speeds x loads``.

    Every input is checked before the first cell; the map is written to ``out`` (netCDF) at
    the end, with ``csv`` and ``plot`` when asked. A progress bar runs on a terminal.
    """
    from stickslip.cli.progress import ProgressBar
    from stickslip.io.netcdf import write_dataset
    from stickslip.sweep.memory.maps import MAX_MAP_CELLS, memory_stability_map

    n_cells = len(speeds) * len(loads)
    if n_cells > MAX_MAP_CELLS:
        raise BadInput(f"--speed x --load is {n_cells:,} operating points, more than "
                       f"{MAX_MAP_CELLS:,}; use fewer points")
    system = memory_system(machine_file)
    check_map_outputs(out, csv, plot, overwrite)
    enabled = show_progress()
    with ProgressBar(enabled, f"stability map {len(speeds)}x{len(loads)} (V, W)", "loads") as bar:
        result = memory_stability_map(system, speeds, loads, progress=bar)
    out.parent.mkdir(parents=True, exist_ok=True)
    write_dataset(result.to_xarray(), out, overwrite=True)
    payload = result.to_dict()
    payload.update({"config": str(config), "dataset": str(out), "csv": None, "plot": None})
    if csv is not None:
        payload["csv"] = str(result.to_csv(csv))
    if plot is not None:
        payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    typer.echo(result.summary())
    typer.echo(f"dataset     {out}")


def memory_boundary_command(machine_file: MachineFile, config: Path, *, param: str,
                            bounds: tuple[float, float] | None, scan: int | None,
                            json: bool) -> None:
    """``boundary --config`` for a law with memory: the speeds or loads where steady sliding
    changes stability (its eigenvalues with the state variable), each bisected to 1e-10.

    ``bounds``: the range scanned (SI; default two decades either side of the file's value);
    ``scan``: its log-spaced points (default that of ``stability``).
    """
    import math

    from stickslip.analysis.memory.stability import (
        SPEED_DECADES,
        SPEED_POINTS,
        SPEED_RTOL,
        critical_loads,
        critical_speeds,
    )

    system = memory_system(machine_file)
    speed = system.schedule.last
    value = speed if param == "speed" else system.load
    spread = 10.0 ** SPEED_DECADES
    lo, hi = bounds if bounds is not None else (value / spread, value * spread)
    points = SPEED_POINTS if scan is None else int(scan)
    if param == "speed":
        critical, unstable = critical_speeds(system, lo, hi, points)
    else:
        critical, unstable = critical_loads(system, speed, lo, hi, points)
    unit = "m/s" if param == "speed" else "N"

    def side(x: float) -> str:
        return "unstable" if any(a <= x <= b for a, b in unstable) else "stable"

    crossings = [{"param": param, "value_SI": v,
                  "below": side(v * (1.0 - 1e-6)), "above": side(v * (1.0 + 1e-6)),
                  "kind": "boundary", "converged": True} for v in critical]
    payload = {"config": str(config), "machine": machine_file.label, "param": param, "unit": unit,
               "range_SI": [lo, hi], "n_scan": points, "rtol": SPEED_RTOL,
               ("load_SI" if param == "speed" else "speed_SI"):
                   system.load if param == "speed" else speed,
               "crossings": crossings, "unstable_ranges_SI": [list(r) for r in unstable],
               "criterion": "linear stability of steady sliding (eigenvalues of the structure "
                            "and the state variable); a local verdict"}
    if json:
        print_json(payload)
        return
    held = (f"load {system.load:.6g} N" if param == "speed" else f"speed {speed:.6g} m/s")
    lines = [f"boundary    {machine_file.label}: steady sliding's stability along the {param} "
             f"({held}), {points} log-spaced points from {lo:.4g} to {hi:.4g} {unit}"]
    for c in crossings:
        lines.append(f"  {param} = {c['value_SI']:.10g} {unit}: {c['below']} below, "
                     f"{c['above']} above")
    if not crossings:
        lines.append(f"  none: steady sliding is {side(math.sqrt(lo * hi))} over the whole range")
    lines.append("  (a local verdict: a start stuck to the drive may still stick-slip where steady "
                 "sliding is stable; stickslip design --config runs it)")
    typer.echo("\n".join(lines))


def has_memory_law(config: Path) -> bool:
    """True for a file whose friction law has memory (and no contact)."""
    from stickslip.cli.machine_config import load_machine_file

    machine_file = load_machine_file(config, normal_coupling=True)
    return machine_file.has_memory_law and not machine_file.has_contact


def memory_boundary(ctx: typer.Context, config: Path, *, param: str | None,
                    range_text: str | None, scan: int, json: bool) -> None:
    """``boundary --config`` for a friction law with memory (an eigenvalue search)."""
    from stickslip.cli.console import typed_options
    from stickslip.cli.machine_config import load_machine_file
    from stickslip.cli.options import parse_range

    typed = typed_options(ctx, ("out", "plot", "rtol", "t_max", "workers"))
    if typed:
        raise BadInput(f"{', '.join(typed)} cannot be given with a friction law with memory: "
                       "boundary --config bisects the eigenvalues' sign changes to 1e-10 and "
                       "runs no simulation")
    param = "speed" if param is None else param
    if param not in ("speed", "load"):
        raise BadInput(f"--param {param!r} must be speed or load")
    machine_file = load_machine_file(config)
    bounds = None
    if range_text is not None:
        bounds = parse_range(range_text, param, positive=True)
    points = scan if typed_options(ctx, ("scan",)) else None
    if points is not None and not 2 <= points <= 10_000:
        raise BadInput(f"--scan {points} must be from 2 to 10000")
    memory_boundary_command(machine_file, config, param=param, bounds=bounds, scan=points,
                            json=json)
