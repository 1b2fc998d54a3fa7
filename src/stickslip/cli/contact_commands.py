"""``cycles``, ``basin`` and ``continue`` with ``--config`` for a machine with its contact.

A machine file's ``[structure] normal_dof`` and ``[contact]`` table (or a flat file's paper
slider with a ``[contact] tangential_stiffness``) run on the exact contact engine
(:mod:`stickslip.analysis.contact_engine`). Its periodic verdicts are observed (a state
repeated to 1e-9), not proven; every answer says so.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import typer

from stickslip.cli.console import BadInput, check_figure_path, check_output_path, print_json

#: Worker processes by default (the engine holds the GIL; a pool only for costly runs).
DEFAULT_WORKERS = 2


def _typed(ctx: typer.Context, names: tuple[str, ...]) -> list[str]:
    """The options among ``names`` given on the command line, as flags."""
    from click.core import ParameterSource

    return [f"--{n.replace('_', '-')}" for n in names
            if ctx.get_parameter_source(n) is ParameterSource.COMMANDLINE]


def _refuse(ctx: typer.Context, names: tuple[str, ...], command: str) -> None:
    typed = _typed(ctx, names)
    if typed:
        raise BadInput(f"{', '.join(typed)} cannot be given to `{command}` with a [contact] "
                       "machine (it runs the exact contact engine)")


def _bar(json: bool, label: str, unit: str = "runs") -> Any:
    from stickslip.cli.progress import ProgressBar

    return ProgressBar(not json and sys.stderr.isatty(), label, unit=unit)


def contact_cycles_command(ctx: typer.Context, config: Path, machine_file: Any, *,
                           json: bool) -> None:
    """``cycles --config`` with a contact (:func:`find_contact_cycles`)."""
    from stickslip.analysis.contact_cycles import find_contact_cycles
    from stickslip.cli.contact_simulation import contact_run_system

    _refuse(ctx, ("seeds", "max_period", "seed"), "cycles")
    system, machine = contact_run_system(config, machine_file)
    try:
        with _bar(json, "cycles: 8 starts") as bar:
            result = find_contact_cycles(system, workers=DEFAULT_WORKERS, progress=bar)
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": machine.name, "n_dof": system.n_dof,
                    "contact_dof": system.tangential_dof, "normal_dof": system.normal_dof})
    if json:
        print_json(payload)
        return
    typer.echo(f"machine     {machine.name}: {system.n_dof} DOF, contact on DOF "
               f"{system.tangential_dof}, normal DOF "
               f"{'-' if system.normal_dof is None else system.normal_dof}\n" + result.summary())


def contact_basin_command(ctx: typer.Context, config: Path, machine_file: Any, *, samples: int,
                          seed: int, box: str | None, initial_states: Path | None,
                          t_max: float, workers: int | None, out: Path | None,
                          overwrite: bool, json: bool) -> None:
    """``basin --config`` with a contact (:func:`contact_basin`): ``labels.csv`` under --out."""
    import numpy as np

    from stickslip.cli.basin_command import parse_box, read_states
    from stickslip.cli.contact_simulation import contact_run_system
    from stickslip.sweep.contact_basin import (
        columns,
        contact_basin,
        default_box,
        sample_contact_box,
    )

    _refuse(ctx, ("backend", "scheduler", "plot"), "basin")
    if box is not None and initial_states is not None:
        raise BadInput("give either --box (sampling) or --initial-states, not both")
    if workers is not None and not 1 <= workers <= 64:
        raise BadInput(f"--workers {workers} must be from 1 to 64")
    if not t_max > 0.0:
        raise BadInput(f"--t-max {t_max:g} must be positive (natural times of the contact DOF)")
    labels = None if out is None else out / "labels.csv"
    if labels is not None:
        check_output_path(labels, overwrite=overwrite, option="--out")
    system, machine = contact_run_system(config, machine_file)
    typed_t_max = bool(_typed(ctx, ("t_max",)))
    horizon = t_max / system.omega_ref if typed_t_max else None
    names = columns(system)
    try:
        if initial_states is not None:
            _, _, values = read_states(initial_states, list(names))
            starts = np.array(values, dtype=np.float64)
        else:
            intervals = parse_box(box) if box is not None else default_box(system)
            starts = sample_contact_box(system, samples, intervals, seed)
        with _bar(json, f"basin {len(starts)} starts (contact)", "samples") as bar:
            result = contact_basin(system, starts, t_max=horizon, workers=workers or DEFAULT_WORKERS,
                                   progress=bar)
    except BadInput:
        raise
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": machine.name, "labels": None,
                    "t_max_s": horizon})
    if labels is not None:
        from stickslip.io.lock import output_lock

        labels.parent.mkdir(parents=True, exist_ok=True)
        with output_lock(labels):
            payload["labels"] = str(result.write_labels(labels))
    if json:
        print_json(payload)
        return
    fr, se = payload["fractions"], payload["standard_errors"]
    parts = [f"{k} {fr[k]:.4f} +- {se[k]:.4f}" for k in fr if fr[k] > 0.0]
    lines = [f"basin       {machine.name}: {system.n_dof} DOF, contact on DOF "
             f"{system.tangential_dof}, starts around {payload['base']} over "
             f"{', '.join(names)} (SI)",
             f"samples     {payload['n']} in {payload['elapsed_s']:.2f} s (one engine run each)",
             f"fractions   {', '.join(parts)} (binomial standard errors)"]
    for kind, (lo, hi) in payload["period_range_s"].items():
        lines.append(f"periods     {kind}: {lo:.6g} to {hi:.6g} s")
    for why, count in payload["undetermined_by"].items():
        lines.append(f"undecided   {count}: {why}")
    lines.append("verdicts    periodic ones observed (a state repeated to 1e-9), not proven")
    if payload["labels"]:
        lines.append(f"labels      {payload['labels']}")
    typer.echo("\n".join(lines))


def contact_continue_command(ctx: typer.Context, config: Path, machine_file: Any, param: str,
                             range_: str, *, points: int | None, out: Path | None,
                             plot: Path | None, overwrite: bool, json: bool) -> None:
    """``continue --config`` with a contact (:func:`continue_contact`): ``--out`` .csv or .json."""
    from stickslip.analysis.contact_continuation import (
        DEFAULT_POINTS,
        MAX_POINTS,
        PARAMETERS,
        continue_contact,
    )
    from stickslip.cli.contact_simulation import contact_run_system
    from stickslip.cli.continue_command import _parse_range
    from stickslip.io.atomic import atomic_write_text

    _refuse(ctx, ("seeds", "max_period", "max_steps"), "continue")
    if param not in PARAMETERS:
        raise BadInput(f"--param {param!r}: a [contact] machine is continued in "
                       f"{' or '.join(PARAMETERS)} (--param speed or --param load)")
    lo, hi = _parse_range(range_, param)
    if not lo > 0.0:
        raise BadInput(f"--range {range_!r}: {param} must be positive")
    n = DEFAULT_POINTS if points is None else points
    if not 2 <= n <= MAX_POINTS:
        raise BadInput(f"--points {n} must be from 2 to {MAX_POINTS}")
    if out is not None:
        if out.suffix.lower() not in (".csv", ".json"):
            raise BadInput(f"--out {str(out)!r} must end in .csv or .json with a [contact] machine")
        check_output_path(out, overwrite=overwrite, option="--out")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    system, machine = contact_run_system(config, machine_file)
    try:
        with _bar(json, f"continue {param}: {2 * n} runs") as bar:
            result = continue_contact(system, param, (lo, hi), points=n,
                                      workers=DEFAULT_WORKERS, progress=bar)
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": machine.name, "out": None, "plot": None})
    if out is not None:
        if out.suffix.lower() == ".csv":
            result.write_csv(out)
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
