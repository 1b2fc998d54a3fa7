"""``stability --config`` and ``map --config`` for a machine whose friction has memory.

Both judge steady sliding by its linearisation, structure and state variable together
(:mod:`stickslip.analysis.memory_stability`): ``stability`` at the file's operating point
(eigenvalues with round-off bounds, the verdict, the critical stiffness and the critical
speeds), ``map`` over a grid of drive speeds and normal loads (the growth rate of every cell).
No simulation runs, so neither takes a horizon.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import typer

from stickslip.cli.console import BadInput, check_figure_path, check_output_path, print_json
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
    of the operating point (:func:`~stickslip.analysis.memory_stability.memory_stability_map`).
    """
    import numpy as np

    from stickslip.analysis.memory_stability import memory_stability
    from stickslip.sweep.memory_map import memory_stability_map

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
    from stickslip.sweep.memory_map import MAX_MAP_CELLS, memory_stability_map

    n_cells = len(speeds) * len(loads)
    if n_cells > MAX_MAP_CELLS:
        raise BadInput(f"--speed x --load is {n_cells:,} operating points, more than "
                       f"{MAX_MAP_CELLS:,}; use fewer points")
    system = memory_system(machine_file)
    if out.suffix.lower() != ".nc":
        raise BadInput(f"output file {str(out)!r} must end in .nc (netCDF)")
    check_output_path(out, overwrite=overwrite, option="--out")
    if csv is not None:
        check_output_path(csv, overwrite=overwrite, option="--csv")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    enabled = not json and sys.stderr.isatty()
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
