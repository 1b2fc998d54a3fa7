"""``stickslip map`` and ``stickslip boundary``: where in (lambda, zeta) does it stick-slip?

``map`` writes an occurrence map (netCDF, optionally CSV and a figure); while it runs,
finished chunks are kept in ``OUT.parts/`` next to the output, so the same command run
again after a crash or a kill resumes where it stopped. The folder is removed once the
output is written. ``boundary`` finds every critical lambda at each zeta.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import (
    BadInput,
    check_distinct_outputs,
    check_figure_path,
    check_grid_memory,
    check_output_path,
    check_run_limits,
    flag_error,
    parse_dva_option,
    parse_friction_option,
    print_json,
    save_plot,
    show_progress,
    warn_fitted_range,
)
from stickslip.cli.options import (
    BACKEND,
    DVA,
    FRICTION,
    GAMMA,
    JSON,
    K_SCALE,
    PLOT,
    SCHEDULER,
    SCHEDULER_TIMEOUT,
    scheduler_context,
)
from stickslip.cli.progress import ProgressBar

LAM_SPEC = Annotated[
    str,
    typer.Option("--lam", help="lambda grid: start:stop:n, log:start:stop:n or v1,v2,... (> 0)"),
]
ZETA_SPEC = Annotated[
    str,
    typer.Option("--zeta", help="zeta grid: start:stop:n, log:start:stop:n or v1,v2,... (>= 0)"),
]
LAM_SPACING = Annotated[
    str | None, typer.Option("--lam-spacing", help="lin or log spacing of a start:stop:n lambda grid")
]
ZETA_SPACING = Annotated[
    str | None, typer.Option("--zeta-spacing", help="lin or log spacing of a start:stop:n zeta grid")
]
T_MAX = Annotated[
    float | None, typer.Option("--t-max", help="dimensionless time horizon of each run (default 5000)")
]
WORKERS = Annotated[
    int | None,
    typer.Option("--workers", help="numba threads (threads backend) or worker processes (dask); "
                 "at most the machine's cores, more are capped"),
]


def _parse_axes(lam: str | None, zeta: str, lam_spacing: str | None, zeta_spacing: str | None
                ) -> tuple[Any, Any]:
    from stickslip.sweep.grid import Axis

    for flag, text, spacing in (("--lam", lam, lam_spacing), ("--zeta", zeta, zeta_spacing)):
        if spacing is not None and text is not None and ":" not in text:
            raise BadInput(f"{flag}-spacing {spacing!r} spaces a start:stop:n range; {flag} "
                           f"{text!r} is a list, whose values are taken as given")
    lam_axis = None if lam is None else Axis.parse(lam, "lambda", lam_spacing)
    return lam_axis, Axis.parse(zeta, "zeta", zeta_spacing)


def grid_config(lam: str | None, zeta: str, lam_spacing: str | None, zeta_spacing: str | None,
                delta: str | None, dva: str, k_scale: float, gamma: float, t_max: float | None,
                friction: str) -> tuple[Any, Any]:
    """The grid of ``map`` and ``basin-map`` from their options: ``(MapConfig, law or None)``.

    With ``--delta`` the grid is ``(lambda, delta)`` at one ``--zeta`` and every cell has the
    linear law ``linear:DELTA`` (the returned law is then None); otherwise every cell has
    ``--friction``. Bad combinations and out-of-range values are one-line ``BadInput``.
    """
    from stickslip.model.friction import CoulombFriction
    from stickslip.sweep.grid import Axis
    from stickslip.sweep.occurrence import MapConfig

    lam_axis, zeta_axis = _parse_axes(lam, zeta, lam_spacing, zeta_spacing)
    law = parse_friction_option(friction)
    delta_axis = None
    if delta is not None:
        if not isinstance(law, CoulombFriction):
            raise BadInput(f"--delta sets the linear law linear:DELTA in every cell; it cannot be "
                           f"combined with --friction {friction}")
        if len(zeta_axis) != 1:
            raise BadInput(f"--delta maps over (lambda, delta) at one zeta: give exactly one "
                           f"--zeta value, not {len(zeta_axis)} ({zeta})")
        delta_axis = Axis.parse(delta, "delta")
    cell_law = None if delta_axis is not None else law
    config = MapConfig.create(lam_axis, zeta_axis, parse_dva_option(dva, k_scale), gamma, t_max=t_max,
                              friction=cell_law, deltas=delta_axis)
    check_run_limits(float(config.lam.values.max()), config.gamma)
    # tabulate the law now: a table that goes negative at this gamma is refused before writing
    law.bands(float(config.lam.values.max()), config.gamma)
    return config, cell_law


def store_path(out: Path) -> Path:
    """The resume store of an output file: ``OUT.parts`` next to it."""
    return out.with_name(out.name + ".parts")


def _tune_exact_foundations(zetas: Any, enabled: bool) -> None:
    """Tune ``--dva optimal-exact`` at every ``zeta`` first, with its own progress bar.

    About 2 s per ``zeta``: 400 of them took minutes of silence before the map's bar showed.
    The optimum is cached (:func:`~stickslip.analysis.absorber_tuning.optimal_foundation_exact`),
    so the map's cells reuse it.
    """
    from stickslip.analysis.absorber_tuning import optimal_foundation_exact

    values = [float(z) for z in zetas]
    with ProgressBar(enabled, "exact absorber optimum", unit="zeta values") as bar:
        for i, zeta in enumerate(values):
            optimal_foundation_exact(zeta)
            bar(i + 1, len(values))


def _check_existing_output(out: Path, fingerprint: str, overwrite: bool) -> bool:
    """True when ``out`` already holds this very map; error when it holds anything else."""
    from stickslip.io.netcdf import read_fingerprint

    if not out.exists() or overwrite:
        return False
    found = read_fingerprint(out)
    if found == fingerprint:
        return True
    what = ("a map of another configuration" if found
            else "something without a stickslip map's fingerprint")
    raise BadInput(f"output file {str(out)!r} exists and holds {what}; pass --overwrite to replace it")


# Over 120 lines: its signature declares the command's options (about half of it) and the
# docstring is the help text; the body checks every input before anything is written, then
# hands over to occurrence_map or, with --config, to the machine's speed/load map.
def map_command(
    ctx: typer.Context,
    out: Annotated[Path, typer.Option("--out", help="netCDF file to write (.nc)")],
    lam: Annotated[str | None, typer.Option(
        "--lam", help="lambda grid: start:stop:n, log:start:stop:n or v1,v2,... (> 0)")] = None,
    zeta: Annotated[str | None, typer.Option(
        "--zeta", help="zeta grid: start:stop:n, log:start:stop:n or v1,v2,... (>= 0)")] = None,
    machine_file: Annotated[Path | None, typer.Option(
        "--config", help="machine.toml in SI: map that machine over --speed and --load instead of "
        "(lambda, zeta); not with --lam, --zeta, --dva, --k-scale, --gamma, --friction, --delta")] = None,
    speed: Annotated[str | None, typer.Option(
        "--speed", help="with --config: belt speeds [m/s], start:stop:n, log:start:stop:n or "
        "v1,v2,...")] = None,
    load: Annotated[str | None, typer.Option(
        "--load", help="with --config: normal loads [N], start:stop:n, log:start:stop:n or "
        "v1,v2,...")] = None,
    lam_spacing: LAM_SPACING = None,
    zeta_spacing: ZETA_SPACING = None,
    dva: DVA = "none",
    k_scale: K_SCALE = 1.0,
    gamma: GAMMA = 2.0,
    t_max: T_MAX = None,
    csv: Annotated[Path | None, typer.Option("--csv", help="also write one CSV row per cell")] = None,
    plot: PLOT = None,
    backend: BACKEND = None,
    workers: WORKERS = None,
    scheduler: SCHEDULER = None,
    chunk_size: Annotated[
        int | None, typer.Option("--chunk-size", help="cells per chunk (progress, tasks, resume)")
    ] = None,
    scheduler_timeout: SCHEDULER_TIMEOUT = 10.0,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="replace an existing --out, --csv or --plot file, "
                           "or a resume store of another configuration")
    ] = False,
    friction: FRICTION = "coulomb",
    delta: Annotated[
        str | None,
        typer.Option("--delta", help="map over (lambda, delta) instead, at the one --zeta value: "
                     "slopes delta of the linear law linear:DELTA (start:stop:n or v1,v2,...; "
                     "> 0 velocity weakening); not with another --friction"),
    ] = None,
    json: JSON = False,
) -> None:
    """Occurrence map over a (lambda, zeta) grid (paper Figs. 8 and 11); resumable.

    Example: stickslip map --lam log:0.1:50:200 --zeta 0.005:0.4:100 --dva optimal --out map.nc

    With --delta: a (lambda, delta) grid at one zeta, each cell with the law linear:DELTA.

    Example: stickslip map --lam log:0.1:50:100 --delta -0.1:0.3:41 --zeta 0.1 --out dmap.nc

    Your machine over belt speed and normal load (docs/structures.md), each cell a certified
    run with lambda = (mu_s - mu_k) W / (V sqrt(m_ref k_ref)) and the friction law's own shape
    at (V, W):

    Example: stickslip map --config machine.toml --speed log:1e-4:0.1:40 --load 10:1000:40 --out vw.nc

    A machine with a [contact] (normal_dof, Jenkins element): each cell is one run of the
    contact engine from start-up (verdict, period, amplitude, separation), in --workers
    processes (default 2). A run costs what one `simulate --config` costs: about 0.05 s for the
    paper's slider on a Jenkins element, 5 to 20 s for the brake pad (examples/brake_pad).
    """
    from stickslip.cli.machine_config import refuse_mix, require_dimensionless

    refuse_mix(ctx, machine_file, ("lam", "zeta", "lam_spacing", "zeta_spacing", "dva", "k_scale",
                             "gamma", "friction", "delta"))
    if machine_file is not None:
        from stickslip.cli.machine_config import load_machine_file

        found = load_machine_file(machine_file, normal_coupling=True)
        if found.has_contact:  # contact-engine runs in worker processes
            from stickslip.cli.contact.map_commands import contact_map_command

            contact_map_command(ctx, machine_file, found, speed, load, out=out, t_max=t_max,
                                csv=csv, plot=plot, overwrite=overwrite, json=json, workers=workers)
            return
        operating_map_command(machine_file, speed, load, out=out, t_max=t_max, csv=csv, plot=plot,
                              overwrite=overwrite, json=json,
                              execution=(backend, workers, scheduler, chunk_size, scheduler_timeout))
        return
    if speed is not None or load is not None:
        raise BadInput("--speed and --load map a machine file: give them with --config machine.toml")
    require_dimensionless(lam=lam, zeta=zeta)
    assert lam is not None and zeta is not None
    from stickslip.cli.cleanup import UndoOnRefusal
    from stickslip.io.lock import output_lock
    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.executors import check_backend
    from stickslip.sweep.occurrence import OccurrenceMap, occurrence_map
    from stickslip.sweep.store import discard_store

    config, law = grid_config(lam, zeta, lam_spacing, zeta_spacing, delta, dva, k_scale, gamma,
                              t_max, friction)
    chosen = check_backend(backend or ("dask" if scheduler else "threads"), workers, scheduler)
    if chunk_size is not None and chunk_size < 1:
        raise BadInput(f"--chunk-size {chunk_size} must be at least 1")
    if out.suffix.lower() != ".nc":
        raise BadInput(f"output file {str(out)!r} must end in .nc (netCDF)")
    check_distinct_outputs(out=out, csv=csv, plot=plot)
    check_output_path(out)
    if csv is not None:
        check_output_path(csv, overwrite=overwrite, option="--csv")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    check_grid_memory(config.n_cells, "--lam/--delta" if delta is not None else "--lam/--zeta")
    reach = scheduler_context(scheduler, scheduler_timeout)  # before any file is made
    fingerprint = config.fingerprint()
    undo = UndoOnRefusal([out.parent], [store_path(out)])  # before anything is made
    out.parent.mkdir(parents=True, exist_ok=True)  # every check passed: writing starts
    with undo, output_lock(out), reach:
        warn_fitted_range(config.dva, config.zeta.values)
        reused = _check_existing_output(out, fingerprint, overwrite)
        store = store_path(out)
        if reused:
            result = OccurrenceMap.from_netcdf(out)
        else:
            enabled = show_progress()
            if config.dva.kind == "optimal-exact":
                _tune_exact_foundations(config.zeta.values, enabled)
            with ProgressBar(enabled, f"map {config.shape[0]}x{config.shape[1]}") as bar:
                result = occurrence_map(config.lam, config.zeta, config.dva, config.gamma,
                                        options=config.options,
                                        friction=law, deltas=config.delta,
                                        execution=ExecutionOptions(
                                            backend=chosen, workers=workers, scheduler=scheduler,
                                            chunk_size=chunk_size, progress=bar, store=store,
                                            overwrite=overwrite))
            result.to_netcdf(out, overwrite=True)
            discard_store(store)
        payload = result.to_dict()
        payload.update({"out": str(out), "csv": None, "plot": None, "reused_output": reused,
                        "store": str(store)})
        if csv is not None:
            result.to_csv(csv)
            payload["csv"] = str(csv)
        if plot is not None:
            payload["plot"] = save_plot(lambda ax: result.plot(ax=ax), plot)
    if json:
        print_json(payload)
        return
    _print_map_summary(payload)


def _print_map_summary(p: dict[str, Any]) -> None:
    counts = p["counts"]
    chunks = p["chunks"]
    rate = p["cells_per_second"]
    grid = f"{p['n_lambda']} lambda x {p['n_zeta']} zeta"
    if "n_delta" in p:
        grid = f"{p['n_lambda']} lambda x {p['n_delta']} delta at zeta={p['zeta']:g}"
    lines = [
        f"map         {grid} = {p['n_cells']} cells, axes ({', '.join(p['axes'])}), "
        f"{p['dva']}, gamma={p['gamma']:g}, t_max={p['t_max']:g}, friction {p['friction']}",
        f"verdicts    stick-slip {counts['stick-slip']}, steady-sliding {counts['steady-sliding']}, "
        f"undetermined {counts['undetermined']}"
        + (f", slip-oscillation {counts['slip-oscillation']}" if counts.get('slip-oscillation') else "")
        + f" (stick-slip fraction {p['stick_slip_fraction']:.4f})",
    ]
    if p["reused_output"]:
        lines.append("computed    nothing: the output already holds this map")
    else:
        lines.append(
            f"computed    {chunks['computed']} of {chunks['total']} chunks "
            f"({chunks['loaded']} resumed) in {p['elapsed_s']:.2f} s"
            + (f", {rate:,.0f} cells/s" if rate else "")
            + f" [{p['backend']}]"
        )
    lines.append(f"output      {p['out']}")
    for key in ("csv", "plot"):
        if p[key]:
            lines.append(f"{key:<11} {p[key]}")
    typer.echo("\n".join(lines))


def boundary_command(
    ctx: typer.Context,
    zeta: Annotated[str | None, typer.Option(
        "--zeta", help="zeta grid: start:stop:n, log:start:stop:n or v1,v2,... (>= 0); "
        "required without --config")] = None,
    zeta_spacing: ZETA_SPACING = None,
    dva: DVA = "none",
    k_scale: K_SCALE = 1.0,
    gamma: GAMMA = 2.0,
    t_max: T_MAX = None,
    lam_min: Annotated[float, typer.Option("--lam-min", help="lower end of the lambda scan")] = 0.01,
    lam_max: Annotated[float, typer.Option("--lam-max", help="upper end of the lambda scan")] = 100.0,
    scan: Annotated[int, typer.Option(
        "--scan", help="log-spaced scan points along lambda (with --config: along --param, "
        "default 12)")] = 48,
    rtol: Annotated[float, typer.Option(
        "--rtol", help="relative tolerance of each crossing (with --config: default 1e-3)")] = 1e-6,
    workers: WORKERS = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="also write the result as netCDF (.nc)")
    ] = None,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="replace an existing --out or --plot file")
    ] = False,
    plot: PLOT = None,
    friction: FRICTION = "coulomb",
    criterion: Annotated[
        str, typer.Option("--criterion", help="startup (the run from start-up, the paper's) or "
                          "existence (a stick-slip cycle exists, whatever the start)")
    ] = "startup",
    machine_file: Annotated[Path | None, typer.Option(
        "--config", help="machine.toml (a [structure], a [contact] or the paper's slider): every "
        "belt speed or load where its start-up verdict changes, instead; with a friction law with "
        "memory, where steady sliding changes stability (eigenvalues); not with --zeta, --dva, "
        "--gamma, --friction, --criterion, --lam-min, --lam-max")] = None,
    param: Annotated[str | None, typer.Option(
        "--param", help="with --config: speed (belt speed) or load (preload); default speed")] = None,
    range_text: Annotated[str | None, typer.Option(
        "--range", help="with --config: A:B with units, e.g. \"1 cm/s:1 m/s\" (a bare number is "
        "SI); default a decade either side of the file's value")] = None,
    json: JSON = False,
) -> None:
    """Critical lambda against zeta: every verdict change, bisected to --rtol (Fig. 11a).

    Example: stickslip boundary --zeta 0.01:0.4:8 --dva none --friction linear:0.02 --json

    A machine file: every belt speed (or load) where its start-up verdict changes, by a
    log-spaced scan and bisection of each change, runs in --workers processes (default 2;
    about 30 runs, 0.05 s each for the paper's slider on a Jenkins element, 5 to 20 s each for
    the brake pad, 0.15 s for the 6-DOF slideway). Unlike design's onset, it sees a verdict
    change again beyond the first (islands of stick-slip or of steady sliding):

    Example: stickslip boundary --config machine.toml --param speed --range "1 cm/s:1 m/s" --json

    A friction law with memory (rate-and-state, LuGre): the speeds or loads where steady
    sliding changes stability, from its eigenvalues (structure and state variable), each
    bisected to 1e-10 over two decades either side (or --range; --scan points, default 161).
    """
    from stickslip.cli.machine_config import refuse_mix, require_dimensionless

    refuse_mix(ctx, machine_file, ("zeta", "zeta_spacing", "dva", "k_scale", "gamma", "friction",
                                   "criterion", "lam_min", "lam_max"))
    if machine_file is not None:
        from stickslip.cli.memory.stability_commands import has_memory_law, memory_boundary

        if has_memory_law(machine_file):
            memory_boundary(ctx, machine_file, param=param, range_text=range_text, scan=scan,
                            json=json)
            return
    if machine_file is not None:
        from stickslip.cli.contact.map_commands import contact_boundary_command

        contact_boundary_command(ctx, machine_file, param=param, range_text=range_text, scan=scan,
                                 rtol=rtol, t_max=t_max, workers=workers, json=json)
        return
    if param is not None or range_text is not None:
        raise BadInput("--param and --range search a machine file: give them with --config "
                       "machine.toml")
    require_dimensionless(zeta=zeta)
    assert zeta is not None
    from stickslip.sweep.boundary import stick_slip_boundary
    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.executors import check_backend

    _, zeta_axis = _parse_axes(None, zeta, None, zeta_spacing)
    spec = parse_dva_option(dva, k_scale)
    law = parse_friction_option(friction)
    if criterion not in ("startup", "existence"):
        raise BadInput(f"--criterion {criterion!r} must be 'startup' or 'existence'")
    check_backend("threads", workers, None)
    if out is not None:
        if out.suffix.lower() != ".nc":
            raise BadInput(f"output file {str(out)!r} must end in .nc (netCDF)")
        check_output_path(out, overwrite=overwrite)
    check_distinct_outputs(out=out, plot=plot)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    result = stick_slip_boundary(zeta_axis, spec, gamma, lam_min=lam_min, lam_max=lam_max,
                                 n_scan=scan, rtol=rtol, t_max=t_max, friction=law,
                                 criterion=criterion, execution=ExecutionOptions(workers=workers))
    warn_fitted_range(spec, zeta_axis.values)
    payload = result.to_dict()
    payload.update({"out": None, "plot": None})
    if out is not None:
        result.to_netcdf(out, overwrite=True)
        payload["out"] = str(out)
    if plot is not None:
        payload["plot"] = save_plot(lambda ax: result.plot(ax=ax), plot, (8.0, 5.0))
    if json:
        print_json(payload)
        return
    _print_boundary_table(payload)


def _print_boundary_table(p: dict[str, Any]) -> None:
    def fmt(x: float | None) -> str:
        return "-" if x is None else f"{x:.7g}"

    analytic = [k for k in ("eq36", "eq39", "eq37", "eq36_linear") if p["rows"] and k in p["rows"][0]]
    names = {"eq36": "Eq. (36)", "eq39": "Eq. (39)", "eq37": "Eq. (37)", "eq36_linear": "Eq.36 z-d"}
    header = f"{'zeta':>10}  {'critical':>12}  " + "".join(
        f"{names[k]:>12}  " for k in analytic) + "all crossings (lambda, kind)"
    lines = [
        f"boundary    {p['dva']}, gamma={p['gamma']:g}, friction {p['friction']}, "
        f"criterion {p['criterion']}, "
        f"lambda in [{p['lam_min']:g}, "
        f"{p['lam_max']:g}], {p['n_scan']} scan points, rtol={p['rtol']:g}, t_max={p['t_max']:g}",
        header,
    ]
    for row in p["rows"]:
        crossings = ", ".join(
            f"{c['lambda']:.7g} {c['kind']}" + ("" if c["converged"] else " (not converged)")
            for c in row["crossings"]
        )
        line = f"{row['zeta']:>10.5g}  {fmt(row['critical_lambda']):>12}  " + "".join(
            f"{fmt(row[k]):>12}  " for k in analytic) + (crossings or "-")
        if row["note"]:
            line += f"  [{row['note']}]"
        lines.append(line)
    if "eq37" in analytic and not str(p["dva"]).startswith("optimal"):
        lines.append("note        Eq. (37) is the paper's criterion for the optimally tuned "
                     "foundation; for this one it only carries its equivalent damping (Eq. 33)")
    if "interpolant" in str(p["friction"]):
        # rtol is the bisection's, on the interpolant: the law's own boundary moves with the
        # law error (an independent audit: 1.3e-4 relative at tol=1e-4, 1.1e-6 at tol=1e-6)
        lines.append("note        rtol is the bisection's, for the law's piecewise-linear interpolant; "
                     "the law's own boundary moves with its tolerance (tol= in --friction)")
    lines.append(f"runs        {p['n_runs']} simulations in {p['elapsed_s']:.2f} s")
    if p.get("out"):
        lines.append(f"output      {p['out']}")
    if p.get("plot"):
        lines.append(f"figure      {p['plot']}")
    typer.echo("\n".join(lines))


def operating_map_command(config: Path, speed: str | None, load: str | None, *, out: Path,
                          t_max: float | None, csv: Path | None, plot: Path | None,
                          overwrite: bool, json: bool,
                          execution: tuple[str | None, int | None, str | None, int | None, float]
                          ) -> None:
    """``map --config``: a machine's verdicts over belt speed and normal load, written to ``out``.

    Every input is checked before the first run and before any file is made; the cells run
    like the dimensionless map's (``execution`` = ``--backend``, ``--workers``,
    ``--scheduler``, ``--chunk-size``, ``--scheduler-timeout``: numba threads by default, or
    serially, or on Dask, bit-identical), finished chunks go to the resume store ``OUT.parts``
    (a killed run resumes from it; ``--overwrite`` discards a store of another configuration),
    and the map is written once at the end (:data:`stickslip.sweep.operating_map.MAX_CELLS`
    bounds it). As for the dimensionless map, an ``out`` that already holds this very map (the
    same :func:`~stickslip.sweep.operating_map.operating_fingerprint`) is reused, not run
    again; one holding anything else is refused unless ``--overwrite``.
    """
    import numpy as np

    from stickslip.analysis.simulation import EngineOptions
    from stickslip.cli.cleanup import UndoOnRefusal
    from stickslip.cli.machine_config import config_machine
    from stickslip.io.lock import output_lock
    from stickslip.io.netcdf import write_dataset
    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.executors import check_backend
    from stickslip.sweep.operating_map import MAX_CELLS, OperatingMap, operating_fingerprint, operating_map
    from stickslip.sweep.store import StoreMismatch, discard_store

    backend, workers, scheduler, chunk_size, scheduler_timeout = execution
    chosen = check_backend(backend or ("dask" if scheduler else "threads"), workers, scheduler)
    if chunk_size is not None and chunk_size < 1:
        raise BadInput(f"--chunk-size {chunk_size} must be at least 1")

    from stickslip.cli.options import operating_axes

    axes = operating_axes(speed, load, "--speed log:1e-4:0.1:40 --load 10:1000:40")
    from stickslip.cli.machine_config import load_machine_file

    machine_file = load_machine_file(config)
    if machine_file.has_memory_law:  # an eigenvalue map: no run, no horizon, in process
        if t_max is not None:
            raise BadInput(f"--t-max {t_max!r}: a map with a friction law with memory judges "
                           "steady sliding by its eigenvalues and runs no simulation")
        if chosen == "dask":
            raise BadInput("--backend dask: a map with a friction law with memory is an "
                           "eigenvalue map, computed in this process")
        from stickslip.cli.memory.stability_commands import memory_map_command

        memory_map_command(machine_file, config, np.asarray(axes[0].values),
                           np.asarray(axes[1].values), out=out, csv=csv, plot=plot,
                           overwrite=overwrite, json=json)
        return
    n_cells = len(axes[0]) * len(axes[1])
    if n_cells > MAX_CELLS:
        raise BadInput(f"--speed x --load is {n_cells:,} operating points, more than {MAX_CELLS:,} "
                       "(each is a full certified run); use fewer points")
    try:
        options = EngineOptions() if t_max is None else EngineOptions(t_max=t_max)
    except ValueError as exc:
        raise flag_error("--t-max", t_max, exc) from None
    machine, _ = config_machine(config)
    if out.suffix.lower() != ".nc":
        raise BadInput(f"output file {str(out)!r} must end in .nc (netCDF)")
    check_distinct_outputs(out=out, csv=csv, plot=plot)
    check_output_path(out, option="--out")
    if csv is not None:
        check_output_path(csv, overwrite=overwrite, option="--csv")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    fingerprint = operating_fingerprint(machine, np.asarray(axes[0].values), np.asarray(axes[1].values),
                                        options)
    reach = scheduler_context(scheduler, scheduler_timeout)  # before any file is made
    store = store_path(out)
    undo = UndoOnRefusal([out.parent], [store])  # before anything is made
    out.parent.mkdir(parents=True, exist_ok=True)  # every check passed: writing starts
    with undo, output_lock(out), reach:
        reused = _check_existing_output(out, fingerprint, overwrite)
        if reused:
            result = OperatingMap.from_netcdf(out)
        else:
            enabled = show_progress()
            with ProgressBar(enabled, f"map {len(axes[0])}x{len(axes[1])} (V, W)") as bar:
                try:
                    result = operating_map(machine, axes[0], axes[1], options=options,
                                           execution=ExecutionOptions(
                                               backend=chosen, workers=workers, scheduler=scheduler,
                                               chunk_size=chunk_size, progress=bar, store=store,
                                               overwrite=overwrite))
                except StoreMismatch as exc:
                    raise BadInput(str(exc)) from None
            write_dataset(result.to_xarray(), out, overwrite=True)
            discard_store(store)
        if csv is not None:
            result.to_csv(csv)
        payload = result.to_dict()
        payload.update({"config": str(config), "dataset": str(out), "reused_output": reused,
                        "csv": None if csv is None else str(csv), "plot": None})
        if plot is not None:
            payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    typer.echo(result.summary())
    typer.echo(f"dataset     {out}" + ("  (reused: it already held this map)" if reused else ""))


def register(app: typer.Typer) -> None:
    """Add the ``map`` and ``boundary`` commands to ``app``."""
    app.command("map")(map_command)
    app.command("boundary")(boundary_command)
