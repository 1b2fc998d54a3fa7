"""``stickslip basin-map``: basin stability over a (lambda, zeta) or (lambda, delta) grid.

Every cell is disturbed by the same fixed sample of knocks about its own steady sliding
(:func:`stickslip.sweep.basin.basin_map`); the map reports the fraction that ends in
stick-slip next to the start-up verdict of ``stickslip map`` on the same grid. The grid axes,
``--delta``, the progress bar and the error handling are those of ``stickslip map``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import (
    BadInput,
    check_figure_path,
    check_grid_memory,
    check_output_path,
    print_json,
    save_plot,
    show_progress,
    warn_fitted_range,
)
from stickslip.cli.map_commands import LAM_SPACING, LAM_SPEC, T_MAX, ZETA_SPACING, ZETA_SPEC
from stickslip.cli.options import DVA, FRICTION, GAMMA, JSON, K_SCALE, PLOT

BOX_HELP = ("disturbances: deviations from each cell's steady sliding, e.g. 'xi=-2:2,v=-2:1' (the "
            "default; dimensionless: xi, v of the slider in V/omega_n and V, xi_a, v_a of the "
            "foundation); unnamed columns are not disturbed")


def basin_map_command(
    lam: LAM_SPEC,
    zeta: ZETA_SPEC,
    lam_spacing: LAM_SPACING = None,
    zeta_spacing: ZETA_SPACING = None,
    delta: Annotated[
        str | None,
        typer.Option("--delta", help="map over (lambda, delta) instead, at the one --zeta value: "
                     "slopes delta of the linear law linear:DELTA (start:stop:n or v1,v2,...; "
                     "> 0 velocity weakening); not with another --friction"),
    ] = None,
    dva: DVA = "none",
    k_scale: K_SCALE = 1.0,
    gamma: GAMMA = 2.0,
    friction: FRICTION = "coulomb",
    t_max: T_MAX = None,
    samples: Annotated[
        int, typer.Option("--samples", help="disturbances per cell (the same sample in every cell)")
    ] = 500,
    seed: Annotated[int, typer.Option("--seed", help="seed of the disturbance sample")] = 0,
    box: Annotated[str | None, typer.Option("--box", help=BOX_HELP)] = None,
    workers: Annotated[int | None, typer.Option("--workers", help="numba threads (all cores)")] = None,
    out: Annotated[Path | None, typer.Option("--out", help="netCDF file to write (.nc)")] = None,
    plot: PLOT = None,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="replace an existing --out or --plot file")
    ] = False,
    json: JSON = False,
) -> None:
    """Basin-stability map over (lambda, zeta) or (lambda, delta), next to the start-up verdict.

    Per cell: the fraction of a fixed sample of disturbed starts that ends in stick-slip.

    Example: stickslip basin-map --lam 0.5:6:12 --zeta 0.02:0.3:8 --samples 400 --out bmap.nc --plot bmap.png

    With --delta: a (lambda, delta) grid at one zeta, each cell with the law linear:DELTA.

    Example: stickslip basin-map --lam log:0.3:10:20 --delta -0.1:0.2:12 --zeta 0.1 --json
    """
    from contextlib import nullcontext

    from stickslip.cli.basin_command import parse_box
    from stickslip.cli.cleanup import UndoOnRefusal
    from stickslip.cli.map_commands import grid_config
    from stickslip.cli.progress import ProgressBar
    from stickslip.io.lock import output_lock
    from stickslip.model._validate import random_seed
    from stickslip.sweep.basin import MAX_SAMPLES, check_box, check_map_work, state_names
    from stickslip.sweep.basin_maps import DEFAULT_MAP_BOX, basin_map
    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.executors import check_backend

    config, law = grid_config(lam, zeta, lam_spacing, zeta_spacing, delta, dva, k_scale, gamma,
                              t_max, friction)
    check_backend("threads", workers, None)  # --workers: a whole number of at least 1
    if not 1 <= samples <= MAX_SAMPLES:
        raise BadInput(f"--samples {samples} must be from 1 to {MAX_SAMPLES:,}")
    check_map_work(config.n_cells, samples)  # bounded before anything starts, like boundary
    random_seed(seed)
    intervals = parse_box(box) if box is not None else dict(DEFAULT_MAP_BOX)
    try:  # the structures are built here first: a bad foundation is --dva's, not --box's
        n_dof = config.structures.n_dof
    except ValueError as exc:
        raise BadInput(f"--dva {dva!r}: {exc}") from None
    try:
        check_box(intervals, state_names(n_dof))
    except ValueError as exc:
        raise BadInput(f"--box: {exc}") from None
    if out is not None:
        if out.suffix.lower() != ".nc":
            raise BadInput(f"output file {str(out)!r} must end in .nc (netCDF)")
        check_output_path(out, overwrite=overwrite, option="--out")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    check_grid_memory(config.n_cells)
    warn_fitted_range(config.dva, config.zeta.values)  # every check passed
    enabled = show_progress()
    shape = config.shape
    undo = UndoOnRefusal([] if out is None else [out.parent])  # before anything is made
    if out is not None:
        out.parent.mkdir(parents=True, exist_ok=True)  # for the lock: writing starts
    with undo, output_lock(out) if out is not None else nullcontext():
        with ProgressBar(enabled, f"basin-map {shape[0]}x{shape[1]}, {samples} samples per cell") as bar:
            result = basin_map(config.lam, config.zeta, config.dva, config.gamma, samples=samples,
                               box=intervals, seed=seed,
                               friction=law, deltas=config.delta,
                               options=config.options,
                               execution=ExecutionOptions(workers=workers, progress=bar))
        payload = result.to_dict()
        payload.update({"out": None, "plot": None})
        if out is not None:
            result.to_netcdf(out, overwrite=True)
            payload["out"] = str(out)
        if plot is not None:
            payload["plot"] = save_plot(lambda ax: result.plot(ax=ax), plot)
    if json:
        print_json(payload)
        return
    _print_summary(payload)


def _print_summary(p: dict[str, Any]) -> None:
    if "n_delta" in p:
        grid = f"{p['n_lambda']} lambda x {p['n_delta']} delta at zeta={p['zeta']:g}"
    else:
        grid = f"{p['n_lambda']} lambda x {p['n_zeta']} zeta"
    box = ", ".join(f"{name}={lo:g}:{hi:g}" for name, (lo, hi) in p["box"].items())
    start = p["startup_counts"]
    rate = p["samples_per_second"]
    lines = [
        f"basin-map   {grid} = {p['n_cells']} cells, {p['dva']}, gamma={p['gamma']:g}, "
        f"t_max={p['t_max']:g}, friction {p['friction']}",
        f"sample      {p['samples']} disturbances per cell (seed {p['seed']}): {box} about each "
        "cell's steady sliding",
        f"start-up    stick-slip {start['stick-slip']}, steady-sliding {start['steady-sliding']}, "
        f"undetermined {start['undetermined']} cells",
        f"disturbed   stick-slip fraction mean {p['mean_stick_slip_fraction']:.4f}, "
        f"max {p['max_stick_slip_fraction']:.4f}; {p['disturbable_cells']} cells slide steadily "
        "from start-up but not after every disturbance",
        f"computed    {p['n_cells'] * p['samples']} runs in {p['elapsed_s']:.2f} s"
        + (f" ({rate:,.0f} samples/s)" if rate else ""),
    ]
    if p["max_undetermined_fraction"] > 0.0:
        lines.append(f"undetermined up to {p['max_undetermined_fraction']:.4f} of a cell's sample "
                     "(raise --t-max)")
    if p["out"]:
        lines.append(f"output      {p['out']}")
    if p["plot"]:
        lines.append(f"plot        {p['plot']}")
    typer.echo("\n".join(lines))


def register(app: typer.Typer) -> None:
    """Add the ``basin-map`` command to ``app``."""
    app.command("basin-map")(basin_map_command)
