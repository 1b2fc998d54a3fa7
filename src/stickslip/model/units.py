"""Physical quantities with units at the outer boundary (pint): "2 kg", "50 kN/m", "0.5 m/s".

Inside the package everything is SI floats; this module is the only place that parses
units. A bare number is taken as SI.
"""

from __future__ import annotations

import math
import re
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

#: Quantities of the ``[friction]`` table, same layout.
FRICTION_QUANTITIES: dict[str, tuple[str, str, str]] = {
    "slope": ("[time] / [length]", "s/m", "linear law: slope sigma of mu = mu_k - sigma v_r"),
    "mu_0": ("", "", "Stribeck law: friction coefficient at vanishing sliding speed"),
    "stribeck_velocity": ("[velocity]", "m/s", "Stribeck law: Stribeck velocity v_s"),
    "exponent": ("", "", "Stribeck law: exponent n"),
    "viscous": ("[time] / [length]", "s/m", "Stribeck law: viscous slope sigma_v"),
    "tolerance": ("", "", "Stribeck law: law approximation error in units of lambda"),
}

#: Quantities of the friction laws with memory (``law = "rate-state"`` or ``"lugre"``,
#: :mod:`stickslip.model.state_friction`), kept apart from ``FRICTION_QUANTITIES`` (the curve
#: laws' keys, which the app lists as fields).
MEMORY_FRICTION_QUANTITIES: dict[str, tuple[str, str, str]] = {
    "a": ("", "", "rate-state direct-effect parameter a"),
    "b": ("", "", "rate-state evolution-effect parameter b"),
    "d_c": ("[length]", "m", "rate-state characteristic slip distance d_c"),
    "mu_ref": ("", "", "rate-state friction coefficient at v_ref"),
    "v_ref": ("[velocity]", "m/s", "rate-state reference slip speed v_ref"),
    "sigma0": ("[force] / [length]", "N/m", "LuGre bristle stiffness sigma0"),
    "sigma1": ("[force] * [time] / [length]", "N s/m", "LuGre bristle damping sigma1"),
    "sigma2": ("[force] * [time] / [length]", "N s/m", "LuGre viscous friction sigma2"),
    "mu_c": ("", "", "LuGre Coulomb friction coefficient mu_c"),
    "lugre_mu_s": ("", "", "LuGre static friction coefficient mu_s"),
    "lugre_stribeck_velocity": ("[velocity]", "m/s", "LuGre Stribeck velocity v_s"),
    "time": ("[time]", "s", "time"),
}

#: Quantities of the ``[structure]`` and ``[absorber]`` tables: the unit
#: of each matrix's entries, modal data and the absorber.
STRUCTURE_QUANTITIES: dict[str, tuple[str, str, str]] = {
    "mass": ("[mass]", "kg", "mass matrix entries"),
    "stiffness": ("[force] / [length]", "N/m", "stiffness matrix entries"),
    "damping": ("[force] * [time] / [length]", "N s/m", "damping matrix entries"),
    "frequency": ("1 / [time]", "Hz", "natural frequency"),
    "mode_shape": ("1 / [mass] ** 0.5", "kg**-0.5", "mass-normalised mode shape value"),
    "rayleigh_alpha": ("1 / [time]", "1/s", "Rayleigh damping alpha of C = alpha M + beta K"),
    "rayleigh_beta": ("[time]", "s", "Rayleigh damping beta of C = alpha M + beta K"),
    "absorber_mass": ("[mass]", "kg", "absorber mass"),
    "max_foundation_deflection": ("[length]", "m",
                                  "largest static deflection of the foundation under mu_k W"),
}


@lru_cache(maxsize=1)
def _registry() -> Any:
    import pint

    return pint.UnitRegistry()


#: One number (decimal point, optional exponent), then an optional unit: ``"2"``, ``"2.5 kg"``,
#: ``"50 kN/m"``, ``"1e-3 N*s/m"``.
#: Largest magnitude of a unit's power (``m^2``, ``kg**-0.5``); the quantities here need 4.
MAX_UNIT_POWER = 12
_POWER = re.compile(r"(?:\*\*|\^)\s*([+-]?\d+(?:\.\d+)?)")
_NUMBER_THEN_UNIT = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$")


#: What :func:`unit_powers_bounded` asks, for messages.
POWER_RULE = f"a unit's power must be one number of magnitude at most {MAX_UNIT_POWER} (m^2, kg**-0.5)"


def unit_powers_bounded(unit: str) -> bool:
    """True when every power in the unit text is one number of magnitude <= ``MAX_UNIT_POWER``.

    A power is a number after ``**`` or ``^`` (``kg**-0.5``, ``m^2``), and is not raised again:
    a chain of powers (``kg**9**9**9``) made pint compute an integer of 10**369 digits, for
    hours, holding the interpreter (the web app's every page with it).

    Parameters
    ----------
    unit : str
        The unit text (``"kN/m"``, ``"kg*m/s**2"``).

    Returns
    -------
    bool
        Whether pint may be given it.
    """
    for power in _POWER.finditer(unit):
        rest = unit[power.end():].lstrip()
        if abs(float(power.group(1))) > MAX_UNIT_POWER or rest.startswith(("**", "^")):
            return False
    return True


def _parse(flag: str, text: str, what: str) -> tuple[float, str]:
    """Split ``text`` into its one number and its unit text (possibly empty).

    A value is one number with an optional unit. A decimal comma (``"1,5 kg"``), two numbers
    (``"2 3 kg"``) and arithmetic (``"2**2000 kg"``) are refused rather than guessed.
    """
    if not text:
        raise ValueError(f"{flag} is empty; expected the {what}")
    if "," in text:
        raise ValueError(f"{flag} {text!r}: use a decimal point, not a comma (one number and a unit)")
    match = _NUMBER_THEN_UNIT.match(text)
    if match is None:
        if text.split()[0].lower().lstrip("+-") in {"nan", "inf", "infinity"}:
            raise ValueError(f"{flag} {text!r} must be finite")
        raise ValueError(f"{flag} {text!r} is not a quantity: expected one number and an optional "
                         "unit, e.g. '2.5 kg'")
    number, unit = match.group(1), match.group(2)
    arithmetic = ValueError(f"{flag} {text!r} must be one number followed by a unit, "
                            "not two numbers or arithmetic")
    if unit.startswith(("*", "/", "^", "+", "-")):
        raise arithmetic
    operators = re.sub(r"\s+", "", unit).replace("**", "^")
    if re.search(r"[*/^]{2}|[*/^]$", operators):
        # pint reads "m//s" as m/s (floor division of units): a typo is refused, not guessed
        raise ValueError(f"{flag} {text!r}: the unit has two operators in a row or ends in one "
                         "(write e.g. 'm/s', 'N*s/m', 'm/s**2')")
    if not unit_powers_bounded(unit):
        raise ValueError(f"{flag} {text!r}: {POWER_RULE}")
    if re.search(r"\d", _POWER.sub("", unit)):
        raise arithmetic
    return float(number), unit


def _angle_exponent(ureg: Any, unit: Any) -> float:
    """The power of the radian in ``unit``'s root units: 1 for rad/s, rpm, deg/s; 0 for Hz.

    pint takes the radian as dimensionless, so it converts ``"75.398 rad/s"`` and ``"720 rpm"``
    to 75.398 "Hz" (1/s). A frequency in Hz counts cycles per second: the caller divides an
    angular frequency by 2 pi (720 rpm = 12 Hz).
    """
    _factor, root = ureg.get_root_units(unit)
    return float(dict(root._units).get("radian", 0))


def to_si(name: str, value: str | float | int, *, source: str | None = None) -> float:
    """Convert ``value`` for quantity ``name`` to an SI float, checking its dimension.

    ``value`` is a number (taken as SI) or a string holding one number with an optional unit
    (``"2 kg"``, ``"50 kN/m"``; a bare number is SI). Raises ``ValueError`` with one line
    naming the value and why: a wrong dimension (a mass given for a stiffness), a decimal
    comma, two numbers, arithmetic, a value that is not a number or a string (a TOML date,
    list or table), or a result that is not finite. ``source`` names where the value came
    from in the message (default: the command-line flag, e.g. ``--m``). A frequency (Hz,
    cycles per second) may be given as an angular frequency: ``"75.398 rad/s"`` and
    ``"720 rpm"`` are 12 Hz; an angle unit in any other quantity is refused.

    Parameters
    ----------
    name : str
        Quantity name (a key of ``QUANTITIES`` or ``FRICTION_QUANTITIES``).
    value : str or float
        A number (already SI) or a quantity string such as ``"2 kg"``.
    source : str, optional
        Where the value came from, for error messages.

    Returns
    -------
    float
        The value in SI units.
    """
    table = next(t for t in (QUANTITIES, FRICTION_QUANTITIES, STRUCTURE_QUANTITIES,
                             MEMORY_FRICTION_QUANTITIES) if name in t)
    dim, si_unit, what = table[name]
    flag = source or f"--{name.replace('_', '-')}"
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"{flag} {value!r} is not a number or a quantity string such as '2 kg'")
    if isinstance(value, (int, float)):
        number = float(value)
    else:
        text = value.strip()
        magnitude, unit_text = _parse(flag, text, what)
        if not unit_text:
            number = magnitude
        else:
            ureg = _registry()
            try:
                unit = ureg.parse_units(unit_text)
            except Exception:
                raise ValueError(f"{flag} {text!r}: {unit_text!r} is not a unit pint understands") from None
            quantity = ureg.Quantity(magnitude, unit)
            angle = _angle_exponent(ureg, unit)
            angular = angle == 1 and si_unit == "Hz" and quantity.check(dim)
            if angle and not angular and quantity.check(dim):
                raise ValueError(f"{flag} {text!r}: an angle unit ({unit_text!r}) does not belong to "
                                 f"the {what} (in {si_unit or 'no unit'})")
            if angular:  # an angular frequency (rad/s, rpm, deg/s): Hz = (rad/s) / (2 pi)
                factor, _root = ureg.get_root_units(unit)
                number = magnitude * float(factor) / (2.0 * math.pi)
            elif dim == "":
                if not quantity.dimensionless:
                    raise ValueError(f"{flag} {text!r} must be dimensionless ({what})")
                number = float(quantity.to("dimensionless").magnitude)
            elif quantity.dimensionless:  # "3 percent" for a mass: a unit, and the wrong one
                raise ValueError(f"{flag} {text!r} has a dimensionless unit, but the {what} is "
                                 f"in {si_unit}: give it in {si_unit} (or a bare number, taken as SI)")
            elif not quantity.check(dim):
                raise ValueError(
                    f"{flag} {text!r} has the wrong unit for the {what}: expected {si_unit} "
                    f"(dimension {dim}), got {quantity.units:~}"
                )
            else:
                try:
                    number = float(quantity.to(si_unit.replace(" ", "*")).magnitude)
                except OverflowError:  # a unit's factor beyond a float (1e308 of a huge unit)
                    number = math.inf
    if not math.isfinite(number):
        raise ValueError(f"{flag} {value!r} must be finite")
    return number
