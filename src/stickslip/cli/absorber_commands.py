"""``stickslip frf`` and ``stickslip tune``: the foundation as a vibration absorber.

Thin commands over :mod:`stickslip.analysis.absorber_tuning` (paper Figs. 3-6 and 10,
Eqs. 28-33).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import (
    BadInput,
    check_figure_path,
    parse_dva,
    print_json,
    save_plot,
    typed_options,
    warn_fitted_range,
)
from stickslip.cli.options import JSON, OVERWRITE

ZETA = Annotated[float, typer.Option("--zeta", help="damping ratio c / (2 sqrt(m k)) >= 0")]


def _zeta(value: float) -> float:
    from stickslip.model._validate import non_negative

    try:
        return non_negative("--zeta", value)
    except ValueError as exc:
        raise BadInput(str(exc)) from None


def _fmt(x: object) -> str:
    if x is None:
        return "-"
    if isinstance(x, float) and math.isinf(x):
        return "unbounded (undamped resonance)"  # |H| of an undamped mode at its frequency
    return f"{x:.6g}" if isinstance(x, float) else str(x)


def frf(
    zeta: ZETA,
    dva: Annotated[
        str,
        typer.Option(
            "--dva",
            help="foundation: none (rigid base), optimal (fitted Eqs. 28-30), optimal-exact, "
            "or M,K,ZETA_A",
        ),
    ] = "optimal",
    k_scale: Annotated[
        float, typer.Option("--k-scale", help="multiply the foundation's K (Figs. 11-15)")
    ] = 1.0,
    plot: Annotated[
        Path | None,
        typer.Option("--plot", help="write the response curves (paper Fig. 5) to this file"),
    ] = None,
    overwrite: OVERWRITE = False,
    json: JSON = False,
) -> None:
    """Frequency response H = k|X|/f of the slider under a harmonic force and its exact peak.

    Example: stickslip frf --zeta 0.1 --dva optimal-exact --plot frf.png
    """
    from stickslip.analysis.frequency_response import response_curves, response_peak
    from stickslip.model import rigid_base

    zeta = _zeta(zeta)
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    foundation = parse_dva(dva, zeta, k_scale)
    warn_fitted_range(dva, [zeta])
    curves = response_curves(zeta, foundation)
    peak = curves.peak
    rigid = response_peak(rigid_base(zeta))
    payload: dict[str, Any] = {
        "zeta": zeta,
        "dva": dva,
        "k_scale": k_scale,
        "foundation": None
        if foundation is None
        else {
            "M": foundation.mass_ratio,
            "K": foundation.stiffness_ratio,
            "zeta_a": foundation.damping_ratio,
        },
        **peak.to_dict(),
        "rigid_base": {"H_max": rigid.h_max, "Omega_peak": rigid.omega_peak},
    }
    if plot is not None:
        payload["plot"] = save_plot(lambda ax: curves.plot(ax=ax), plot, (6.5, 4.2))
    if json:
        print_json(payload)
        return
    lines = []
    if foundation is None:
        lines.append(f"system      rigid base (zeta={_fmt(zeta)})")
    else:
        lines.append(
            f"system      elastic foundation M={_fmt(foundation.mass_ratio)}, "
            f"K={_fmt(foundation.stiffness_ratio)}, zeta_a={_fmt(foundation.damping_ratio)} "
            f"(zeta={_fmt(zeta)})"
        )
    lines += [
        f"H_max       {_fmt(peak.h_max)} at Omega = {_fmt(peak.omega_peak)}",
        f"zeta_eq     {_fmt(peak.equivalent_damping)}  (Eq. 32: 1 / (2 H_max))",
        "peaks       " + ", ".join(f"H={_fmt(h)} at {_fmt(w)}" for w, h in peak.local_maxima),
        f"rigid base  H_max {_fmt(rigid.h_max)} at Omega = {_fmt(rigid.omega_peak)}",
    ]
    if plot is not None:
        lines.append(f"figure      {plot}")
    typer.echo("\n".join(lines))


def tune(
    ctx: typer.Context,
    zeta: Annotated[float | None, typer.Option(
        "--zeta", help="damping ratio c / (2 sqrt(m k)) >= 0 (required without --config)")] = None,
    config: Annotated[Path | None, typer.Option(
        "--config", help="machine.toml with a [structure] and an [absorber] (mass, attach_dof): "
        "tune that absorber on your machine (objective absorber: H-infinity at the contact; "
        "stick-slip: also the absorber that maximises the critical speed); not with --zeta, "
        "--mass-ratio, --gamma, --lam-max")] = None,
    mass_ratio: Annotated[
        float | None,
        typer.Option("--mass-ratio", help="fix M = m_a/m and optimise only K and zeta_a"),
    ] = None,
    objective: Annotated[
        str,
        typer.Option("--objective", help="absorber (minimum H_max, the paper's criterion), "
                     "stick-slip (maximum simulated stick-slip onset) or stability (maximum "
                     "friction weakening delta with stable steady sliding)"),
    ] = "absorber",
    gamma: Annotated[float, typer.Option("--gamma", help="mu_k/(mu_s - mu_k), stick-slip objective")] = 2.0,
    lam_max: Annotated[
        float, typer.Option("--lam-max", help="stick-slip objective: onsets above count as none")
    ] = 100.0,
    json: JSON = False,
) -> None:
    """Optimal foundation for a given zeta: exact numerical optimum next to Eqs. (28)-(31).

    With --objective stick-slip the foundation maximises the simulated stick-slip onset
    instead, with M bounded by the absorber optimum's M_opt (Eq. 28) unless --mass-ratio
    sets the bound. With --objective stability it maximises the largest friction weakening
    delta for which steady sliding stays linearly stable (same bound).

    Example: stickslip tune --zeta 0.1 --objective stability --json

    Your machine (docs/structures.md): stickslip tune --config machine.toml --objective stick-slip
    """
    from stickslip.analysis.absorber_tuning import tune_foundation
    from stickslip.analysis.theory import MAX_TUNING_ZETA
    from stickslip.model._validate import at_most, non_negative, ratio

    if config is not None:
        _tune_machine(ctx, config, objective, json)
        return
    if zeta is None:
        raise BadInput("give --zeta (the dimensionless slider), or --config machine.toml with an "
                       "[absorber] table")
    zeta = _zeta(zeta)
    if zeta > MAX_TUNING_ZETA:
        raise BadInput(f"--zeta {zeta!r} is above {MAX_TUNING_ZETA}: no tuning is defined there")
    try:
        if mass_ratio is not None:
            mass_ratio = ratio("--mass-ratio", mass_ratio)
        # checked whatever the objective: a value given is never silently ignored
        gamma = at_most("--gamma", non_negative("--gamma", gamma))
        lam_max = ratio("--lam-max", lam_max)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    if objective not in ("absorber", "stick-slip", "stability"):
        raise BadInput(f"--objective {objective!r} must be 'absorber', 'stick-slip' or 'stability'")
    idle = typed_options(ctx, ("gamma", "lam_max")) if objective != "stick-slip" else []
    if idle:
        verb, pronoun = ("set", "them") if len(idle) > 1 else ("sets", "it")
        raise BadInput(f"{' and '.join(idle)} {verb} the stick-slip objective; --objective "
                       f"{objective} does not use {pronoun}")
    warn_fitted_range("optimal", [zeta])  # every objective is compared with Eqs. (28)-(31)
    if objective == "stick-slip":
        _tune_stick_slip(zeta, gamma, mass_ratio, lam_max, json)
        return
    if objective == "stability":
        _tune_stability(zeta, mass_ratio, json)
        return
    result = tune_foundation(zeta, mass_ratio=mass_ratio)
    payload = result.to_dict()
    if json:
        print_json(payload)
        return
    fit, rel = payload["fitted"], payload["relative_difference"]
    rows = [
        ("M", payload["M"], fit["M"], rel["M"], "Eq. (28)"),
        ("K", payload["K"], fit["K"], rel["K"], "Eq. (29)"),
        ("zeta_a", payload["zeta_a"], fit["zeta_a"], rel["zeta_a"], "Eq. (30)"),
        ("H_max", payload["H_max"], fit["H_max"], rel["H_max"], "Eq. (31)"),
        ("zeta_eq", payload["zeta_eq"], fit["zeta_eq"], rel["zeta_eq"], "Eq. (33)"),
    ]
    mode = "M fixed" if result.mass_ratio_fixed else "M, K, zeta_a free"
    lines = [
        f"optimal foundation for zeta = {_fmt(zeta)} ({mode})",
        f"{'':8s} {'exact':>12s} {'paper fit':>12s} {'fit/exact-1':>12s}",
    ]
    for name, exact, fitted, diff, eq in rows:
        lines.append(f"{name:8s} {exact:12.6g} {fitted:12.6g} {diff:+12.2%}  {eq}")
    lines.append(
        f"H_max at the fitted parameters (exact FRF): {_fmt(fit['H_max_exact_at_fitted'])}"
    )
    if any(result.at_bound):
        lines.append("note: the optimum lies on a search bound (see DEFAULT_MASS_BOUNDS)")
    typer.echo("\n".join(lines))


def _tune_machine(ctx: typer.Context, config: Path, objective: str, json: bool) -> None:
    """``tune --config``: the absorber of the file's ``[absorber]`` tuned on its ``[structure]``.

    ``absorber``: the H-infinity optimum (minimum peak receptance at the contact, the paper's
    criterion generalised, :func:`stickslip.analysis.machine_absorber.tune_machine_absorber`);
    ``stick-slip``: that and the absorber that maximises the critical speed. Each is reported
    with the critical speed and load it gives, next to those of the bare machine.
    """
    from stickslip.analysis.machine_absorber import (
        ONSET_NOTE,
        CriticalPoint,
        tune_machine_absorber,
    )
    from stickslip.cli.machine_config import config_machine, load_machine_file, refuse_mix

    refuse_mix(ctx, config, ("zeta", "mass_ratio", "gamma", "lam_max"))
    if objective not in ("absorber", "stick-slip"):
        raise BadInput(f"--objective {objective!r} with --config must be 'absorber' or 'stick-slip' "
                       "(the stability objective is for the dimensionless slider)")
    machine_file = load_machine_file(config)
    try:
        absorber = machine_file.absorber()
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    if absorber is None:
        raise BadInput(f"{machine_file.label} has no [absorber] table (mass = \"3 kg\", attach_dof "
                       "= N): tune --config tunes that absorber on the file's [structure]")
    machine, reduction = config_machine(config)
    attach = absorber.attach_dof
    if attach is not None and reduction is not None:
        attach = reduction.kept_dofs.index(attach)
    designs = tune_machine_absorber(machine, absorber.mass, attach,
                                    stick_slip=objective == "stick-slip")
    bare = CriticalPoint.of(machine)
    payload = {"config": str(config), "objective": objective, "machine": machine.to_dict(),
               "critical": bare.to_dict(), "absorbers": [d.to_dict() for d in designs],
               "reduction": None if reduction is None else reduction.summary()}
    if json:
        print_json(payload)
        return
    lines = [machine.summary(),
             f"without absorber: {bare.describe()}"]
    for d in designs:
        lines.append(f"absorber ({d.objective}): m_a={d.mass:.4g} kg, k_a={d.stiffness:.4g} N/m, "
                     f"c_a={d.damping:.4g} N s/m -> {d.critical.describe()}, "
                     f"peak receptance {d.peak_receptance:.4g} m/N")
    if machine.n_dof > 1:
        lines.append(f"note: {ONSET_NOTE}")
    typer.echo("\n".join(lines))


def _mass_bounds(zeta: float, mass_ratio: float | None) -> tuple[float, float]:
    """``(M / 20, M)`` with ``M`` given by ``--mass-ratio`` or Eq. (28): no more mass than the absorber."""
    from stickslip.analysis.theory import optimal_mass_ratio_fit

    top = optimal_mass_ratio_fit(zeta) if mass_ratio is None else mass_ratio
    return top / 20.0, top


def _tune_stability(zeta: float, mass_ratio: float | None, json: bool) -> None:
    from stickslip.analysis.stability_tuning import optimal_foundation_stability

    bounds = _mass_bounds(zeta, mass_ratio)
    tuning = optimal_foundation_stability(zeta, mass_ratio_bounds=bounds)
    payload = tuning.to_dict()
    printed, printed_delta = tuning.rounded(4)
    payload["delta_crit_as_printed"] = printed_delta  # of M, K, zeta_a to 4 significant digits
    if json:
        print_json(payload)
        return
    ref = payload["absorber_optimum"]
    typer.echo("\n".join([
        f"stability-optimal foundation for zeta = {_fmt(zeta)} (M in [{bounds[0]:.4g}, {bounds[1]:.4g}], "
        f"K in [{payload['stiffness_ratio_bounds'][0]:.4g}, {payload['stiffness_ratio_bounds'][1]:.4g}])",
        f"{'':22s} {'M':>9s} {'K':>9s} {'zeta_a':>9s}  critical weakening delta_crit",
        f"{'stability optimum':22s} {payload['M']:9.4g} {payload['K']:9.4g} "
        f"{payload['zeta_a']:9.4g}  {payload['delta_crit']:.6g}",
        f"{'absorber optimum':22s} {ref['M']:9.4g} {ref['K']:9.4g} {ref['zeta_a']:9.4g}  "
        f"{ref['delta_crit']:.6g}  (Eqs. 28-30)",
        f"{'rigid base':22s} {'':9s} {'':9s} {'':9s}  {payload['rigid_base_delta_crit']:.6g}  (= zeta)",
        "steady sliding is linearly stable for every friction law whose weakening at the belt "
        "speed, delta = -(dF/du)/2, is below delta_crit",
        *([f"note: K lies on its lower bound: the foundation's static deflection under the kinetic "
           f"friction force is {payload['foundation_deflection_ratio']:.4g} times the slider spring's "
           "(the largest allowed); softer foundations stabilise further but drift further"]
          if payload["K"] <= payload["stiffness_ratio_bounds"][0] * (1 + 1e-9) else []),
        *([f"note: the optimum sits on the edge of a window of instability: the foundation as "
           f"printed, ({printed.mass_ratio:.4g}, {printed.stiffness_ratio:.4g}, "
           f"{printed.damping_ratio:.4g}), is stable only below delta = {printed_delta:.6g} "
           "(--json gives the optimum to full precision; stickslip.analysis.stability.stability_intervals "
           "lists the windows)"]
          if printed_delta < payload["delta_crit"] * (1 - 1e-6) else []),
    ]))


def _tune_stick_slip(zeta: float, gamma: float, mass_ratio: float | None, lam_max: float,
                     json: bool) -> None:
    from stickslip.analysis.stick_slip_tuning import optimal_foundation_stick_slip

    bounds = _mass_bounds(zeta, mass_ratio)
    result = optimal_foundation_stick_slip(zeta, gamma, mass_ratio_bounds=bounds, lam_max=lam_max)
    payload = result.to_dict()
    if json:
        print_json(payload)
        return
    ref = payload["absorber_optimum"]

    def onset(value: float | None) -> str:
        return f">= {lam_max:g} (none found)" if value is None else f"{value:.6g}"

    typer.echo("\n".join([
        f"stick-slip-optimal foundation for zeta = {_fmt(zeta)}, gamma = {_fmt(gamma)} "
        f"(M in [{bounds[0]:.4g}, {bounds[1]:.4g}])",
        f"{'':22s} {'M':>9s} {'K':>9s} {'zeta_a':>9s}  stick-slip onset lambda_c",
        f"{'stick-slip optimum':22s} {payload['M']:9.4g} {payload['K']:9.4g} "
        f"{payload['zeta_a']:9.4g}  {onset(payload['lambda_crit'])}",
        f"{'absorber optimum':22s} {ref['M']:9.4g} {ref['K']:9.4g} {ref['zeta_a']:9.4g}  "
        f"{onset(ref['lambda_crit'])}  (Eqs. 28-30)",
    ]))


def register(app: typer.Typer) -> None:
    """Add the ``frf`` and ``tune`` commands to ``app``."""
    app.command("frf")(frf)
    app.command("tune")(tune)
