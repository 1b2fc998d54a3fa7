"""The web app's inputs: its text fields, their parsing into a physical system, cache keys.

The fields are the quantities of ``stickslip design`` and its TOML file (the ``[system]`` and
``[friction]`` tables), parsed by the same functions
(:mod:`stickslip.model.inputs`): the app names a bad value by its field's label instead of a
flag, and reports every bad field at once. No Streamlit here: the page is
:mod:`stickslip.app.streamlit_app`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from stickslip.model.friction_input import friction_csv_columns
from stickslip.model.inputs import (
    FRICTION_FIELDS,
    FRICTION_LAWS,
    InputProblems,
    friction_fields,
    missing_system_quantities,
    quantities_to_si,
)
from stickslip.model.physical import PhysicalFoundation, PhysicalFriction, PhysicalSystem

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
#: Widget key -> (label, default text) of the friction fields; the keys are those of the
#: ``[friction]`` table (``FRICTION_QUANTITIES`` of ``to_si``). ``mu_0`` may stay empty (= mu_s).
FRICTION_INPUTS: dict[str, tuple[str, str]] = {
    "slope": ("Friction slope σ (μ = μk − σ v_r)", "0.02 s/m"),
    "mu_0": ("μ0 at vanishing sliding speed (empty: μs)", ""),
    "stribeck_velocity": ("Stribeck velocity v_s", "0.5 m/s"),
    "exponent": ("Stribeck exponent n", "1"),
    "viscous": ("Viscous slope σ_v", "0 s/m"),
}
#: Widget keys of the uploaded friction curve (its text and file name, in ``raw``).
FRICTION_TABLE = "friction_table"
FRICTION_TABLE_NAME = "friction_table_name"

SiKey = tuple[tuple[str, Any], ...]
FoundationKey = tuple[float, float, float]

__all__ = [
    "DEFAULTS",
    "FOUNDATION_INPUTS",
    "FRICTION_FIELDS",
    "FRICTION_INPUTS",
    "FRICTION_LAWS",
    "FRICTION_TABLE",
    "FRICTION_TABLE_NAME",
    "SYSTEM_INPUTS",
    "FoundationKey",
    "SiKey",
    "parse_friction_inputs",
    "parse_inputs",
    "si_key",
    "system_from_key",
]


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
    labels = {key: label for key, (label, _) in (SYSTEM_INPUTS | FOUNDATION_INPUTS).items()}
    texts = {key: str(raw.get(key, "")).strip() for key in labels}
    _, partial_foundation = missing_system_quantities(texts)
    if partial_foundation:
        errors.append("An existing foundation needs all of m_a, k_a and c_a (leave all three "
                      "empty to have one recommended)")
    given_foundation = [] if partial_foundation else [k for k in FOUNDATION_INPUTS if texts[k]]
    errors += [f"{labels[key]} is empty" for key in SYSTEM_INPUTS if not texts[key]]
    values: dict[str, float] = {}
    try:
        values = quantities_to_si({key: texts[key] for key in [*SYSTEM_INPUTS, *given_foundation]},
                                  source=lambda key: f"{labels[key]}:")
    except InputProblems as exc:
        errors += [message for _, message in exc.problems]
    friction, friction_errors = parse_friction_inputs(raw)
    errors += friction_errors
    if errors or friction is None:
        return None, errors
    if friction.mu_0 is not None and friction.mu_0 > values["mu_s"]:  # in the app's words
        return None, [f"{FRICTION_INPUTS['mu_0'][0]}: {friction.mu_0:g} is above μs = "
                      f"{values['mu_s']:g} (friction at vanishing speed is at most static friction)"]
    try:
        foundation = None
        if given_foundation:
            foundation = PhysicalFoundation(values["m_a"], values["k_a"], values["c_a"])
        system = PhysicalSystem(mass=values["m"], stiffness=values["k"], damping=values["c"],
                                mu_s=values["mu_s"], mu_k=values["mu_k"], load=values["load"],
                                speed=values["speed"],
                                foundation=foundation, friction=friction)
    except ValueError as exc:
        return None, [f"Invalid input: {exc}"]
    try:
        system.slider()  # the law in the engine's units: mu >= 0, ...
    except ValueError as exc:
        return None, ["Friction law: " + " ".join(str(exc).split())]
    return system, []


def parse_friction_inputs(raw: Mapping[str, str]) -> tuple[PhysicalFriction | None, list[str]]:
    """The friction law of the inputs in SI units, or one error line per bad friction field.

    Only the fields of the chosen law are read (:data:`FRICTION_FIELDS`); they go through
    :func:`stickslip.model.inputs.friction_fields`, the parser of the ``[friction]`` table of
    ``stickslip design``. The uploaded curve is read by
    :func:`stickslip.model.friction.friction_csv_columns`, as a curve file is.
    """
    law = str(raw.get("friction_law", "coulomb") or "coulomb").strip().lower()
    if law not in FRICTION_LAWS:
        return None, [f"Friction law {law!r} is not one of {', '.join(FRICTION_LAWS)}"]
    errors: list[str] = []
    fields: dict[str, str] = {}
    for key in FRICTION_FIELDS[law]:
        text = str(raw.get(key, "")).strip()
        if text:
            fields[key] = text
        elif key != "mu_0":  # mu_0 may stay empty: mu_s
            errors.append(f"{FRICTION_INPUTS[key][0]} is empty")
    columns = None
    if law == "table":
        name = str(raw.get(FRICTION_TABLE_NAME, "") or "(uploaded)")
        text = str(raw.get(FRICTION_TABLE, ""))
        if not text.strip():
            errors.append("Friction table: upload a CSV file with columns v [m/s] and mu")
        else:
            try:  # its rules and messages (a header, units, an f column) are the file's
                columns = friction_csv_columns(text, name)
            except ValueError as exc:
                errors.append("Friction table: " + " ".join(str(exc).split()))
    try:
        values = friction_fields({"law": law, **fields}, table_columns=columns,
                                 source=lambda key: f"{FRICTION_INPUTS[key][0]}:")
    except InputProblems as exc:
        errors += [message for _, message in exc.problems]
    if errors:
        return None, errors
    try:
        return PhysicalFriction(**values), []
    except ValueError as exc:
        return None, ["Friction law: " + " ".join(str(exc).split())]


def si_key(system: PhysicalSystem) -> SiKey:
    """The SI inputs as a hashable key for the caches."""
    items: list[tuple[str, Any]] = [
        ("m", system.mass), ("k", system.stiffness), ("c", system.damping), ("mu_s", system.mu_s),
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
    return PhysicalSystem(mass=v["m"], stiffness=v["k"], damping=v["c"], mu_s=v["mu_s"], mu_k=v["mu_k"],
                          load=v["load"], speed=v["speed"], foundation=foundation,
                          friction=friction)
