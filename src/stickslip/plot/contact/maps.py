"""The picture of a contact machine's map over belt speed and load (``map --config`` with a contact).

One function of the plotting contract (:mod:`stickslip.plot.figure`): data in, an optional
``ax``, a :class:`~stickslip.plot.figure.PlotResult` out.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from stickslip.plot.figure import PlotResult, new_axes
from stickslip.plot.maps import COLORS

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from stickslip.sweep.contact.maps import ContactMap


def _log_spaced(values: Any) -> bool:
    v = np.asarray(values, dtype=np.float64)
    return bool(v.size > 2 and np.all(v > 0) and v.max() / v.min() > 20.0)


def contact_map_plot(data: ContactMap, *, ax: Axes | None = None, legend: bool = True,
                     title: str | None = None) -> PlotResult:
    """Draw the start-up verdict of each (belt speed, load) cell; separated cells are hatched.

    Parameters
    ----------
    data : ContactMap
        From :func:`stickslip.sweep.contact.maps.contact_map`.
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    legend : bool
        Add a legend of the verdicts (and of the hatching).
    title : str, optional
        Axes title; by default the machine's name.

    Returns
    -------
    PlotResult
        The artists are the cell image and, if any cell separated, the hatching.
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from stickslip.analysis.verdict import VERDICTS

    fig, ax = new_axes(ax)
    codes = [v.code for v in VERDICTS]
    index = np.vectorize(codes.index)(data.verdict)
    mesh = ax.pcolormesh(data.speed, data.load, index.T,
                         cmap=ListedColormap([COLORS[v.value] for v in VERDICTS]),
                         vmin=-0.5, vmax=len(codes) - 0.5, shading="nearest")
    artists: list[Any] = [mesh]
    if np.any(data.separated):
        hatch = ax.contourf(data.speed, data.load, data.separated.T.astype(float), levels=[0.5, 1.5],
                            colors="none", hatches=["//"]) if min(data.separated.shape) > 1 else None
        if hatch is not None:
            artists.append(hatch)
    if _log_spaced(data.speed):
        ax.set_xscale("log")
    if _log_spaced(data.load):
        ax.set_yscale("log")
    ax.set_xlabel("belt speed V [m/s]")
    ax.set_ylabel("load W [N]")
    ax.set_title(title if title is not None else
                 f"{data.machine.get('name', 'machine')}: start-up verdict (contact engine)")
    if legend:
        handles = [Patch(facecolor=COLORS[v.value], edgecolor="0.4", label=v.value)
                   for v in VERDICTS if np.any(data.verdict == v.code)]
        if len(artists) > 1:
            handles.append(Patch(facecolor="none", edgecolor="0.4", hatch="//", label="separated"))
        ax.legend(handles=handles, loc="upper left", fontsize="small")
    return PlotResult(fig, [ax], artists)
