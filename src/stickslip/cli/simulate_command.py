"""``stickslip simulate``: one run, certified verdict, optional JSON and figure."""

from __future__ import annotations

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
    warn_fitted_range,
)
from stickslip.cli.options import DVA, FRICTION, GAMMA, JSON, K_SCALE, OVERWRITE

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
T_MAX = Annotated[float, typer.Option("--t-max", help="dimensionless time horizon")]


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
    t_max: T_MAX = 5000.0,
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
    json: JSON = False,
) -> None:
    """One simulation: certified verdict, period, amplitude, events.

    Example: stickslip simulate --lam 3 --zeta 0.1 --dva optimal --friction linear:0.05 --json

    Your machine in SI (docs/structures.md): stickslip simulate --config machine.toml --json
    gives period_s, amplitude_m (half the peak-to-peak displacement of the contact DOF) next to
    the dimensionless period, amplitude, lambda, zeta and gamma; --t-max and --initial stay
    dimensionless (tau = omega_n t, displacements in V / omega_n of the contact DOF).
    """
    from stickslip.analysis.simulation import EngineOptions
    from stickslip.analysis.simulation import simulate as run_simulation
    from stickslip.cli.machine_config import configured_machine, refuse_mix, require_dimensionless
    from stickslip.model import Slider, chain_structure

    refuse_mix(ctx, config)
    foundation = None
    run = None
    if config is not None:
        run = configured_machine(config)
        structure, slider = run.structure, run.slider
        check_run_limits(slider.lam, slider.gamma, max_events=max_events, plot_from=t_plot_start)
    else:
        require_dimensionless(lam=lam, zeta=zeta)
        assert lam is not None and zeta is not None
        slider = Slider(lam, gamma=gamma, friction=parse_friction_option(friction))
        check_run_limits(slider.lam, slider.gamma, max_events=max_events, plot_from=t_plot_start)
        foundation = parse_dva(dva, zeta, k_scale)
        structure = chain_structure(zeta, () if foundation is None else (foundation,))
    init = parse_initial(initial, structure.n_dof)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    if config is None:
        warn_fitted_range(dva, [zeta])
    result = run_simulation(structure, slider, initial=init,
                            options=EngineOptions(t_max=t_max, max_events=max_events))
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
        payload["plot"] = str(result.plot(t_start=t_plot_start).savefig(plot))
    if json:
        print_json(payload)
        return
    _print_summary(payload)


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
        lines.insert(1, f"machine     {p['config']}: {p['machine']['n_dof']} DOF, contact on DOF "
                        f"{p['machine']['contact_dof']}; period {fmt(p['period_s'])} s, amplitude "
                        f"{fmt(p['amplitude_m'])} m")
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
