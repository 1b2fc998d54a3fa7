"""The figure of a contact machine's time history (``stickslip.plot.contact.history``).

A hand-made history with known phases (source: written here, a stick, a slip, a separation
and a slip again) checks what is drawn: every axis labelled with its unit, the curves being
the history's values, the stick and separation phases shaded over exactly their samples.
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip.plot.contact.history import contact_history_plot, phase_spans

MODES = ["stick"] * 3 + ["slip forward"] * 2 + ["separation"] * 4 + ["slip forward"]


def _history(normal: bool = True) -> dict[str, list[object]]:
    t = np.linspace(0.0, 9e-4, len(MODES))
    history: dict[str, list[object]] = {
        "t_s": t.tolist(), "tangential_m": (1e-6 * np.sin(t * 7e3)).tolist(),
        "tangential_velocity_m_s": np.zeros(t.size).tolist(),
        "normal_force_N": [1000.0, 900.0, 800.0, 500.0, 100.0, 0.0, 0.0, 0.0, 0.0, 300.0],
        "mode": list(MODES)}
    if normal:
        history["normal_m"] = (2e-5 * np.cos(t * 7e3)).tolist()
    return history


def test_every_axis_is_labelled_with_its_unit() -> None:
    result = contact_history_plot(_history(), title="brake pad", period_s=2.4315e-4)
    labels = [a.get_ylabel() for a in result.axes]
    assert labels == ["tangential displacement [m]", "normal displacement [m]",
                      "normal force N [N]"]
    assert result.axes[-1].get_xlabel() == "time t [s]"
    assert result.figure.get_suptitle() == "brake pad (period 0.00024315 s)"


def test_the_curves_are_the_historys_values() -> None:
    history = _history()
    result = contact_history_plot(history)
    for a, key in zip(result.axes, ("tangential_m", "normal_m", "normal_force_N"), strict=True):
        (line,) = a.get_lines()
        np.testing.assert_array_equal(line.get_xdata(), history["t_s"])
        np.testing.assert_array_equal(line.get_ydata(), history[key])


def test_stick_and_separation_are_shaded_over_their_samples() -> None:
    t = _history()["t_s"]
    assert phase_spans(t, MODES, "stick") == [(0.0, pytest.approx(3e-4))]
    assert phase_spans(t, MODES, "separation") == [(pytest.approx(5e-4), pytest.approx(9e-4))]
    assert phase_spans([0.0, 1.0, 2.0], ["stick", "slip forward", "stick"], "stick") == [
        (0.0, 1.0), (2.0, 2.0)]
    result = contact_history_plot(_history())
    top = result.axes[0]
    assert len(top.patches) == 2  # one stick span, one separation span
    texts = [t.get_text() for t in top.get_legend().get_texts()]
    assert texts == ["stick", "separation (N = 0)"]


def test_without_a_normal_dof_two_panels() -> None:
    result = contact_history_plot(_history(normal=False))
    assert [a.get_ylabel() for a in result.axes] == ["tangential displacement [m]",
                                                     "normal force N [N]"]


def test_a_history_without_its_keys_is_refused() -> None:
    with pytest.raises(ValueError, match="lacks normal_force_N"):
        contact_history_plot({"t_s": [0.0], "tangential_m": [0.0], "mode": ["stick"]})
    with pytest.raises(ValueError, match="lacks samples"):
        contact_history_plot({"t_s": [], "tangential_m": [], "normal_force_N": [], "mode": []})
