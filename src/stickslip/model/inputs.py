"""Physical inputs as text: one parser for the command line, its TOML file and the web app.

A machine is given as quantities with units ("2 kg", "50 kN/m") for the system (the
``[system]`` table) and the fields of a friction law (the ``[friction]`` table).
``stickslip design`` and ``stickslip basin --config`` read them from flags and a TOML file
(:mod:`stickslip.io.config` reads the file), the web app from its text fields; all of them
turn the values into SI floats and a :class:`~stickslip.model.physical.PhysicalFriction` here,
so the rules (units, which fields a law takes, what is missing) are written once. This module
returns SI values; :func:`stickslip.model.physical.physical_friction_from_config` and the
callers build the physical objects from them.

Each caller says where a value came from with ``source(key)``, the prefix of its messages
(``"--m"``, ``"--config 'machine.toml': m ="``, ``"Slider mass m:"``); every bad value is
reported, not only the first (:class:`InputProblems`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

from stickslip.model.units import FRICTION_QUANTITIES, QUANTITIES, to_si

#: Quantities of the system (the ``[system]`` table), in the order they are asked for.
SYSTEM_QUANTITIES = ("m", "k", "c", "mu_s", "mu_k", "load", "speed")
#: The system quantities without a default (``c`` is 0 when not given).
REQUIRED_QUANTITIES = ("m", "k", "mu_s", "mu_k", "load", "speed")
#: An existing foundation: all three or none.
FOUNDATION_QUANTITIES = ("m_a", "k_a", "c_a")
#: The friction laws of the ``law`` key, the paper's first.
FRICTION_LAWS = ("coulomb", "linear", "stribeck", "table")
#: The quantities each law reads (others are ignored by the app; ``mu_0`` may be absent =
#: ``mu_s``; ``tolerance`` is optional for ``stribeck``).
FRICTION_FIELDS: dict[str, tuple[str, ...]] = {
    "coulomb": (),
    "linear": ("slope",),
    "stribeck": ("mu_0", "stribeck_velocity", "exponent", "viscous"),
    "table": (),
}

#: Keys of the ``[friction]`` table each law takes (besides ``law``); any other is refused
#: (issue 22 point 2: a ``slope`` under ``law = "coulomb"`` is a mistake, not a no-op).
LAW_KEYS: dict[str, frozenset[str]] = {
    "coulomb": frozenset(),
    "linear": frozenset({"slope"}),
    "stribeck": frozenset({"mu_0", "stribeck_velocity", "exponent", "viscous", "tolerance"}),
    "table": frozenset({"table"}),
}

#: Keys a law cannot do without (the others have a documented default), with an example each.
LAW_REQUIRED: dict[str, frozenset[str]] = {"linear": frozenset({"slope"}),
                                           "stribeck": frozenset({"stribeck_velocity"})}
LAW_EXAMPLES = {"slope": '"0.02 s/m"', "stribeck_velocity": '"5 mm/s"'}

#: Friction laws with memory (the smooth stiff engine): their ``[friction]`` keys are read by
#: :mod:`stickslip.model.state_friction_input`.
MEMORY_LAWS = ("rate-state", "lugre")

Source = Callable[[str], str | None]


class InputProblems(ValueError):
    """Every bad input at once: ``problems`` holds ``(key, one-line message)`` pairs.

    ``str()`` joins the messages with ``"; "``, so a caller that shows one line (the command
    line) shows them all, and one problem reads exactly as its message.
    """

    def __init__(self, problems: Sequence[tuple[str, str]]) -> None:
        self.problems: tuple[tuple[str, str], ...] = tuple(problems)
        super().__init__("; ".join(message for _, message in self.problems))


def is_given(value: Any) -> bool:
    """A value was given: not ``None`` and not an empty (or blank) string.

    Parameters
    ----------
    value : object
        A field's value as given (a number, text, or ``None``).

    Returns
    -------
    bool
        True when the value counts as given.
    """
    return value is not None and not (isinstance(value, str) and not value.strip())


def quantities_to_si(values: Mapping[str, Any], *, source: Source | None = None) -> dict[str, float]:
    """Every given value of ``values`` (keys of ``QUANTITIES`` or ``FRICTION_QUANTITIES``) in SI.

    Parameters
    ----------
    values : mapping
        Quantity name -> number (SI) or text with an optional unit. Values that are not given
        (:func:`is_given`) are skipped.
    source : callable, optional
        ``source(key)``: where the value came from, the prefix of its error message (default
        :func:`~stickslip.model.units.to_si`'s own).

    Returns
    -------
    dict
        Quantity name -> value in SI units, for every given value.

    Raises
    ------
    InputProblems
        One message per bad value (wrong unit, not a number, not finite).

    Returns
    -------
    dict of str to float
        The given values in SI units (kg, N/m, N s/m, N, m/s, s/m), by quantity name.
    """
    out: dict[str, float] = {}
    problems: list[tuple[str, str]] = []
    for key, value in values.items():
        if not is_given(value):
            continue
        if key not in QUANTITIES and key not in FRICTION_QUANTITIES:
            raise ValueError(f"{key!r} is not a physical quantity of the model")
        try:
            out[key] = to_si(key, value.strip() if isinstance(value, str) else value,
                             source=None if source is None else source(key))
        except ValueError as exc:
            problems.append((key, str(exc)))
    if problems:
        raise InputProblems(problems)
    return out


def missing_system_quantities(values: Mapping[str, Any]) -> tuple[list[str], list[str]]:
    """The required system quantities not given, and the foundation ones given (if not all).

    Parameters
    ----------
    values : mapping
        Quantity name -> value as given (:func:`is_given` decides what counts).

    Returns
    -------
    missing : list of str
        Keys of :data:`REQUIRED_QUANTITIES` without a value.
    partial_foundation : list of str
        The keys of :data:`FOUNDATION_QUANTITIES` that are given when some, but not all three,
        are (else empty).
    """
    missing = [key for key in REQUIRED_QUANTITIES if not is_given(values.get(key))]
    given = [key for key in FOUNDATION_QUANTITIES if is_given(values.get(key))]
    return missing, (given if given and len(given) != len(FOUNDATION_QUANTITIES) else [])


def law_name(table: Mapping[str, Any], where: str) -> str:
    """The ``law`` of a ``[friction]`` table, lower case (``coulomb`` when absent).

    Parameters
    ----------
    table : mapping
        The ``[friction]`` table.
    where : str
        Where it comes from, for the message.

    Returns
    -------
    str
        One of :data:`LAW_KEYS` or :data:`MEMORY_LAWS`.

    Raises
    ------
    InputProblems
        Not a string, or not a law this package has (the message names it and the laws).
    """
    law = table.get("law", "coulomb")
    if not isinstance(law, str):
        raise InputProblems([("law", f"{where}: law = {law!r} must be a string")])
    name = law.strip().lower()
    if name not in LAW_KEYS and name not in MEMORY_LAWS:
        raise InputProblems([("law", f"{where}: law = {law!r} is not one of "
                                     f"{', '.join((*LAW_KEYS, *MEMORY_LAWS))}")])
    return name


def friction_fields(table: Mapping[str, Any], *, source: Source | None = None,
                    table_columns: tuple[Sequence[float], Sequence[float]] | None = None,
                    where: str = "[friction]") -> dict[str, Any]:
    """The friction law of a ``[friction]`` table (or the app's fields) in SI units.

    Returns the keyword arguments of :class:`~stickslip.model.physical.PhysicalFriction`
    (``law``, the given quantities in SI, ``table_v`` and ``table_mu``), which checks the
    law's name and that a ``table`` law has its curve.

    Parameters
    ----------
    table : mapping
        ``law`` (one of :data:`FRICTION_LAWS`, default ``coulomb``) and quantities of
        ``FRICTION_QUANTITIES`` (``slope`` s/m, ``mu_0``, ``stribeck_velocity`` m/s,
        ``exponent``, ``viscous`` s/m, ``tolerance``), numbers or text with units. A ``table``
        key (a file name) is allowed here and ignored: the file's columns come in
        ``table_columns``, read by the caller (:mod:`stickslip.io.config` for a TOML file).
    source : callable, optional
        ``source(key)``, the prefix of a value's error message.
    table_columns : (v, mu), optional
        The measured curve of the ``table`` law: sliding speeds [m/s] and friction
        coefficients.
    where : str
        Names the table in messages about the table itself (unknown keys, the law).

    Returns
    -------
    dict
        Keyword arguments of :class:`~stickslip.model.physical.PhysicalFriction`.

    Raises
    ------
    InputProblems
        Unknown keys, keys that do not belong to the law (:data:`LAW_KEYS`), a law that is
        not a string, and every bad value.
    ValueError
        ``table`` is not a mapping.

    Returns
    -------
    dict
        Keyword arguments of :class:`~stickslip.model.physical.PhysicalFriction`.
    """
    if not isinstance(table, Mapping):
        raise ValueError(f"{where} must be a table of keys, not {table!r}")
    unknown = sorted(set(table) - set(FRICTION_QUANTITIES) - {"law", "table"})
    if unknown:
        raise InputProblems([("law", f"{where}: unknown keys {', '.join(unknown)} (allowed: law, "
                                     f"table, {', '.join(FRICTION_QUANTITIES)})")])
    values: dict[str, Any] = {"law": law_name(table, where)}
    allowed = LAW_KEYS.get(values["law"])
    if allowed is not None:
        foreign = sorted(set(table) - allowed - {"law"})
        if foreign:
            raise InputProblems([(foreign[0], f"{where}: {', '.join(foreign)} = {table[foreign[0]]!r} "
                                              f"does not belong to the {values['law']} law (its "
                                              f"keys: {', '.join(sorted(allowed)) or 'none'})")])
    missing = sorted(LAW_REQUIRED.get(values["law"], frozenset()) - set(table))
    if missing:  # a silent default (slope 0, v_s = 1 m/s) would answer for another machine
        raise InputProblems([(missing[0], f"{where}: law = {values['law']!r} needs "
                                          f"{', '.join(missing)}, e.g. {missing[0]} = "
                                          f"{LAW_EXAMPLES[missing[0]]}")])
    values.update(quantities_to_si({key: table[key] for key in FRICTION_QUANTITIES if key in table},
                                   source=source))
    if table_columns is not None:
        values["table_v"], values["table_mu"] = (tuple(float(x) for x in column)
                                                 for column in table_columns)
    return values
