"""Validation helpers shared by every parameter object.

Each helper raises ``ValueError`` with one line that names the offending value and says
why it is rejected, so that the command line can print it verbatim.
"""

from __future__ import annotations

import math


def finite(name: str, value: float) -> float:
    """Return ``value`` as a float, rejecting NaN, infinities and non-numbers."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}={value!r} must be finite")
    return x


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
