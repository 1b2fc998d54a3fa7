"""Figures of the complex-eigenvalue analysis: the root locus over mu and the stability map.

Both follow the plotting contract of :mod:`stickslip.plot.figure`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from stickslip.plot.figure import PlotResult, new_axes, new_grid

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from stickslip.analysis.contact.eigenvalue_maps import RootLocus, StabilityMap
    from stickslip.sweep.memory.maps import MemoryStabilityMap


def root_locus_plot(data: RootLocus, *, ax: Sequence[Axes] | None = None,
                    title: str | None = None) -> PlotResult:
    """Frequencies (Hz) and real parts (1/s) of the eigenvalues against the friction coefficient.

    One line per eigenvalue branch with ``omega >= 0`` at ``mu = 0``; the critical ``mu`` of
    the damped structure and of the undamped one (mode coalescence) are marked by vertical
    lines.

    Parameters
    ----------
    data : RootLocus
        From :func:`stickslip.analysis.contact.eigenvalue_maps.root_locus`.
    ax : sequence of two Axes, optional
        Frequency panel, real-part panel; new figure when None.
    title : str, optional
        Figure title.

    Returns
    -------
    PlotResult
        Axes ``[frequency, real part]``.
    """
    fig, axes = new_grid(2, 1, axes=ax, figsize=(6.4, 6.0), sharex=True)
    artists: list[Any] = []
    mu = data.mu
    branches = [j for j in range(data.eigenvalues.shape[1]) if data.eigenvalues[0, j].imag >= 0.0]
    for number, j in enumerate(branches, start=1):
        s = data.eigenvalues[:, j]
        artists += axes[0].plot(mu, np.abs(s.imag) / (2 * math.pi), lw=1.5, label=f"branch {number}")
        artists += axes[1].plot(mu, s.real, lw=1.5)
    artists.append(axes[1].axhline(0.0, color="0.4", lw=0.8))
    marks = ((data.critical_mu, "C3", "-", "critical mu"),
             (data.critical_mu_undamped, "k", "--", "critical mu, undamped (coalescence)"))
    for value, color, style, label in marks:
        if value is None:
            continue
        for a in axes:
            artists.append(a.axvline(value, color=color, ls=style, lw=1.0,
                                     label=f"{label} = {value:.4g}" if a is axes[0] else None))
    axes[0].set_ylabel("frequency [Hz]")
    axes[1].set_ylabel("real part [1/s]")
    axes[1].set_xlabel("friction coefficient mu")
    axes[0].legend(fontsize="small", loc="best")
    if title:
        fig.suptitle(title)
    return PlotResult(fig, axes, artists)


def stability_map_plot(data: StabilityMap, *, ax: Axes | None = None, log_y: bool = False,
                       title: str | None = None) -> PlotResult:
    """Where steady sliding is unstable over (mu, a second parameter), with the growth rate.

    Color: the largest real part of the eigenvalues (1/s); the zero contour is the stability
    boundary. Cells proven unstable are hatched.

    Parameters
    ----------
    data : StabilityMap
        From :func:`stickslip.analysis.contact.eigenvalue_maps.stability_map`.
    ax : Axes, optional
        Axes to draw into; new figure when None.
    log_y : bool
        Logarithmic second axis (speeds over decades).
    title : str, optional
        Axes title.

    Returns
    -------
    PlotResult
        One axes.
    """
    fig, axis = new_axes(ax)
    growth = data.growth
    limit = float(np.max(np.abs(growth))) or 1.0
    mesh = axis.pcolormesh(data.mu, data.values, growth, cmap="RdBu_r", vmin=-limit, vmax=limit,
                           shading="nearest")
    artists: list[Any] = [mesh]
    grid_2d = data.mu.size > 1 and data.values.size > 1  # contours need a 2 x 2 grid at least
    if grid_2d and growth.min() < 0.0 < growth.max():
        artists.append(axis.contour(data.mu, data.values, growth, levels=[0.0], colors="k",
                                    linewidths=1.2))
    if grid_2d and np.any(data.verdict == 1):
        artists.append(axis.contourf(data.mu, data.values, (data.verdict == 1).astype(float),
                                     levels=[0.5, 1.5], colors="none", hatches=["//"]))
    fig.colorbar(mesh, ax=axis, label="largest real part [1/s] (> 0: unstable)")
    axis.set_xlabel("friction coefficient mu")
    axis.set_ylabel(data.name)
    if log_y:
        axis.set_yscale("log")
    if title:
        axis.set_title(title)
    return PlotResult(fig, [axis], artists)


def memory_map_plot(data: MemoryStabilityMap, *, ax: Axes | None = None,
                    title: str | None = None) -> PlotResult:
    """Growth rate of steady sliding over drive speed and normal load (friction with memory).

    Color: the largest real part of the eigenvalues (1/s, symmetric logarithmic scale: the
    rates span decades); the zero contour is the Hopf boundary; cells proven unstable are
    hatched; a star marks the system's own speed and load. Both axes are logarithmic when
    their values span more than a decade.

    Parameters
    ----------
    data : MemoryStabilityMap
        From :func:`stickslip.sweep.memory.maps.memory_stability_map`.
    ax : Axes, optional
        Axes to draw into; new figure when None.
    title : str, optional
        Axes title (default: the law and the structure).

    Returns
    -------
    PlotResult
        One axes.
    """
    from matplotlib.colors import SymLogNorm

    fig, axis = new_axes(ax)
    growth = data.growth_rate.T  # rows: loads (y), columns: speeds (x)
    limit = float(np.max(np.abs(growth))) or 1.0
    linthresh = limit * 1e-3  # rates within a thousandth of the largest: the linear band
    mesh = axis.pcolormesh(data.speed, data.load, growth, cmap="RdBu_r", shading="nearest",
                           norm=SymLogNorm(linthresh, vmin=-limit, vmax=limit))
    artists: list[Any] = [mesh]
    grid_2d = data.speed.size > 1 and data.load.size > 1
    if grid_2d and growth.min() < 0.0 < growth.max():
        artists.append(axis.contour(data.speed, data.load, growth, levels=[0.0], colors="k",
                                    linewidths=1.2))
    unstable = (data.verdict == "unstable").T
    if grid_2d and unstable.any():
        artists.append(axis.contourf(data.speed, data.load, unstable.astype(float),
                                     levels=[0.5, 1.5], colors="none", hatches=["//"]))
    artists += axis.plot([data.system.schedule.last], [data.system.load], marker="*", ms=12,
                         color="gold", mec="k", ls="none", label="the file's operating point")
    axis.legend(loc="lower left", fontsize="small", framealpha=0.9)
    fig.colorbar(mesh, ax=axis, label=r"largest real part $\max\,\Re\,s$ [1/s] (> 0: unstable)")
    axis.set_xlabel(r"drive speed $V$ [m/s]")
    axis.set_ylabel(r"normal load $N$ [N]")
    for values, set_scale in ((data.speed, axis.set_xscale), (data.load, axis.set_yscale)):
        if values.size > 1 and values.min() > 0.0 and values.max() / values.min() > 10.0:
            set_scale("log")
    law = data.system.friction.to_dict().get("law", "memory")
    axis.set_title(title or f"steady sliding with {law} friction ({data.system.n_dof} DOF): "
                   "linear stability")
    return PlotResult(fig, [axis], artists)
