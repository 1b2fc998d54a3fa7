"""The web app's figures and number formatting (Matplotlib, through :mod:`stickslip.plot`).

The page's standing figures are cached as PNG images keyed on their inputs
(:func:`run_figures_png`, :func:`occurrence_png`): drawing and rendering them took 2.3-2.7 s
of every rerun, also for inputs computed before (issue 31).
"""

from __future__ import annotations

import io
import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import pandas as pd
import streamlit as st
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter, NullLocator

from stickslip.analysis.continuation import ContinuationResult
from stickslip.analysis.simulation import SimulationResult
from stickslip.app.computations import (
    LambdaAxis,
    length_scale_at,
    occurrence_maps,
    operating_point_runs,
    si_of_lambda,
)
from stickslip.app.inputs import FoundationKey, SiKey, system_from_key
from stickslip.model.friction import FrictionLaw
from stickslip.model.physical import PhysicalSystem
from stickslip.plot.figure import new_grid
from stickslip.plot.simulation import phase_portrait_plot, time_history_plot
from stickslip.sweep.occurrence import OccurrenceMap

#: Samples of the exact trajectory per figure (every mode switch is added to them).
PLOT_POINTS = 1500
#: Resolution of the page's images (Streamlit's own for ``st.pyplot``), dots per inch.
PNG_DPI = 200
#: Widest image Streamlit shows unchanged, px (its ``MAXIMUM_CONTENT_WIDTH``): a wider one is
#: decoded, shrunk and encoded again at every rerun (0.2 s per figure), so it is shrunk once.
PNG_MAX_WIDTH = 2 * 730


def png(fig: Figure) -> bytes:
    """``fig`` as a PNG image at most :data:`PNG_MAX_WIDTH` wide (:data:`PNG_DPI` at most).

    Drawn once, at the resolution that gives the width Streamlit shows unchanged: no tight
    bounding box (the page's figures use constrained layout, which already keeps titles,
    labels and legends inside the figure) and no shrinking afterwards. Both cost a second draw
    or a decode and encode: the page's three figures took 3.2 s that way, 1.9 s this way.
    """
    buffer = io.BytesIO()
    width = float(fig.get_size_inches()[0])
    fig.savefig(buffer, format="png", dpi=min(PNG_DPI, PNG_MAX_WIDTH / width))
    return buffer.getvalue()


@st.cache_data(show_spinner="Drawing the time histories...", max_entries=128)
def run_figures_png(lam: float, zeta: float, gamma: float, foundation: FoundationKey,
                    law: FrictionLaw, titles: tuple[str, ...],
                    si: tuple[float, float, float]) -> tuple[bytes, ...]:
    """:func:`figure_of_run` of each run of :func:`operating_point_runs`, as PNG images."""
    runs = operating_point_runs(lam, zeta, gamma, foundation, law)
    return tuple(png(figure_of_run(result, title, si))
                 for result, title in zip(runs.values(), titles, strict=True))


@st.cache_data(show_spinner="Drawing the occurrence maps...", max_entries=64)
def occurrence_png(lam: float, zeta: float, gamma: float, foundation: FoundationKey | None,
                   law: FrictionLaw, key: SiKey) -> bytes:
    """:func:`occurrence_figure` of :func:`occurrence_maps` as a PNG image (``key``: the system)."""
    maps = occurrence_maps(lam, zeta, gamma, foundation, law)
    return png(occurrence_figure(maps, system_from_key(key), lam, zeta))


def fmt(x: float | None, unit: str = "") -> str:
    """``x`` to 4 significant digits with its unit; an em dash for None or not finite."""
    if x is None or not math.isfinite(x):
        return "—"
    return f"{x:.4g}" + (f" {unit}" if unit else "")


def figure_of_run(result: SimulationResult, title: str,
                  si: tuple[float, float, float] | None = None) -> Figure:
    """Time history of the slider (stick phases shaded) next to the phase portrait.

    ``si``: ``(1/omega_n [s], V/omega_n [m], V [m/s])`` draws both in s, m and m/s
    (:func:`~stickslip.plot.simulation.time_history_plot`); dimensionless without.
    """
    fig, (ax_t, ax_p) = new_grid(1, 2, figsize=(10.0, 3.0), width_ratios=(2.2, 1.0))
    time_history_plot(result, ax=ax_t, quantity="position", n_points=PLOT_POINTS, si=si)
    phase_portrait_plot(result, ax=ax_p, n_points=PLOT_POINTS, si=si)
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
    root_mk = math.sqrt(system.mass * system.stiffness)
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
    _lambda_in_si(axes[-1], system, lam, "speed", "y", label="belt speed V [m/s]")
    entries["operating point"] = star
    fig.legend(list(entries.values()), list(entries), loc="outside lower center",
               ncols=min(len(entries), 4), frameon=False, fontsize="small")
    return fig


def _lambda_in_si(ax: Axes, system: PhysicalSystem, lam: float, axis: LambdaAxis,
                  which: str, label: str | None = None) -> None:
    """A secondary axis of ``ax`` reading ``lambda`` (on its x or y axis, ``which``) in SI.

    Eq. (22) at the operating point ``lam``: the belt speed ``V = lam V_op / lambda`` at the
    same load, or the load ``W = lambda W_op / lam`` at the same speed.
    """
    if axis == "speed":
        product = lam * system.speed

        def forward(x: Any) -> Any:
            x = np.asarray(x, dtype=np.float64)
            return np.divide(product, x, out=np.full_like(x, np.inf), where=x > 0)

        # V(lambda) is its own inverse
        functions: tuple[Callable[[Any], Any], Callable[[Any], Any]] = (forward, forward)
        label = label or "belt speed V [m/s] (same load)"
    else:
        ratio = system.load / lam
        functions = (lambda x: x * ratio, lambda w: w / ratio)
        label = label or "normal load W [N] (same speed)"
    if which == "x":
        sec = ax.secondary_xaxis("top", functions=functions)
        _plain_log_ticks(sec.xaxis)
        sec.set_xlabel(label)
    else:
        sec = ax.secondary_yaxis("right", functions=functions)
        sec.yaxis.set_minor_locator(NullLocator())  # unlabelled, and slow to lay out
        sec.set_ylabel(label)


def _plain_log_ticks(axis: Any) -> None:
    """Ticks at 1, 2, 5 times powers of ten, written as plain numbers (no minor labels)."""
    axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
    axis.set_minor_locator(NullLocator())
    axis.set_minor_formatter(NullFormatter())


def bifurcation_figure(results: Mapping[str, ContinuationResult], system: PhysicalSystem,
                       lam: float, axis: LambdaAxis | None) -> Figure:
    """The bifurcation diagrams side by side, the operating ``lambda`` marked.

    Each panel is :meth:`ContinuationResult.plot` (stable solid, unstable dashed, steady
    sliding on the axis, events marked) on a logarithmic ``lambda`` axis; a secondary axis on
    top reads ``lambda`` as the belt
    speed or the load (:func:`stickslip.app.computations.lambda_axis`; none when neither).
    """
    fig = Figure(figsize=(11.0, 4.4), layout="constrained")
    axes = fig.subplots(1, len(results), sharey=True, squeeze=False)[0]
    for ax, (name, result) in zip(axes, results.items(), strict=True):
        result.plot(ax=ax)
        ax.axvline(lam, color="gold", lw=1.2, zorder=0, label="operating point")
        ax.legend(loc="best", fontsize="small")
        ax.set_title(name)
        ax.set_xscale("log")  # the range spans decades; V = lam V_op / lambda stays legible
        _plain_log_ticks(ax.xaxis)
        ax.set_xlabel("λ")
        ax.set_ylabel("")
        if axis is not None:
            _lambda_in_si(ax, system, lam, axis, "x")
    top = max([1.0] + [p.amplitude for r in results.values() for b in r.branches for p in b.points])
    axes[0].set_ylim(top=1.05 * top)  # shared: every branch of both panels in view
    axes[0].set_ylabel("amplitude (V / ω_n)")
    return fig


def bifurcation_events_table(results: Mapping[str, ContinuationResult], system: PhysicalSystem,
                             axis: LambdaAxis | None) -> pd.DataFrame:
    """One row per event of every diagram: where, its type, its amplitude (also in metres).

    The SI columns (belt speed or load, amplitude in m from ``V / omega_n`` at that point)
    are present when ``lambda`` stands for one of them (``axis``).
    """
    rows = []
    for name, result in results.items():
        for e in result.events:
            row = {"machine": name, "event": e.type, "λ": f"{e.param:.8g}"}
            if axis is not None:
                si = si_of_lambda(system, axis, e.param)
                row["belt speed V [m/s]" if axis == "speed" else "load W [N]"] = fmt(si)
            row["amplitude (V/ω_n)"] = fmt(e.amplitude)
            if axis is not None:
                row["amplitude [m]"] = fmt(e.amplitude * length_scale_at(system, axis, e.param))
            row["detail"] = e.detail
            rows.append(row)
    return pd.DataFrame(rows)
