"""The slider page with a friction law with memory (rate-and-state, LuGre).

What ``stickslip design --config`` reports for such a machine
(:func:`~stickslip.analysis.memory.design.memory_design`): the runs from stick and from steady
sliding nudged off it, the linear verdict with the critical stiffness, speeds and loads, and
the start-up run's time history. The computation takes a few seconds and is cached per input.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import streamlit as st

from stickslip.app.figures import fmt, png
from stickslip.app.memory_inputs import memory_key, parse_memory_inputs
from stickslip.app.messages import show_error
from stickslip.model.state_friction import MemorySystem

#: Samples of the start-up run's time history.
HISTORY_SAMPLES = 1500
#: Periods of the start-up's cycle shown (or the last fifth of the run without a cycle).
PERIODS_SHOWN = 3


def memory_report(system: MemorySystem) -> tuple[dict[str, Any], bytes]:
    """The design report (JSON-ready) and the start-up run's figure (PNG) of ``system``
    (module-level: the machine page runs it in its worker process)."""
    from stickslip.analysis.memory.design import STARTUP_KICK, memory_design
    from stickslip.analysis.memory.simulation import simulate_memory
    from stickslip.plot.memory.history import memory_history_plot

    report = memory_design(system)
    payload = report.to_dict()
    kick = 0.0 if system.quasi_static else STARTUP_KICK
    run = report.startup if report.startup is not None else report.nudged
    span = (PERIODS_SHOWN * run.period if math.isfinite(run.period)
            else 0.2 * run.t_end)
    times = np.linspace(max(run.t_end - span, 0.0), run.t_end, HISTORY_SAMPLES)
    shown = simulate_memory(system, t_max=run.t_end, kick=kick, history_times=times)
    assert shown.history is not None
    title = f"{'start-up' if report.startup is not None else 'run'}: {run.verdict.value}"
    figure = memory_history_plot(shown.history, drive_speed=system.schedule.last,
                                 title=title).figure
    return payload, png(figure)


def show_memory_results(raw: Mapping[str, str]) -> None:
    """The page's results for a law with memory (errors, one line each, when inputs are bad)."""
    system, errors = parse_memory_inputs(raw)
    if system is None:
        for line in errors:
            show_error(line)
        st.info("Nothing is computed until every input is valid.")
        return
    from stickslip.app.messages import show_failure
    from stickslip.app.workers import wait_for

    # in a worker, as the machine page's: these runs take up to a minute, and the pool bounds
    # how many wait (an independent audit found them in the page's own thread)
    try:
        p, image = wait_for(("memory-inputs", memory_key(raw)), memory_report, system,
                            what="Linearisation, critical speeds and loads, two runs")
    except Exception as exc:
        show_failure(exc, "The design of these inputs")
        return
    show_memory_report(p, image)


def show_memory_machine(machine_file: Any, digest: str) -> None:
    """The machine page's report for an uploaded machine file with a law with memory."""
    from stickslip.app.messages import show_failure
    from stickslip.app.workers import wait_for

    try:
        system = machine_file.memory_system()
        p, image = wait_for(("memory", digest), memory_report, system,
                            what="Designing the machine with friction with memory")
    except Exception as exc:
        show_failure(exc, "The design of this machine")
        return
    st.caption(f"{system.n_dof} DOF, contact on DOF {system.contact_dof}; the report of "
               "'stickslip design --config' for a friction law with memory.")
    show_memory_report(p, image)


def show_memory_report(p: dict[str, Any], image: bytes) -> None:
    """Lay out a memory-law design report (its JSON payload) and its figure."""
    st.subheader("Does it stick-slip?")
    st.caption(p["friction"])
    cols = st.columns(3)
    cols[0].metric("Verdict", p["verdict"], help="the start-up's (stuck to the drive), or the "
                   "nudged run's where the start-up's is undetermined")
    cols[1].metric("Steady sliding (linearised)", p["stability"]["verdict"],
                   help="eigenvalues of steady sliding, structure and state variable together")
    cols[2].metric("Growth rate", fmt(p["stability"]["growth_rate_per_s"], "1/s"))
    if p["bistable"]:
        st.info("Bistable: steady sliding survives small disturbances, but a start stuck to the "
                "drive ends in a cycle.")
    rows = {}
    for key, label in (("startup", "start-up (stuck to the drive)"),
                       ("nudged", "nudged (steady sliding, slip speed 1.01 V)")):
        r = p[key]
        if r is None:
            continue
        rows[label] = {"verdict": r["verdict"], "period [s]": fmt(r["period_s"]),
                       "amplitude [m]": fmt(r["amplitude_m"]),
                       "time in quasi-stick": fmt(None if r["stick_ratio"] is None
                                                      else 100.0 * r["stick_ratio"], "%"),
                       "why": r["certificate"] or r["status_message"]}
    st.dataframe(pd.DataFrame.from_dict(rows, orient="index"), width="stretch")
    st.image(image)

    st.subheader("Critical values (linearisation)")
    s = p["stability"]
    ranges = "; ".join(f"{fmt(a, 'm/s')} to {fmt(b, 'm/s')}" for a, b in s["unstable_speeds_m_per_s"])
    loads = "; ".join(f"{fmt(a, 'N')} to {fmt(b, 'N')}" for a, b in p["unstable_loads_N"])
    critical = {
        "critical stiffness k_c": fmt(s["critical_stiffness_N_per_m"], "N/m"),
        "critical drive speeds": ", ".join(fmt(v, "m/s") for v in s["critical_speeds_m_per_s"])
        or "none in the scan",
        "unstable speeds": ranges or "none in the scan",
        "critical normal loads": ", ".join(fmt(w, "N") for w in p["critical_loads_N"])
        or "none in the scan",
        "unstable loads": loads or "none in the scan",
    }
    st.table(pd.DataFrame({"value": list(critical.values())}, index=list(critical)))
    lo, hi, _ = s["speed_grid_m_per_s"]
    w_lo, w_hi, _ = p["load_grid_N"]
    st.caption(f"Scans: drive speed {fmt(lo, 'm/s')} to {fmt(hi, 'm/s')}, normal load "
               f"{fmt(w_lo, 'N')} to {fmt(w_hi, 'N')}, each sign change of the growth rate "
               "bisected to 1e-10. A stable verdict is local (see the runs).")
    st.info(p["foundation"])
    st.download_button("Design report (JSON)", json.dumps(p, indent=2),
                       file_name="stickslip-design-memory.json", mime="application/json",
                       key="download_memory_json", on_click="ignore")
