"""``stickslip simulate --config`` for a machine with its contact (normal DOF, Jenkins element).

The machine file's ``[structure] normal_dof`` and ``[contact]`` table (or a flat file's
paper slider with a ``[contact] tangential_stiffness``) run on the exact contact engine,
:mod:`stickslip.analysis.contact.engine`: stick, slip, separation and re-contact, answers in
seconds, metres and newtons.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import typer

from stickslip.cli.console import BadInput, print_json

#: Options of the paper's engine that the contact engine does not take.
REFUSED = {"initial": "--initial", "t_plot_start": "--plot-from", "initial_kick": "--initial-kick"}


def contact_run_system(config: Path, machine_file: Any) -> tuple[Any, Any]:
    """The :class:`~stickslip.analysis.contact.engine.ContactSystem` of a file, and its machine.

    Raises
    ------
    BadInput
        One line naming the file when a value is wrong or the machine is not supported.
    """
    from stickslip.analysis.contact.engine import contact_system
    from stickslip.cli.machine_config import collect_inputs, config_system, warn_truncated
    from stickslip.io.machine_file import machine_from_file
    from stickslip.model.machine import machine_from_physical_system

    try:
        contact = machine_file.contact()
        if machine_file.has_structure:
            values = collect_inputs({}, config, normal_coupling=True)
            machine, reduction = machine_from_file(machine_file, values, normal_coupling=True)
            warn_truncated(reduction)
        else:
            system = config_system(config, normal_coupling=True)
            machine, reduction = machine_from_physical_system(system), None
        index = None if contact is None else contact.normal_dof
        if reduction is not None and index is not None:
            index = reduction.kept_dofs.index(index)
        return contact_system(machine, contact, normal_dof=index), machine
    except BadInput:
        raise
    except ValueError as exc:
        message = str(exc)
        raise BadInput(message if message.startswith("--config") else
                       f"{machine_file.label}: {message}") from None


def simulate_contact_command(ctx: typer.Context, config: Path, machine_file: Any, *,
                             t_max: str | None, max_events: int, history_times: str | None,
                             plot: Path | None, json: bool) -> None:
    """Run a contact machine and print the answer (``--json``: verdict, period_s, amplitude_m,
    separated, the last events, the machine; ``--history-times``: the time history)."""
    from stickslip.analysis.contact.eigenvalues import self_locking_note
    from stickslip.analysis.contact.engine import simulate_contact
    from stickslip.analysis.verdict import Verdict
    from stickslip.cli.time_options import parse_history_times, parse_t_max_seconds

    typed = [flag for name, flag in REFUSED.items()
             if getattr(ctx.get_parameter_source(name), "name", None) == "COMMANDLINE"]
    if plot is not None:
        typed.append("--plot")
    if typed:
        raise BadInput(f"{', '.join(typed)} cannot be given with a [contact] machine (it starts "
                       "from the startup state; use --history-times A:B:N for its time history)")
    if max_events < 1:
        raise BadInput(f"--max-events {max_events} must be at least 1")
    system, machine = contact_run_system(config, machine_file)
    time_scale = 1.0 / system.omega_ref
    horizon = parse_t_max_seconds(t_max, time_scale)
    if horizon is not None and not (math.isfinite(horizon) and horizon > 0.0):
        raise BadInput(f"--t-max {t_max!r} must be positive")
    times = None if history_times is None else parse_history_times(history_times)
    try:
        run = simulate_contact(system, t_max=horizon, max_events=max_events)
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = run.to_dict()
    if run.verdict is Verdict.UNDETERMINED:
        payload["note"] = self_locking_note(system)
    payload.update({"config": str(config), "machine": machine.name, "n_dof": system.n_dof,
                    "contact_dof": system.tangential_dof, "normal_dof": system.normal_dof,
                    "contact": _contact_summary(system)})
    if times is not None:
        if float(times[-1]) > run.t_end:
            raise BadInput(f"--history-times {history_times!r} goes beyond the end of the run "
                           f"({run.t_end:.6g} s); give B <= that or a longer --t-max")
        payload["history"] = run.history(times)
    if json:
        print_json(payload)
        return
    typer.echo(_summary(payload))


def _contact_summary(system: Any) -> dict[str, Any]:
    """The contact's numbers in SI (None where absent)."""
    return {"normal_stiffness_N_m": system.normal_stiffness if system.normal_dof is not None
            else None,
            "normal_damping_N_s_m": system.normal_damping if system.normal_dof is not None
            else None,
            "tangential_stiffness_N_m": system.tangential_stiffness,
            "tangential_damping_N_s_m": system.tangential_damping
            if system.tangential_stiffness is not None else None,
            "contact_mass_kg": system.contact_mass}


def _summary(p: dict[str, Any]) -> str:
    from stickslip.analysis.contact.engine import start_description

    def fmt(x: object) -> str:
        return "-" if x is None else (f"{x:.6g}" if isinstance(x, float) else str(x))

    counts = ", ".join(f"{k} {v}" for k, v in p["event_counts"].items()) or "none"
    lines = [
        f"machine     {p['machine']}: {p['n_dof']} DOF, contact on DOF {p['contact_dof']}, normal "
        f"DOF {fmt(p['normal_dof'])}",
        f"verdict     {p['verdict']}",
        f"certificate {p['certificate']}",
        f"period      {fmt(p['period_s'])} s   amplitude {fmt(p['amplitude_m'])} m "
        "(half peak-to-peak of the contact DOF)",
        f"start       {start_description(p.get('initial_mode'))}",
        f"separated   {'yes: the contact lifted off' if p['separated'] else 'no'}",
        f"events      {p['n_events']} ({counts}) up to t = {fmt(p['t_end_s'])} s",
    ]
    if p.get("note"):
        lines.append(f"note        {p['note']}")
    return "\n".join(lines)
