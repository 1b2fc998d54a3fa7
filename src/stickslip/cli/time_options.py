"""The time options of ``stickslip simulate``: the horizon ``--t-max`` and ``--history-times``.

One home for both engines' parsers (the exact engine, friction with memory, the contact
engine), so that each command module imports them from here.
"""

from __future__ import annotations

from typing import Any

from stickslip.cli.console import BadInput

#: Most ``--history-times`` points.
MAX_HISTORY_POINTS = 1_000_000


def parse_history_times(text: str) -> Any:
    """``A:B:N`` -> N equally spaced times from A to B seconds (numpy array)."""
    import numpy as np

    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise BadInput(f"--history-times {text!r} must be A:B:N (seconds from A to B, N points), "
                       "e.g. 0:40:401") from None
    if not (np.isfinite(a) and np.isfinite(b)) or a < 0.0 or b < a:
        raise BadInput(f"--history-times {text!r}: need 0 <= A <= B (seconds)")
    if not 1 <= n <= MAX_HISTORY_POINTS:
        raise BadInput(f"--history-times {text!r}: N = {n} must be from 1 to {MAX_HISTORY_POINTS}")
    return np.linspace(a, b, n)


def parse_t_max(text: str | None, time_scale: float | None) -> float | None:
    """``--t-max``: a bare number is dimensionless (returned as is); a time with units is turned
    into tau with ``time_scale`` (s per unit tau; None: no machine file, refused)."""
    if text is None:
        return None
    seconds = _seconds(text)
    if seconds is None:  # a bare number: checked by the engine's options, with their messages
        return float(text)
    if time_scale is None:
        raise BadInput(f"--t-max {text!r}: a time with units needs --config (the machine's time "
                       "scale); without it give dimensionless tau, e.g. --t-max 5000")
    return seconds / time_scale


def parse_t_max_seconds(text: str | None, time_scale: float) -> float | None:
    """``--t-max`` in seconds: a time with units as given (no round trip through tau, which
    put ``"60 s"`` at 59.99999999999999 s and a history sample at 60 s outside the run), a bare
    number in units of ``time_scale`` (s per unit tau)."""
    if text is None:
        return None
    seconds = _seconds(text)
    return float(text) * time_scale if seconds is None else seconds


def _seconds(text: str) -> float | None:
    """A time with units in seconds (positive; BadInput otherwise), None for a bare number."""
    try:
        float(text)
    except ValueError:
        pass
    else:
        return None
    from stickslip.model.units import to_si

    try:
        seconds = to_si("time", text, source="--t-max")
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    if not seconds > 0.0:
        raise BadInput(f"--t-max {text!r} must be positive")
    return seconds
