"""Validation helpers shared by every parameter object.

Each helper raises ``ValueError`` with one line that names the offending value and says
why it is rejected, so that the command line can print it verbatim.
"""

from __future__ import annotations

import math


def finite(name: str, value: float) -> float:
    """Return ``value`` as a float, rejecting NaN, infinities and non-numbers.

    Booleans (``True``, ``numpy.bool_``) are not numbers here, although Python converts
    them to 1.0 and 0.0: ``Slider(lam=True)`` is a mistake, not lambda = 1.
    """
    if _is_boolean(value):
        raise ValueError(f"{name}={value!r} is a boolean, not a number")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}={value!r} must be finite")
    return x


def _is_boolean(value: object) -> bool:
    """True for ``bool`` and NumPy's boolean scalar (which is not a subclass of ``bool``)."""
    kind = type(value)
    return isinstance(value, bool) or (kind.__module__ == "numpy" and kind.__name__ in ("bool", "bool_"))


def whole_number(name: str, value: int, minimum: int = 1) -> int:
    """Return ``value`` as an int of at least ``minimum``, rejecting booleans and fractions."""
    try:
        n = int(value)
        exact = not _is_boolean(value) and n == value
    except (TypeError, ValueError, OverflowError):
        exact = False
    if not exact or n < minimum:
        raise ValueError(f"{name}={value!r} must be a whole number of at least {minimum}")
    return n


def random_seed(value: int, name: str = "seed") -> int:
    """A seed of NumPy's random generators: a whole number 0, 1, 2, ... (no upper bound)."""
    try:
        return whole_number(name, value, 0)
    except ValueError:
        raise ValueError(f"{name}={value!r} must be a whole number of at least 0 (0, 1, 2, ...)") from None


def positive(name: str, value: float) -> float:
    """Return ``value`` as a finite float that is strictly positive."""
    x = finite(name, value)
    if x <= 0.0:
        raise ValueError(f"{name}={value!r} must be positive")
    return x


def non_negative(name: str, value: float) -> float:
    """Return ``value`` as a finite float that is zero or positive."""
    x = finite(name, value)
    if x < 0.0:
        raise ValueError(f"{name}={value!r} must not be negative")
    return x


#: Largest accepted dimensionless parameter (``lambda``, ``gamma``, ``zeta``, ``M``, ``K``,
#: ``zeta_a``, ``k_scale``, swept grid values). The paper's values are ``lambda`` 0.01-100,
#: ``gamma`` 2, ``zeta`` <= 0.9, ``M`` and ``K`` of order one: 1e6 is four orders of magnitude
#: beyond anything physical, and it keeps every derived quantity finite and well scaled --
#: ``K**2`` (a spring of the stiffness matrix) <= 1e12, the slip-II force
#: ``2 gamma lambda`` <= 2e12, the startup offset ``gamma lambda / K**2`` and the entries of
#: the matrix exponential far from overflow (1.8e308). Larger inputs used to overflow to
#: ``inf`` and make the engine spin forever or crash.
MAX_PARAMETER = 1e6

#: Smallest accepted mass or stiffness ratio (``M``, ``K``): both are inverted by the engine
#: (``M**-1`` in the equations of motion, ``K**-2`` in the equilibrium offset), so the same
#: six orders of magnitude apply below one.
MIN_RATIO = 1e-6


def at_most(name: str, value: float, limit: float = MAX_PARAMETER) -> float:
    """Return ``value`` as a finite float whose magnitude is at most ``limit``."""
    x = finite(name, value)
    if abs(x) > limit:
        raise ValueError(
            f"{name}={value!r} is beyond the supported range (magnitude at most {limit:g}; "
            "larger values overflow the dimensionless equations)"
        )
    return x


def within(name: str, value: float, low: float, high: float, why: str) -> float:
    """Return ``value`` as a finite float in ``[low, high]``; ``why`` says what lies beyond.

    The message names the value, the range and the reason, e.g. ``vs=1e-308 is outside the
    supported range [1e-06, 1e+06] (...)``.
    """
    x = finite(name, value)
    if not low <= x <= high:
        raise ValueError(f"{name}={value!r} is outside the supported range [{low:g}, {high:g}] ({why})")
    return x


def ratio(name: str, value: float) -> float:
    """A mass or stiffness ratio: positive, between :data:`MIN_RATIO` and :data:`MAX_PARAMETER`."""
    x = at_most(name, positive(name, value))
    if x < MIN_RATIO:
        raise ValueError(
            f"{name}={value!r} is below the supported range {name} >= {MIN_RATIO:g} "
            "(its inverse would overflow the dimensionless equations)"
        )
    return x


def friction_range(lam: float, gamma: float) -> None:
    """Refuse ``lambda`` or ``gamma`` above :data:`MAX_PARAMETER` (``2 gamma lambda`` overflows)."""
    at_most("lambda", lam)
    at_most("gamma", gamma)
