"""Figures of one simulation: time history with stick phases shaded, phase portrait.

Follows the plotting contract of :mod:`stickslip.plot.figure`: every ``*_plot`` takes the
result first and keyword-only options with ``ax=None``, draws, and returns a
:class:`~stickslip.plot.figure.PlotResult`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from stickslip.plot.figure import PlotResult, new_axes, new_grid

if TYPE_CHECKING:
    from stickslip.analysis.simulation import SimulationResult, TimeHistory

STICK_COLOR = "#f2c14e"
PRIMARY_COLOR = "black"
FOUNDATION_COLOR = "0.55"


HISTORY_SIZE = (7.0, 3.2)


def _history(result: SimulationResult, t_start: float, n_points: int) -> TimeHistory:
    return result.time_history(n_points=n_points, t_start=t_start)


def _shade_stick(ax: Axes, result: SimulationResult, t_start: float,
                 time_scale: float | None = None) -> list[Any]:
    artists: list[Any] = []
    for start, end in result.stick_intervals(t_start) * (time_scale or 1.0):
        artists.append(ax.axvspan(start, end, color=STICK_COLOR, alpha=0.35, lw=0,
                                  label=None if artists else "stick"))
    return artists


def _si_scales(si: tuple[float, float, float] | None) -> tuple[float, float, float]:
    """``(time, length, speed)`` scales of the ``si`` keyword, checked (1.0 each without)."""
    if si is None:
        return 1.0, 1.0, 1.0
    if len(si) != 3 or not all(np.isfinite(x) and x > 0.0 for x in si):
        raise ValueError(f"si={si!r} must be (time scale [s], length scale [m], speed [m/s]), "
                         "each positive")
    return float(si[0]), float(si[1]), float(si[2])


def time_history_plot(
    result: SimulationResult,
    *,
    ax: Axes | None = None,
    quantity: str = "position",
    t_start: float = 0.0,
    n_points: int = 4000,
    show_foundation: bool = True,
    si: tuple[float, float, float] | None = None,
    legend: bool = True,
) -> PlotResult:
    """Draw ``xi`` (or ``xi'``) against ``tau`` with stick phases shaded (paper Figs. 7, 12-13).

    Parameters
    ----------
    result : SimulationResult
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    quantity : {"position", "velocity"}
        Dimensionless displacement ``xi`` (units ``V/omega_n``) or velocity ``xi'`` (units ``V``).
    t_start : float
        First time drawn, dimensionless.
    n_points : int
        Samples of the exact trajectory (every mode switch is added).
    show_foundation : bool
        Also draw the first foundation mass (grey), as in Figs. 12-13.
    si : tuple of float, optional
        ``(1/omega_n [s], V/omega_n [m], V [m/s])`` of the physical system: draw the time in s,
        the displacement (from the kinetic-friction equilibrium) in m and the velocity in m/s.
    legend : bool
        Add a legend, outside the axes on the right (the stick shading fills the axes: inside,
        any place covers data). A figure of many panels may give one legend instead.

    Returns
    -------
    PlotResult
        One axes; the artists are the stick shading, the curves and the belt-speed line.
    """
    if quantity not in ("position", "velocity"):
        raise ValueError(f"quantity={quantity!r} must be 'position' or 'velocity'")
    time_scale, length_scale, speed = _si_scales(si)
    fig, ax = new_axes(ax, figsize=HISTORY_SIZE)
    hist = _history(result, t_start, n_points)
    data = hist.position if quantity == "position" else hist.velocity
    t = hist.t
    if si is not None:
        t, data = t * time_scale, data * (length_scale if quantity == "position" else speed)
    artists: list[Any] = _shade_stick(ax, result, t_start, None if si is None else time_scale)
    symbol = "\\xi" if quantity == "position" else "\\xi'"
    if si is not None:
        symbol = "x" if quantity == "position" else "v"
    artists += ax.plot(t, data[:, 0], color=PRIMARY_COLOR, lw=1.0, label=f"${symbol}$ slider")
    if show_foundation and data.shape[1] > 1:
        sym_a = "\\xi_a" if quantity == "position" else "\\xi_a'"
        if si is not None:
            sym_a = "x_a" if quantity == "position" else "v_a"
        artists += ax.plot(t, data[:, 1], color=FOUNDATION_COLOR, lw=1.0,
                           label=f"${sym_a}$ foundation")
    if quantity == "velocity":
        artists.append(ax.axhline(speed if si is not None else 1.0, color="tab:red", lw=0.8,
                                  ls="--", label="belt speed"))
    if si is None:
        ax.set_xlabel(r"dimensionless time $\tau$")
        ax.set_ylabel(f"${symbol}$")
    else:
        ax.set_xlabel("time t [s]")
        ax.set_ylabel(f"${symbol}$ [m]" if quantity == "position" else f"${symbol}$ [m/s]")
    ax.set_xlim(t[0], t[-1])
    if legend:
        outside_legend(ax)
    return PlotResult(fig, [ax], artists)


def outside_legend(ax: Axes) -> Any:
    """The legend of ``ax`` outside it, on the right: it never covers a curve."""
    return ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                     fontsize="small", frameon=False)


def phase_portrait_plot(
    result: SimulationResult,
    *,
    ax: Axes | None = None,
    t_start: float = 0.0,
    n_points: int = 4000,
    si: tuple[float, float, float] | None = None,
    legend: bool = True,
) -> PlotResult:
    """Draw the trajectory in the ``(xi, xi')`` plane (paper Figs. 14-15).

    Stick phases lie on the line ``xi' = 1``; a stick-slip limit cycle is a closed orbit.

    Parameters
    ----------
    result : SimulationResult
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    t_start : float
        First time drawn, dimensionless.
    n_points : int
        Samples of the exact trajectory.
    si : tuple of float, optional
        ``(1/omega_n [s], V/omega_n [m], V [m/s])``: draw the plane in m and m/s.
    legend : bool
        Add a legend (outside the axes, on the right: it never covers the orbit).

    Returns
    -------
    PlotResult
        One axes; the artists are the orbit, the start marker and the belt-speed line.
    """
    _, length_scale, speed = _si_scales(si)
    fig, ax = new_axes(ax, figsize=(4.4, 4.0))
    hist = _history(result, t_start, n_points)
    x, v = hist.position[:, 0], hist.velocity[:, 0]
    if si is not None:
        x, v = x * length_scale, v * speed
    artists: list[Any] = ax.plot(x, v, color=PRIMARY_COLOR, lw=0.9)
    artists += ax.plot(x[0], v[0], "o", color="tab:green", ms=4, label="start")
    artists.append(ax.axhline(speed if si is not None else 1.0, color="tab:red", lw=0.8,
                              ls="--", label="belt speed"))
    if si is not None:  # millimetre-sized SI ticks are long: fewer of them
        from matplotlib.ticker import MaxNLocator

        ax.xaxis.set_major_locator(MaxNLocator(nbins=4))
    ax.set_xlabel(r"$\xi$" if si is None else "slider x [m]")
    ax.set_ylabel(r"$\xi'$" if si is None else "slider v [m/s]")
    if legend:
        outside_legend(ax)
    return PlotResult(fig, [ax], artists)


def simulation_plot(
    result: SimulationResult,
    *,
    ax: Sequence[Axes] | None = None,
    t_start: float = 0.0,
    n_points: int = 4000,
    title: str | None = None,
) -> PlotResult:
    """Three panels: displacement and velocity histories, and the phase portrait.

    Parameters
    ----------
    result : SimulationResult
    ax : sequence of three matplotlib Axes, optional
        Displacement, velocity and phase-plane axes to draw into; by default a new figure
        with the histories on the left and the phase portrait on the right.
    t_start : float
        First time drawn, dimensionless.
    n_points : int
        Samples of the exact trajectory.
    title : str, optional
        Figure title; by default (on a new figure) the structure, ``lambda``, ``zeta``,
        ``gamma`` and the verdict. Given axes keep their figure's title unless one is passed.

    Returns
    -------
    PlotResult
        Axes in the order displacement, velocity, phase plane.
    """
    if ax is None:
        fig = Figure(figsize=(11.0, 6.0), layout="constrained")
        grid = fig.add_gridspec(2, 2, width_ratios=(2.2, 1.0))
        ax_x = fig.add_subplot(grid[0, 0])
        axes = [ax_x, fig.add_subplot(grid[1, 0], sharex=ax_x), fig.add_subplot(grid[:, 1])]
        if title is None:
            s = result.slider
            title = (
                f"{result.structure.name}: $\\lambda$={s.lam:.4g}, "
                f"$\\zeta$={result.structure.zeta:.4g}, $\\gamma$={s.gamma:.4g} -- "
                f"{result.verdict.value}"
            )
    else:
        fig, axes = new_grid(3, 1, axes=ax)
    artists: list[Any] = []
    for panel, quantity in zip(axes[:2], ("position", "velocity"), strict=True):
        artists += time_history_plot(result, ax=panel, quantity=quantity, t_start=t_start,
                                     n_points=n_points).artists
    artists += phase_portrait_plot(result, ax=axes[2], t_start=t_start, n_points=n_points).artists
    if title is not None:
        artists.append(fig.suptitle(title))
    return PlotResult(fig, axes, artists)
