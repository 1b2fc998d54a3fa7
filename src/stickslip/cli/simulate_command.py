"""``stickslip simulate``: one run, certified verdict, optional JSON and figure."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from stickslip.cli.console import (
    BadInput,
    check_figure_path,
    check_run_limits,
    parse_dva,
    parse_friction_option,
    print_json,
    typed_options,
    warn,
    warn_fitted_range,
)
from stickslip.cli.options import DVA, FRICTION, GAMMA, JSON, K_SCALE, OVERWRITE
from stickslip.cli.time_options import parse_history_times, parse_t_max, parse_t_max_seconds

if TYPE_CHECKING:
    from stickslip.cli.machine_config import ConfiguredMachine
    from stickslip.model.initial import InitialState

LAM = Annotated[float | None, typer.Option(
    "--lam", help="lambda = (mu_s - mu_k) W / (V sqrt(m k)) > 0 (required without --config)")]
ZETA = Annotated[float | None, typer.Option(
    "--zeta", help="damping ratio c / (2 sqrt(m k)) >= 0 (required without --config)")]
CONFIG = Annotated[Path | None, typer.Option(
    "--config", help="machine.toml in SI (the paper's m, k, c or a [structure] table, [friction]): "
    "one run of that machine, answers in seconds and metres beside the dimensionless ones; "
    "not with --lam, --zeta, --gamma, --dva, --k-scale, --friction")]
T_MAX = Annotated[str | None, typer.Option(
    "--t-max", help="time horizon: dimensionless tau (default 5000), or a time with units with "
    "--config (\"40 s\"); for friction with memory a bare number is tau = omega_n t and the "
    "default covers 100 natural times")]
HISTORY_TIMES = Annotated[str | None, typer.Option(
    "--history-times", help="A:B:N: add `history` (t_s, x_m, v_m_s, mu, state) at N times from A "
    "to B seconds (--config with a friction law with memory or a [contact] machine)")]
INITIAL_KICK = Annotated[float | None, typer.Option(
    "--initial-kick", help="F: start with the slip speed at (1 + F) V, the contact moving at -F V, "
    "positions and state of steady sliding (a friction law with memory: --config, or "
    "--friction rate-state:...|lugre:...)")]

def parse_initial(text: str, n_dof: int) -> InitialState | None:
    """``startup`` or ``2 n`` comma-separated numbers: positions then velocities."""
    if text.strip().lower() == "startup":
        return None
    try:
        values = [float(x) for x in text.split(",")]
    except ValueError:
        raise BadInput(f"--initial {text!r} is not 'startup' or a list of numbers") from None
    if len(values) != 2 * n_dof:
        raise BadInput(
            f"--initial {text!r} has {len(values)} numbers; expected {2 * n_dof} "
            f"(positions then velocities of {n_dof} DOF)"
        )
    import numpy as np

    from stickslip.model.initial import InitialState

    return InitialState(np.array(values[:n_dof]), np.array(values[n_dof:]), f"user-defined: {text}")


def simulate(
    ctx: typer.Context,
    lam: LAM = None,
    zeta: ZETA = None,
    config: CONFIG = None,
    gamma: GAMMA = 2.0,
    dva: DVA = "none",
    k_scale: K_SCALE = 1.0,
    t_max: T_MAX = None,
    initial: Annotated[
        str,
        typer.Option("--initial", help="startup (default), or 2n comma-separated numbers for n "
                     "DOF: the n positions, then the n velocities, dimensionless and shifted "
                     "(positions from the kinetic-friction equilibrium, Eqs. 15-16; velocities "
                     "in units of the belt speed); slider first, then the foundation (with "
                     "--config: the order of its structure's DOFs), e.g. 0.5,0,0,0"),
    ] = "startup",
    max_events: Annotated[int, typer.Option("--max-events", help="bound on mode switches")] = 100_000,
    plot: Annotated[
        Path | None, typer.Option("--plot", help="write time history and phase portrait here")
    ] = None,
    t_plot_start: Annotated[
        float, typer.Option("--plot-from", help="first time drawn in the figure")
    ] = 0.0,
    friction: FRICTION = "coulomb",
    overwrite: OVERWRITE = False,
    history_times: HISTORY_TIMES = None,
    initial_kick: INITIAL_KICK = None,
    json: JSON = False,
) -> None:
    """One simulation: certified verdict, period, amplitude, events.

    Example: stickslip simulate --lam 3 --zeta 0.1 --dva optimal --friction linear:0.05 --json

    Your machine in SI (docs/structures.md): stickslip simulate --config machine.toml --json
    gives period_s, amplitude_m (half the peak-to-peak displacement of the contact DOF) next to
    the dimensionless period, amplitude, lambda, zeta and gamma; --t-max and --initial stay
    dimensionless (tau = omega_n t, displacements in V / omega_n of the contact DOF).

    A machine with its contact ([structure] normal_dof and [contact], docs/brake_squeal.md)
    runs on the exact contact engine: stick, slip and separation; --json adds separated.
    """
    from stickslip.analysis.simulation import EngineOptions
    from stickslip.analysis.simulation import simulate as run_simulation
    from stickslip.cli.machine_config import configured_machine, refuse_mix, require_dimensionless
    from stickslip.model import Slider, chain_structure

    refuse_mix(ctx, config)
    if plot is None and typed_options(ctx, ("t_plot_start",)):
        raise BadInput("--plot-from sets the first time drawn in --plot's figure; give --plot too")
    foundation = None
    run = None
    if config is not None and _ran_on_another_engine(
            ctx, config, t_max=t_max, max_events=max_events, history_times=history_times,
            initial_kick=initial_kick, plot=plot, json=json):
        return
    memory_law = friction.strip().lower().startswith(("rate-state:", "lugre:"))
    for name, value in (("--history-times", history_times), ("--initial-kick", initial_kick)):
        if value is not None and not memory_law:
            raise BadInput(f"{name} works with a friction law with memory (--friction "
                           "rate-state:... or lugre:..., or --config with [friction] law = "
                           "\"rate-state\" or \"lugre\")"
                           + (" or a machine file with a [contact]"
                              if name == "--history-times" else ""))
    if config is not None:
        run = configured_machine(config)
        structure, slider = run.structure, run.slider
        check_run_limits(slider.lam, slider.gamma, max_events=max_events, plot_from=t_plot_start)
    else:
        require_dimensionless(lam=lam, zeta=zeta)
        assert lam is not None and zeta is not None
        if memory_law:
            _simulate_memory_dimensionless(ctx, lam=lam, zeta=zeta, dva=dva, k_scale=k_scale,
                                           friction=friction, t_max=t_max,
                                           history_times=history_times,
                                           initial_kick=initial_kick, plot=plot, json=json)
            return
        slider = Slider(lam, gamma=gamma, friction=parse_friction_option(friction))
        check_run_limits(slider.lam, slider.gamma, max_events=max_events, plot_from=t_plot_start)
        foundation = parse_dva(dva, zeta, k_scale)
        structure = chain_structure(zeta, () if foundation is None else (foundation,))
    init = parse_initial(initial, structure.n_dof)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    if config is None:
        warn_fitted_range(dva, [zeta])
    horizon = parse_t_max(t_max, None if run is None else run.reference.time_scale)
    result = run_simulation(structure, slider, initial=init,
                            options=EngineOptions(t_max=5000.0 if horizon is None else horizon,
                                                  max_events=max_events))
    payload = result.to_dict()
    if run is not None and config is not None:
        payload.update(machine_answers(payload, run, config))
    payload["safe_disturbance_sentence"] = result.safe_disturbance.sentence()
    if foundation is not None:
        payload["foundation"] = {
            "M": foundation.mass_ratio,
            "K": foundation.stiffness_ratio,
            "zeta_a": foundation.damping_ratio,
        }
    else:
        payload["foundation"] = None
    if plot is not None:
        if t_plot_start is not None and t_plot_start >= result.t_end:
            raise BadInput(f"--plot-from {t_plot_start:g} is at or past the run's end, tau = "
                           f"{result.t_end:.6g}: the figure would be empty")
        payload["plot"] = str(result.plot(t_start=t_plot_start).savefig(plot))
    if json:
        print_json(payload)
        return
    _print_summary(payload)


def _ran_on_another_engine(ctx: typer.Context, config: Path, *, t_max: str | None,
                           max_events: int, history_times: str | None,
                           initial_kick: float | None, plot: Path | None, json: bool) -> bool:
    """Run a machine with a contact or a friction law with memory on its engine; True if so."""
    from stickslip.cli.machine_config import load_machine_file

    machine_file = load_machine_file(config, normal_coupling=True)
    if machine_file.has_contact and not machine_file.has_memory_law:
        from stickslip.cli.contact.simulation import simulate_contact_command

        simulate_contact_command(ctx, config, machine_file, t_max=t_max,
                                 max_events=max_events, history_times=history_times,
                                 plot=plot, json=json)
        return True
    if machine_file.has_memory_law:
        from stickslip.cli.machine_config import refuse_contact_with_memory

        refuse_contact_with_memory(machine_file)  # neither engine has both: one line
        _simulate_memory(ctx, machine_file, t_max=t_max, history_times=history_times,
                         initial_kick=initial_kick, plot=plot, json=json)
        return True
    return False


def _refuse_exact_engine_options(ctx: typer.Context, plot: Path | None,
                                 names: tuple[str, ...] = ("initial", "max_events", "t_plot_start"),
                                 ) -> None:
    """Options of the exact engine, typed next to a friction law with memory: one line."""
    typed = [name for name in names
             if getattr(ctx.get_parameter_source(name), "name", None) == "COMMANDLINE"]
    if typed or plot is not None:
        flags = ", ".join(["--" + n.replace("_", "-").replace("t-plot-start", "plot-from")
                           for n in typed] + (["--plot"] if plot is not None else []))
        raise BadInput(f"{flags} cannot be given with a friction law with memory (use "
                       "--initial-kick, --history-times, --t-max)")


def _simulate_memory_dimensionless(ctx: typer.Context, *, lam: float, zeta: float, dva: str,
                                   k_scale: float, friction: str, t_max: str | None,
                                   history_times: str | None, initial_kick: float | None,
                                   plot: Path | None, json: bool) -> None:
    """``--friction rate-state:...`` / ``lugre:...``: the dimensionless system on the stiff engine.

    The system in the slider's units (``m = k = 1``, drive speed 1, time tau = omega_n t):
    the structure of ``--zeta`` and ``--dva``, the normal load ``--lam`` (for these laws the
    load number ``W / (V sqrt(m k))``), the law's numbers as
    :func:`stickslip.model.state_friction_input.parse_state_friction` reads them. Answers are
    dimensionless (``period``, ``amplitude``; the ``*_s`` and ``*_m`` keys are then in tau
    and ``V / omega_n``).
    """
    from stickslip.analysis.memory.simulation import simulate_memory
    from stickslip.model import chain_structure
    from stickslip.model.state_friction import MemorySystem, SpeedSchedule
    from stickslip.model.state_friction_input import parse_state_friction

    _refuse_exact_engine_options(ctx, plot, ("initial", "max_events", "t_plot_start", "gamma"))
    raw = friction.strip()
    kind, _, arg = raw.partition(":")
    try:
        law = parse_state_friction(kind.strip().lower(), arg, raw)
    except ValueError as exc:
        raise BadInput(f"--friction: {exc}") from None
    foundation = parse_dva(dva, zeta, k_scale)
    structure = chain_structure(zeta, () if foundation is None else (foundation,))
    if not (math.isfinite(lam) and lam > 0.0):
        raise BadInput(f"--lam {lam!r} must be positive and finite: with a friction law with "
                       "memory it is the load number W / (V sqrt(m k))")
    try:
        system = MemorySystem(structure.mass, structure.damping, structure.stiffness,
                              structure.contact_dof, lam, law, SpeedSchedule.constant(1.0))
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    horizon = parse_t_max(t_max, None)
    times = None if history_times is None else parse_history_times(history_times)
    try:
        result = simulate_memory(system, t_max=horizon, kick=initial_kick or 0.0,
                                 history_times=times)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    payload = result.to_dict()
    payload.update({"period": payload["period_s"], "amplitude": payload["amplitude_m"],
                    "lambda": lam, "zeta": zeta, "units": "dimensionless: m = k = V = 1, "
                    "time tau = omega_n t, lengths in V / omega_n, load = lambda"})
    if json:
        print_json(payload)
        return
    def shown(x: float | None) -> str:
        return "-" if x is None else f"{x:.6g}"

    typer.echo(f"verdict     {payload['verdict']}\ncertificate "
               f"{payload['certificate'] or '- (' + payload['status_message'] + ')'}\n"
               f"period      {shown(payload['period'])}   amplitude {shown(payload['amplitude'])}\n"
               "units       dimensionless: m = k = V = 1, load = lambda; the engine's m/s, s and m "
               "read as V, 1/omega_n (tau) and V/omega_n")


def _simulate_memory(ctx: typer.Context, machine_file: Any, *, t_max: str | None,
                     history_times: str | None, initial_kick: float | None, plot: Path | None,
                     json: bool) -> None:
    """``simulate --config`` with a friction law with memory: the smooth stiff engine, in SI."""

    import numpy as np

    from stickslip.analysis.memory.simulation import simulate_memory

    _refuse_exact_engine_options(ctx, plot)
    try:
        system = machine_file.memory_system()
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    time_scale = None
    if not system.quasi_static:
        c = system.contact_dof
        time_scale = math.sqrt(float(system.mass[c, c]) / float(system.stiffness[c, c]))
    if t_max is not None and time_scale is None:
        try:
            float(t_max)
        except ValueError:
            pass
        else:
            raise BadInput(f"--t-max {t_max!r}: the quasi-static slider (m = 0) has no natural "
                           "time; give a time with units, e.g. --t-max \"40 s\"")
    horizon = parse_t_max_seconds(t_max, 1.0 if time_scale is None else time_scale)
    times = None if history_times is None else parse_history_times(history_times)
    try:
        result = simulate_memory(system, t_max=horizon, kick=initial_kick or 0.0,
                                 history_times=times)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    if times is not None and float(times[-1]) > result.t_end:
        beyond = int(np.sum(times > result.t_end))
        warn(f"--history-times {history_times!r}: {beyond} of its {times.size} times lie beyond "
             f"the end of the run ({result.t_end:.6g} s, where it stopped); their history "
             "entries are null")
    payload = result.to_dict()
    payload["config"] = str(machine_file.path)
    if json:
        print_json(payload)
        return

    def fmt(x: object) -> str:
        return "-" if x is None else (f"{x:.6g}" if isinstance(x, float) else str(x))

    steady = payload["steady_sliding"]
    typer.echo("\n".join([
        f"machine     {payload['config']}: {system.n_dof} DOF"
        + (" (quasi-static slider, m = 0)" if system.quasi_static else ""),
        f"friction    {payload['friction']['description']}",
        f"verdict     {payload['verdict']}",
        f"certificate {payload['certificate'] or '- (' + payload['status_message'] + ')'}",
        f"period      {fmt(payload['period_s'])} s   amplitude {fmt(payload['amplitude_m'])} m",
        f"sliding     steady sliding at {fmt(steady['speed_m_s'])} m/s is "
        + ("linearly stable" if steady["stable"] else "linearly UNSTABLE")
        + f" (growth rate {fmt(steady['growth_rate_per_s'])} 1/s)",
        f"initial     {payload['initial_condition']}",
        f"run         {fmt(payload['t_end_s'])} s, {payload['steps']} steps "
        f"({payload['rejected_steps']} rejected)",
    ]))


def machine_answers(payload: dict[str, Any], run: ConfiguredMachine, config: Path) -> dict[str, Any]:
    """The SI answers of a machine-file run, from the dimensionless ones and the scales.

    ``period_s = period / omega_n`` (Eq. 17, ``tau = omega_n t``), ``amplitude_m = amplitude
    V / omega_n`` (Eqs. 15-16: displacements are in units of ``V / omega_n``; a half
    peak-to-peak is unchanged by the equilibrium shift), with ``omega_n = sqrt(k_ref / m_ref)``
    of the contact DOF (:mod:`stickslip.model.machine`). No cycle: None.
    """
    scales = run.scales()

    def times(key: str, scale: float) -> float | None:
        value = payload.get(key)
        return None if value is None else float(value) * scale

    return {
        "config": str(config),
        "period_s": times("period", scales["time_scale_s"]),
        "amplitude_m": times("amplitude", scales["length_scale_m"]),
        "t_end_s": times("t_end", scales["time_scale_s"]),
        "dimensionless": {**run.groups(), "period": payload.get("period"),
                          "amplitude": payload.get("amplitude")},
        "scales": scales,
        "machine": run.machine.to_dict(),
        "reduction": None if run.reduction is None else run.reduction.summary(),
        "reduced_from": None if run.reduction is None else {
            "n_dof": run.reduction.n_full, "contact_dof": run.reduction.kept_dofs[0]},
    }


def _print_summary(p: dict[str, Any]) -> None:
    def fmt(x: object) -> str:
        return "-" if x is None else (f"{x:.6g}" if isinstance(x, float) else str(x))

    lines = [
        f"system      {p['structure']} (lambda={fmt(p['lambda'])}, zeta={fmt(p['zeta'])}, "
        f"gamma={fmt(p['gamma'])})",
        f"verdict     {p['verdict']}",
        f"certificate {p['certificate'] or '- (' + p['status_message'] + ')'}",
        f"stick phases {p['n_stick']}   period {fmt(p['period'])}   amplitude {fmt(p['amplitude'])}"
        f"   stick ratio {fmt(p['stick_ratio'])}",
        f"max xi'     {fmt(p['max_velocity'])}   t_end {fmt(p['t_end'])}   events {p['n_events']}",
        f"initial     {p['initial_condition']}",
        f"friction    {p['friction']['description']}",
        "sliding     steady sliding is "
        + ("linearly stable" if p["steady_sliding_stable"] else
           "neutral (marginally stable: the growth rate is zero to round-off)"
           if p.get("steady_sliding_neutral") else "linearly UNSTABLE")
        + f" (growth rate {fmt(p['growth_rate'])} per unit tau)",
        f"disturbance {_disturbance_line(p)}",
    ]
    if p.get("foundation"):
        f = p["foundation"]
        lines.insert(1, f"foundation  M={fmt(f['M'])}, K={fmt(f['K'])}, zeta_a={fmt(f['zeta_a'])}")
    if p.get("config"):
        size = f"{p['machine']['n_dof']} DOF, contact on DOF {p['machine']['contact_dof']}"
        if p.get("reduced_from"):
            full = p["reduced_from"]
            size = (f"{full['n_dof']} DOF reduced to {p['machine']['n_dof']}, contact on DOF "
                    f"{full['contact_dof']} (reduced DOF {p['machine']['contact_dof']})")
        lines.insert(1, f"machine     {p['config']}: {size}; period {fmt(p['period_s'])} s, "
                        f"amplitude {fmt(p['amplitude_m'])} m")
    if p.get("plot"):
        lines.append(f"figure      {p['plot']}")
    typer.echo("\n".join(lines))


def _disturbance_line(p: dict[str, Any]) -> str:
    """The safe disturbance margin, said to be about disturbances of steady sliding.

    The margin (:mod:`stickslip.analysis.disturbance`) is about knocks to a machine that is
    already sliding steadily; the verdict above is about the start-up, which is no small knock
    of steady sliding. Without saying so, "verdict stick-slip" followed by "a kick below 1 V
    cannot start stick-slip" reads as a contradiction.
    """
    line = f"of steady sliding: {p['safe_disturbance_sentence']}"
    if p.get("steady_sliding_neutral"):
        line += " (neutral: a small disturbance neither grows nor decays)"
    elif p["verdict"] == "stick-slip" and p["steady_sliding_stable"]:
        line += " (the start-up above is not such a disturbance: it starts far from steady sliding)"
    return line


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command to ``app``."""
    app.command("simulate")(simulate)
