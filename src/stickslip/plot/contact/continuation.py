"""Period and amplitude of a contact machine's attractors against its speed or load.

Follows the plotting contract of :mod:`stickslip.plot.figure`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes

from stickslip.plot.figure import PlotResult

if TYPE_CHECKING:
    from stickslip.analysis.contact.continuation import ContactContinuation

#: Axis label of each parameter (mathtext, SI unit).
PARAM_LABELS = {"speed": r"belt speed $V$ (m/s)", "load": r"preload $W$ (N)"}
#: Colour per verdict.
VERDICT_COLORS = {"stick-slip": "black", "slip-oscillation": "tab:blue"}


def contact_continuation_plot(data: ContactContinuation, *,
                              ax: Axes | Sequence[Axes] | None = None,
                              title: str | None = None) -> PlotResult:
    """Period (s) and amplitude (m) of the followed attractors against the parameter.

    Continued branches solid with dots, start-up branches that reach another attractor
    dashed with open circles; steady-sliding points are marked on the parameter axis of the
    amplitude panel (amplitude 0). The parameter axis is logarithmic when the range spans
    more than a decade.

    Parameters
    ----------
    data : ContactContinuation
        From :func:`stickslip.analysis.contact.continuation.continue_contact`.
    ax : Axes or pair of Axes, optional
        Two axes (period, amplitude); one axes (period, amplitude on its twin); None: a new
        figure with two panels sharing the parameter axis.
    title : str, optional
        Title of the first panel.

    Returns
    -------
    PlotResult
        The period axes and the amplitude axes.
    """
    if ax is None:
        from matplotlib.figure import Figure

        fig = Figure(figsize=(7.2, 6.0), layout="constrained")
        top, bottom = fig.subplots(2, 1, sharex=True)
    elif isinstance(ax, Axes):
        top, bottom = ax, ax.twinx()
        fig = ax.get_figure(root=True)  # type: ignore[assignment]
    else:
        top, bottom = ax[0], ax[1]
        fig = top.get_figure(root=True)  # type: ignore[assignment]
    artists: list[Any] = []
    labelled: set[str] = set()

    def label(name: str) -> str | None:
        if name in labelled:
            return None
        labelled.add(name)
        return name

    for branch in data.branches:
        outs = [getattr(data.points[i], branch.source) for i in branch.indices]
        x = np.array([data.points[i].value for i in branch.indices])
        if branch.verdict == "steady-sliding":
            artists += bottom.plot(x, np.zeros(x.size), "-", color="0.5", lw=2.5,
                                   label=label("steady sliding"))
            continue
        period = np.array([o.period_s for o in outs], dtype=float)
        amplitude = np.array([o.amplitude_m for o in outs], dtype=float)
        style = "-o" if branch.source == "continued" else "--o"
        face = None if branch.source == "continued" else "none"
        color = VERDICT_COLORS.get(branch.verdict, "tab:orange")
        name = f"{branch.verdict} ({'continued' if branch.source == 'continued' else 'start-up'})"
        artists += top.plot(x, period, style, color=color, mfc=face, ms=4, label=label(name))
        artists += bottom.plot(x, amplitude, style, color=color, mfc=face, ms=4)
    lo, hi = data.value_range
    for axis in (top, bottom):
        if hi / lo > 10.0:
            axis.set_xscale("log")
        axis.set_xlim(lo, hi)
    bottom.set_xlabel(PARAM_LABELS[data.param])
    top.set_ylabel(r"period $T$ (s)")
    bottom.set_ylabel(r"amplitude of $q_t$, $\frac{1}{2}$ peak to peak (m)")
    top.set_title(title or f"{data.system.n_dof}-DOF machine with its contact: attractors "
                  f"against {data.param}\n(followed by runs; observed, not proven)",
                  fontsize="medium")
    if labelled:
        handles = [a for a in artists if not str(a.get_label()).startswith("_")]
        top.legend(handles=handles, loc="best", fontsize="small", frameon=False)
    return PlotResult(fig, [top, bottom], artists)


__all__ = ["contact_continuation_plot"]
