"""``stickslip design``: the paper's design procedure (Fig. 16) in physical units."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from stickslip.cli.console import BadInput, print_json, show_progress, warn
from stickslip.cli.machine_config import collect_inputs, load_machine_file, out_of_scale
from stickslip.cli.progress import DesignProgress
from stickslip.model._validate import friction_range
from stickslip.model.units import QUANTITIES, to_si

if TYPE_CHECKING:
    from stickslip.analysis.simulation import EngineOptions
    from stickslip.model.physical import PhysicalFriction, PhysicalSystem



#: An example value of each SI unit of :data:`QUANTITIES`, in a unit other than the SI one where
#: that shows the conversion (the help says "[kg]; units allowed, e.g. '2 kg'").
UNIT_EXAMPLES = {"kg": "2 kg", "N/m": "50 kN/m", "N s/m": "20 N*s/m", "N": "500 N", "m/s": "5 cm/s"}


def quantity_help(name: str) -> str:
    """Help text of the flag of quantity ``name``: what it is, its SI unit and an example.

    A dimensionless quantity (a friction coefficient) says so and takes a plain number.
    """
    _, unit, what = QUANTITIES[name]
    if not unit:
        return f"{what} (dimensionless number, e.g. 0.5)"
    return f"{what} [{unit}]; units allowed, e.g. '{UNIT_EXAMPLES[unit]}'"


def _opt(name: str) -> Any:
    return typer.Option(f"--{name.replace('_', '-')}", help=quantity_help(name))


def read_config(path: Path) -> dict[str, Any]:
    """The flat quantities of the machine file (``m``, ``k``, ``mu_s``, ...), as written.

    The one reader of the machine file is :func:`stickslip.io.machine_file.read_machine_file`;
    this keeps its flat part for the flags to override.
    """
    return dict(load_machine_file(path).raw)


def read_friction_config(path: Path | None) -> PhysicalFriction:
    """The ``[friction]`` table of the TOML file (docs/friction.md); Coulomb without one."""
    from stickslip.model.physical import PhysicalFriction

    if path is None:
        return PhysicalFriction()
    return load_machine_file(path).friction()


def design_machine_file(flags: dict[str, Any], config: Path, *, stick_slip: bool,
                        options: EngineOptions | None = None,
                        progress: Callable[[str, int], None] | None = None) -> Any:
    """The machine of a ``[structure]`` file designed: verdict, critical speed/load, absorbers."""
    from stickslip.analysis.machine_absorber import design_machine
    from stickslip.cli.machine_config import config_machine

    machine_file = load_machine_file(config)
    machine, reduction = config_machine(config, flags)
    absorber = machine_file.absorber()
    attach = None
    if absorber is not None and absorber.attach_dof is not None:
        attach = (absorber.attach_dof if reduction is None
                  else reduction.kept_dofs.index(absorber.attach_dof))
    report = design_machine(machine, None if absorber is None else absorber.mass, attach,
                            stick_slip=stick_slip, options=options, progress=progress)
    return report, reduction


#: Scan runs of ``design``'s list of verdict changes along the speed (a decade either side:
#: steps of 12 %, half those of the onset search).
SPEED_SCAN = 41


def speed_changes(machine: Any, options: EngineOptions, shown: bool) -> dict[str, Any]:
    """Every belt speed in ``[V / 10, 10 V]`` where the bare machine's start-up verdict changes.

    The search of ``boundary --config`` (:func:`~stickslip.analysis.contact.boundary.contact_boundary`
    on the exact engine): :data:`SPEED_SCAN` log-spaced runs, each change bisected to 0.1 %, on
    the default worker processes. Returns its JSON form.
    """
    from stickslip.analysis.contact.boundary import contact_boundary
    from stickslip.cli.progress import ProgressBar

    with ProgressBar(shown, "verdict along the speed", "runs") as bar:
        found = contact_boundary(machine, "speed", machine.speed / 10.0, machine.speed * 10.0,
                                 n_scan=SPEED_SCAN, rtol=1e-3, t_max=options.t_max,
                                 max_events=options.max_events, progress=bar)
    return found.to_dict()


def speed_changes_text(p: dict[str, Any]) -> str:
    """The lines of :func:`speed_changes` in the design report."""
    lo, hi = p["range_SI"]
    head = (f"start-up verdict along the speed, bare machine, {lo:.4g} to {hi:.4g} m/s "
            f"({p['n_scan']} scan runs, each change bisected to {p['rtol'] * 100:g} %):")
    if not p["crossings"]:
        verdicts = " / ".join(sorted({s["verdict"] for s in p["scan"]}))
        return f"{head} {verdicts} at every scan run (no change wider than a scan step)"
    lines = [head]
    for c in p["crossings"]:
        a, b = c["bracket"]
        where = (f"at {c['value_SI']:.4g} m/s" if c["kind"] == "boundary"
                 else f"between {a:.4g} and {b:.4g} m/s (undetermined: not a boundary)")
        lines.append(f"  {c['below']} below, {c['above']} above, {where}")
    return "\n".join(lines)


def design(
    m: Annotated[str | None, _opt("m")] = None,
    k: Annotated[str | None, _opt("k")] = None,
    c: Annotated[str | None, _opt("c")] = None,
    mu_s: Annotated[str | None, _opt("mu_s")] = None,
    mu_k: Annotated[str | None, _opt("mu_k")] = None,
    load: Annotated[str | None, _opt("load")] = None,
    speed: Annotated[str | None, _opt("speed")] = None,
    m_a: Annotated[str | None, _opt("m_a")] = None,
    k_a: Annotated[str | None, _opt("k_a")] = None,
    c_a: Annotated[str | None, _opt("c_a")] = None,
    config: Annotated[
        Path | None, typer.Option("--config", help="machine TOML file: the same keys (m, k, ..., flat or "
                                           "in a [system] table) or a [structure] table; optional "
                                           "[friction] and [absorber] tables; a flag given too "
                                           "replaces the file's value of its key (with a warning)")
    ] = None,
    stick_slip_optimum: Annotated[
        bool,
        typer.Option("--stick-slip-optimum/--no-stick-slip-optimum",
                     help="also find the foundation best against stick-slip (seconds on 1-2 "
                          "DOF, minutes on a [structure] machine)"),
    ] = True,
    max_foundation_deflection: Annotated[
        str | None,
        typer.Option("--max-foundation-deflection",
                     help="largest static deflection of the foundation under the kinetic friction "
                          "force mu_k W [m], e.g. '2 mm': bounds the stability-optimal foundation, "
                          "reported for a speed-dependent friction law (default 4 mu_k W / k)"),
    ] = None,
    t_max: Annotated[
        float | None,
        typer.Option("--t-max", help="dimensionless time horizon omega_n t of each simulation "
                                     "(default 5000): raise it when a verdict is undetermined"),
    ] = None,
    speed_scan: Annotated[
        bool,
        typer.Option("--speed-scan/--no-speed-scan",
                     help="a [structure] machine: also list every belt speed where the bare "
                          f"machine's start-up verdict changes, a decade either side of its speed "
                          f"({SPEED_SCAN} scan runs, each change bisected to 0.1 %)"),
    ] = True,
    json: Annotated[bool, typer.Option("--json", help="print one JSON object and nothing else")] = False,
) -> None:
    """Will it stick-slip, at which speed or load, and which foundation stops it (Fig. 16).

    Example: stickslip design --m "2 kg" --k "50 kN/m" --c "20 N*s/m" --mu-s 0.5 --mu-k 0.3
    --load "500 N" --speed "5 cm/s"

    Without --c (or c in the file) the slider is undamped, c = 0, and the report says so.

    The same keys, and a friction table, from a TOML file: stickslip design --config machine.toml

    Any linear structure: a [structure] table in the file (matrices from .mtx/.npy/.csv or
    modes, contact_dof), and an [absorber] table (mass, attach_dof) for the absorber that
    fixes it (docs/structures.md).
    """
    from stickslip.analysis.design import design_foundation

    options = _engine_options(t_max)
    flags = {"m": m, "k": k, "c": c, "mu_s": mu_s, "mu_k": mu_k, "load": load, "speed": speed,
             "m_a": m_a, "k_a": k_a, "c_a": c_a}
    given = [f"--{name.replace('_', '-')}" for name, value in flags.items() if value is not None]
    given += [flag for flag, value in (("--t-max", t_max), ("--max-foundation-deflection",
                                                            max_foundation_deflection))
              if value is not None]
    if config is not None and load_machine_file(config, normal_coupling=True).has_contact:
        from stickslip.cli.contact.design_command import contact_design_command

        contact_design_command(config, load_machine_file(config, normal_coupling=True), given,
                               json=json)
        return
    if config is not None and load_machine_file(config).has_memory_law:
        memory_design_command(config, given, json=json)
        return
    if config is not None and _has_structure(config):
        with DesignProgress(show_progress()) as bar:
            machine_report, reduction = design_machine_file(flags, config, stick_slip=stick_slip_optimum,
                                                            options=options, progress=bar)
        machine_payload = machine_report.to_dict()
        machine_payload["reduction"] = None if reduction is None else reduction.summary()
        if speed_scan:
            machine_payload["speed_scan"] = speed_changes(machine_report.machine, options,
                                                          show_progress())
        if json:
            print_json(machine_payload)
            return
        if reduction is not None:
            typer.echo(reduction.summary())
        typer.echo(machine_report.summary())
        if speed_scan:
            typer.echo(speed_changes_text(machine_payload["speed_scan"]))
        return
    system = _slider_system(flags, config)
    deflection = None
    if max_foundation_deflection is not None:
        try:
            deflection = to_si("max_foundation_deflection", max_foundation_deflection)
        except ValueError as exc:
            raise BadInput(str(exc)) from None
        if not deflection > 0.0:
            raise BadInput(f"--max-foundation-deflection {max_foundation_deflection!r} must be positive")
    with DesignProgress(show_progress()) as bar:
        report = design_foundation(system, stick_slip_optimum=stick_slip_optimum,
                                   max_foundation_deflection=deflection, options=options, progress=bar)
    payload = report.to_dict()
    payload["damping_given"] = _damping_given(c, config)
    overridden = _overridden(flags, config)
    if overridden:
        payload["warnings"] = [*payload.get("warnings", []), overridden]
    for warning in payload.get("warnings", []):  # on stderr, as every command's (and in --json)
        warn(warning)
    if json:
        print_json(payload)
        return
    typer.echo(format_report(payload))


def _slider_system(flags: dict[str, Any], config: Path | None) -> PhysicalSystem:
    """The 1-DOF machine of the flags or file, its dimensionless groups in range (a lambda
    beyond it is said with the operating point, and the file, it comes from)."""
    from stickslip.model.physical import PhysicalFoundation
    from stickslip.model.physical import PhysicalSystem as System

    v = collect_inputs(flags, config)
    foundation = None
    if "m_a" in v:
        foundation = PhysicalFoundation(v["m_a"], v["k_a"], v["c_a"])
    system = System(mass=v["m"], stiffness=v["k"], damping=v["c"], mu_s=v["mu_s"], mu_k=v["mu_k"],
                    load=v["load"], speed=v["speed"], foundation=foundation,
                    friction=read_friction_config(config))
    try:
        slider = system.slider()
        friction_range(slider.lam, slider.gamma)
    except ValueError as exc:
        source = f"--config {str(config)!r}: " if config is not None else ""
        raise BadInput(source + out_of_scale(v["speed"], v["load"], exc)) from None
    return system


def memory_design_command(config: Path, given: list[str], *, json: bool) -> None:
    """``design --config`` for a friction law with memory
    (:func:`~stickslip.analysis.memory.design.memory_design`): the runs from stick and from near
    steady sliding, the linear verdict, the critical stiffness, speeds and loads."""
    from stickslip.analysis.memory.design import memory_design
    from stickslip.cli.memory.stability_commands import memory_system

    machine_file = load_machine_file(config)
    if given:
        raise BadInput(f"{machine_file.label}: {', '.join(given)} cannot be given with a friction "
                       "law with memory: change the machine file (each run has simulate's "
                       "default horizon; simulate --config --t-max runs longer)")
    system = memory_system(machine_file)
    with DesignProgress(show_progress()) as bar:
        bar("linearisation, two runs", 0)
        report = memory_design(system)
    payload = report.to_dict()
    payload.update({"config": str(config), "machine": machine_file.label})
    if json:
        print_json(payload)
        return
    typer.echo(f"machine     {config}: {system.n_dof} DOF, contact_dof "
               f"{system.contact_dof}\nverdict     {report.verdict}\n" + report.summary())


def _engine_options(t_max: float | None) -> EngineOptions:
    """The engine limits of ``--t-max`` (the defaults without it); one line on a bad value."""
    from stickslip.analysis.simulation import EngineOptions

    if t_max is None:
        return EngineOptions()
    try:
        return EngineOptions(t_max=t_max)
    except ValueError as exc:
        raise BadInput(f"--t-max {t_max!r}: {exc}") from None


def _overridden(flags: dict[str, Any], config: Path | None) -> str:
    """The warning that flags replaced values of the machine file (flags win, key by key), or ""."""
    if config is None:
        return ""
    raw = read_config(config)
    given = [key for key, value in flags.items() if value is not None]
    replaced = [key for key in given if key in raw]
    if not replaced:
        return ""
    kept = [key for key in flags if key in raw and key not in given]
    names = ", ".join(f"--{key.replace('_', '-')}" for key in replaced)
    rest = f"; {', '.join(kept)} from the file" if kept else ""
    return (f"{names} replace the values of --config {str(config)!r} (the flags win, key by "
            f"key{rest}): check that the mix is one machine")


def _damping_given(c: str | None, config: Path | None) -> bool:
    """True when the slider's damping ``c`` came from ``--c`` or the machine file."""
    return c is not None or (config is not None and "c" in read_config(config))


def _has_structure(config: Path) -> bool:
    return load_machine_file(config).has_structure


def _num(x: float | None, unit: str = "") -> str:
    """A number in 4 significant digits, with its unit; "-" for none. Never "-0"."""
    if x is None:
        return "-"
    return f"{x + 0.0:.4g}{(' ' + unit) if unit else ''}"


def _stability_word(s: dict[str, Any]) -> str:
    """``stable``, ``neutral`` (growth rate zero to round-off) or ``UNSTABLE``, as simulate says."""
    if s["stable"]:
        return "stable"
    return "neutral" if s.get("neutral") else "UNSTABLE"


def _slope_text(sigma: float) -> str:
    """The friction slope ``d mu / d v_r`` steady sliding tolerates (``sigma`` in s/m, >= -sigma)."""
    if sigma > 0.0:
        return f"a friction slope down to -{_num(sigma, 's/m')}"
    if sigma == 0.0:
        return "no friction weakening at all (slope 0 s/m: the slider is undamped)"
    return f"no weakening: it needs a friction slope of at least +{_num(-sigma, 's/m')}"


def _critical_rows(p: dict[str, Any], keys: tuple[str, ...], indent: str) -> list[str]:
    """One line per critical-value row (``lambda_c``, ``V_c``, ``W_c``) and its note beneath."""
    lines = []
    for key in keys:
        lam, speed, load = (p["critical_lambda"][key], p["critical_speed"][key],
                            p["critical_load"][key])
        lam_load = p["critical_lambda_load"][key]
        if lam == 0.0:
            values = "lambda_c=0: stick-slip at every belt speed and every normal load"
        elif lam_load is not None and lam_load != lam:
            values = (f"V_c={_num(speed, 'm/s'):>12} (lambda_c={_num(lam)})  "
                      f"W_c={_num(load, 'N'):>10} (lambda_c={_num(lam_load)})")
        else:
            values = (f"lambda_c={_num(lam):>10}  V_c={_num(speed, 'm/s'):>14}  "
                      f"W_c={_num(load, 'N'):>12}")
        lines.append(f"{indent}{key:24} {values}")
        if p["critical_note"][key]:
            lines.append(f"{indent}{'':24} ({p['critical_note'][key]})")
    return lines


def format_report(p: dict[str, Any]) -> str:
    """Plain-text table of the design report."""
    g = _num
    f = p["foundation"]
    r = p["recommended_foundation"]
    own_law = p["critical_law"]["rigid_simulation"] != p["critical_law"]["rigid_theory"]
    head = ("Coulomb theory", "Coulomb Eq. 36", "own law sim.") if own_law else (
        "theory", "exact Eq. 36", "simulation")
    lines = [
        f"dimensionless groups  lambda={g(p['lambda'])}  zeta={g(p['zeta'])}  gamma={g(p['gamma'])}"
        f"  zeta_eq={g(p['zeta_eq'])} ({p['zeta_eq_source']}"
        f"{'; the Coulomb procedure' if own_law else ''})",
    ]
    if p["system"]["c"] == 0.0:
        lines.append("slider damping c = 0 (undamped, zeta = 0)"
                     + ("" if p.get("damping_given", True) else ": no --c given (nor c in the file)"))
    lines += [
        "",
        f"{'':24}{head[0]:>16}{head[1]:>16}{head[2]:>16}",
        f"{'rigid base':24}{p['verdict']['rigid']['theory']:>16}{p['verdict']['rigid']['exact']:>16}"
        f"{p['verdict']['rigid']['simulation']:>16}",
        f"{'with foundation':24}{p['verdict']['foundation']['theory']:>16}{'':>16}"
        f"{p['verdict']['foundation']['simulation']:>16}",
        "",
    ]
    closed_forms = ("rigid_theory", "rigid_exact", "foundation_theory")
    simulated = ("rigid_simulation", "foundation_simulation")
    if own_law:
        lines += [
            f"stick-slip below the critical belt speed V_c (at the load W={g(p['system']['load'], 'N')}) "
            f"/ above the critical normal load W_c (at the speed V={g(p['system']['speed'], 'm/s')}):",
            "  the paper's procedure, for its Coulomb law (mu = mu_k while sliding), closed forms:",
            *_critical_rows(p, closed_forms, "    "),
            f"  the machine's friction law ({p['critical_law']['rigid_simulation']}), exact boundary "
            "search by simulation (the law moves with V and W: one search along each):",
            *_critical_rows(p, simulated, "    "),
        ]
    else:
        lines += ["stick-slip below the critical belt speed / above the critical normal load:",
                  *_critical_rows(p, ("rigid_theory", "rigid_exact", "rigid_simulation",
                                      "foundation_theory", "foundation_simulation"), "  ")]
    recommended = (f"m_a={g(r['m_a'], 'kg')}, k_a={g(r['k_a'], 'N/m')}, c_a={g(r['c_a'], 'N s/m')}")
    dimensionless = f"(M={g(f['M'])}, K={g(f['K'])}, zeta_a={g(f['zeta_a'])})"
    lines.append("")
    if f["source"].startswith("recommended"):
        procedure = "the paper's Coulomb procedure, Fig. 16" if own_law else "Fig. 16 procedure"
        lines.append(f"foundation assessed: the recommended one ({procedure}, Eqs. 28-30): "
                     f"{recommended}  {dimensionless}")
    else:
        assessed = f"m_a={g(f['m_a'], 'kg')}, k_a={g(f['k_a'], 'N/m')}, c_a={g(f['c_a'], 'N s/m')}"
        if assessed == recommended:  # one line, not the same foundation twice
            lines.append(f"foundation assessed ({f['source']}), the recommended one (Eqs. 28-30) "
                         f"to the digits shown: {assessed}  {dimensionless}")
        else:
            lines += [f"foundation assessed ({f['source']}): {assessed}  {dimensionless}",
                      f"recommended foundation (Eqs. 28-30): {recommended}"]
    best = p.get("stick_slip_optimal_foundation")
    if best:
        onset = (f">= {best['lambda_crit_at_least']:g} (none found: V_c <= "
                 f"{g(best['critical_speed_at_most'], 'm/s')}, W_c >= "
                 f"{g(best['critical_load_at_least'], 'N')})" if best["lambda_crit"] is None
                 else f"{best['lambda_crit']:.4g}, V_c={g(best['critical_speed'], 'm/s')}, "
                 f"W_c={g(best['critical_load'], 'N')}")
        lines.append(
            f"stick-slip-optimal foundation{' (Coulomb law)' if own_law else ''}: "
            f"m_a={g(best['m_a'], 'kg')}, k_a={g(best['k_a'], 'N/m')}, "
            f"c_a={g(best['c_a'], 'N s/m')}; stick-slip onset lambda_c {onset}"
        )
        if best.get("assumption"):
            lines.append(f"  ({best['assumption']})")
        if best.get("own_law"):
            o = best["own_law"]
            note = f" ({o['note']})" if o["note"] else ""
            lines.append(f"  with the machine's friction law: V_c={g(o['speed'], 'm/s')}, "
                         f"W_c={g(o['load'], 'N')}{note}")
    stable_best = p.get("stability_optimal_foundation")
    if stable_best:
        lines.append(
            f"stability-optimal foundation: m_a={g(stable_best['m_a'], 'kg')}, "
            f"k_a={g(stable_best['k_a'], 'N/m')}, c_a={g(stable_best['c_a'], 'N s/m')}; tolerates "
            f"{_slope_text(stable_best['sigma_crit'])} "
            f"(delta_crit={g(stable_best['delta_crit'])}); static deflection under mu_k W "
            f"{g(stable_best['foundation_deflection'], 'm')} "
            f"(bound {g(stable_best['max_foundation_deflection'], 'm')})"
        )
        if stable_best["delta_crit_as_printed"] < stable_best["delta_crit"] * (1.0 - 1e-6):
            lines.append(
                "  note: the optimum sits on the edge of a window of instability: built from the "
                f"values above, it tolerates only {_slope_text(stable_best['sigma_crit_as_printed'])} "
                f"(delta_crit={g(stable_best['delta_crit_as_printed'])}); --json gives it to full "
                "precision")
        weakening = (p.get("stability") or {}).get("rigid", {}).get("delta_local")
        if weakening is not None and weakening >= stable_best["delta_crit"]:
            lines.append(
                f"  note: the friction law's own weakening at V (delta={g(weakening)}) is beyond "
                "what it tolerates: this foundation does not keep steady sliding linearly stable "
                "at this operating point")
    stab = p.get("stability")
    if stab:
        lines += ["", f"steady sliding with the friction law ({p['friction']}):"]
        for name in ("rigid", "foundation"):
            s = stab[name]
            lines.append(
                f"  {('rigid base' if name == 'rigid' else 'with foundation'):22}"
                f"{_stability_word(s):>9}  growth rate {g(s['growth_rate'], '1/s')}"
                f"{' (zero to round-off: marginally stable)' if s.get('neutral') else ''}; "
                f"tolerates {_slope_text(s['sigma_crit'])} "
                f"(delta_crit={g(s['delta_crit'])}, law's delta={g(s['delta_local'])}, "
                f"margin {g(s['margin'])})"
            )
            lines.append(f"  {'':22}{'':>9}  {s['safe_disturbance']['sentence']}")
            lines.append(f"  {'':22}{'':>9}  {s['boundaries']['sentence']}")
        lines.append("  (linear stability is local: the simulation rows' V_c and W_c are where a "
                     "start from rest stops sticking; between the two, steady sliding is stable "
                     "yet a start from rest ends in stick-slip)")
    return "\n".join(lines)


def register(app: typer.Typer) -> None:
    """Add the ``design`` command to ``app``."""
    app.command("design")(design)
