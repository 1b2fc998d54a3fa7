"""``stickslip cycles``: the periodic motions that exist at a point, whatever the start."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import check_run_limits, parse_dva, parse_friction_option, print_json
from stickslip.cli.options import DVA, FRICTION, GAMMA, JSON, K_SCALE


def cycles(
    ctx: typer.Context,
    lam: Annotated[float | None, typer.Option("--lam", help="lambda > 0 (required without --config)")] = None,
    zeta: Annotated[float | None, typer.Option(
        "--zeta", help="damping ratio >= 0 (required without --config)")] = None,
    config: Annotated[Path | None, typer.Option(
        "--config", help="machine.toml in SI (m, k, c or a [structure], [friction]): the cycles of "
        "that machine, periods in s and amplitudes in m beside the dimensionless ones; not with "
        "--lam, --zeta, --gamma, --dva, --k-scale, --friction")] = None,
    gamma: GAMMA = 2.0,
    dva: DVA = "none",
    k_scale: K_SCALE = 1.0,
    friction: FRICTION = "coulomb",
    seeds: Annotated[int, typer.Option("--seeds", help="random starts that seed Newton's method")] = 24,
    max_period: Annotated[int, typer.Option("--max-period", help="longest cycle, in stick phases")] = 2,
    seed: Annotated[int, typer.Option("--seed", help="seed of the starts")] = 0,
    t_max: Annotated[str | None, typer.Option(
        "--t-max", help="horizon of each seeding run: dimensionless tau (default 5000), or a time "
        "with units with --config (\"40 s\"); a cycle slower than it is not searched")] = None,
    json: JSON = False,
) -> None:
    """Periodic motions at a point, stable and unstable: stick-slip cycles (fixed points of the
    breakaway return map) and slip oscillations (never sticking; velocity-dependent friction).

    Example: stickslip cycles --lam 15 --zeta 0.1 --dva optimal --json

    Your machine: stickslip cycles --config machine.toml --json
    """
    from stickslip.analysis.cycles import find_cycles
    from stickslip.analysis.engine_run import EngineOptions
    from stickslip.cli.console import BadInput, typed_options
    from stickslip.cli.machine_config import configured_machine, refuse_mix, require_dimensionless
    from stickslip.cli.time_options import parse_t_max
    from stickslip.model.parameters import Slider
    from stickslip.model.structure import chain_structure

    refuse_mix(ctx, config)
    if config is None:
        require_dimensionless(lam=lam, zeta=zeta)
    if not 1 <= seeds <= 10_000:
        raise BadInput(f"--seeds {seeds} must be from 1 to 10000")
    if not 1 <= max_period <= 8:
        raise BadInput(f"--max-period {max_period} must be from 1 to 8")
    run = None
    if config is not None:
        from stickslip.cli.machine_config import load_machine_file

        machine_file = load_machine_file(config, normal_coupling=True)
        if t_max is not None and machine_file.has_memory_law:
            raise BadInput(f"--t-max {t_max!r}: the cycles of a machine with a friction law with "
                           "memory take their own horizons; leave it out")
        seeding = typed_options(ctx, ("seeds", "max_period", "seed"))
        if seeding and machine_file.has_memory_law:  # a contact machine refuses them itself
            raise BadInput(f"{', '.join(seeding)}: the cycles of a machine with a friction law "
                           "with memory are found from runs of their own starts, not seeded; "
                           "leave them out")
        if machine_file.has_contact and not machine_file.has_memory_law:
            from stickslip.cli.contact.commands import contact_cycles_command

            contact_cycles_command(ctx, config, machine_file, json=json, t_max=t_max)
            return
        _refuse_contact(machine_file)
        if machine_file.has_memory_law:  # the stiff engine's runs from kicked starts
            _memory_cycles(machine_file, config, json)
            return
        run = configured_machine(config)
        structure, slider = run.structure, run.slider
    else:
        assert lam is not None and zeta is not None
        slider = Slider(lam, gamma=gamma, friction=parse_friction_option(friction))
        found = parse_dva(dva, zeta, k_scale)
        structure = chain_structure(zeta, () if found is None else (found,))
    check_run_limits(slider.lam, slider.gamma)  # as simulate: 2 gamma lambda must not overflow
    horizon = parse_t_max(t_max, None if run is None else run.reference.time_scale)
    options = EngineOptions() if horizon is None else EngineOptions(t_max=horizon)
    from stickslip.cli.console import show_progress
    from stickslip.cli.progress import DesignProgress

    # a spinner and the time: the seeds' runs and Newton's iterations report no count (an
    # independent audit: --seeds 400 ran minutes without a sign)
    with DesignProgress(show_progress(), "cycles", counted=False) as bar:
        bar(f"{seeds} seeds, periods up to {max_period} stick phases (--seeds, --max-period "
            "bound it; Ctrl-C stops it)", 0)
        result = find_cycles(structure, slider, seeds=seeds, max_period=max_period, seed=seed,
                             options=options, slip_oscillations=True)
    payload = result.to_dict()
    if run is not None:
        # seconds and metres: tau = omega_n t (Eq. 17), displacements in V / omega_n (Eqs. 15-16)
        scales = run.scales()
        payload.update({"config": str(config), "scales": scales, "machine": run.machine.to_dict()})
        for c in payload["cycles"] + payload["candidates"] + payload["slip_oscillations"]:
            c["period_s"] = None if c["period"] is None else c["period"] * scales["time_scale_s"]
            c["amplitude_m"] = (None if c["amplitude"] is None
                                else c["amplitude"] * scales["length_scale_m"])
    if json:
        print_json(payload)
        return
    _print(payload)


def _refuse_contact(machine_file: Any) -> None:
    """A contact beside a law with memory: one line (no engine has both)."""
    from stickslip.cli.machine_config import refuse_contact_with_memory

    refuse_contact_with_memory(machine_file)


def _memory_cycles(machine_file: Any, config: Path, json: bool) -> None:
    """``cycles --config`` for a friction law with memory (:func:`find_memory_cycles`)."""
    from stickslip.analysis.memory.cycle_search import find_memory_cycles
    from stickslip.cli.console import BadInput
    from stickslip.cli.memory.stability_commands import memory_system

    system = memory_system(machine_file)
    if len(system.schedule.speeds) > 1:
        raise BadInput(f"{machine_file.label}: speed is a schedule; cycles need one drive speed")
    try:
        result = find_memory_cycles(system)
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload["config"] = str(config)
    if json:
        print_json(payload)
        return
    typer.echo(result.summary())


def _print(p: dict[str, Any]) -> None:
    lines = [f"cycles      {p['structure']} (lambda={p['lambda']:.6g}, zeta={p['zeta']:.6g}, "
             f"gamma={p['gamma']:.6g}), friction {p['friction']}"]
    if not p["cycles"] and not p["candidates"]:
        lines.append(f"none found  from {p['n_seeds']} starts: no stick-slip cycle of the periods searched"
                     + (" within the horizon" if p["n_runs_cut_short"] else ""))
    elif not p["cycles"]:
        lines.append(f"none proven from {p['n_seeds']} starts: only the candidates below, which "
                     "no proof makes cycles (undetermined)")
    for i, c in enumerate(p["cycles"], start=1):
        mults = ", ".join(f"{m['abs']:.4g}" for m in c["multipliers"])
        why = (f"|Floquet multipliers| {mults}" if mults else
               "rigid base: a stick phase resets the whole state, the return map has no multipliers")
        si = (f" ({c['period_s']:.6g} s, {c['amplitude_m']:.6g} m)" if "period_s" in c else "")
        lines.append(f"cycle {i}     period {c['period']:.6g}  amplitude {c['amplitude']:.6g}{si}  "
                     f"stick ratio {c['stick_ratio']:.4g}  {c['stick_phases']} stick phase(s)  "
                     f"{'stable' if c['stable'] else 'UNSTABLE'} ({why})")
    for i, c in enumerate(p["candidates"], start=1):
        mults = ", ".join(f"{m['abs']:.4g}" for m in c["multipliers"])
        si = (f" ({c['period_s']:.6g} s, {c['amplitude_m']:.6g} m)" if "period_s" in c else "")
        lines.append(f"candidate {i} period {c['period']:.6g}  amplitude {c['amplitude']:.6g}{si}  "
                     f"{c['stick_phases']} stick phase(s)  |Floquet multipliers| {mults}  "
                     f"NOT PROVEN: {c['not_proven']}")
    for i, c in enumerate(p["slip_oscillations"], start=1):
        mults = ", ".join(f"{m['abs']:.4g}" for m in c["multipliers"])
        si = (f" ({c['period_s']:.6g} s, {c['amplitude_m']:.6g} m)" if "period_s" in c else "")
        lines.append(f"slip osc. {i} period {c['period']:.6g}  amplitude {c['amplitude']:.6g}{si}  "
                     f"peak velocity {c['peak_velocity']:.6g}  never sticks  "
                     f"{'stable' if c['stable'] else 'UNSTABLE'} (|Floquet multipliers| {mults}; "
                     f"found by {', '.join(c['found_by'])})")
    lines.append(f"search      {p['n_seeds']} starts, {p['n_map_evaluations']} return-map evaluations")
    if p["n_runs_cut_short"]:
        lines.append(f"horizon     {p['n_runs_cut_short']} of them ended at tau = {p['t_max']:g} "
                     "(or an event budget) before their next breakaway: a cycle slower than that "
                     "is not searched; raise --t-max")
    if p.get("n_runs_unsettled"):
        from stickslip.analysis.cycles import SEED_BREAKAWAYS

        lines.append(f"unsettled   {p['n_runs_unsettled']} of the starts' runs, still sticking after "
                     f"{SEED_BREAKAWAYS} stick phases, are on none of these cycles: they settle on "
                     "a cycle of more stick phases than --max-period, approach one slowly, or "
                     "wander (simulate from such a start says which)")
    typer.echo("\n".join(lines))


def register(app: typer.Typer) -> None:
    """Add the ``cycles`` command to ``app``."""
    app.command("cycles")(cycles)
