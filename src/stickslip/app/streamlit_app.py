"""The stickslip web app: the design procedure of the paper's Fig. 16 in a browser.

Run it with ``stickslip app`` (or ``streamlit run`` on this file). Inputs are text with
units ("2 kg", "50 kN/m"), parsed once by :func:`stickslip.model.units.to_si`; everything
after that is SI floats and dimensionless groups. Every number shown comes from the public
Python API (:func:`~stickslip.analysis.design.design_foundation`, :func:`~stickslip.simulate`,
:func:`~stickslip.sweep.occurrence_map`,
:func:`~stickslip.analysis.tuning.optimal_foundation_stick_slip`); this script
only lays out inputs and results. Invalid input shows one line per problem and nothing is
computed.

The friction law while sliding (issue 10, point 5) is chosen in the sidebar: ``coulomb`` (the
paper's), ``linear`` (slope in s/m), ``stribeck`` or ``table`` (an uploaded CSV with columns
``v`` [m/s] and ``mu``); its fields are the keys of the ``[friction]`` table of the TOML used by
``stickslip design`` (:class:`~stickslip.model.physical.PhysicalFriction`, units parsed by
``to_si``). The design report's stability section is shown as a table.
"""

from __future__ import annotations

import csv
import dataclasses
import io
import json
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import streamlit as st
from matplotlib.figure import Figure
from matplotlib.ticker import NullLocator
from numpy.typing import NDArray

from stickslip import (
    STARTUP_DESCRIPTION,
    Foundation,
    Mode,
    PhysicalFoundation,
    PhysicalSystem,
    SimulationResult,
    Slider,
    Structure,
    __version__,
    elastic_foundation,
    rigid_base,
    simulate,
)
from stickslip.analysis.design import design_foundation
from stickslip.analysis.dva import DvaSpec
from stickslip.analysis.tuning import optimal_foundation_stick_slip
from stickslip.model.friction import CoulombFriction, FrictionLaw, friction_csv_columns
from stickslip.model.physical import PhysicalFriction, foundation_to_physical
from stickslip.model.units import FRICTION_QUANTITIES, QUANTITIES, to_si
from stickslip.plot.figure import new_grid
from stickslip.plot.simulation import phase_portrait_plot, time_history_plot
from stickslip.sweep import OccurrenceMap, occurrence_map
from stickslip.sweep.basin import BasinResult, basin_stability, equilibrium_state, sample_box
from stickslip.sweep.execution import ExecutionOptions

#: Widget key -> (label, default text). The keys are the quantity names of ``to_si``.
SYSTEM_INPUTS: dict[str, tuple[str, str]] = {
    "m": ("Slider mass m", "2 kg"),
    "k": ("Spring stiffness k", "50 kN/m"),
    "c": ("Damping coefficient c", "20 N*s/m"),
    "mu_s": ("Static friction coefficient μs", "0.5"),
    "mu_k": ("Kinetic friction coefficient μk", "0.3"),
    "load": ("Normal load W", "500 N"),
    "speed": ("Belt speed V", "5 cm/s"),
}
FOUNDATION_INPUTS: dict[str, tuple[str, str]] = {
    "m_a": ("Foundation mass m_a", ""),
    "k_a": ("Foundation stiffness k_a", ""),
    "c_a": ("Foundation damping c_a", ""),
}
DEFAULTS: dict[str, str] = {key: default for key, (_, default) in
                            (SYSTEM_INPUTS | FOUNDATION_INPUTS).items()}
#: The friction laws of the selectbox (widget key ``friction_law``), the paper's first.
FRICTION_LAWS = ("coulomb", "linear", "stribeck", "table")
#: Widget key -> (label, default text) of the friction fields; the keys are those of the
#: ``[friction]`` table (``FRICTION_QUANTITIES`` of ``to_si``). ``mu_0`` may stay empty (= mu_s).
FRICTION_INPUTS: dict[str, tuple[str, str]] = {
    "slope": ("Friction slope σ (μ = μk − σ v_r)", "0.02 s/m"),
    "mu_0": ("μ0 at vanishing sliding speed (empty: μs)", ""),
    "stribeck_velocity": ("Stribeck velocity v_s", "0.5 m/s"),
    "exponent": ("Stribeck exponent n", "1"),
    "viscous": ("Viscous slope σ_v", "0 s/m"),
}
#: The fields of each law.
FRICTION_FIELDS: dict[str, tuple[str, ...]] = {
    "coulomb": (),
    "linear": ("slope",),
    "stribeck": ("mu_0", "stribeck_velocity", "exponent", "viscous"),
    "table": (),
}
#: Widget keys of the uploaded friction curve (its text and file name, in ``raw``).
FRICTION_TABLE = "friction_table"
FRICTION_TABLE_NAME = "friction_table_name"

#: Occurrence map around the operating point: lambda from lam/SPAN to lam*SPAN (log-spaced),
#: zeta from 0 to twice the operating zeta.
MAP_SHAPE = (30, 12)
MAP_LAMBDA_SPAN = 10.0
MAP_ZETA_FLOOR = 0.05  # zeta range used when the slider has no damping
#: Time horizon of the time-history figures, dimensionless tau.
PLOT_HORIZON = (40.0, 3000.0)
#: Disturbed starts per basin, and their box about steady sliding (dimensionless, the knocks of
#: docs/disturbances.md): ``xi - xi_eq`` in units of V/omega_n, ``xi'`` in units of V.
BASIN_SAMPLES = 4000
BASIN_XI = 6.0
BASIN_V = (-4.0, 1.5)
#: Samples of the exact trajectory per figure (every mode switch is added to them).
PLOT_POINTS = 1500

SiKey = tuple[tuple[str, Any], ...]
FoundationKey = tuple[float, float, float]


# ---------------------------------------------------------------- inputs -----------------

def _field_error(name: str, label: str, exc: ValueError) -> str:
    """``to_si``'s message names the command-line flag; the app names the field instead."""
    message = str(exc)
    flag = f"--{name.replace('_', '-')}"
    if message.startswith(flag):
        message = message[len(flag):].strip()
    return f"{label}: {message}"


def parse_inputs(raw: Mapping[str, str]) -> tuple[PhysicalSystem | None, list[str]]:
    """Turn the text inputs into a :class:`PhysicalSystem` (SI), or one error line per problem.

    Parameters
    ----------
    raw : mapping
        Text of every field of :data:`SYSTEM_INPUTS` and :data:`FOUNDATION_INPUTS` (the three
        foundation fields all empty for no existing foundation); ``friction_law`` (one of
        :data:`FRICTION_LAWS`, ``coulomb`` when absent) and the fields of that law
        (:data:`FRICTION_FIELDS`), and for ``table`` the uploaded CSV text
        (:data:`FRICTION_TABLE`, its file name in :data:`FRICTION_TABLE_NAME`).

    Returns
    -------
    system : PhysicalSystem or None
        ``None`` exactly when ``errors`` is not empty.
    errors : list of str
        One line per bad input (wrong unit, not a number, non-positive, ``mu_k >= mu_s``, a
        friction law outside its range).
    """
    errors: list[str] = []
    values: dict[str, float] = {}
    labels = {key: label for key, (label, _) in (SYSTEM_INPUTS | FOUNDATION_INPUTS).items()}
    given_foundation = [key for key in FOUNDATION_INPUTS if str(raw.get(key, "")).strip()]
    if given_foundation and len(given_foundation) != len(FOUNDATION_INPUTS):
        errors.append("An existing foundation needs all of m_a, k_a and c_a (leave all three "
                      "empty to have one recommended)")
    for key in [*SYSTEM_INPUTS, *given_foundation]:
        text = str(raw.get(key, "")).strip()
        if not text:
            errors.append(f"{labels[key]} is empty")
            continue
        try:
            values[key] = to_si(key, text)
        except ValueError as exc:
            errors.append(_field_error(key, labels[key], exc))
    friction, friction_errors = parse_friction_inputs(raw)
    errors += friction_errors
    if errors or friction is None:
        return None, errors
    try:
        foundation = None
        if given_foundation:
            foundation = PhysicalFoundation(values["m_a"], values["k_a"], values["c_a"])
        system = PhysicalSystem(m=values["m"], k=values["k"], c=values["c"], mu_s=values["mu_s"],
                                mu_k=values["mu_k"], load=values["load"], speed=values["speed"],
                                foundation=foundation, friction=friction)
    except ValueError as exc:
        return None, [f"Invalid input: {exc}"]
    if friction.mu_0 is not None and friction.mu_0 > system.mu_s:
        return None, [f"{FRICTION_INPUTS['mu_0'][0]}: {friction.mu_0:g} is above μs = "
                      f"{system.mu_s:g} (friction at vanishing speed is at most static friction)"]
    try:
        system.slider()  # the law in the engine's units: mu >= 0, ...
    except ValueError as exc:
        return None, ["Friction law: " + " ".join(str(exc).split())]
    return system, []


def parse_friction_inputs(raw: Mapping[str, str]) -> tuple[PhysicalFriction | None, list[str]]:
    """The friction law of the inputs in SI units, or one error line per bad friction field.

    Only the fields of the chosen law are read (:data:`FRICTION_FIELDS`); values with units
    go through ``to_si`` as in the ``[friction]`` table of ``stickslip design``.
    """
    law = str(raw.get("friction_law", "coulomb") or "coulomb").strip().lower()
    if law not in FRICTION_LAWS:
        return None, [f"Friction law {law!r} is not one of {', '.join(FRICTION_LAWS)}"]
    errors: list[str] = []
    values: dict[str, Any] = {"law": law}
    for key in FRICTION_FIELDS[law]:
        label = FRICTION_INPUTS[key][0]
        text = str(raw.get(key, "")).strip()
        if not text:
            if key != "mu_0":
                errors.append(f"{label} is empty")
            continue
        try:
            values[key] = to_si(key, text)
        except ValueError as exc:
            errors.append(_field_error(key, label, exc))
    if law == "table":
        name = str(raw.get(FRICTION_TABLE_NAME, "") or "(uploaded)")
        text = str(raw.get(FRICTION_TABLE, ""))
        if not text.strip():
            errors.append("Friction table: upload a CSV file with columns v [m/s] and mu")
        else:
            try:
                header = next(line for line in text.splitlines()
                              if line.strip() and not line.startswith("#"))
                if "mu" not in [h.strip().lower() for h in header.split(",")]:
                    raise ValueError(f"{name} needs columns v [m/s] and mu, got {header.strip()}")
                v, mu = friction_csv_columns(text, name)
                values["table_v"], values["table_mu"] = tuple(v), tuple(mu)
            except ValueError as exc:
                errors.append("Friction table: " + " ".join(str(exc).split()))
    if errors:
        return None, errors
    try:
        return PhysicalFriction(**values), []
    except ValueError as exc:
        return None, ["Friction law: " + " ".join(str(exc).split())]


def si_key(system: PhysicalSystem) -> SiKey:
    """The SI inputs as a hashable key for the caches."""
    items: list[tuple[str, Any]] = [
        ("m", system.m), ("k", system.k), ("c", system.c), ("mu_s", system.mu_s),
        ("mu_k", system.mu_k), ("load", system.load), ("speed", system.speed)]
    if system.foundation is not None:
        f = system.foundation
        items += [("m_a", f.m_a), ("k_a", f.k_a), ("c_a", f.c_a)]
    if system.friction.law != "coulomb":
        items.append(("friction", dataclasses.astuple(system.friction)))
    return tuple(items)


def system_from_key(key: SiKey) -> PhysicalSystem:
    """Inverse of :func:`si_key`."""
    v = dict(key)
    foundation = PhysicalFoundation(v["m_a"], v["k_a"], v["c_a"]) if "m_a" in v else None
    friction = PhysicalFriction(*v["friction"]) if "friction" in v else PhysicalFriction()
    return PhysicalSystem(m=v["m"], k=v["k"], c=v["c"], mu_s=v["mu_s"], mu_k=v["mu_k"],
                          load=v["load"], speed=v["speed"], foundation=foundation,
                          friction=friction)


# ---------------------------------------------------------- computations (cached) --------

@st.cache_data(show_spinner="Running the design procedure (Fig. 16)...", max_entries=128)
def design_report(key: SiKey) -> dict[str, Any]:
    """:func:`design_foundation` of the system, as its JSON dictionary (SI units)."""
    return design_foundation(system_from_key(key)).to_dict()


@st.cache_data(show_spinner="Simulating the operating point...", max_entries=64)
def operating_point_runs(lam: float, zeta: float, gamma: float, foundation: FoundationKey,
                         friction: FrictionLaw | None = None) -> dict[str, SimulationResult]:
    """Rigid base and foundation runs from the startup state, recorded for the figures.

    ``friction`` is the dimensionless law of the contact (the paper's Coulomb law by default).

    Both run to a common horizon: one and a half times the longer of the two times needed
    to certify the verdict (so a stick-slip cycle shows at least twice), within
    :data:`PLOT_HORIZON`.
    """
    slider = Slider(lam, gamma=gamma, friction=friction or CoulombFriction())
    structures = _structures(zeta, foundation)
    certified = max(simulate(s, slider, record=False).t_end for s in structures.values())
    horizon = min(max(PLOT_HORIZON[0], 1.5 * certified), PLOT_HORIZON[1])
    return {name: simulate(s, slider, t_max=horizon, run_to_t_max=True)
            for name, s in structures.items()}


def _structures(zeta: float, foundation: FoundationKey) -> dict[str, Structure]:
    """The machine without and with its foundation (dimensionless)."""
    return {"rigid base": rigid_base(zeta),
            "with foundation": elastic_foundation(zeta, Foundation(*foundation))}


@st.cache_data(show_spinner="Sampling disturbed starts...", max_entries=16)
def basin_runs(lam: float, zeta: float, gamma: float, foundation: FoundationKey,
               friction: FrictionLaw | None = None) -> dict[str, BasinResult]:
    """Certified verdicts of :data:`BASIN_SAMPLES` disturbed starts, without and with the foundation.

    The starts are uniform in ``xi - xi_eq`` in ``[-BASIN_XI, BASIN_XI]`` and ``xi'`` in
    :data:`BASIN_V` about steady sliding (the foundation, if any, at its steady-sliding
    state), with one seed, so both machines are knocked alike (issue 13; ``stickslip basin``).
    """
    slider = Slider(lam, gamma=gamma, friction=friction or CoulombFriction())
    results = {}
    for name, structure in _structures(zeta, foundation).items():
        xi_eq = float(equilibrium_state(structure, slider)[0])
        box = {"xi": (xi_eq - BASIN_XI, xi_eq + BASIN_XI), "v": BASIN_V}
        states = sample_box(structure, slider, BASIN_SAMPLES, box, seed=1)
        results[name] = basin_stability(structure, slider, states)
    return results


@st.cache_data(show_spinner="Computing the occurrence maps...", max_entries=64)
def occurrence_maps(lam: float, zeta: float, gamma: float, foundation: FoundationKey | None,
                    friction: FrictionLaw | None = None) -> dict[str, OccurrenceMap]:
    """Verdicts on a ``lambda x zeta`` grid around the operating point (paper Figs. 8, 11).

    Two maps: the rigid base, and the foundation (the given one, fixed in SI units, or the
    one of Eqs. 28-30 tuned at every ``zeta`` of the grid); every cell with the friction law
    ``friction`` (dimensionless, as at the operating point).
    """
    n_lam, n_zeta = MAP_SHAPE
    lams = np.geomspace(lam / MAP_LAMBDA_SPAN, lam * MAP_LAMBDA_SPAN, n_lam)
    top = 2.0 * zeta if zeta > 0.0 else MAP_ZETA_FLOOR
    zetas = (np.arange(n_zeta) + 0.5) * (top / n_zeta)  # cell centres; edges 0 .. top
    dva = DvaSpec("optimal") if foundation is None else DvaSpec("explicit", Foundation(*foundation))
    return {name: occurrence_map(lams, zetas, spec, gamma, friction=friction,
                                 execution=ExecutionOptions(backend="serial"))
            for name, spec in (("rigid base", DvaSpec("none")), ("with foundation", dva))}


@st.cache_data(show_spinner="Searching the stick-slip-optimal foundation...", max_entries=32)
def stick_slip_optimum(zeta: float, gamma: float, lam_max: float) -> dict[str, Any]:
    """:func:`optimal_foundation_stick_slip` at ``(zeta, gamma)``, as its dictionary."""
    return optimal_foundation_stick_slip(zeta, gamma, lam_max=lam_max).to_dict()


# ------------------------------------------------------------------ outputs --------------

def _fmt(x: float | None, unit: str = "") -> str:
    if x is None or not math.isfinite(x):
        return "—"
    return f"{x:.4g}" + (f" {unit}" if unit else "")


def figure_of_run(result: SimulationResult, title: str) -> Figure:
    """Time history of ``xi`` (stick phases shaded) next to the phase portrait."""
    fig, (ax_t, ax_p) = new_grid(1, 2, figsize=(10.0, 3.0), width_ratios=(2.2, 1.0))
    time_history_plot(result, ax=ax_t, quantity="position", n_points=PLOT_POINTS)
    phase_portrait_plot(result, ax=ax_p, n_points=PLOT_POINTS)
    fig.suptitle(title)
    return fig


def occurrence_figure(maps: Mapping[str, OccurrenceMap], system: PhysicalSystem, lam: float,
                      zeta: float) -> Figure:
    """The maps side by side (closed-form boundaries overlaid), the operating point marked.

    Secondary axes in SI: the damping coefficient ``c = 2 zeta sqrt(m k)`` on top, the belt
    speed ``V = lambda_op V_op / lambda`` (at the same load) on the right. One legend below
    collects the entries of both panels.
    """
    fig = Figure(figsize=(11.0, 4.6), layout="constrained")
    axes = fig.subplots(1, len(maps), sharey=True, squeeze=False)[0]
    speed_times_lam = lam * system.speed
    root_mk = math.sqrt(system.m * system.k)

    def reciprocal(x: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(x, dtype=np.float64)
        return np.divide(speed_times_lam, x, out=np.full_like(x, np.inf), where=x > 0)

    entries: dict[str, Any] = {}
    for ax, (name, result) in zip(axes, maps.items(), strict=True):
        result.plot(ax=ax, style="image", legend=True, title=name)
        legend = ax.get_legend()
        entries |= {text.get_text(): handle for text, handle in
                    zip(legend.get_texts(), legend.legend_handles, strict=True)}
        legend.remove()
        (star,) = ax.plot([zeta], [lam], marker="*", ms=16, color="gold", mec="black", ls="none")
        top = ax.secondary_xaxis("top", functions=(lambda z: 2.0 * root_mk * z,
                                                   lambda c: c / (2.0 * root_mk)))
        top.set_xlabel("damping c [N s/m]")
    speed = axes[-1].secondary_yaxis("right", functions=(reciprocal, reciprocal))
    speed.yaxis.set_minor_locator(NullLocator())  # unlabelled, and slow to lay out
    speed.set_ylabel("belt speed V [m/s]")
    entries["operating point"] = star
    fig.legend(list(entries.values()), list(entries), loc="outside lower center",
               ncols=min(len(entries), 4), frameon=False, fontsize="small")
    return fig


def report_json(raw: Mapping[str, str], report: Mapping[str, Any],
                runs: Mapping[str, SimulationResult], optimum: Mapping[str, Any] | None) -> str:
    """The downloadable design report: inputs as typed, the design report, the two runs.

    The friction inputs are those of the chosen law (``friction_law`` and its fields, the
    uploaded table's file name).
    """
    summaries = {}
    for name, result in runs.items():
        summary = result.to_dict()
        summary.pop("events")  # thousands of entries; the CSV has the trajectory
        summaries[name] = summary
    payload = {
        "stickslip_version": __version__,
        "inputs": {key: raw.get(key, "") for key in DEFAULTS} | _friction_inputs(raw),
        "initial_condition": STARTUP_DESCRIPTION,
        "design": dict(report),
        "operating_point": summaries,
        "stick_slip_optimal_foundation": dict(optimum) if optimum is not None else None,
    }
    return json.dumps(payload, indent=2, allow_nan=False)


def _friction_inputs(raw: Mapping[str, str]) -> dict[str, str]:
    law = str(raw.get("friction_law", "coulomb") or "coulomb")
    out = {"friction_law": law} | {key: str(raw.get(key, "")) for key in FRICTION_FIELDS.get(law, ())}
    if law == "table":
        out[FRICTION_TABLE_NAME] = str(raw.get(FRICTION_TABLE_NAME, ""))
    return out


def history_csv(runs: Mapping[str, SimulationResult], system: PhysicalSystem,
                n_points: int = 2000) -> str:
    """The trajectories of the runs, dimensionless and in SI, one row per sample.

    Columns: ``structure``, ``tau``, ``t_s``, ``xi``, ``xi_dot``, ``xi_a``, ``xi_a_dot``
    (empty on the rigid base), ``x_m`` (slider displacement from its kinetic-friction
    equilibrium, m), ``v_m_s`` (slider velocity, m/s), ``mode``.
    """
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(["structure", "tau", "t_s", "xi", "xi_dot", "xi_a", "xi_a_dot", "x_m", "v_m_s",
                     "mode"])
    for name, result in runs.items():
        t, q, v, modes = result.time_history(n_points=n_points)
        has_foundation = q.shape[1] > 1
        for i in range(t.size):
            writer.writerow([
                name, repr(float(t[i])), repr(float(t[i] * system.time_scale)),
                repr(float(q[i, 0])), repr(float(v[i, 0])),
                repr(float(q[i, 1])) if has_foundation else "",
                repr(float(v[i, 1])) if has_foundation else "",
                repr(float(q[i, 0] * system.length_scale)), repr(float(v[i, 0] * system.speed)),
                Mode(int(modes[i])).label,
            ])
    return buffer.getvalue()


# ---------------------------------------------------------------------- page -------------

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
    law = side.selectbox("Friction law", FRICTION_LAWS, key="friction_law")
    raw["friction_law"] = str(law)
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
    _table(list(rows.values()), {
        "critical λ": [_fmt(report["critical_lambda"][k]) for k in rows],
        "critical speed V_c [m/s]": [_fmt(report["critical_speed"][k]) for k in rows],
        "critical load W_c [N]": [_fmt(report["critical_load"][k]) for k in rows],
    })
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
    st.dataframe(pd.DataFrame({
        "stable": ["yes" if stab[k]["stable"] else "no" for k in present],
        "growth rate [1/s]": [_fmt(stab[k]["growth_rate"]) for k in present],
        "δ_crit": [_fmt(stab[k]["delta_crit"]) for k in present],
        "δ_local": [_fmt(stab[k]["delta_local"] + 0.0) for k in present],  # no "-0"
        "margin": [_fmt(stab[k]["margin"]) for k in present],
        "σ_crit [s/m]": [_fmt(stab[k]["sigma_crit"]) for k in present],
    }, index=[rows[k] for k in present]), key="stability_table")
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


def _show_foundation(report: Mapping[str, Any], system: PhysicalSystem) -> None:
    st.subheader("Foundation")
    r = report["recommended_foundation"]
    f = report["foundation"]
    rows = {"recommended (Eqs. 28-30)": r}
    if system.foundation is not None:
        rows["given (assessed above)"] = f
    _table(list(rows), {
        "m_a [kg]": [_fmt(x["m_a"]) for x in rows.values()],
        "k_a [N/m]": [_fmt(x["k_a"]) for x in rows.values()],
        "c_a [N s/m]": [_fmt(x["c_a"]) for x in rows.values()],
    })
    st.caption(f"Foundation assessed: {f['source']}; dimensionless M = {_fmt(f['M'])}, "
               f"K = {_fmt(f['K'])}, ζ_a = {_fmt(f['zeta_a'])}; ζ_eq = {_fmt(report['zeta_eq'])} "
               f"({report['zeta_eq_source']}).")


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
        phys = foundation_to_physical(Foundation(opt["M"], opt["K"], opt["zeta_a"]), system.m,
                                      system.k)
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
            column.pyplot(result.plot(marker_size=2.0, title=name).figure)
        st.caption(f"Dimensionless: ξ in units of V/ω_n = {_fmt(system.length_scale, 'm')} from the "
                   f"kinetic-friction equilibrium, ξ' in units of V = {_fmt(system.speed, 'm/s')}; "
                   "with the foundation, the foundation mass starts at rest in its steady state.")


def main() -> None:
    """Lay out the page; the script body that Streamlit runs on every interaction."""
    st.set_page_config(page_title="stickslip: stick-slip design", layout="wide")
    st.title("Stick-slip on an elastic foundation")
    st.caption("Will this sliding system stick-slip, at which belt speed or load, and which "
               "foundation suppresses it? The design procedure of the paper's Fig. 16, checked "
               f"by certified simulation. stickslip {__version__}; initial condition: "
               f"{STARTUP_DESCRIPTION}.")
    raw = _input_widgets()
    system, errors = parse_inputs(raw)
    if system is None:
        for line in errors:
            st.error(line)
        st.info("Nothing is computed until every input is valid.")
        return
    try:
        _show_results(raw, system)
    except ValueError as exc:  # valid inputs whose dimensionless groups leave the model's range
        st.error("Cannot analyse these inputs: " + " ".join(str(exc).split()))


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
    _show_verdicts(report)
    _show_critical(report, system)
    _show_foundation(report, system)
    _show_stability(report)
    optimum = _show_stick_slip_optimum(report, system)

    f = report["foundation"]
    assessed: FoundationKey = (f["M"], f["K"], f["zeta_a"])
    st.subheader("Operating point: time history and phase portrait")
    st.caption(f"Dimensionless: τ = ω_n t (1 unit = {_fmt(system.time_scale, 's')}), ξ in units of "
               f"V/ω_n = {_fmt(system.length_scale, 'm')} from the kinetic-friction equilibrium, "
               f"ξ' in units of V. Stick phases shaded.")
    law = system.slider().friction
    runs = operating_point_runs(lam, zeta, gamma, assessed, law)
    for name, result in runs.items():
        side = "rigid" if name == "rigid base" else "foundation"
        st.pyplot(figure_of_run(result, f"{name}: {report['verdict'][side]['simulation']}"))

    st.subheader("Occurrence map around the operating point")
    given = assessed if system.foundation is not None else None
    maps = occurrence_maps(lam, zeta, gamma, given, law)
    st.pyplot(occurrence_figure(maps, system, lam, zeta))
    st.caption("Each cell is a certified simulation from the startup state at this γ. "
               + ("Right: the given foundation (fixed in SI units)." if given else
                  "Right: the foundation of Eqs. (28)-(30) tuned at each ζ of the grid."))

    _show_disturbances(report, system, assessed)

    st.subheader("Download")
    col1, col2 = st.columns(2)
    col1.download_button("Design report (JSON)", report_json(raw, report, runs, optimum),
                         file_name="stickslip-design.json", mime="application/json",
                         key="download_json")
    col2.download_button("Time histories (CSV)", history_csv(runs, system),
                         file_name="stickslip-time-history.csv", mime="text/csv",
                         key="download_csv")


if __name__ == "__main__":
    main()
