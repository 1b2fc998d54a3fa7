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


def _shade_stick(ax: Axes, result: SimulationResult, t_start: float) -> list[Any]:
    from stickslip.analysis.verdict import Mode

    artists: list[Any] = []
    times = np.append(result.segment_times, result.t_end)
    for i, mode in enumerate(result.segment_modes):
        if mode == Mode.STICK and times[i + 1] > t_start:
            label = "stick" if not artists else None
            artists.append(
                ax.axvspan(max(times[i], t_start), times[i + 1], color=STICK_COLOR, alpha=0.35,
                           lw=0, label=label)
            )
    return artists


def time_history_plot(
    result: SimulationResult,
    *,
    ax: Axes | None = None,
    quantity: str = "position",
    t_start: float = 0.0,
    n_points: int = 4000,
    show_foundation: bool = True,
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

    Returns
    -------
    PlotResult
        One axes; the artists are the stick shading, the curves and the belt-speed line.
    """
    if quantity not in ("position", "velocity"):
        raise ValueError(f"quantity={quantity!r} must be 'position' or 'velocity'")
    fig, ax = new_axes(ax, figsize=HISTORY_SIZE)
    hist = _history(result, t_start, n_points)
    data = hist.position if quantity == "position" else hist.velocity
    artists: list[Any] = _shade_stick(ax, result, t_start)
    symbol = "\\xi" if quantity == "position" else "\\xi'"
    artists += ax.plot(hist.t, data[:, 0], color=PRIMARY_COLOR, lw=1.0, label=f"${symbol}$ slider")
    if show_foundation and data.shape[1] > 1:
        sym_a = "\\xi_a" if quantity == "position" else "\\xi_a'"
        artists += ax.plot(hist.t, data[:, 1], color=FOUNDATION_COLOR, lw=1.0,
                           label=f"${sym_a}$ foundation")
    if quantity == "velocity":
        artists.append(ax.axhline(1.0, color="tab:red", lw=0.8, ls="--", label="belt speed"))
    ax.set_xlabel(r"dimensionless time $\tau$")
    ax.set_ylabel(f"${symbol}$")
    ax.set_xlim(hist.t[0], hist.t[-1])
    ax.legend(loc="upper right", fontsize="small", framealpha=0.85)
    return PlotResult(fig, [ax], artists)


def phase_portrait_plot(
    result: SimulationResult,
    *,
    ax: Axes | None = None,
    t_start: float = 0.0,
    n_points: int = 4000,
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

    Returns
    -------
    PlotResult
        One axes; the artists are the orbit, the start marker and the belt-speed line.
    """
    fig, ax = new_axes(ax, figsize=(4.4, 4.0))
    hist = _history(result, t_start, n_points)
    artists: list[Any] = ax.plot(hist.position[:, 0], hist.velocity[:, 0], color=PRIMARY_COLOR,
                                 lw=0.9)
    artists += ax.plot(hist.position[0, 0], hist.velocity[0, 0], "o", color="tab:green", ms=4,
                       label="start")
    artists.append(ax.axhline(1.0, color="tab:red", lw=0.8, ls="--", label="belt speed"))
    ax.set_xlabel(r"$\xi$")
    ax.set_ylabel(r"$\xi'$")
    ax.legend(loc="lower right", fontsize="small", frameon=False)
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
