"""Time history of a run with friction with memory: displacement, slip speed and friction.

Follows the plotting contract of :mod:`stickslip.plot.figure`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from stickslip.plot.figure import PlotResult, new_grid

if TYPE_CHECKING:
    from matplotlib.axes import Axes


def memory_history_plot(history: Mapping[str, Sequence[float]], *, drive_speed: float,
                        ax: Sequence[Axes] | None = None, title: str | None = None) -> PlotResult:
    """Three panels against time: the contact's displacement, its slip speed and ``mu``.

    Parameters
    ----------
    history : mapping
        ``t_s`` (s), ``x_m`` (m), ``slip_speed_m_s`` (m/s) and ``mu`` of
        :class:`~stickslip.analysis.memory.simulation.MemoryResult` ``.history``.
    drive_speed : float
        The drive speed ``V``, m/s (a dotted line in the slip-speed panel; a slip speed below
        1 % of it is shaded as quasi-stick).
    ax : sequence of three Axes, optional
        The panels; a new figure when None.
    title : str, optional
        Figure title.

    Returns
    -------
    PlotResult
        The figure and its three axes.
    """
    fig, axes = new_grid(3, 1, axes=ax, figsize=(8.0, 6.4), sharex=True)
    t = np.asarray(history["t_s"], dtype=float)
    slip = np.asarray(history["slip_speed_m_s"], dtype=float)
    panels: list[tuple[str, Any]] = [
        (r"displacement $x$ [m]", history["x_m"]),
        (r"slip speed $v = V - \dot x$ [m/s]", slip),
        (r"friction coefficient $\mu$", history["mu"]),
    ]
    stuck = np.abs(slip) < 0.01 * drive_speed
    artists: list[Any] = []
    for axis, (label, values) in zip(axes, panels, strict=True):
        artists += axis.plot(t, np.asarray(values, dtype=float), color="C0", lw=1.2)
        axis.set_ylabel(label)
        if stuck.any():
            axis.fill_between(t, 0.0, 1.0, where=stuck, color="0.85", step="mid",
                              transform=axis.get_xaxis_transform(), lw=0.0,
                              label=r"quasi-stick ($|v| < 0.01\,V$)")
    artists.append(axes[1].axhline(drive_speed, color="0.4", ls=":", lw=1.0, label=r"drive speed $V$"))
    axes[1].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    axes[-1].set_xlabel(r"time $t$ [s]")
    if title:
        fig.suptitle(title)
    return PlotResult(fig, axes, artists)
