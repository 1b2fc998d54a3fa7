"""``stickslip stability``: complex-eigenvalue analysis of steady sliding with normal-load coupling."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import BadInput, print_json
from stickslip.cli.options import JSON, OVERWRITE

#: Largest friction coefficient ``--mu-max`` accepts.
MU_MAX_LIMIT = 100.0
#: ``--mu-max`` when not given.
MU_MAX_DEFAULT = 2.0


def stability(
    config: Annotated[Path, typer.Option(
        "--config", help="machine.toml in SI with a [structure] (contact_dof, normal_dof) and a "
        "[contact] table (normal_stiffness, optional normal_damping)")],
    mu_max: Annotated[float | None, typer.Option(
        "--mu-max", help="largest friction coefficient searched for the critical one "
        f"[default: {MU_MAX_DEFAULT:g}]", show_default=False)] = None,
    plot: Annotated[Path | None, typer.Option(
        "--plot", help="write the root locus over mu here (frequencies and real parts)")] = None,
    map_plot: Annotated[Path | None, typer.Option(
        "--map", help="write the stability map over (mu, speed) here (speed matters only "
        "through the friction law's slope)")] = None,
    overwrite: OVERWRITE = False,
    json: JSON = False,
) -> None:
    """Complex-eigenvalue analysis (CEA) of steady sliding: eigenvalues in 1/s with frequencies
    in Hz and damping ratios, stable or not, the critical friction coefficient with the
    machine's damping and without damping (mode coalescence, flutter), the modes involved,
    and the speeds and loads (a decade either side) where steady sliding is unstable.

    With a friction law with memory (rate-state, lugre) it gives the eigenvalues of steady
    sliding with the state variable, the verdict, the critical stiffness (Hopf; Rice and
    Ruina's k_c for a 1-DOF rate-and-state slider) and the critical speeds; --map draws the
    growth rate over a decade of speed and load either side.

    The friction force mu N on contact_dof follows the normal force N = load - k_n q[normal_dof]
    of the contact spring: a non-symmetric stiffness entry mu k_n couples the modes.

    Example: stickslip stability --config examples/brake_pad/machine.toml --json
    """
    from stickslip.cli.console import check_distinct_outputs, check_figure_path

    if mu_max is not None and not 0.0 < mu_max <= MU_MAX_LIMIT:
        raise BadInput(f"--mu-max {mu_max!r} must be above 0 and at most {MU_MAX_LIMIT:g}")
    check_distinct_outputs(plot=plot, map=map_plot)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    if map_plot is not None:
        check_figure_path(map_plot, overwrite=overwrite, option="--map")
    from stickslip.cli.machine_config import load_machine_file

    memory_file = load_machine_file(config, normal_coupling=True)
    if memory_file.has_memory_law:  # the linearisation with the state variable
        from stickslip.cli.memory.stability_commands import memory_stability_command

        if plot is not None:
            raise BadInput("--plot draws the root locus over mu of the contact's complex-eigenvalue "
                           "analysis; with a friction law with memory, --map draws the growth "
                           "rate over speed and load")
        if mu_max is not None:
            raise BadInput(f"--mu-max {mu_max:g} bounds the search over mu of the contact's "
                           "complex-eigenvalue analysis; with a friction law with memory the "
                           "linearisation of steady sliding searches no mu (leave it out)")
        memory_stability_command(memory_file, config, map_plot, json)
        return
    result, ranges, machine, contact, index = _analyse(
        config, MU_MAX_DEFAULT if mu_max is None else mu_max)
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": machine.name,
                    "contact_dof": machine.contact_dof, "normal_dof": index,
                    "operating_ranges": ranges.to_dict()})
    if plot is not None:
        payload["plot"] = str(result.plot(title=machine.name).savefig(plot))
    if map_plot is not None:
        payload["map"] = str(_speed_map(result, machine, contact, index).savefig(map_plot))
    if json:
        print_json(payload)
        return
    _print(payload)


def _analyse(config: Path, mu_max: float) -> tuple[Any, Any, Any, Any, int | None]:
    """The analysis of ``config``: result, operating ranges, machine, contact, normal DOF index."""
    from stickslip.analysis.contact.eigenvalue_maps import operating_ranges
    from stickslip.analysis.contact.eigenvalues import complex_eigenvalue_analysis
    from stickslip.cli.machine_config import collect_inputs, config_system, load_machine_file, warn_truncated
    from stickslip.io.machine_file import machine_from_file
    from stickslip.model.machine import machine_from_physical_system

    machine_file = load_machine_file(config, normal_coupling=True)
    try:
        contact = machine_file.contact()
        if machine_file.has_structure:
            values = collect_inputs({}, config, normal_coupling=True)
            if values["mu_s"] == values["mu_k"] and machine_file.friction_table is None:
                raise BadInput(f"{machine_file.label}: mu_s = mu_k = {values['mu_k']:g}: the model "
                               "needs static friction above kinetic friction; the eigenvalues of "
                               "steady sliding depend on mu_k alone (a Coulomb law), so any mu_s "
                               "above it gives the same analysis")
            machine, reduction = machine_from_file(machine_file, values, normal_coupling=True)
            warn_truncated(reduction)
        else:
            system = config_system(config, normal_coupling=True)
            machine, reduction = machine_from_physical_system(system), None
        index = None if contact is None else contact.normal_dof
        if reduction is not None and index is not None:
            index = reduction.kept_dofs.index(index)
        result = complex_eigenvalue_analysis(machine, contact, normal_dof=index, mu_max=mu_max)
        ranges = operating_ranges(machine, contact, normal_dof=index)
    except BadInput:
        raise
    except ValueError as exc:
        message = str(exc)
        raise BadInput(message if message.startswith("--config") else
                       f"{machine_file.label}: {message}") from None
    return result, ranges, machine, contact, index


def _speed_map(result: Any, machine: Any, contact: Any, index: int | None) -> Any:
    """The (mu, speed) map over a decade either side of the machine's speed."""
    import numpy as np

    from stickslip.analysis.contact.eigenvalue_maps import stability_map
    from stickslip.analysis.contact.friction_coupling import coupled_system

    speeds = machine.speed * np.logspace(-1.0, 1.0, 25)
    systems = [coupled_system(machine, contact, normal_dof=index, speed=float(v))[0] for v in speeds]
    found = [c.mu for c in (result.critical, result.critical_undamped) if c.mu]
    top = 1.5 * max([*found, result.mu])
    data = stability_map(systems, speeds, np.linspace(0.0, top, 121), "speed [m/s]")
    return data.plot(log_y=True, title=f"{machine.name}: growth rate of steady sliding")


def _print(p: dict[str, Any]) -> None:
    from stickslip.analysis.contact.critical_coefficient import critical_text

    normal = ("none (a constant normal load)" if p["normal_dof"] is None else p["normal_dof"])
    lines = [f"stability   {p['machine']}: contact_dof {p['contact_dof']}, normal_dof {normal}",
             f"steady      mu(V) = {p['mu']:.6g}, d mu/d v_r = {p['friction_slope_s_per_m']:.6g} s/m, "
             f"N = {p['normal_force_N']:.6g} N",
             f"verdict     {p['verdict'].upper() if p['verdict'] == 'unstable' else p['verdict']}"
             + (" (every eigenvalue within round-off of the imaginary axis or left of it: neutral)"
                if p["verdict"] == "marginal" else "")]
    lines.append("modes       frequency [Hz]  damping ratio  real part [1/s]")
    for m in p["modes"]:
        flag = "  <- unstable" if m["growth_rate_per_s"] > 0 and p["verdict"] == "unstable" else ""
        # + 0.0: a rounded -0 prints as 0
        lines.append(f"            {m['frequency_hz']:14.6g}  {m['damping_ratio'] + 0.0:13.4g}  "
                     f"{m['growth_rate_per_s'] + 0.0:15.6g}{flag}")
    values = p["eigenvalues"]
    lines.append("eigenvalues " + (", ".join(f"{re + 0.0:.6g}{im + 0.0:+.6g}j" for re, im in values)
                                   + " [1/s]"
                                   if len(values) <= 12 else f"{len(values)} (listed by --json)"))
    lines.append(f"natural     {', '.join(f'{f:.6g}' for f in p['natural_frequencies_hz'])} Hz "
                 "(modes 1, 2, ...: the structure pressed on the belt, mu = 0)")
    lines.append(f"critical mu {critical_text(p['critical'], p['mu'])}")
    lines.append(f"undamped    {critical_text(p['critical_undamped'], p['mu'])}")
    ranges = p["operating_ranges"]
    for key, unit, grid_key in (("unstable_speeds_m_per_s", "m/s", "speed_grid_m_per_s"),
                                ("unstable_loads_N", "N", "load_grid_N")):
        what, runs, grid = key.split("_")[1], ranges[key], ranges[grid_key]
        text = (", ".join(f"{a:.4g} to {b:.4g} {unit}" for a, b in runs) if runs else "none")
        lines.append(f"{what:<11} unstable: {text} (mu = mu(V), grid {grid[0]:.4g} to "
                     f"{grid[1]:.4g} {unit}, {grid[2]} points; ends inside it are the boundaries)")
    if p["friction_slope_s_per_m"] == 0.0:
        lines.append("note        with a friction law flat at V (Coulomb) neither speed nor load "
                     "changes the eigenvalues")
    for key in ("plot", "map"):
        if p.get(key):
            lines.append(f"figure      {p[key]}")
    typer.echo("\n".join(lines))


def register(app: typer.Typer) -> None:
    """Add the ``stability`` command to ``app``."""
    app.command("stability")(stability)
