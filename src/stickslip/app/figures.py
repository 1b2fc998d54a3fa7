"""The web app's figures and number formatting (Matplotlib, through :mod:`stickslip.plot`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import NullLocator
from numpy.typing import NDArray

from stickslip.analysis.simulation import SimulationResult
from stickslip.model.physical import PhysicalSystem
from stickslip.plot.figure import new_grid
from stickslip.plot.simulation import phase_portrait_plot, time_history_plot
from stickslip.sweep.occurrence import OccurrenceMap

#: Samples of the exact trajectory per figure (every mode switch is added to them).
PLOT_POINTS = 1500


def fmt(x: float | None, unit: str = "") -> str:
    """``x`` to 4 significant digits with its unit; an em dash for None or not finite."""
    if x is None or not math.isfinite(x):
        return "—"
    return f"{x:.4g}" + (f" {unit}" if unit else "")


def figure_of_run(result: SimulationResult, title: str) -> Figure:
    """Time history of ``xi`` (stick phases shaded) next to the phase portrait."""
    fig, (ax_t, ax_p) = new_grid(1, 2, figsize=(10.0, 3.0), width_ratios=(2.2, 1.0))
    time_history_plot(result, ax=ax_t, quantity="position", n_points=PLOT_POINTS)
    phase_portrait_plot(result, ax=ax_p, n_points=PLOT_POINTS)
    fig.suptitle(title)
    return fig


def occurrence_figure(maps: Mapping[str, OccurrenceMap], system: PhysicalSystem, lam: float,
                      zeta: float) -> Figure:
    """The maps side by side (closed-form boundaries overlaid), the operating point marked.

    Secondary axes in SI: the damping coefficient ``c = 2 zeta sqrt(m k)`` on top, the belt
    speed ``V = lambda_op V_op / lambda`` (at the same load) on the right. One legend below
    collects the entries of both panels.
    """
    fig = Figure(figsize=(11.0, 4.6), layout="constrained")
    axes = fig.subplots(1, len(maps), sharey=True, squeeze=False)[0]
    speed_times_lam = lam * system.speed
    root_mk = math.sqrt(system.mass * system.stiffness)

    def reciprocal(x: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(x, dtype=np.float64)
        return np.divide(speed_times_lam, x, out=np.full_like(x, np.inf), where=x > 0)

    entries: dict[str, Any] = {}
    for ax, (name, result) in zip(axes, maps.items(), strict=True):
        result.plot(ax=ax, style="image", legend=True, title=name)
        legend = ax.get_legend()
        entries |= {text.get_text(): handle for text, handle in
                    zip(legend.get_texts(), legend.legend_handles, strict=True)}
        legend.remove()
        (star,) = ax.plot([zeta], [lam], marker="*", ms=16, color="gold", mec="black", ls="none")
        top = ax.secondary_xaxis("top", functions=(lambda z: 2.0 * root_mk * z,
                                                   lambda c: c / (2.0 * root_mk)))
        top.set_xlabel("damping c [N s/m]")
    speed = axes[-1].secondary_yaxis("right", functions=(reciprocal, reciprocal))
    speed.yaxis.set_minor_locator(NullLocator())  # unlabelled, and slow to lay out
    speed.set_ylabel("belt speed V [m/s]")
    entries["operating point"] = star
    fig.legend(list(entries.values()), list(entries), loc="outside lower center",
               ncols=min(len(entries), 4), frameon=False, fontsize="small")
    return fig
