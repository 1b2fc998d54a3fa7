"""The bifurcation diagram of a continuation: amplitude against the parameter.

Follows the plotting contract of :mod:`stickslip.plot.figure`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes

from stickslip.plot.figure import PlotResult, new_axes

if TYPE_CHECKING:
    from stickslip.analysis.continuation import ContinuationResult

#: Colour per branch kind.
KIND_COLORS = {"stick-slip": "black", "slip-oscillation": "tab:blue"}
#: Marker per event type.
EVENT_MARKERS = {"fold": ("s", "tab:red"), "period-doubling": ("D", "tab:purple"),
                 "torus": ("^", "tab:green"), "grazing": ("o", "tab:orange"), "hopf": ("*", "tab:blue")}


def _runs(stable: np.ndarray) -> list[tuple[int, int, bool]]:
    """Maximal runs ``(start, stop, stable)`` of equal stability (``stop`` inclusive, shared)."""
    out: list[tuple[int, int, bool]] = []
    start = 0
    for i in range(1, stable.size + 1):
        if i == stable.size or stable[i] != stable[start]:
            out.append((start, min(i, stable.size - 1), bool(stable[start])))
            start = i
    return out


def continuation_plot(
    data: ContinuationResult,
    *,
    ax: Axes | None = None,
    show_steady: bool = True,
    show_events: bool = True,
) -> PlotResult:
    """Amplitude of every continued branch against the parameter (stable solid, unstable dashed).

    Steady sliding (amplitude 0) is drawn on the axis, solid where it is linearly stable and
    dashed where it is not; named events are marked and listed in the legend.

    Parameters
    ----------
    data : ContinuationResult
        Of :func:`stickslip.analysis.continuation.continue_cycles`.
    ax : Axes, optional
        Draw into it (a new figure otherwise).
    show_steady, show_events : bool
        Draw steady sliding; mark the events.

    Returns
    -------
    PlotResult
        One axes: the diagram (amplitude in ``V/omega_n`` against the parameter).
    """
    fig, ax = new_axes(ax)
    artists: list[Any] = []
    labelled: set[str] = set()

    def label(text: str) -> str | None:
        if text in labelled:
            return None
        labelled.add(text)
        return text

    for branch in data.branches:
        p = np.array([q.param for q in branch.points])
        a = np.array([q.amplitude for q in branch.points])
        st = np.array([q.stable for q in branch.points], dtype=bool)
        color = KIND_COLORS.get(branch.kind, "0.3")
        for i, j, stable in _runs(st):
            text = f"{branch.kind}, {'stable' if stable else 'unstable'}"
            (line,) = ax.plot(p[i:j + 1], a[i:j + 1], color=color, lw=1.6,
                              ls="-" if stable else "--", label=label(text))
            artists.append(line)
    if show_steady and data.steady_param.size:
        sp, ok = np.asarray(data.steady_param), np.asarray(data.steady_stable)
        for i, j, stable in _runs(ok):
            text = f"steady sliding, {'stable' if stable else 'unstable'}"
            (line,) = ax.plot(sp[i:j + 1], np.zeros(j + 1 - i), color="tab:gray", lw=2.4,
                              ls="-" if stable else ":", label=label(text))
            artists.append(line)
    if show_events:
        for e in data.events:
            marker, color = EVENT_MARKERS.get(e.type, ("x", "k"))
            artists.append(ax.plot([e.param], [e.amplitude], marker=marker, color=color, ls="none",
                                   ms=7, label=label(e.type))[0])
    ax.set_xlabel(data.param)
    ax.set_ylabel("amplitude  (V / omega_n)")
    ax.set_xlim(*data.param_range)
    ax.set_ylim(bottom=-0.02 * max([1.0] + [q.amplitude for b in data.branches for q in b.points]))
    ax.legend(loc="best", fontsize="small")
    return PlotResult(fig, [ax], artists)
