"""The web app's "identify from a record" page: ``stickslip identify`` in a browser (issue 31).

Upload a measured stick-slip record (CSV: time and force and/or displacement, the format of
``stickslip identify``), give the slider mass, the normal load and the belt speed, choose the
friction law; the page shows the fitted stiffness, damping and friction law with their
standard errors (:meth:`~stickslip.analysis.identification.result.IdentificationResult.summary`),
the fit figure, and the machine file of ``--write-config``, which it downloads or takes on to
the slider page. The fit is :func:`stickslip.analysis.identification.record_fit.identify` on the record
read by :func:`stickslip.io.record.record_from_text` (the command line's reader, from memory:
nothing of the upload is written to the server's disk), in a worker process
(:mod:`stickslip.app.workers`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

#: The largest record accepted here, bytes (the command line reads up to 1 GiB).
MAX_RECORD_MB = 20
#: Laws offered, as ``stickslip identify --law``.
LAWS = ("coulomb", "linear", "stribeck", "auto")
#: Widget key -> (label, default) of the known quantities (those of the example record).
KNOWN_INPUTS: dict[str, tuple[str, str]] = {
    "m": ("Slider mass m", "1 kg"),
    "load": ("Normal load W", "100 N"),
    "speed": ("Belt speed V", "5 cm/s"),
}
#: Friction-law fields of the slider page set from a fit (its ``[friction]`` keys).
_FIT_TO_SLIDER = {"linear": ("slope",), "stribeck": ("stribeck_velocity", "exponent", "viscous")}


def identify_upload(content: bytes, name: str, known_text: Mapping[str, str], law: str,
                    columns: str) -> Any:
    """The fit of an uploaded record (what ``stickslip identify`` prints), or one-line ``ValueError``.

    Parameters
    ----------
    content : bytes
        The CSV file.
    name : str
        Its name (messages give its base name only).
    known_text : mapping
        ``m``, ``load``, ``speed`` as typed, with units.
    law : str
        One of :data:`LAWS`.
    columns : str
        The ``--columns`` text (empty: from the header's names).

    Returns
    -------
    IdentificationResult
    """
    from pathlib import PurePath

    from stickslip.analysis.identification.record_fit import identify
    from stickslip.io.record import parse_columns, record_from_text
    from stickslip.model.units import to_si

    if len(content) > MAX_RECORD_MB * 1024**2:
        raise ValueError(f"the record holds {len(content) / 1024**2:.1f} MB, beyond the "
                         f"{MAX_RECORD_MB} MB accepted here")
    if law not in LAWS:
        raise ValueError(f"friction law {law!r} is not one of {', '.join(LAWS)}")
    known = {}
    for key, (label, _) in KNOWN_INPUTS.items():
        known[key] = to_si(key, str(known_text.get(key, "")).strip(), source=f"{label}:")
        if not known[key] > 0.0:
            raise ValueError(f"{label}: {known_text.get(key)!r} must be positive")
    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError(f"record {PurePath(name).name!r} is not UTF-8 text") from None
    spec = parse_columns(columns) if columns.strip() else None
    record = record_from_text(text, PurePath(name).name, spec)
    return identify(record, known, law=law)


def slider_inputs(result: Any) -> dict[str, str]:
    """The slider page's fields (widget key -> text with units) of a fitted record: the
    values ``--write-config`` writes."""
    values = {name: (p.value if p.value is not None else p.estimate)
              for name, p in result.parameters.items()}
    fields = {"m": f"{result.mass!r} kg", "k": f"{values['k']!r} N/m",
              "c": f"{max(values['c'], 0.0)!r} N*s/m", "mu_s": repr(values["mu_s"]),
              "mu_k": repr(values["mu_k"]), "load": f"{result.load!r} N",
              "speed": f"{result.speed!r} m/s", "m_a": "", "k_a": "", "c_a": "",
              "friction_law": result.law if result.law in ("coulomb", *_FIT_TO_SLIDER) else "coulomb"}
    units = {"slope": "s/m", "stribeck_velocity": "m/s", "exponent": "", "viscous": "s/m"}
    for key in _FIT_TO_SLIDER.get(result.law, ()):
        fields[key] = f"{values[key]!r} {units[key]}".strip()
    if result.law == "stribeck":
        fields["mu_0"] = ""  # mu_0 = mu_s, as --write-config writes it
    return fields


def _fit_in_worker(content: bytes, name: str, known_text: tuple[tuple[str, str], ...], law: str,
                   columns: str) -> Any:
    """:func:`identify_upload` in a worker process of :mod:`stickslip.app.workers`."""
    return identify_upload(content, name, dict(known_text), law, columns)


def _take_to_slider(fields: Mapping[str, str]) -> None:
    """Button callback: fill the slider page with the fit and open it."""
    import streamlit as st

    for key, value in fields.items():
        st.session_state[key] = value
    st.session_state["page"] = "paper's slider"


def show_identify_page() -> None:
    """Lay out the "identify from a record" page (Streamlit)."""
    import hashlib

    import streamlit as st

    from stickslip.app.figures import cached_png
    from stickslip.app.messages import show_error, show_failure, show_warning
    from stickslip.app.workers import wait_for

    st.title("Identify the machine from a measured record")
    st.caption("Upload a stick-slip record as CSV (time and the spring force and/or the slider "
               "displacement, units in the header, e.g. 't [s],x [mm],F [N]'; the format of "
               "'stickslip identify'), and give what is known. The fit gives k, c and the "
               f"friction law with standard errors. Largest record: {MAX_RECORD_MB} MB.")
    upload = st.file_uploader("Record (CSV)", type=["csv"], key="record_file")
    known_text = {key: st.text_input(label, value=default, key=f"identify_{key}")
                  for key, (label, default) in KNOWN_INPUTS.items()}
    law = str(st.selectbox("Friction law to fit", LAWS, key="identify_law"))
    columns = st.text_input("Columns (optional, as --columns: t,x,F or 't=time:ms,F=-load:kN')",
                            value="", key="identify_columns")
    if upload is None:
        st.info("Nothing is computed until a record is uploaded.")
        return
    content = upload.getvalue()
    name = str(upload.name)
    known = tuple(sorted(known_text.items()))
    key = ("identify", hashlib.sha256(content).hexdigest(), name, known, law, columns)
    try:
        result = wait_for(key, _fit_in_worker, content, name, known, law, columns,
                          what="Fitting the record")
    except Exception as exc:
        show_failure(exc, "The fit of this record")
        return
    for warning in result.warnings:
        show_warning(warning)
    st.subheader(f"Fit: {result.law} law")
    st.text(result.summary())
    st.image(cached_png(key, lambda: result.plot().figure))
    try:
        config = result.to_config()
    except ValueError as exc:
        show_error(str(exc))
        return
    col1, col2 = st.columns(2)
    col1.download_button("Machine file (TOML, as --write-config)", config,
                         file_name="machine.toml", mime="application/toml",
                         key="download_identified_toml", on_click="ignore")
    col2.button("Take these values to the slider page", key="identified_to_slider",
                on_click=_take_to_slider, args=(slider_inputs(result),))
