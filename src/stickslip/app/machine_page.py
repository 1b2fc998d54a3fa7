"""The web app's "your machine" page: a machine file with its matrices, or modes typed in.

Issue 18 point 3: the app takes the machine the command line takes. Either the machine TOML
and the matrix files it names are uploaded together (read from memory by
:func:`stickslip.io.machine_file.read_machine_file`, the one reader, so every check and message
is the command line's; issue 31: the machine file may name only the files uploaded with it, by
base name, and nothing is read from the server's disk), or the modes from a modal test are
typed (frequencies in Hz,
damping ratios, mass-normalised mode-shape values at the contact in 1/sqrt(kg)) with the
operating point; the typed fields become a ``[structure]`` ``modes`` table read by the same
reader. The answers are :func:`stickslip.analysis.machine_absorber.design_machine`'s.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from stickslip.io.machine_file import UPLOAD_MAX_DOF, UPLOAD_MAX_MB

#: The statement of both limits, shown on the page.
LIMITS = (f"Largest model accepted: {UPLOAD_MAX_DOF:,} DOF, {UPLOAD_MAX_MB} MB of files in all "
          "(the command line 'stickslip design --config' takes larger ones).")

#: The typed modal machine's fields: key -> (label, default).
MODE_INPUTS: dict[str, tuple[str, str]] = {
    "frequencies": ("Natural frequencies [Hz], comma-separated", "55, 150"),
    "damping_ratios": ("Damping ratios, comma-separated", "0.03, 0.02"),
    "shapes": ("Mode shapes at the contact [1/sqrt(kg)], mass-normalised", "0.07, 0.03"),
    "mu_s": ("Static friction coefficient mu_s", "0.15"),
    "mu_k": ("Kinetic friction coefficient mu_k", "0.10"),
    "load": ("Normal load W", "2600 N"),
    "speed": ("Belt speed V", "0.5 mm/s"),
}


def _toml_value(text: str) -> str:
    """A typed value as TOML: a number stays a number, anything else a quoted string."""
    try:
        return repr(float(text))
    except ValueError:
        return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _number_list(text: str, label: str) -> str:
    items = [item.strip() for item in str(text).split(",") if item.strip()]
    if not items:
        raise ValueError(f"{label}: give at least one number")
    try:
        return "[" + ", ".join(repr(float(item)) for item in items) + "]"
    except ValueError:
        raise ValueError(f"{label}: {text!r} is not a comma-separated list of numbers") from None


def modes_machine_toml(raw: Mapping[str, str]) -> str:
    """The machine TOML of the typed modes and operating point (:data:`MODE_INPUTS`)."""
    lines = [f"{key} = {_toml_value(str(raw.get(key, '')).strip())}"
             for key in ("mu_s", "mu_k", "load", "speed")]
    modes = ", ".join(f"{key} = {_number_list(raw.get(key, ''), MODE_INPUTS[key][0])}"
                      for key in ("frequencies", "damping_ratios", "shapes"))
    return "\n".join([*lines, "", "[structure]", 'name = "modal model"', f"modes = {{{modes}}}", ""])


def machine_from_files(files: Mapping[str, bytes], toml_name: str | None = None) -> tuple[Any, Any, Any]:
    """``(machine, absorber, reduction)`` of uploaded files: one ``.toml`` and what it names.

    Parameters
    ----------
    files : mapping
        File name -> content. The names are the base names the TOML refers to.
    toml_name : str, optional
        Which file is the machine TOML (default: the one ``.toml`` among them).

    Returns
    -------
    machine, absorber, reduction
        :class:`~stickslip.model.machine.Machine`, the ``[absorber]`` (or None) and the
        reduction of a large model (or None).

    Raises
    ------
    ValueError
        One line: no or several TOML files, or the reader's message (which names the file
        by its base name, never a path of the server; the limits of an upload are
        :data:`~stickslip.io.machine_file.UPLOAD_MAX_MB` and ``UPLOAD_MAX_DOF``).
    """
    from stickslip.io.machine_file import machine_from_file
    from stickslip.model.inputs import quantities_to_si

    machine_file = uploaded_machine_file(files, toml_name)
    toml_name = Path(machine_file.path).name
    if not machine_file.has_structure:
        raise ValueError(f"machine file {toml_name!r} has no [structure] table: the paper's "
                         "slider is entered on the main page")
    values = quantities_to_si({key: machine_file.raw.get(key)
                               for key in ("mu_s", "mu_k", "load", "speed")},
                              source=lambda key: f"machine file {toml_name!r}: {key} =")
    missing = [key for key in ("mu_s", "mu_k", "load", "speed") if key not in values]
    if missing:
        raise ValueError(f"machine file {toml_name!r} lacks {', '.join(missing)}")
    machine, reduction = machine_from_file(machine_file, values)
    absorber = machine_file.absorber()
    return machine, absorber, reduction


def uploaded_machine_file(files: Mapping[str, bytes], toml_name: str | None = None) -> Any:
    """The uploaded machine TOML, read (not yet its matrices): one ``.toml`` among ``files``.

    Parameters
    ----------
    files : mapping
        File name -> content, by base name.
    toml_name : str, optional
        Which file is the machine TOML (default: the one ``.toml`` among them).

    Returns
    -------
    MachineFile
        Named ``machine file 'NAME'`` in messages; it may name only ``files``.

    Raises
    ------
    ValueError
        One line: no or several TOML files, or the reader's message.
    """
    from stickslip.io.machine_file import read_machine_file

    if toml_name is None:
        tomls = [name for name in files if name.lower().endswith(".toml")]
        if len(tomls) != 1:
            raise ValueError(f"upload exactly one machine .toml file with its matrices "
                             f"(got {len(tomls)})")
        toml_name = tomls[0]
    toml_name = Path(toml_name).name
    return read_machine_file(Path(toml_name), label=f"machine file {toml_name!r}", files=files)


def machine_design(machine: Any, absorber: Any, reduction: Any, *, stick_slip: bool = False,
                   progress: Any = None) -> Any:
    """The design report of the machine (:func:`~stickslip.analysis.machine_absorber.design_machine`).

    ``stick_slip`` also finds the absorber that maximises the simulated stick-slip onset
    (many simulations: minutes on a 2-core machine); ``progress(stage, runs)`` is called as
    the work goes on.
    """
    from stickslip.analysis.machine_absorber import design_machine

    attach = None
    if absorber is not None and absorber.attach_dof is not None:
        attach = (absorber.attach_dof if reduction is None
                  else reduction.kept_dofs.index(absorber.attach_dof))
    return design_machine(machine, None if absorber is None else absorber.mass, attach,
                          stick_slip=stick_slip, progress=progress)


def design_in_worker(machine: Any, absorber: Any, reduction: Any, stick_slip: bool) -> Any:
    """:func:`machine_design` run by a worker process of :mod:`stickslip.app.workers`."""
    from stickslip.app.workers import report

    return machine_design(machine, absorber, reduction, stick_slip=stick_slip, progress=report)


def files_digest(files: Mapping[str, bytes]) -> str:
    """A fingerprint of uploaded files (names and contents): the key of their results."""
    import hashlib

    digest = hashlib.sha256()
    for name in sorted(files):
        for part in (name.encode("utf-8"), files[name]):
            digest.update(len(part).to_bytes(8, "little"))
            digest.update(part)
    return digest.hexdigest()


def _absorber_table(report: Any) -> Any:
    """The tuned absorbers side by side (SI), one row per objective."""
    import pandas as pd

    from stickslip.app.figures import fmt

    names = {"hinf": "H-infinity (smallest receptance peak)",
             "stick-slip": "stick-slip (largest stick-slip-free range)"}
    return pd.DataFrame({
        "k [N/m]": [fmt(a.stiffness) for a in report.absorbers],
        "c [N s/m]": [fmt(a.damping) for a in report.absorbers],
        "critical speed V_c [m/s]": [fmt(a.critical.speed) for a in report.absorbers],
        "critical load W_c [N]": [fmt(a.critical.load) for a in report.absorbers],
        "peak receptance [m/N]": [fmt(a.peak_receptance) for a in report.absorbers],
    }, index=[names.get(a.objective, a.objective) for a in report.absorbers])


def show_machine_page() -> None:
    """Lay out the "your machine" page (Streamlit)."""
    import streamlit as st

    from stickslip.analysis.machine_absorber import ONSET_NOTE
    from stickslip.app.figures import cached_png
    from stickslip.app.machine_bifurcation import show_machine_bifurcation
    from stickslip.app.machine_contact import show_contact_machine
    from stickslip.app.messages import show_failure
    from stickslip.app.workers import wait_for
    from stickslip.plot.operating import machine_modes_plot

    st.title("Your machine: any linear structure, the contact on any DOF")
    st.caption("Upload the machine TOML of 'stickslip design --config' with the matrix files it "
               "names (.mtx, .npy, .csv), or type the modes of a modal test at the contact. "
               "The machine file may name only the files uploaded with it, by their names "
               "without folders. " + LIMITS)
    source = st.radio("Structure from", ("typed modes", "uploaded files"), key="machine_source",
                      horizontal=True)
    try:
        if source == "uploaded files":
            uploads = st.file_uploader("Machine file and matrices", accept_multiple_files=True,
                                       type=["toml", "mtx", "npy", "csv"], key="machine_files")
            if not uploads:
                st.info("Nothing is computed until the machine .toml and its files are uploaded.")
                return
            files = {str(u.name): u.getvalue() for u in uploads}
            machine_file = uploaded_machine_file(files)
            if machine_file.has_contact:  # its own analyses, each with its own messages
                show_contact_machine(machine_file, files_digest(files))
                return
            if machine_file.has_memory_law:  # the design report of its own law
                from stickslip.app.memory_page import show_memory_machine

                show_memory_machine(machine_file, files_digest(files))
                return
        else:
            raw = {key: st.text_input(label, value=default, key=f"machine_{key}")
                   for key, (label, default) in MODE_INPUTS.items()}
            files = {"modes.toml": modes_machine_toml(raw).encode("utf-8")}
        machine, absorber, reduction = machine_from_files(files)
        digest = files_digest(files)
        report = wait_for(("machine", digest, False), design_in_worker, machine, absorber,
                          reduction, False, what="Designing the machine")
    except Exception as exc:
        show_failure(exc, "The design of this machine")
        return
    st.subheader("Verdict at the operating point")
    st.text(report.summary())
    if reduction is not None:
        st.caption(reduction.summary())
    if report.absorbers:
        st.subheader("Absorbers")
        asked = st.session_state.get("stick_slip_absorber") == digest
        if not asked and st.button("Find the stick-slip absorber too (many simulations: "
                                   "minutes)", key="find_stick_slip_absorber"):
            st.session_state["stick_slip_absorber"] = digest
            asked = True
        if asked:
            try:
                report = wait_for(("machine", digest, True), design_in_worker, machine,
                                  absorber, reduction, True, what="Searching the stick-slip absorber")
            except Exception as exc:
                show_failure(exc, "The stick-slip absorber search")
        st.dataframe(_absorber_table(report), key="absorber_table")
        st.caption(f"Absorber mass {report.absorbers[0].mass:.4g} kg on "
                   + ("the foundation (the machine mounted on it)"
                      if report.absorbers[0].attach_dof is None
                      else f"DOF {absorber.attach_dof} of the file")
                   + ". H-infinity: the smallest peak of the receptance at the contact; "
                   "stick-slip: the largest range of belt speeds and loads without stick-slip "
                   "(simulated onset, the machine's friction law). " + ONSET_NOTE + ".")
    payload = report.to_dict()
    st.image(cached_png(("modes", digest),
                        lambda: machine_modes_plot(machine, reduction=reduction).figure))
    show_machine_bifurcation(machine, digest)
    st.download_button("Design report (JSON)", __import__("json").dumps(payload, indent=2, default=str),
                       file_name="stickslip-machine.json", mime="application/json",
                       key="download_machine_json", on_click="ignore")
