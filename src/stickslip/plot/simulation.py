"""Figures of one simulation: time history with stick phases shaded, phase portrait.

Follows the plotting contract of the package: every ``*_plot`` takes ``ax=None`` (a new
figure is made when omitted), accepts only the keywords it documents, draws, and returns
the artists it made. No ``plt.show()``, no global style changes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from stickslip.analysis.simulation import SimulationResult, TimeHistory

STICK_COLOR = "#f2c14e"
PRIMARY_COLOR = "black"
FOUNDATION_COLOR = "0.55"


def _new_axes(ax: Axes | None) -> Axes:
    if ax is not None:
        return ax
    fig = Figure(figsize=(7.0, 3.2), layout="constrained")
    return fig.add_subplot()


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
) -> list[Any]:
    """Draw ``xi`` (or ``xi'``) against ``tau`` with stick phases shaded (paper Figs. 7, 12-13).

    Parameters
    ----------
    result : SimulationResult
    ax : matplotlib Axes, optional
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
    list of matplotlib artists
    """
    if quantity not in ("position", "velocity"):
        raise ValueError(f"quantity={quantity!r} must be 'position' or 'velocity'")
    ax = _new_axes(ax)
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
    return artists


def phase_portrait_plot(
    result: SimulationResult,
    *,
    ax: Axes | None = None,
    t_start: float = 0.0,
    n_points: int = 4000,
) -> list[Any]:
    """Draw the trajectory in the ``(xi, xi')`` plane (paper Figs. 14-15).

    Stick phases lie on the line ``xi' = 1``; a stick-slip limit cycle is a closed orbit.
    """
    ax = _new_axes(ax)
    hist = _history(result, t_start, n_points)
    artists: list[Any] = ax.plot(hist.position[:, 0], hist.velocity[:, 0], color=PRIMARY_COLOR,
                                 lw=0.9)
    artists += ax.plot(hist.position[0, 0], hist.velocity[0, 0], "o", color="tab:green", ms=4,
                       label="start")
    artists.append(ax.axhline(1.0, color="tab:red", lw=0.8, ls="--", label="belt speed"))
    ax.set_xlabel(r"$\xi$")
    ax.set_ylabel(r"$\xi'$")
    ax.legend(loc="lower right", fontsize="small", frameon=False)
    return artists


def simulation_plot(
    result: SimulationResult,
    *,
    fig: Figure | None = None,
    t_start: float = 0.0,
    n_points: int = 4000,
    title: str | None = None,
) -> Figure:
    """Three panels: displacement and velocity histories, and the phase portrait."""
    if fig is None:
        fig = Figure(figsize=(11.0, 6.0), layout="constrained")
    grid = fig.add_gridspec(2, 2, width_ratios=(2.2, 1.0))
    ax_x = fig.add_subplot(grid[0, 0])
    ax_v = fig.add_subplot(grid[1, 0], sharex=ax_x)
    ax_p = fig.add_subplot(grid[:, 1])
    time_history_plot(result, ax=ax_x, quantity="position", t_start=t_start, n_points=n_points)
    time_history_plot(result, ax=ax_v, quantity="velocity", t_start=t_start, n_points=n_points)
    phase_portrait_plot(result, ax=ax_p, t_start=t_start, n_points=n_points)
    s = result.slider
    if title is None:
        title = (
            f"{result.structure.name}: $\\lambda$={s.lam:.4g}, $\\zeta$={result.structure.zeta:.4g}, "
            f"$\\gamma$={s.gamma:.4g} -- {result.verdict.value}"
        )
    fig.suptitle(title)
    return fig
