"""Friction laws with memory from text: the machine file's ``[friction]`` table, speed
schedules and the dimensionless ``--friction rate-state:...`` / ``lugre:...`` syntax.

The laws and the system live in :mod:`stickslip.model.state_friction`; this module only turns
what a user writes into them, with one-line errors that name the key and the value.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from stickslip.model.inputs import MEMORY_LAWS
from stickslip.model.state_friction import (
    MAX_SCHEDULE_STEPS,
    LuGreFriction,
    MemorySystem,
    RateStateFriction,
    SpeedSchedule,
    StateFriction,
)

#: Keys of ``[friction]`` for each memory law: key -> (quantity name for units, or None).
RATE_STATE_KEYS = {"a": "a", "b": "b", "d_c": "d_c", "mu_ref": "mu_ref", "v_ref": "v_ref",
                   "evolution": None}
LUGRE_KEYS = {"sigma0": "sigma0", "sigma1": "sigma1", "sigma2": "sigma2", "mu_c": "mu_c",
              "mu_s": "lugre_mu_s", "stribeck_velocity": "lugre_stribeck_velocity"}


def state_friction_from_table(table: dict[str, Any], *, source: str = "[friction]") -> StateFriction:
    """A memory law from a machine file's ``[friction]`` table (values may carry units).

    ``law = "rate-state"``: ``a``, ``b``, ``d_c`` (a length), ``mu_ref``, ``v_ref`` (a speed),
    ``evolution`` (``"aging"``, the default, or ``"slip"``). ``law = "lugre"``: ``sigma0``
    (N/m), ``sigma1``, ``sigma2`` (N s/m), ``mu_c``, ``mu_s``, ``stribeck_velocity`` (m/s).
    Every problem is one ``ValueError`` line naming ``source``, the key and the value.

    Parameters
    ----------
    table : dict
        The ``[friction]`` table.
    source : str
        How messages name it.

    Returns
    -------
    RateStateFriction or LuGreFriction
        The law, SI.
    """
    from stickslip.model.units import to_si

    law = str(table.get("law", "")).strip().lower()
    keys = RATE_STATE_KEYS if law == "rate-state" else LUGRE_KEYS
    unknown = sorted(set(table) - set(keys) - {"law"})
    if unknown:
        raise ValueError(f"{source}: unknown keys {', '.join(unknown)} for law = {law!r} "
                         f"(allowed: {', '.join(keys)})")
    required = [k for k in keys if k != "evolution" and k not in table]
    if required:
        raise ValueError(f"{source}: law = {law!r} needs {', '.join(required)}")
    values: dict[str, Any] = {}
    for key, quantity in keys.items():
        if key not in table:
            continue
        if key == "evolution":
            values[key] = str(table[key]).strip().lower()
            continue
        assert quantity is not None
        values[key] = to_si(quantity, table[key], source=f"{source}: {key} =")
    try:
        if law == "rate-state":
            return RateStateFriction(**values)
        return LuGreFriction(**values)
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None


#: Keys of ``rate-state:...`` and ``lugre:...`` on the dimensionless command line.
DIMENSIONLESS_KEYS = {
    "rate-state": {"a": "a", "b": "b", "dc": "d_c", "mu_ref": "mu_ref", "vref": "v_ref",
                   "evolution": "evolution"},
    "lugre": {"sigma0": "sigma0", "sigma1": "sigma1", "sigma2": "sigma2", "mu_c": "mu_c",
              "mu_s": "mu_s", "vs": "stribeck_velocity"},
}


def parse_state_friction(kind: str, arg: str, raw: str) -> StateFriction:
    """``rate-state:a=..,b=..,dc=..,mu_ref=..,vref=..[,evolution=slip]`` or ``lugre:...``.

    Dimensionless: the system in units of the slider (``m = k = 1``, drive speed ``V = 1``),
    so ``dc`` is ``d_c`` in ``V / omega_n``, ``vref`` and ``vs`` are in ``V``, ``sigma0`` in
    ``k`` and ``sigma1``, ``sigma2`` in ``sqrt(m k)``; the normal load is ``--lam`` in
    ``V sqrt(m k)`` (for these laws ``lambda = W / (V sqrt(m k))``, the load number).

    Parameters
    ----------
    kind : str
        ``rate-state`` or ``lugre``.
    arg : str
        The comma-separated ``key=value`` list.
    raw : str
        The whole text, for messages.

    Returns
    -------
    RateStateFriction or LuGreFriction
        The law (numbers in the units above).
    """
    names = DIMENSIONLESS_KEYS[kind]
    values: dict[str, Any] = {}
    for item in arg.split(","):
        key, eq, value = item.partition("=")
        key = key.strip().lower()
        if not eq or key not in names:
            raise ValueError(f"friction law {raw!r}: {item.strip()!r} is not one of "
                             f"{', '.join(k + '=...' for k in names)}")
        if names[key] in values:
            raise ValueError(f"friction law {raw!r}: key {key!r} given twice")
        if key == "evolution":
            values[names[key]] = value.strip().lower()
            continue
        try:
            values[names[key]] = float(value)
        except ValueError:
            raise ValueError(f"friction law {raw!r}: {key}={value.strip()!r} is not a number") from None
    missing = [k for k, field in names.items() if k != "evolution" and field not in values]
    if missing:
        raise ValueError(f"friction law {raw!r}: {kind} needs {', '.join(k + '=...' for k in missing)}")
    try:
        if kind == "rate-state":
            return RateStateFriction(**values)
        return LuGreFriction(**values)
    except ValueError as exc:
        raise ValueError(f"friction law {raw!r}: {exc}") from None


def is_memory_law(friction_table: Any) -> bool:
    """True when a ``[friction]`` table names a law with memory (``rate-state``, ``lugre``).

    Parameters
    ----------
    friction_table : object
        A ``[friction]`` table (or None).

    Returns
    -------
    bool
        Whether its ``law`` is ``rate-state`` or ``lugre``.
    """
    return (isinstance(friction_table, dict) and isinstance(friction_table.get("law"), str)
            and friction_table["law"].strip().lower() in MEMORY_LAWS)


def speed_schedule_from_config(value: Any, *, source: str) -> SpeedSchedule:
    """``speed = "5 um/s"`` or a schedule ``[["0 s", "1 um/s"], ["10 s", "10 um/s"]]``.

    Each row is a time (from which the speed holds) and a load-point speed, with units; the
    first time is 0 s. One ``ValueError`` line names the bad entry.

    Parameters
    ----------
    value : str, float or list
        One speed or a list of ``[time, speed]`` pairs.
    source : str
        How messages name the key.

    Returns
    -------
    SpeedSchedule
        The drive speeds, SI.
    """
    from stickslip.model.units import to_si

    if not isinstance(value, list):
        return SpeedSchedule.constant(_positive_speed(to_si("speed", value, source=f"{source} ="),
                                                      value, source))
    if len(value) > MAX_SCHEDULE_STEPS:  # before any row is parsed
        raise ValueError(f"{source} has {len(value)} rows, more than the {MAX_SCHEDULE_STEPS} "
                         "steps a schedule takes")
    times: list[float] = []
    speeds: list[float] = []
    for i, row in enumerate(value):
        if not isinstance(row, list) or len(row) != 2:
            raise ValueError(f"{source}[{i}] = {row!r} must be a pair [time, speed], e.g. "
                             "[\"10 s\", \"10 um/s\"]")
        times.append(to_si("time", row[0], source=f"{source}[{i}] time ="))
        speed = to_si("speed", row[1], source=f"{source}[{i}] speed =")
        if 0 < i < len(value) - 1 and speed == 0.0:
            speeds.append(speed)  # a hold (slide-hold-slide): only between slides
            continue
        speeds.append(_positive_speed(speed, row[1], f"{source}[{i}] speed", in_schedule=True))
    try:
        return SpeedSchedule(tuple(times), tuple(speeds))
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None


def _positive_speed(v: float, raw: Any, source: str, *, in_schedule: bool = False) -> float:
    if v > 0.0:
        return v
    if in_schedule and v == 0.0:
        raise ValueError(f"{source} = {raw!r}: the first and the last speed of a schedule must be "
                         "positive (runs start from steady sliding at the first, verdicts are "
                         "about the last); 0, a hold, only between two slides")
    hold = "; a schedule may hold at 0 between two slides" if in_schedule else ""
    raise ValueError(f"{source} = {raw!r} must be positive (the drive moves forwards){hold}")


#: Flat keys a machine file with a memory law may give.
MEMORY_SYSTEM_KEYS = ("m", "k", "c", "load", "speed", "m_a", "k_a", "c_a")


def memory_system_from_config(raw: dict[str, Any], friction_table: dict[str, Any], *,
                              label: str, structure: tuple[Any, Any, Any, int] | None = None,
                              ) -> MemorySystem:
    """The :class:`MemorySystem` of a machine file whose ``[friction]`` has memory.

    ``raw``: the flat quantities as written (``m``, ``k``, ``c``, ``load``, ``speed``, and
    ``m_a``, ``k_a``, ``c_a`` for a foundation under the slider); ``m = "0 kg"`` selects the
    quasi-static slider. ``speed`` may be a schedule (:func:`speed_schedule_from_config`).
    ``structure``: ``(mass, damping, stiffness, contact_dof)`` in SI from a ``[structure]``
    table instead of ``m``, ``k``, ``c``. ``mu_s`` and ``mu_k`` belong to the curve laws and
    are refused here (the memory laws carry their own coefficients).

    Parameters
    ----------
    raw : dict
        The flat quantities as written.
    friction_table : dict
        The ``[friction]`` table.
    label : str
        How messages name the file.
    structure : tuple, optional
        ``(mass, damping, stiffness, contact_dof)`` of a ``[structure]``, SI.

    Returns
    -------
    MemorySystem
        The system, SI.
    """
    from stickslip.model.units import to_si

    law = state_friction_from_table(friction_table, source=f"{label}: [friction]")
    foreign = [key for key in ("mu_s", "mu_k") if key in raw]
    if foreign:
        raise ValueError(f"{label}: {', '.join(foreign)} belong to the curve laws; law = "
                         f"{law.law!r} takes its own coefficients in [friction] "
                         + ("(mu_ref, a, b)" if law.law == "rate-state" else "(mu_c, mu_s)"))
    for key in ("load", "speed"):
        if key not in raw:
            raise ValueError(f"{label} lacks {key} (e.g. {key} = "
                             + ("\"10 N\")" if key == "load" else "\"1 um/s\")"))
    load = to_si("load", raw["load"], source=f"{label}: load =")
    if not load > 0.0:
        raise ValueError(f"{label}: load = {raw['load']!r} must be positive")
    schedule = speed_schedule_from_config(raw["speed"], source=f"{label}: speed")
    if structure is not None:
        mass, damping, stiffness, contact = structure
    else:
        for key in ("m", "k"):
            if key not in raw:
                raise ValueError(f"{label} lacks {key} (the slider's mass and stiffness, e.g. "
                                 "m = \"1 kg\", k = \"2 N/m\")")
        si = {key: to_si(key, raw[key], source=f"{label}: {key} =")
              for key in MEMORY_SYSTEM_KEYS if key in raw and key not in ("load", "speed")}
        for key in ("m", "k", "c", "m_a", "k_a", "c_a"):
            if key in si and si[key] < 0.0:
                raise ValueError(f"{label}: {key} = {raw[key]!r} must not be negative")
        if not si["k"] > 0.0:
            raise ValueError(f"{label}: k = {raw['k']!r} must be positive")
        m, k, c = si["m"], si["k"], si.get("c", 0.0)
        found = [key for key in ("m_a", "k_a", "c_a") if key in si]
        if found and len(found) < 3:
            raise ValueError(f"{label}: a foundation needs all of m_a, k_a and c_a")
        if found:
            if m == 0.0:
                raise ValueError(f"{label}: m = {raw['m']!r}: the quasi-static slider (m = 0) "
                                 "has no foundation")
            ma, ka, ca = si["m_a"], si["k_a"], si["c_a"]
            if not (ma > 0.0 and ka > 0.0):
                raise ValueError(f"{label}: the foundation's m_a and k_a must be positive")
            mass = np.diag([m, ma])
            stiffness = np.array([[k, -k], [-k, k + ka]])
            damping = np.array([[c, -c], [-c, c + ca]])
        else:
            mass, stiffness, damping = np.array([[m]]), np.array([[k]]), np.array([[c]])
        contact = 0
    try:
        return MemorySystem(mass, damping, stiffness, contact, load, law, schedule)
    except ValueError as exc:
        raise ValueError(f"{label}: {exc}") from None
