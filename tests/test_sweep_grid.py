"""Grid axes of sweeps: ``start:stop:n``, log spacing, comma lists, and one-line errors."""

from __future__ import annotations

import numpy as np
import pytest

from stickslip.sweep.grid import Axis, as_axis


def test_linear_range_includes_both_ends() -> None:
    axis = Axis.parse("0:0.4:5", "zeta")
    assert axis.spacing == "linear"
    np.testing.assert_array_equal(axis.values, [0.0, 0.1, 0.2, 0.30000000000000004, 0.4])
    assert axis.values[-1] == 0.4


@pytest.mark.parametrize("text, spacing", [("0.1:50:200", "log"), ("log:0.1:50:200", None),
                                           ("LOG:0.1:50:200", "log")])
def test_log_range_is_geometric_with_exact_ends(text: str, spacing: str | None) -> None:
    axis = Axis.parse(text, "lambda", spacing)
    assert axis.spacing == "log" and len(axis) == 200
    assert axis.values[0] == 0.1 and axis.values[-1] == 50.0
    ratios = axis.values[1:] / axis.values[:-1]
    np.testing.assert_allclose(ratios, ratios[0], rtol=1e-12)


def test_lin_prefix_and_spacing_word() -> None:
    assert Axis.parse("lin:1:3:3", "lambda").spacing == "linear"
    assert Axis.parse("1:3:3", "lambda", "lin").spacing == "linear"


def test_comma_list_is_sorted_and_a_single_number_is_one_point() -> None:
    axis = Axis.parse(" 1, 0.5 ,0.1", "lambda")
    assert axis.spacing == "list"
    np.testing.assert_array_equal(axis.values, [0.1, 0.5, 1.0])
    np.testing.assert_array_equal(Axis.parse("0.3", "zeta").values, [0.3])
    np.testing.assert_array_equal(Axis.parse("0.3:0.3:1", "zeta").values, [0.3])


def test_spacing_is_ignored_for_lists_and_values_are_read_only() -> None:
    axis = Axis.parse("0.1,0.2", "lambda", "log")
    assert axis.spacing == "list"
    with pytest.raises(ValueError):
        axis.values[0] = 2.0


def test_as_axis_accepts_arrays_specs_and_axes() -> None:
    axis = as_axis(np.array([0.2, 0.1]), "zeta")
    np.testing.assert_array_equal(axis.values, [0.1, 0.2])
    assert as_axis(axis, "zeta") is axis
    assert as_axis("log:1:10:2", "lambda").spacing == "log"


@pytest.mark.parametrize(
    ("text", "spacing", "needle"),
    [
        ("", None, "lambda grid is empty"),
        ("  ", None, "lambda grid is empty"),
        ("0.1:50", None, "is not start:stop:n"),
        ("0.1:50:3:4", None, "is not start:stop:n"),
        ("a:50:3", None, "'a' is not a number"),
        ("0.1:50:x", None, "n='x' must be a whole number"),
        ("0.1:50:2.5", None, "n='2.5' must be a whole number"),
        ("0.1:50:0", None, "n=0 must be at least 1"),
        ("0.1:50:-3", None, "n=-3 must be at least 1"),
        ("50:0.1:3", None, "stop=0.1 is below start=50.0"),
        ("0.1:50:1", None, "one point needs start == stop"),
        ("1:1:3", None, "start == stop gives 3 equal points"),
        ("0:50:3", "log", "log spacing needs positive bounds"),
        ("log:-1:50:3", None, "log spacing needs positive bounds"),
        ("log:0.1:50:3", "lin", "says log spacing but linear spacing was requested"),
        ("0.1:50:3", "cubic", "spacing 'cubic' is not 'lin' or 'log'"),
        ("nan:1:3", None, "'nan' must be finite"),
        ("0.1:inf:3", None, "'inf' must be finite"),
        ("0.1,nan", None, "'nan' must be finite"),
        ("0.1,,0.2", None, "has an empty entry"),
        ("0.1,0.1", None, "repeats the value 0.1"),
        ("0.1:50:2000000", None, "exceeds the limit"),
    ],
)
def test_malformed_axes_raise_one_line(text: str, spacing: str | None, needle: str) -> None:
    with pytest.raises(ValueError) as info:
        Axis.parse(text, "lambda", spacing)
    message = str(info.value)
    assert needle in message
    assert "\n" not in message


def test_empty_array_is_rejected() -> None:
    with pytest.raises(ValueError, match="zeta grid is empty"):
        as_axis(np.array([]), "zeta")
