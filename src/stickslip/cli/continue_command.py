"""``stickslip continue``: branches of periodic motions against one parameter (issue 20)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import (
    BadInput,
    check_distinct_outputs,
    check_figure_path,
    check_output_path,
    parse_dva,
    print_json,
    typed_options,
)
from stickslip.cli.options import DVA, FRICTION, GAMMA, JSON, K_SCALE, OVERWRITE, PLOT, parse_range

#: ``--points`` typed for a machine without a contact.
POINTS_REFUSED = ("--points is for a [contact] machine (followed by runs); other machines are "
                  "continued by steps (--max-steps)")


def continue_branches(
    ctx: typer.Context,
    param: Annotated[str, typer.Option("--param", help="lam, zeta, gamma, delta, K, M or zeta_a; with "
                                       "--config: speed, load, mu_s or mu_k")],
    range_: Annotated[str, typer.Option("--range", help="A:B, the parameter's interval (with --config "
                                        "in units, e.g. '2 mm/s:20 mm/s' or '1 kN:3 kN'; SI if bare)")],
    config: Annotated[Path | None, typer.Option(
        "--config", help="machine.toml in SI (m, k, c or a [structure], [friction]): that machine's "
        "diagram, the axis in m/s or N, periods in s and amplitudes in m; not with --lam, --zeta, "
        "--gamma, --dva, --k-scale, --friction")] = None,
    lam: Annotated[float, typer.Option("--lam", help="lambda > 0 (unless continued)")] = 10.0,
    zeta: Annotated[float, typer.Option("--zeta", help="damping ratio >= 0 (unless continued)")] = 0.1,
    gamma: GAMMA = 2.0,
    dva: DVA = "none",
    k_scale: K_SCALE = 1.0,
    friction: FRICTION = "coulomb",
    seeds: Annotated[int, typer.Option("--seeds", help="random starts of the cycle search")] = 12,
    max_period: Annotated[int, typer.Option("--max-period", help="longest cycle, in stick phases")] = 2,
    max_steps: Annotated[int, typer.Option("--max-steps", help="steps per branch (bound)")] = 400,
    points: Annotated[int | None, typer.Option(
        "--points", help="with a [contact] machine: parameter values, log-spaced, ends included "
        "(default 25)")] = None,
    out: Annotated[Path | None, typer.Option("--out", help="write the branches as netCDF here (a "
                                             "[contact] machine: .csv or .json)")] = None,
    plot: PLOT = None,
    overwrite: OVERWRITE = False,
    json: JSON = False,
) -> None:
    """Bifurcation diagram: stick-slip cycles and slip oscillations, stable and unstable.

    Example: stickslip continue --param lam --range 0.5:5 --zeta 0.1 --dva none --json

    Your machine: stickslip continue --config machine.toml --param speed --range '1 mm/s:20 mm/s'

    With a [contact] (attractors followed by runs): stickslip continue --config machine.toml
    --param speed --range '1 cm/s:10 cm/s' --points 25 --out branches.csv --plot branches.png
    """
    from stickslip.analysis.continuation import (
        AnySystem,
        ContinuationSystem,
        MachineSystem,
    )
    from stickslip.cli.machine_config import configured_machine, refuse_mix
    from stickslip.model.friction_input import parse_friction

    refuse_mix(ctx, config)
    if config is not None:
        from stickslip.cli.machine_config import load_machine_file

        machine_file = load_machine_file(config, normal_coupling=True)
        if machine_file.has_contact and not machine_file.has_memory_law:
            _contact_continuation(ctx, config, machine_file, param, range_, points=points,
                                  out=out, plot=plot, overwrite=overwrite, json=json)
            return
        from stickslip.cli.machine_config import refuse_contact_with_memory

        refuse_contact_with_memory(machine_file)
        if points is not None:
            raise BadInput(POINTS_REFUSED)
        if machine_file.has_memory_law:  # shooting continuation in the drive speed
            _memory_continuation(ctx, machine_file, param, range_, out=out, plot=plot,
                                 overwrite=overwrite, json=json)
            return
    if points is not None:
        raise BadInput(POINTS_REFUSED)
    _check_param(param, config)
    if config is None and param in ("lam", "zeta", "gamma") and typed_options(ctx, (param,)):
        raise BadInput(f"--{param} is the continued parameter (--param {param}): its values come "
                       f"from --range; leave --{param} out")
    lo, hi = parse_range(range_, param if config is not None else None)
    if not 1 <= seeds <= 10_000:
        raise BadInput(f"--seeds {seeds} must be from 1 to 10000")
    if not 1 <= max_period <= 8:
        raise BadInput(f"--max-period {max_period} must be from 1 to 8")
    if not 10 <= max_steps <= 100_000:
        raise BadInput(f"--max-steps {max_steps} must be from 10 to 100000")
    if out is not None:
        if out.suffix.lower() != ".nc":
            raise BadInput(f"--out {str(out)!r} must end in .nc (netCDF)")
        check_output_path(out, overwrite=overwrite, option="--out")
    check_distinct_outputs(out=out, plot=plot)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    system: AnySystem
    if config is not None:
        run = configured_machine(config)
        system = MachineSystem(run.machine)
    else:
        system = ContinuationSystem(lam, zeta, gamma, parse_dva(dva, zeta, k_scale), parse_friction(friction))
    for bound in (lo, hi):  # every value of the range must make a valid system
        try:
            system.with_value(param, bound).build()
        except ValueError as exc:
            raise BadInput(f"--range {range_!r}: {param} = {bound:g} makes no valid system: {exc}") from None
    result = _traced(system, param, lo, hi, max_period=max_period, seeds=seeds, max_steps=max_steps)
    payload = result.to_dict()
    payload.update({"dataset": None, "plot": None})
    if out is not None:
        from stickslip.io.netcdf import write_dataset
        from stickslip.io.provenance import provenance_attributes

        ds = result.to_xarray()
        resolved = {k: v for k, v in payload.items() if k in ("param", "range", "system")}
        ds.attrs.update(provenance_attributes(f"continuation in {param}", resolved))
        payload["dataset"] = str(write_dataset(ds, out, overwrite=True))
    if plot is not None:
        payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    _print(result.summary(), payload)



def _traced(system: Any, param: str, lo: float, hi: float, *, max_period: int, seeds: int,
            max_steps: int) -> Any:
    """:func:`~stickslip.analysis.continuation.continue_cycles` with a spinner and the time on a
    terminal (the branches' steps are open-ended), so that a long trace is seen to work (an
    independent audit: 45 s and more without a sign)."""
    from stickslip.analysis.continuation import continue_cycles
    from stickslip.cli.console import show_progress
    from stickslip.cli.progress import DesignProgress

    with DesignProgress(show_progress(), "continue", counted=False) as bar:
        bar(f"{param} over [{lo:g}, {hi:g}], cycles up to {max_period} stick phases, {seeds} seeds "
            "(Ctrl-C stops it)", 0)
        return continue_cycles(system, param, (lo, hi), max_period=max_period, seeds=seeds,
                               max_steps=max_steps)


def _contact_continuation(ctx: typer.Context, config: Path, machine_file: Any, param: str,
                          range_: str, *, points: int | None, out: Path | None,
                          plot: Path | None, overwrite: bool, json: bool) -> None:
    """``continue --config`` with a contact (:func:`continue_contact`): ``--out`` .csv or .json."""
    from stickslip.analysis.contact.continuation import (
        DEFAULT_POINTS,
        MAX_POINTS,
        PARAMETERS,
        continue_contact,
    )
    from stickslip.cli.contact.commands import DEFAULT_WORKERS, progress_bar, refuse_options
    from stickslip.cli.contact.simulation import contact_run_system
    from stickslip.io.atomic import atomic_write_text

    refuse_options(ctx, ("seeds", "max_period", "max_steps"), "continue")
    if param not in PARAMETERS:
        raise BadInput(f"--param {param!r}: a [contact] machine is continued in "
                       f"{' or '.join(PARAMETERS)} (--param speed or --param load)")
    lo, hi = parse_range(range_, param, positive=True)
    if not lo > 0.0:
        raise BadInput(f"--range {range_!r}: {param} must be positive")
    n = DEFAULT_POINTS if points is None else points
    if not 2 <= n <= MAX_POINTS:
        raise BadInput(f"--points {n} must be from 2 to {MAX_POINTS}")
    if out is not None:
        if out.suffix.lower() not in (".csv", ".json"):
            raise BadInput(f"--out {str(out)!r} must end in .csv or .json with a [contact] machine")
        check_output_path(out, overwrite=overwrite, option="--out")
    check_distinct_outputs(out=out, plot=plot)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    system, machine = contact_run_system(config, machine_file)
    try:
        with progress_bar(json, f"continue {param}: {2 * n} runs") as bar:
            result = continue_contact(system, param, (lo, hi), points=n,
                                      workers=DEFAULT_WORKERS, progress=bar)
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": machine.name, "out": None, "plot": None})
    if out is not None:
        if out.suffix.lower() == ".csv":
            atomic_write_text(out, result.to_csv())
        else:
            import json as json_module

            atomic_write_text(out, json_module.dumps(result.to_dict(), allow_nan=False) + "\n")
        payload["out"] = str(out)
    if plot is not None:
        payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    lines = [f"machine     {machine.name}: {system.n_dof} DOF, contact on DOF "
             f"{system.tangential_dof}", result.summary()]
    lines += [f"{key}: {payload[key]}" for key in ("out", "plot") if payload[key]]
    typer.echo("\n".join(lines))


def _memory_continuation(ctx: typer.Context, machine_file: Any, param: str, range_: str, *,
                         out: Path | None, plot: Path | None, overwrite: bool, json: bool) -> None:
    """``continue --config`` for a friction law with memory
    (:func:`~stickslip.analysis.memory.continuation.continue_memory_orbits`)."""
    from click.core import ParameterSource

    from stickslip.analysis.memory.continuation import continue_memory_orbits
    from stickslip.cli.memory.stability_commands import memory_system

    if param != "speed":
        raise BadInput(f"--param {param!r}: a machine with friction with memory is continued in "
                       "the drive speed (--param speed)")
    for name in ("seeds", "max_period", "max_steps"):
        if ctx.get_parameter_source(name) is ParameterSource.COMMANDLINE:
            raise BadInput(f"--{name.replace('_', '-')} is for the curve laws' continuation; with "
                           "friction with memory the orbits are seeded by runs and shot")
    if out is not None:
        raise BadInput("--out: the netCDF file is written for the curve laws; with friction with "
                       "memory --json holds the branches")
    lo, hi = parse_range(range_, "speed", positive=True)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    system = memory_system(machine_file)
    try:
        result = continue_memory_orbits(system, (lo, hi))
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload.update({"config": str(machine_file.label), "plot": None})
    if plot is not None:
        payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    typer.echo(result.summary() + (f"\nplot: {payload['plot']}" if payload["plot"] else ""))


def _print(summary: str, payload: dict[str, Any]) -> None:
    lines = [summary]
    for key in ("dataset", "plot"):
        if payload[key]:
            lines.append(f"{key}: {payload[key]}")
    typer.echo("\n".join(lines))


def register(app: typer.Typer) -> None:
    """Add the ``continue`` command to ``app``."""
    app.command("continue")(continue_branches)


def _check_param(param: str, config: Path | None) -> None:
    """One line when ``--param`` is not a parameter of the system continued."""
    from stickslip.analysis.continuation import MACHINE_PARAMETERS, PARAMETERS

    allowed = PARAMETERS if config is None else tuple(MACHINE_PARAMETERS)
    if param not in allowed:
        machine_only = config is None and param in MACHINE_PARAMETERS
        raise BadInput(f"--param {param!r} is not one of {', '.join(allowed)}"
                       + ("" if config is None else " (a machine file's parameters)")
                       + (f" ({param} is a machine file's parameter: give --config)"
                          if machine_only else ""))
