"""The stickslip web app: the design procedure of the paper's Fig. 16 in a browser.

Run it with ``stickslip app`` (or ``streamlit run`` on this file). Inputs are text with
units ("2 kg", "50 kN/m"), parsed by :mod:`stickslip.model.inputs` as the command line's; everything
after that is SI floats and dimensionless groups. Every number shown comes from the public
Python API (:func:`~stickslip.analysis.design.design_foundation`, :func:`~stickslip.simulate`,
:func:`~stickslip.sweep.occurrence_map`,
:func:`~stickslip.analysis.stick_slip_tuning.optimal_foundation_stick_slip`,
:func:`~stickslip.analysis.continuation.continue_cycles`); this script
only lays out inputs and results. Invalid input shows one line per problem and nothing is
computed.

The friction law while sliding (issue 10, point 5) is chosen in the sidebar: ``coulomb`` (the
paper's), ``linear`` (slope in s/m), ``stribeck`` or ``table`` (an uploaded CSV with columns
``v`` [m/s] and ``mu``); its fields are the keys of the ``[friction]`` table of the TOML used by
``stickslip design`` (:class:`~stickslip.model.physical.PhysicalFriction`, units parsed by
``to_si``). The design report's stability section is shown as a table. The laws with memory
(``rate-state``, ``lugre``) show what ``stickslip design --config`` gives for them instead
(:mod:`stickslip.app.memory_page`).

This module is the page only; the inputs (:mod:`stickslip.app.inputs`), the cached
computations (:mod:`stickslip.app.computations`), the figures (:mod:`stickslip.app.figures`)
and the downloads (:mod:`stickslip.app.exports`) have modules of their own.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import partial
from typing import Any

import pandas as pd
import streamlit as st

from stickslip.analysis.design import coulomb_tuning_note
from stickslip.app.computations import (
    BASIN_SAMPLES,
    BASIN_V,
    BASIN_XI,
    basin_runs,
    bifurcation_diagrams,
    bifurcation_range,
    design_report,
    lambda_axis,
    operating_point_runs,
    stick_slip_optimum,
)
from stickslip.app.exports import bifurcation_csv, bifurcation_netcdf, history_csv, report_json
from stickslip.app.figures import (
    bifurcation_events_table,
    bifurcation_figure,
    cached_png,
    fmt,
    occurrence_map_charts,
    run_charts,
)
from stickslip.app.inputs import (
    DEFAULTS,
    FOUNDATION_INPUTS,
    FRICTION_FIELDS,
    FRICTION_INPUTS,
    FRICTION_LAWS,
    FRICTION_TABLE,
    FRICTION_TABLE_NAME,
    SYSTEM_INPUTS,
    FoundationKey,
    parse_inputs,
    si_key,
    system_from_key,
)
from stickslip.app.memory_inputs import MEMORY_FIELDS, MEMORY_INPUTS, MEMORY_LAWS
from stickslip.app.messages import show_error, show_warning
from stickslip.io.provenance import package_version
from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.model.parameters import Foundation
from stickslip.model.physical import PhysicalSystem, foundation_to_physical
from stickslip.model.units import FRICTION_QUANTITIES, QUANTITIES

#: Names of the app's modules kept reachable from the script (tests and users import them here).
__all__ = [
    "BASIN_SAMPLES",
    "BASIN_V",
    "BASIN_XI",
    "DEFAULTS",
    "FRICTION_INPUTS",
    "design_report",
    "history_csv",
    "main",
    "operating_point_runs",
    "parse_inputs",
    "report_json",
    "si_key",
    "system_from_key",
]

_fmt = fmt  # the page's short name
#: The app's pages, in the sidebar.
PAGES = ("paper's slider", "your machine (matrices or modes)", "identify from a record",
         "frequency response and absorber tuning")


def _input_widgets() -> dict[str, str]:
    side = st.sidebar
    side.header("Sliding system")
    side.caption("Values with units, e.g. '2 kg', '50 kN/m', '0.5 m/s'; a bare number is SI.")
    raw = {}
    for key, (label, default) in SYSTEM_INPUTS.items():
        _, unit, what = QUANTITIES[key]
        raw[key] = side.text_input(label, value=default, key=key,
                                   help=f"{what}" + (f" [{unit}]" if unit else " (dimensionless)"))
    side.header("Existing foundation (optional)")
    side.caption("Leave empty to have the foundation of Eqs. (28)-(30) recommended and assessed.")
    for key, (label, default) in FOUNDATION_INPUTS.items():
        _, unit, what = QUANTITIES[key]
        raw[key] = side.text_input(label, value=default, key=key, help=f"{what} [{unit}]")
    side.header("Friction law while sliding")
    side.caption("coulomb: μ = μk (the paper's); linear: μ = μk − σ v_r; stribeck: falls from "
                 "μ0 to μk around v_s; table: a measured curve μ(v). The [friction] table of "
                 "'stickslip design'.")
    law = side.selectbox("Friction law", (*FRICTION_LAWS, *MEMORY_LAWS), key="friction_law")
    raw["friction_law"] = str(law)
    if law in MEMORY_LAWS:
        side.caption("A law with memory carries its own friction coefficients: the μs and μk "
                     "fields above are not used. The [friction] table of a machine file.")
        for key in MEMORY_FIELDS[str(law)]:
            label, default = MEMORY_INPUTS[key]
            raw[key] = side.text_input(label, value=default, key=key)
        return raw
    for key in FRICTION_FIELDS[str(law)]:
        label, default = FRICTION_INPUTS[key]
        _, unit, what = FRICTION_QUANTITIES[key]
        raw[key] = side.text_input(label, value=default, key=key,
                                   help=what + (f" [{unit}]" if unit else " (dimensionless)"))
    if law == "table":
        uploaded = side.file_uploader("Measured friction curve (CSV: columns v [m/s], mu)",
                                      type=["csv"], key=FRICTION_TABLE)
        if uploaded is not None:
            raw[FRICTION_TABLE] = uploaded.getvalue().decode("utf-8", errors="replace")
            raw[FRICTION_TABLE_NAME] = str(uploaded.name)
    return raw


def _table(index: list[str], columns: dict[str, list[str]]) -> None:
    st.table(pd.DataFrame(columns, index=index))


def _show_verdicts(report: Mapping[str, Any]) -> None:
    v = report["verdict"]
    col1, col2 = st.columns(2)
    col1.metric("Verdict on the rigid base", v["rigid"]["simulation"],
                help="certified simulation from the startup state")
    col2.metric("Verdict with foundation", v["foundation"]["simulation"],
                help="certified simulation from the startup state")
    _table(["rigid base", "with foundation"], {
        "theory": [v["rigid"]["theory"], v["foundation"]["theory"]],
        "exact (Eq. 36)": [v["rigid"]["exact"], "—"],
        "simulation": [v["rigid"]["simulation"], v["foundation"]["simulation"]],
    })


def _show_critical(report: Mapping[str, Any], system: PhysicalSystem) -> None:
    st.subheader("Critical belt speed and normal load")
    rows = {
        "rigid_theory": "rigid base, theory (Eq. 39)",
        "rigid_exact": "rigid base, exact (Eq. 36)",
        "rigid_simulation": "rigid base, simulation",
        "foundation_theory": "with foundation, theory (Eq. 37 with ζ_eq)",
        "foundation_simulation": "with foundation, simulation",
    }
    columns = {
        "critical λ": [_fmt(report["critical_lambda"][k]) for k in rows],
        "critical speed V_c [m/s]": [_fmt(report["critical_speed"][k]) for k in rows],
        "critical load W_c [N]": [_fmt(report["critical_load"][k]) for k in rows],
    }
    laws = report.get("critical_law") or {}
    if any(laws.get(k) != laws.get("rigid_theory") for k in rows):  # not the paper's law alone
        columns["friction law"] = [str(laws.get(k, "")) for k in rows]
    _table(list(rows.values()), columns)
    speed = report["critical_speed"]["foundation_simulation"]
    load = report["critical_load"]["foundation_simulation"]
    st.markdown(
        f"Stick-slip happens below the critical speed and above the critical load. With the "
        f"foundation (simulation): stick-slip below V_c = {_fmt(speed, 'm/s')} (operating at "
        f"{_fmt(system.speed, 'm/s')}) or above W_c = {_fmt(load, 'N')} (operating at "
        f"{_fmt(system.load, 'N')})."
    )


def _show_stability(report: Mapping[str, Any]) -> None:
    """The design report's ``stability`` section: is steady sliding stable, and by how much."""
    st.subheader("Stability of steady sliding")
    st.caption(f"Friction law: {report['friction']}.")
    stab = report.get("stability")
    if not stab:
        return
    rows = {"rigid": "rigid base", "foundation": "with foundation"}
    present = [k for k in rows if k in stab]
    st.table(pd.DataFrame({  # a plain table: the data grid took 0.05-0.1 s of every rerun
        "stable": ["yes" if stab[k]["stable"] else "neutral" if stab[k].get("neutral") else "no"
                   for k in present],
        "growth rate [1/s]": [_fmt(stab[k]["growth_rate"]) for k in present],
        "δ_crit": [_fmt(stab[k]["delta_crit"]) for k in present],
        "δ_local": [_fmt(stab[k]["delta_local"] + 0.0) for k in present],  # no "-0"
        "margin": [_fmt(stab[k]["margin"]) for k in present],
        "σ_crit [s/m]": [_fmt(stab[k]["sigma_crit"]) for k in present],
    }, index=[rows[k] for k in present]))
    side = "foundation" if "foundation" in stab else present[0]
    st.markdown(
        f"Steady sliding stays stable for friction slopes dμ/dv_r down to "
        f"−{_fmt(stab[side]['sigma_crit'], 's/m')} ({rows[side]}; "
        + (f"rigid base −{_fmt(stab['rigid']['sigma_crit'], 's/m')}; " if side != "rigid" else "")
        + f"this law's slope at the belt speed: "
        f"{_fmt(-stab[side].get('sigma_local', 0.0) + 0.0, 's/m')})."
    )
    for key in present:  # the certified safe disturbance margin (issue 13)
        margin = stab[key].get("safe_disturbance")
        if margin:
            st.markdown(f"Disturbances, {rows[key]}: {margin['sentence']}.")
        bounds = stab[key].get("boundaries")
        if bounds:  # where steady sliding changes stability along V and W (Hopf boundary)
            st.markdown(f"{rows[key].capitalize()}: {bounds['sentence']}.")


def _show_foundation(report: Mapping[str, Any], system: PhysicalSystem) -> None:
    st.subheader("Foundation")
    r = report["recommended_foundation"]
    f = report["foundation"]
    rows = {"recommended (Eqs. 28-30)": r}
    if system.foundation is not None:
        rows["given (assessed above)"] = f
    stable = report.get("stability_optimal_foundation")
    if stable:  # 'stickslip design' lists it for a law that depends on the sliding speed
        rows["stability-optimal"] = stable
    _table(list(rows), {
        "m_a [kg]": [_fmt(x["m_a"]) for x in rows.values()],
        "k_a [N/m]": [_fmt(x["k_a"]) for x in rows.values()],
        "c_a [N s/m]": [_fmt(x["c_a"]) for x in rows.values()],
    })
    st.caption(f"Foundation assessed: {f['source']}; dimensionless M = {_fmt(f['M'])}, "
               f"K = {_fmt(f['K'])}, ζ_a = {_fmt(f['zeta_a'])}; ζ_eq = {_fmt(report['zeta_eq'])} "
               f"({report['zeta_eq_source']}).")
    if stable:
        sigma = stable["sigma_crit"]
        tolerated = (f"friction slopes dμ/dv_r down to −{_fmt(sigma, 's/m')}" if sigma > 0.0
                     else f"no weakening (it needs a slope of at least +{_fmt(-sigma, 's/m')})")
        st.caption(f"Stability-optimal foundation (as listed by 'stickslip design'): steady "
                   f"sliding tolerates {tolerated} (δ_crit = {_fmt(stable['delta_crit'])}); "
                   f"static deflection under μk W {_fmt(stable['foundation_deflection'], 'm')} "
                   f"(bound {_fmt(stable['max_foundation_deflection'], 'm')}); M = "
                   f"{_fmt(stable['M'])}, K = {_fmt(stable['K'])}, ζ_a = {_fmt(stable['zeta_a'])}.")


def _show_stick_slip_optimum(report: Mapping[str, Any], system: PhysicalSystem
                             ) -> Mapping[str, Any] | None:
    with st.expander("Stick-slip-optimal foundation (beyond the paper)"):
        st.markdown(
            "The foundation of Eqs. (28)-(30) is tuned as a vibration absorber. This search "
            "maximises the stick-slip onset itself over (M, K, ζ_a), with the mass ratio at most "
            "that of Eq. (28), by certified simulation. It takes a few seconds."
        )
        lam_max = max(100.0, 2.0 * report["lambda"])
        key = (report["zeta"], report["gamma"], lam_max)
        if st.button("Find the stick-slip-optimal foundation", key="find_stick_slip_optimum"):
            st.session_state["stick_slip_optimum"] = (key, stick_slip_optimum(*key))
        stored = st.session_state.get("stick_slip_optimum")
        if stored is None or stored[0] != key:
            return None
        opt = stored[1]
        phys = foundation_to_physical(Foundation(opt["M"], opt["K"], opt["zeta_a"]), system.mass,
                                      system.stiffness)
        ref = opt["absorber_optimum"]

        def onset(lam_c: float | None) -> str:
            if lam_c is None:
                return (f"no stick-slip up to λ = {_fmt(lam_max)} (belt speeds down to "
                        f"{_fmt(system.speed_for_lambda(lam_max), 'm/s')})")
            return (f"λ_c = {_fmt(lam_c)}: stick-slip below V_c = "
                    f"{_fmt(system.speed_for_lambda(lam_c), 'm/s')}, above W_c = "
                    f"{_fmt(system.load_for_lambda(lam_c), 'N')}")

        st.markdown(
            f"**Stick-slip-optimal foundation:** m_a = {_fmt(phys.m_a, 'kg')}, "
            f"k_a = {_fmt(phys.k_a, 'N/m')}, c_a = {_fmt(phys.c_a, 'N s/m')} "
            f"(M = {_fmt(opt['M'])}, K = {_fmt(opt['K'])}, ζ_a = {_fmt(opt['zeta_a'])}).\n\n"
            f"- its onset: {onset(opt['lambda_crit'])}\n"
            f"- absorber optimum of Eqs. (28)-(30): {onset(ref['lambda_crit'])}"
        )
        note = coulomb_tuning_note(system.friction.law)
        if note:
            st.caption(f"This foundation {note}.")
        return opt


def _show_disturbances(report: Mapping[str, Any], system: PhysicalSystem,
                       foundation: FoundationKey) -> None:
    """Basin stability of the machine without and with its foundation, on demand."""
    with st.expander("Disturbances: which knocks start stick-slip (beyond the paper)"):
        st.markdown(
            f"From the start-up the verdict is one state's. A machine is also knocked: this "
            f"samples {BASIN_SAMPLES:,} starts about steady sliding (position within "
            f"±{_fmt(BASIN_XI * system.length_scale, 'm')}, velocity "
            f"{_fmt(BASIN_V[0] * system.speed, 'm/s')} to {_fmt(BASIN_V[1] * system.speed, 'm/s')} "
            f"in the ground frame) and gives each a certified verdict. Inside the drawn ellipse "
            f"the Lyapunov certificate proves that no knock can start stick-slip."
        )
        law = system.slider().friction
        key = (report["lambda"], report["zeta"], report["gamma"], foundation, law)
        if st.button("Sample the disturbed starts", key="sample_basin"):
            st.session_state["basin"] = (key, basin_runs(*key))
        stored = st.session_state.get("basin")
        if stored is None or stored[0] != key:
            return
        results = stored[1]
        _table(list(results), {
            "ends in stick-slip": [f"{r.fractions['stick-slip']:.3f} ± {r.standard_errors['stick-slip']:.3f}"
                                   for r in results.values()],
            "ends in steady sliding": [f"{r.fractions['steady-sliding']:.3f}" for r in results.values()],
            "undetermined": [f"{r.fractions['undetermined']:.3f}" for r in results.values()],
        })
        for column, (name, result) in zip(st.columns(len(results)), results.items(), strict=True):
            column.image(cached_png(("basin", name, *key),  # drawn once per machine
                                    partial(_basin_figure, result, name)))
        st.caption(f"Dimensionless: ξ in units of V/ω_n = {_fmt(system.length_scale, 'm')} from the "
                   f"kinetic-friction equilibrium, ξ' in units of V = {_fmt(system.speed, 'm/s')}; "
                   "with the foundation, the foundation mass starts at rest in its steady state.")


def _basin_figure(result: Any, name: str) -> Any:
    """The basin of one machine (its states by verdict, the safe region), titled ``name``."""
    return result.plot(marker_size=2.0, title=name).figure


def _show_bifurcation(report: Mapping[str, Any], system: PhysicalSystem,
                      foundation: FoundationKey) -> None:
    """Bifurcation diagrams in lambda around the operating point, on demand (issue 20)."""
    with st.expander("Bifurcation diagram: every cycle, stable or not (beyond the paper)"):
        onsets = [report["critical_lambda"][k] for k in ("rigid_exact", "rigid_simulation",
                                                           "foundation_simulation")]
        lo, hi = bifurcation_range(report["lambda"], onsets)
        axis = lambda_axis(system)
        if axis == "speed":
            reading = (f"belt speed from {_fmt(system.speed_for_lambda(hi), 'm/s')} to "
                       f"{_fmt(system.speed_for_lambda(lo), 'm/s')} at the load "
                       f"{_fmt(system.load, 'N')}")
        elif axis == "load":
            reading = (f"normal load from {_fmt(system.load_for_lambda(lo), 'N')} to "
                       f"{_fmt(system.load_for_lambda(hi), 'N')} at the belt speed "
                       f"{_fmt(system.speed, 'm/s')} (this friction law is given in m/s, so "
                       f"changing the speed would change the law itself)")
        else:
            reading = ("the friction law held as it is at the operating point: with this law a "
                       "change of λ is neither a change of belt speed nor of load alone")
        st.markdown(
            f"Pseudo-arclength continuation of the exact return map (`continue_cycles`, as "
            f"`stickslip continue`): the stick-slip cycles and slip oscillations of the machine, "
            f"stable (solid) and unstable (dashed), steady sliding on the axis, folds, grazing and "
            f"Hopf points marked, for λ from {_fmt(lo)} to {_fmt(hi)} (operating λ = "
            f"{_fmt(report['lambda'])}): {reading}. Rigid base and the assessed foundation. "
            f"It takes a few seconds to a minute."
        )
        law = system.slider().friction
        key = ((lo, hi), report["lambda"], report["zeta"], report["gamma"], foundation, law)
        if st.button("Continue the cycles (seconds to a minute)", key="continue_cycles"):
            st.session_state["bifurcation"] = (key, bifurcation_diagrams(*key))
        stored = st.session_state.get("bifurcation")
        if stored is None or stored[0] != key:
            return
        results = stored[1]
        st.image(cached_png(("bifurcation", *key),  # drawn once per range and machine
                            lambda: bifurcation_figure(results, system, report["lambda"], axis)))
        st.caption("Amplitude in units of V/ω_n of each point (the belt speed there). The "
                   "interval where a stable cycle and stable steady sliding coexist is "
                   "bistable: which one the machine settles to depends on its start and knocks.")
        st.dataframe(bifurcation_events_table(results, system, axis), key="bifurcation_events",
                     hide_index=True)
        for name, result in results.items():
            st.caption(f"{name}: " + "; ".join(
                f"{b.kind} branch ({len(b.points)} points) stopped: {b.stop_reason}"
                for b in result.branches) if result.branches else f"{name}: no periodic motion "
                f"found in the range")
        col1, col2 = st.columns(2)
        col1.download_button("Bifurcation diagrams (CSV)", bifurcation_csv(results, system, axis),
                             file_name="stickslip-bifurcation.csv", mime="text/csv",
                             key="download_bifurcation_csv", on_click="ignore")
        col2.download_button("Bifurcation diagrams (netCDF)", bifurcation_netcdf(results),
                             file_name="stickslip-bifurcation.nc", mime="application/x-netcdf",
                             key="download_bifurcation_netcdf", on_click="ignore")


def main() -> None:
    """Lay out the page; the script body that Streamlit runs on every interaction.

    An unexpected error shows Streamlit's generic message, never its traceback (which names
    server paths): ``stickslip app`` passes ``--client.showErrorDetails none``, and the script
    sets it too for a server started with ``streamlit run`` on this file.
    """
    st.set_option("client.showErrorDetails", "none")
    st.set_page_config(page_title="stickslip: stick-slip design", layout="wide")
    page = st.sidebar.radio("Machine", PAGES, key="page")
    if page == PAGES[1]:
        from stickslip.app.machine_page import show_machine_page

        show_machine_page()
        return
    if page == PAGES[2]:
        from stickslip.app.identify_page import show_identify_page

        show_identify_page()
        return
    if page == PAGES[3]:
        from stickslip.app.tuning_page import show_tuning_page

        show_tuning_page()
        return
    st.title("Stick-slip on an elastic foundation")
    st.caption("Will this sliding system stick-slip, at which belt speed or load, and which "
               "foundation suppresses it? The design procedure of the paper's Fig. 16, checked "
               f"by certified simulation. stickslip {package_version()}; initial condition: "
               f"{STARTUP_DESCRIPTION}.")
    raw = _input_widgets()
    if raw["friction_law"] in MEMORY_LAWS:
        from stickslip.app.memory_page import show_memory_results

        show_memory_results(raw)
        return
    system, errors = parse_inputs(raw)
    if system is None:
        for line in errors:
            show_error(line)
        st.info("Nothing is computed until every input is valid.")
        return
    try:
        _show_results(raw, system)
    except ValueError as exc:  # valid inputs whose dimensionless groups leave the model's range
        show_error("Cannot analyse these inputs: " + str(exc))


def _side(name: str) -> str:
    """The design report's key of a run's structure."""
    return "rigid" if name == "rigid base" else "foundation"


def _show_cycle(name: str, result: Any, system: PhysicalSystem) -> None:
    """The certified cycle's period and amplitude in s and m (and dimensionless)."""
    if not result.cycle_length:
        st.caption(f"{name}: no periodic stick-slip cycle ({result.verdict.value}).")
        return
    cols = st.columns(3)
    cols[0].metric(f"{name}: period T", _fmt(result.period * system.time_scale, "s"),
                   help=f"τ = {_fmt(result.period)} in units of 1/ω_n")
    cols[1].metric(f"{name}: amplitude", _fmt(result.amplitude * system.length_scale, "m"),
                   help=f"half the peak-to-peak slider displacement; {_fmt(result.amplitude)} "
                        "in units of V/ω_n")
    cols[2].metric(f"{name}: time stuck", _fmt(100.0 * result.stick_ratio, "%"),
                   help="fraction of the period the slider sticks to the belt")


def _show_results(raw: Mapping[str, str], system: PhysicalSystem) -> None:
    report = design_report(si_key(system))
    lam, zeta, gamma = report["lambda"], report["zeta"], report["gamma"]

    st.subheader("Dimensionless groups")
    cols = st.columns(5)
    cols[0].metric("λ", _fmt(lam), help="(μs − μk) W / (V √(mk))")
    cols[1].metric("ζ", _fmt(zeta), help="c / (2 √(mk))")
    cols[2].metric("γ", _fmt(gamma), help="μk / (μs − μk)")
    cols[3].metric("ζ_eq", _fmt(report["zeta_eq"]), help=report["zeta_eq_source"])
    cols[4].metric("ω_n [rad/s]", _fmt(system.natural_frequency), help="√(k/m)")

    st.subheader("Does it stick-slip?")
    for warning in report.get("warnings", []):  # those of 'stickslip design'
        show_warning(warning)
    _show_verdicts(report)
    _show_critical(report, system)
    _show_foundation(report, system)
    _show_stability(report)
    optimum = _show_stick_slip_optimum(report, system)

    f = report["foundation"]
    assessed: FoundationKey = (f["M"], f["K"], f["zeta_a"])
    st.subheader("Operating point: time history and phase portrait")
    st.caption(f"Slider displacement x from its kinetic-friction equilibrium and velocity v, in "
               f"SI (the computation's τ = ω_n t has 1 unit = {_fmt(system.time_scale, 's')}, "
               f"ξ = x / {_fmt(system.length_scale, 'm')}, ξ' = v / V). Stick phases shaded.")
    law = system.slider().friction
    runs = operating_point_runs(lam, zeta, gamma, assessed, law)
    si = (system.time_scale, system.length_scale, system.speed)
    charts = run_charts(lam, zeta, gamma, assessed, law, si)
    for (name, result), (history, portrait) in zip(runs.items(), charts, strict=True):
        st.markdown(f"**{name}: {report['verdict'][_side(name)]['simulation']}**")
        left, right = st.columns((2.2, 1.0))
        left.vega_lite_chart(history, width="stretch")
        right.vega_lite_chart(portrait, width="stretch")
        _show_cycle(name, result, system)

    st.subheader("Occurrence map around the operating point")
    given = assessed if system.foundation is not None else None
    for column, chart in zip(st.columns(2), occurrence_map_charts(
            lam, zeta, gamma, given, law, si_key(system)), strict=True):
        column.vega_lite_chart(chart, width="stretch")
    st.caption("Each cell is a certified simulation from the startup state at this γ; the "
               "star is the operating point. "
               + ("Right: the given foundation (fixed in SI units)." if given else
                  "Right: the foundation of Eqs. (28)-(30) tuned at each ζ of the grid.")
               + " Drag to pan, scroll to zoom, double-click to reset; the menu (⋯) saves a "
               "chart as PNG or SVG.")

    _show_disturbances(report, system, assessed)
    _show_bifurcation(report, system, assessed)

    st.subheader("Download")
    col1, col2 = st.columns(2)  # written when clicked, not at every rerun (0.1 s for the CSV)
    col1.download_button("Design report (JSON)", lambda: report_json(raw, report, runs, optimum),
                         file_name="stickslip-design.json", mime="application/json",
                         key="download_json", on_click="ignore")
    col2.download_button("Time histories (CSV)", lambda: history_csv(runs, system),
                         file_name="stickslip-time-history.csv", mime="text/csv",
                         key="download_csv", on_click="ignore")


if __name__ == "__main__":
    main()
