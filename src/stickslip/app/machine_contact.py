"""The machine page for a machine with its contact: ``stickslip stability`` and ``simulate``.

A machine file with ``[structure] normal_dof`` and a ``[contact]`` table (normal-load
coupling, separation, brake squeal) or a ``[contact] tangential_stiffness`` (a Jenkins
element) is built here as the command line builds it (``stickslip.cli.contact.simulation``
and ``stickslip.cli.stability_command``, which the app may not import: the same readers, the
same order, so the same numbers), from the uploaded files only. The page shows

* the complex-eigenvalue analysis of steady sliding
  (:func:`~stickslip.analysis.contact.eigenvalues.complex_eigenvalue_analysis`, ``mu_max`` 2
  as the command's default): verdict, modes, critical friction coefficients with and without
  damping and the root locus (a Jenkins element's extension and, when it has a mass, its
  point's velocity are states of that analysis);
* the time history from the start-up state
  (:func:`~stickslip.analysis.contact.engine.simulate_contact`, the command's defaults):
  verdict, certificate, period (s), amplitude (m), separation, the event counts, and the last
  periods drawn by :func:`stickslip.plot.contact.history.contact_history_plot`.

Both run in the worker process (:mod:`stickslip.app.workers`): the brake pad's run takes
several seconds.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

#: The one information line that says which analyses a contact machine gets.
APPLIES = ("This machine has a contact ([structure] normal_dof and [contact], or a Jenkins "
           "element): the page shows its complex-eigenvalue analysis ('stickslip stability') "
           "and its time history ('stickslip simulate'). The design, the absorbers and the "
           "bifurcation diagram do not take a contact in this version.")
#: Periods of the motion drawn (or natural periods of the contact DOF when none repeats).
PERIODS_DRAWN = 4
#: Samples of the drawn time history.
HISTORY_SAMPLES = 1201


@dataclass(frozen=True)
class ContactMachine:
    """A machine with its contact, as the command line builds it from a machine file.

    Attributes
    ----------
    machine : Machine
        Structure (SI), contact DOF, operating point.
    contact : Contact or None
        The ``[contact]`` table and ``normal_dof``.
    normal_index : int or None
        Index of the normal DOF in ``machine``'s matrices (after a reduction).
    label : str
        How messages name the file (``machine file 'machine.toml'``).
    reduction : object or None
        The reduction of a large model.
    """

    machine: Any
    contact: Any
    normal_index: int | None
    label: str
    reduction: Any = None


@dataclass(frozen=True)
class ContactHistory:
    """What the page shows of a run: the JSON answer and the sampled history.

    Attributes
    ----------
    payload : dict
        :meth:`~stickslip.analysis.contact.engine.ContactRun.to_dict` with ``machine``,
        ``n_dof``, ``contact_dof`` and ``normal_dof`` (those of ``stickslip simulate --json``).
    history : dict
        :meth:`~stickslip.analysis.contact.engine.ContactRun.history` over the last
        :data:`PERIODS_DRAWN` periods (``t_s`` in s, displacements in m, force in N).
    """

    payload: dict[str, Any]
    history: dict[str, list[Any]]


def contact_machine(machine_file: Any) -> ContactMachine:
    """The :class:`ContactMachine` of a read machine file (uploaded files, by base name).

    Parameters
    ----------
    machine_file : MachineFile
        From :func:`stickslip.io.machine_file.read_machine_file` with the uploaded files.

    Raises
    ------
    ValueError
        One line naming the file: a missing or bad value, a friction law with memory.
    """
    from stickslip.io.machine_file import machine_from_file
    from stickslip.model.inputs import quantities_to_si
    from stickslip.model.machine import machine_from_physical_system
    from stickslip.model.physical import PhysicalFoundation, PhysicalSystem

    label = machine_file.label
    if machine_file.has_memory_law:
        raise ValueError(f"{label}: a [contact] (normal_dof, Jenkins element) runs with the "
                         "Coulomb law (mu_s, mu_k) only, not with a friction law with memory; "
                         "remove one of them")
    needed = ["mu_s", "mu_k", "load", "speed"] + ([] if machine_file.has_structure else ["m", "k"])
    values = quantities_to_si(dict(machine_file.raw), source=lambda key: f"{label}: {key} =")
    missing = [key for key in needed if key not in values]
    if missing:
        raise ValueError(f"{label} lacks {', '.join(missing)}")
    contact = machine_file.contact()
    reduction = None
    if machine_file.has_structure:
        machine, reduction = machine_from_file(machine_file, values, normal_coupling=True)
    else:
        foundation_keys = ("m_a", "k_a", "c_a")
        given = [key for key in foundation_keys if key in values]
        if given and len(given) != len(foundation_keys):
            raise ValueError(f"{label}: an existing foundation needs all of m_a, k_a and c_a")
        try:
            system = PhysicalSystem(
                mass=values["m"], stiffness=values["k"], damping=values.get("c", 0.0),
                mu_s=values["mu_s"], mu_k=values["mu_k"], load=values["load"],
                speed=values["speed"], friction=machine_file.friction(),
                foundation=PhysicalFoundation(values["m_a"], values["k_a"], values["c_a"])
                if given else None)
        except ValueError as exc:  # named once: the friction table's message names the file
            message = str(exc)
            raise ValueError(message if message.startswith(f"{label}:")
                             else f"{label}: {message}") from None
        machine = machine_from_physical_system(system)
    index = None if contact is None else contact.normal_dof
    if reduction is not None and index is not None:
        index = reduction.kept_dofs.index(index)
    return ContactMachine(machine, contact, index, label, reduction)


def stability_in_worker(cm: ContactMachine) -> tuple[Any, Any]:
    """The complex-eigenvalue analysis and its root locus (run by a worker process).

    Returns
    -------
    StabilityResult, RootLocus
        As ``stickslip stability --config`` computes them (the default ``--mu-max``, the
        analysis's :data:`~stickslip.analysis.contact.critical_coefficient.MU_MAX`).

    Raises
    ------
    ValueError
        One line naming the file (e.g. steady sliding without contact).
    """
    from stickslip.analysis.contact.eigenvalues import complex_eigenvalue_analysis

    try:
        result = complex_eigenvalue_analysis(cm.machine, cm.contact, normal_dof=cm.normal_index)
    except ValueError as exc:
        raise ValueError(f"{cm.label}: {exc}") from None
    return result, result.root_locus()


def history_window(period_s: float | None, t_end: float, omega_ref: float) -> tuple[float, float]:
    """The stretch drawn, s: the last :data:`PERIODS_DRAWN` periods of the run.

    Without a period (steady sliding, undetermined) the last :data:`PERIODS_DRAWN` natural
    periods ``2 pi / omega_ref`` of the contact DOF; never before the start.
    """
    span = PERIODS_DRAWN * (period_s if period_s else 2.0 * math.pi / omega_ref)
    return max(0.0, t_end - span), t_end


def simulate_in_worker(cm: ContactMachine) -> ContactHistory:
    """The time history from the start-up state, as ``stickslip simulate --config`` runs it.

    Raises
    ------
    ValueError
        One line naming the file (a friction law other than Coulomb's, a bad contact).
    """
    import numpy as np

    from stickslip.analysis.contact.engine import contact_system, simulate_contact

    try:
        system = contact_system(cm.machine, cm.contact, normal_dof=cm.normal_index)
        run = simulate_contact(system)
    except ValueError as exc:
        raise ValueError(f"{cm.label}: {exc}") from None
    payload = run.to_dict()
    payload.update({"machine": cm.machine.name, "n_dof": system.n_dof,
                    "contact_dof": system.tangential_dof, "normal_dof": system.normal_dof})
    start, end = history_window(run.period_s, run.t_end, system.omega_ref)
    return ContactHistory(payload, run.history(np.linspace(start, end, HISTORY_SAMPLES)))


def modes_table(stability: Mapping[str, Any]) -> Any:
    """The modes of ``StabilityResult.to_dict()`` as a table; unstable ones marked."""
    import pandas as pd

    unstable = stability["verdict"] == "unstable"
    modes = stability["modes"]
    return pd.DataFrame({
        "frequency [Hz]": [f"{m['frequency_hz']:.6g}" for m in modes],
        "damping ratio": [f"{m['damping_ratio']:.4g}" for m in modes],
        "real part [1/s]": [f"{m['growth_rate_per_s']:.6g}" for m in modes],
        "unstable": ["yes" if unstable and m["growth_rate_per_s"] > 0 else "" for m in modes],
    }, index=[f"mode {i}" for i in range(1, len(modes) + 1)])


def plain_title(text: str) -> str:
    """``text`` for a Matplotlib title: every ``$`` escaped, so no mathtext is read from it."""
    return text.replace("$", r"\$")


def verdict_text(verdict: str) -> str:
    """The stability verdict as the command prints it (``UNSTABLE`` in capitals)."""
    return verdict.upper() if verdict == "unstable" else verdict


def show_contact_machine(machine_file: Any, digest: str) -> None:
    """Lay out the machine page of a machine with its contact (Streamlit)."""
    import streamlit as st

    from stickslip.app.messages import literal_markdown, show_failure, show_info
    from stickslip.app.workers import wait_for

    show_info(APPLIES)
    try:
        cm = contact_machine(machine_file)
    except Exception as exc:
        show_failure(exc, "Reading this machine")
        return
    st.caption(literal_markdown(f"{cm.machine.name}: {cm.machine.n_dof} DOF, contact on DOF "
               f"{cm.machine.contact_dof}, normal DOF "
               f"{'-' if cm.normal_index is None else cm.normal_index}"
               + ("" if cm.reduction is None else f" ({cm.reduction.summary()})")))
    payload: dict[str, Any] = {"machine": cm.machine.name}
    _queue_run(("contact-run", digest), cm)  # behind the analysis, while the page draws it
    st.subheader("Steady sliding: complex-eigenvalue analysis")
    try:
        result, locus = wait_for(("contact-stability", digest), stability_in_worker, cm,
                                 what="Analysing steady sliding")
        payload["stability"] = _show_stability(result, locus, cm.machine.name, digest)
    except Exception as exc:
        show_failure(exc, "The complex-eigenvalue analysis")
    st.subheader("Time history from the start-up state")
    try:
        run = wait_for(("contact-run", digest), simulate_in_worker, cm,
                       what="Running the machine with its contact")
        payload["simulation"] = _show_run(run, digest)
    except Exception as exc:
        show_failure(exc, "The time history")
    st.download_button("Stability and time history (JSON)",
                       __import__("json").dumps(payload, indent=2, default=str),
                       file_name="stickslip-contact.json", mime="application/json",
                       key="download_contact_json", on_click="ignore")


def _queue_run(key: tuple[str, str], cm: ContactMachine) -> None:
    """Start the time history in the worker now, unless it is kept or the server is busy
    (then :func:`~stickslip.app.workers.wait_for` says so when the page asks for it)."""
    from stickslip.app.workers import Busy, result, submit

    if result(key) is None:
        try:
            submit(key, simulate_in_worker, cm)
        except Busy:
            pass


def _show_stability(result: Any, locus: Any, name: str, digest: str) -> dict[str, Any]:
    """The analysis's verdict, critical coefficients, modes and root locus; its JSON.

    ``digest`` (of the uploaded files) keys the root locus's image: drawn once per machine.
    """
    import streamlit as st

    from stickslip.analysis.contact.critical_coefficient import critical_text
    from stickslip.app.figures import cached_png
    from stickslip.plot.stability import root_locus_plot

    data = result.to_dict()
    col1, col2, col3 = st.columns(3)
    col1.metric("Steady sliding", verdict_text(data["verdict"]))
    for col, key, label in ((col2, "critical", "Critical mu (damped)"),
                            (col3, "critical_undamped", "Critical mu (undamped)")):
        mu = data[key]["mu"]
        col.metric(label, "none" if mu is None else "-" if data[key]["kind"] == "unstable at mu = 0"
                   else f"{mu:.8g}")
    st.text("\n".join([
        f"steady      mu(V) = {data['mu']:.6g}, d mu/d v_r = "
        f"{data['friction_slope_s_per_m']:.6g} s/m, N = {data['normal_force_N']:.6g} N",
        f"verdict     {verdict_text(data['verdict'])}",
        f"natural     {', '.join(f'{f:.6g}' for f in data['natural_frequencies_hz'])} Hz "
        "(modes 1, 2, ...: the structure pressed on the belt, mu = 0)",
        f"critical mu {critical_text(data['critical'], detail=False)}",
        f"undamped    {critical_text(data['critical_undamped'], detail=False)}"]))
    st.dataframe(modes_table(data), key="contact_modes_table")
    st.image(cached_png(("root-locus", digest),
                        lambda: root_locus_plot(locus, title=plain_title(name)).figure))
    return dict(data)


def _show_run(run: ContactHistory, digest: str) -> dict[str, Any]:
    """The run's verdict, certificate, start, period, amplitude, separation, events and figure (its
    image drawn once per machine, keyed by ``digest``)."""
    import streamlit as st

    from stickslip.analysis.contact.engine import start_description
    from stickslip.app.figures import cached_png
    from stickslip.plot.contact.history import contact_history_plot

    p = run.payload
    cols = st.columns(4)
    cols[0].metric("Time history", str(p["verdict"]))
    cols[1].metric("Period", "—" if p["period_s"] is None else f"{p['period_s']:.8g} s")
    cols[2].metric("Amplitude", "—" if p["amplitude_m"] is None else f"{p['amplitude_m']:.6g} m")
    cols[3].metric("Separated", "yes" if p["separated"] else "no")
    counts = ", ".join(f"{k} {v}" for k, v in p["event_counts"].items()) or "none"
    st.text(f"certificate {p['certificate']}\n"
            f"start       {start_description(p.get('initial_mode'))}\n"
            f"events      {p['n_events']} ({counts}) up to t = {p['t_end_s']:.6g} s\n"
            "amplitude   half the peak-to-peak displacement of the contact DOF over the last "
            "period")
    st.image(cached_png(("contact-run", digest), lambda: contact_history_plot(
        run.history, title=f"{plain_title(str(p['machine']))}: the last periods",
        period_s=p["period_s"]).figure))
    return dict(p)
