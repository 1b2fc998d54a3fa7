"""Physical quantities with units at the outer boundary (pint): "2 kg", "50 kN/m", "0.5 m/s".

Inside the package everything is SI floats; this module is the only place that parses
units. A bare number is taken as SI.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

# name -> (pint dimensionality, SI unit label, description)
QUANTITIES: dict[str, tuple[str, str, str]] = {
    "m": ("[mass]", "kg", "slider mass"),
    "k": ("[force] / [length]", "N/m", "slider stiffness"),
    "c": ("[force] * [time] / [length]", "N s/m", "slider damping coefficient"),
    "mu_s": ("", "", "static friction coefficient"),
    "mu_k": ("", "", "kinetic friction coefficient"),
    "load": ("[force]", "N", "normal load W"),
    "speed": ("[velocity]", "m/s", "belt speed V"),
    "m_a": ("[mass]", "kg", "foundation mass"),
    "k_a": ("[force] / [length]", "N/m", "foundation stiffness"),
    "c_a": ("[force] * [time] / [length]", "N s/m", "foundation damping coefficient"),
}


@lru_cache(maxsize=1)
def _registry() -> Any:
    import pint

    return pint.UnitRegistry()


def to_si(name: str, value: str | float | int) -> float:
    """Convert ``value`` for quantity ``name`` to an SI float, checking its dimension.

    Raises ``ValueError`` with one line naming the value and why (for example a mass given
    for a stiffness).
    """
    dim, si_unit, what = QUANTITIES[name]
    flag = f"--{name.replace('_', '-')}"
    if isinstance(value, bool):
        raise ValueError(f"{flag} {value!r} is not a quantity")
    if isinstance(value, (int, float)):
        number = float(value)
    else:
        text = str(value).strip()
        if not text:
            raise ValueError(f"{flag} is empty; expected the {what}")
        ureg = _registry()
        try:
            quantity = ureg.Quantity(text)
        except Exception:
            raise ValueError(f"{flag} {text!r} is not a quantity pint understands") from None
        if not isinstance(quantity, ureg.Quantity):  # a plain number
            number = float(quantity)
        elif dim == "":
            if not quantity.dimensionless:
                raise ValueError(f"{flag} {text!r} must be dimensionless ({what})")
            number = float(quantity.to("dimensionless").magnitude)
        elif quantity.dimensionless:
            number = float(quantity.magnitude)
        elif not quantity.check(dim):
            raise ValueError(
                f"{flag} {text!r} has the wrong unit for the {what}: expected {si_unit} "
                f"(dimension {dim}), got {quantity.units:~}"
            )
        else:
            number = float(quantity.to(si_unit.replace(" ", "*")).magnitude)
    if not math.isfinite(number):
        raise ValueError(f"{flag} {value!r} must be finite")
    return number
