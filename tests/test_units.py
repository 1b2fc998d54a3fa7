"""Physical inputs are read exactly as meant (issue 12, point 4): one number, an optional unit.

Source of the expected SI values: the unit definitions (1 kN = 1000 N, 1 g = 1e-3 kg).
"""

from __future__ import annotations

import datetime

import pytest
from hypothesis import given
from hypothesis import strategies as st

from stickslip.model.units import to_si


@pytest.mark.parametrize(("name", "text", "expected"), [
    ("m", "2 kg", 2.0), ("m", "2.5kg", 2.5), ("m", "3 g", 3e-3), ("m", "1e-3 kg", 1e-3),
    ("k", "50 kN/m", 5e4), ("c", "0.1 N*s/m", 0.1), ("speed", "0.5 m/s", 0.5),
    ("speed", "36 km/h", 10.0), ("mu_s", "0.5", 0.5), ("m", "7", 7.0), ("m", 7, 7.0),
    ("load", "2 kg*m/s**2", 2.0), ("load", "2 kg*m*s^-2", 2.0), ("k", "3 kg/s^2", 3.0),
])
def test_quantities_convert_to_si(name: str, text: str | float, expected: float) -> None:
    assert to_si(name, text) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(("text", "reason"), [
    ("1,5 kg", "decimal point, not a comma"),
    ("2 3 kg", "one number followed by a unit"),
    ("2**2000 kg", "one number followed by a unit"),
    ("2*3 kg", "one number followed by a unit"),
    ("kg", "is not a quantity"),
    ("", "is empty"),
    ("2 m", "wrong unit"),
    ("2 blorps", "not a unit"),
    ("1e308 t", "must be finite"),
    ("nan kg", "must be finite"),
    ("-inf kg", "must be finite"),
    # a chain of powers: pint computed 9**9**9 (10**369 digits) for hours, the web app's
    # server with it (audit of 2026-11-27); one huge power, and a number after a product
    ("2 kg**9**9**9", "power must be one number"),
    ("2 kg^9^9^9", "power must be one number"),
    ("2 kg*9**9**9", "power must be one number"),
    ("2 kg**2**64", "power must be one number"),
    ("2 kg**99", "power must be one number"),
    ("2 kg*3", "one number followed by a unit"),
    # pint read "m//s" as m/s: a typo was taken silently (independent audit, 2026-11-29)
    ("2 kg//", "two operators in a row"),
    ("2 kg/*g", "two operators in a row"),
    ("2 kg*", "ends in one"),
])
def test_misreadable_text_is_refused_with_one_line(text: str, reason: str) -> None:
    with pytest.raises(ValueError, match=reason) as info:
        to_si("m", text)
    assert "\n" not in str(info.value) and "--m" in str(info.value)


@pytest.mark.parametrize("value", [datetime.date(1952, 1, 1), [2], {"a": 1}, True, None])
def test_toml_values_that_are_not_numbers_or_strings_are_refused(value: object) -> None:
    with pytest.raises(ValueError, match="is not a number or a quantity string"):
        to_si("m", value, source="--config 'machine.toml': m =")  # type: ignore[arg-type]


@given(st.floats(min_value=1e-300, max_value=1e300, allow_nan=False))
def test_any_finite_number_round_trips_through_its_text(x: float) -> None:
    # property: repr of a float followed by its SI unit reads back exactly
    assert to_si("m", f"{x!r} kg") == x


def test_a_doubled_operator_in_a_speed_is_refused() -> None:
    """``"5 m//s"`` was computed as 5 m/s by design, simulate --config and --range."""
    with pytest.raises(ValueError, match="two operators in a row"):
        to_si("speed", "5 m//s")
    assert to_si("speed", "5 m / s") == 5.0 and to_si("speed", "3 mm/s") == pytest.approx(3e-3)
