"""``cycles``, ``basin`` and ``continue`` with ``--config`` for a machine with its contact.

A machine file's ``[structure] normal_dof`` and ``[contact]`` table (or a flat file's paper
slider with a ``[contact] tangential_stiffness``) run on the exact contact engine
(:mod:`stickslip.analysis.contact.engine`). Its periodic verdicts are observed (a state
repeated to 1e-9), not proven; every answer says so.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import typer

from stickslip.analysis.contact.pool import DEFAULT_WORKERS
from stickslip.cli.console import BadInput, print_json, show_progress, typed_options

__all__ = ["DEFAULT_WORKERS", "progress_bar", "refuse_options"]



def refuse_options(ctx: typer.Context, names: tuple[str, ...], command: str) -> None:
    """Options that the contact engine does not take, typed: one line."""
    typed = typed_options(ctx, names)
    if typed:
        raise BadInput(f"{', '.join(typed)} cannot be given to `{command}` with a [contact] "
                       "machine (it runs the exact contact engine)")


def progress_bar(json: bool, label: str, unit: str = "runs", shorten: str | None = None) -> Any:
    """The progress bar on a terminal (not with --json); without one, ``shorten`` (or the
    default hint) goes into a note on stderr when the run is projected to be long
    (:class:`ProgressBar`)."""
    from stickslip.cli.progress import DEFAULT_SHORTEN, ProgressBar

    return ProgressBar(show_progress(), label, unit=unit,
                       shorten=DEFAULT_SHORTEN if shorten is None else shorten)


def contact_cycles_command(ctx: typer.Context, config: Path, machine_file: Any, *,
                           json: bool, t_max: str | None = None) -> None:
    """``cycles --config`` with a contact (:func:`find_contact_cycles`); ``t_max`` the horizon
    of each start's run (``--t-max``: seconds with a unit, or natural times)."""
    from stickslip.analysis.contact.cycles import find_contact_cycles
    from stickslip.cli.contact.simulation import contact_run_system
    from stickslip.cli.time_options import parse_t_max_seconds

    refuse_options(ctx, ("seeds", "max_period", "seed"), "cycles")
    system, machine = contact_run_system(config, machine_file)
    time_scale = 1.0 / system.omega_ref
    horizon = parse_t_max_seconds(t_max, time_scale)
    if horizon is not None and not (math.isfinite(horizon) and horizon > 0.0):
        raise BadInput(f"--t-max {t_max!r} must be positive")
    try:
        with progress_bar(json, "cycles: 8 starts") as bar:
            result = find_contact_cycles(system, t_max=horizon, workers=DEFAULT_WORKERS,
                                         progress=bar)
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
