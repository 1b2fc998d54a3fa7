"""The slider page's inputs for a friction law with memory (rate-and-state, LuGre).

The fields are the keys of a machine file's ``[friction]`` table for these laws and are parsed
by the same function (:func:`~stickslip.model.state_friction_input.memory_system_from_config`),
so the page and ``stickslip design --config`` see the same machine. The slider's ``m``, ``k``,
``c``, load, speed and foundation come from the page's other fields; its ``μs``/``μk`` fields
belong to the curve laws and are not used (each memory law carries its own coefficients). No
Streamlit here.
"""

from __future__ import annotations

from collections.abc import Mapping

from stickslip.app.inputs import SYSTEM_INPUTS
from stickslip.model.state_friction import MemorySystem
from stickslip.model.state_friction_input import MEMORY_LAWS, memory_system_from_config

#: Widget key -> (label, default text). The key after ``memory_`` is the ``[friction]`` key;
#: the defaults are the 1-DOF rate-and-state slider and Canudas de Wit et al.'s (1995) LuGre.
MEMORY_INPUTS: dict[str, tuple[str, str]] = {
    "memory_a": ("Direct effect a", "0.01"),
    "memory_b": ("Evolution effect b", "0.015"),
    "memory_d_c": ("Critical slip distance d_c", "10 um"),
    "memory_mu_ref": ("Reference friction μ_ref", "0.6"),
    "memory_v_ref": ("Reference slip speed v_ref", "1 um/s"),
    "memory_evolution": ("State evolution (aging or slip)", "aging"),
    "memory_sigma0": ("Bristle stiffness σ0", "1e5 N/m"),
    "memory_sigma1": ("Bristle damping σ1", "316.22776601683796 N*s/m"),
    "memory_sigma2": ("Viscous friction σ2", "0.4 N*s/m"),
    "memory_mu_c": ("Coulomb level μ_c", "1.0"),
    "memory_mu_s": ("Static level μ_s", "1.5"),
    "memory_stribeck_velocity": ("Stribeck velocity v_s", "1 mm/s"),
}
#: The fields of each law, in the order shown.
MEMORY_FIELDS: dict[str, tuple[str, ...]] = {
    "rate-state": ("memory_a", "memory_b", "memory_d_c", "memory_mu_ref", "memory_v_ref",
                   "memory_evolution"),
    "lugre": ("memory_sigma0", "memory_sigma1", "memory_sigma2", "memory_mu_c", "memory_mu_s",
              "memory_stribeck_velocity"),
}
#: The slider's fields a memory law uses (``μs``, ``μk`` are the curve laws').
SLIDER_FIELDS = ("m", "k", "c", "load", "speed")
FOUNDATION_FIELDS = ("m_a", "k_a", "c_a")

__all__ = ["MEMORY_FIELDS", "MEMORY_INPUTS", "MEMORY_LAWS", "memory_key", "parse_memory_inputs"]


def memory_key(raw: Mapping[str, str]) -> tuple[tuple[str, str], ...]:
    """The texts a memory-law machine is built from, as a hashable cache key."""
    law = str(raw.get("friction_law", "")).strip().lower()
    keys = ("friction_law", *SLIDER_FIELDS, *FOUNDATION_FIELDS, *MEMORY_FIELDS.get(law, ()))
    return tuple((key, str(raw.get(key, "")).strip()) for key in keys)


def parse_memory_inputs(raw: Mapping[str, str]) -> tuple[MemorySystem | None, list[str]]:
    """The machine of the page's fields with a law with memory, or the lines that say why not.

    Parameters
    ----------
    raw : mapping
        The page's texts: ``friction_law`` (one of :data:`MEMORY_LAWS`), the slider's
        ``m``, ``k``, ``c``, ``load``, ``speed``, the foundation's ``m_a``, ``k_a``, ``c_a``
        (all three or none) and the law's fields (:data:`MEMORY_FIELDS`).

    Returns
    -------
    system : MemorySystem or None
        ``None`` exactly when ``errors`` is not empty.
    errors : list of str
        One line per problem, naming the field by its label.
    """
    texts = dict(memory_key(raw))
    law = texts["friction_law"].lower()
    if law not in MEMORY_LAWS:
        return None, [f"Friction law {law!r} is not one of {', '.join(MEMORY_LAWS)}"]
    empty = [MEMORY_INPUTS[key][0] for key in MEMORY_FIELDS[law] if not texts[key]]
    empty += [SYSTEM_INPUTS[key][0] for key in ("m", "k", "load", "speed") if not texts[key]]
    foundation = [key for key in FOUNDATION_FIELDS if texts[key]]
    if foundation and len(foundation) != len(FOUNDATION_FIELDS):
        return None, ["An existing foundation needs all of m_a, k_a and c_a (leave all three "
                      "empty for none)"]
    if empty:
        return None, [f"{name} is empty" for name in empty]
    flat = {key: texts[key] for key in (*SLIDER_FIELDS, *foundation) if texts[key]}
    table = {"law": law, **{key.removeprefix("memory_"): texts[key]
                            for key in MEMORY_FIELDS[law]}}
    try:
        return memory_system_from_config(flat, table, label="Inputs"), []
    except ValueError as exc:
        message = " ".join(str(exc).split()).removeprefix("Inputs: ").removeprefix("[friction]: ")
        labels = {key.removeprefix("memory_"): label for key, (label, _) in MEMORY_INPUTS.items()}
        labels |= {key: label for key, (label, _) in SYSTEM_INPUTS.items()}
        first = message.replace("=", " ").split(" ", 1)[0]
        return None, [f"{labels[first]}: {message}" if first in labels else message]
