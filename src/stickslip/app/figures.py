"""The web app's figures and number formatting.

The slider page's standing charts (time histories, phase portraits, occurrence maps) are
Vega-Lite specifications drawn by the browser (:mod:`stickslip.app.charts`), cached on their
inputs (:func:`run_charts`, :func:`occurrence_map_charts`). The figures shown on demand (the
bifurcation diagrams, the basins, the pages of other machines) are Matplotlib's, through
:mod:`stickslip.plot`, sent as PNG images (:func:`png`).
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
from stickslip.app.charts import Spec, occurrence_charts, phase_portrait_chart, time_history_chart
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

#: Resolution of the page's images (Streamlit's own for ``st.pyplot``), dots per inch.
PNG_DPI = 200
#: Widest image Streamlit shows unchanged, px (its ``MAXIMUM_CONTENT_WIDTH``): a wider one is
#: decoded, shrunk and encoded again at every rerun (0.2 s per figure), so it is shrunk once.
PNG_MAX_WIDTH = 2 * 730


def png(fig: Figure) -> bytes:
    """``fig`` as a PNG image at most :data:`PNG_MAX_WIDTH` wide (:data:`PNG_DPI` at most).

    Drawn once, at the resolution that gives the width Streamlit shows unchanged: no tight
    bounding box (the package's figures use constrained layout, which already keeps titles,
    labels and legends inside the figure) and no shrinking afterwards, each of which would
    cost a second draw or a decode and encode.
    """
    buffer = io.BytesIO()
    width = float(fig.get_size_inches()[0])
    fig.savefig(buffer, format="png", dpi=min(PNG_DPI, PNG_MAX_WIDTH / width))
    return buffer.getvalue()


@st.cache_data(show_spinner=False, max_entries=128)
def run_charts(lam: float, zeta: float, gamma: float, foundation: FoundationKey,
               law: FrictionLaw, si: tuple[float, float, float]) -> tuple[tuple[Spec, Spec], ...]:
    """Time history and phase portrait (:mod:`stickslip.app.charts`) of each run of
    :func:`operating_point_runs`, in SI (``si``: ``(1/omega_n [s], V/omega_n [m], V [m/s])``)."""
    runs = operating_point_runs(lam, zeta, gamma, foundation, law)
    return tuple((time_history_chart(result, si), phase_portrait_chart(result, si))
                 for result in runs.values())


@st.cache_data(show_spinner=False, max_entries=64)
def occurrence_map_charts(lam: float, zeta: float, gamma: float,
                          foundation: FoundationKey | None, law: FrictionLaw,
                          key: SiKey) -> list[Spec]:
    """:func:`~stickslip.app.charts.occurrence_charts` of :func:`occurrence_maps` (``key``:
    the system, for its SI axes)."""
    maps = occurrence_maps(lam, zeta, gamma, foundation, law)
    return occurrence_charts(maps, system_from_key(key), lam, zeta)


@st.cache_data(show_spinner=False, max_entries=64)
def cached_png(key: tuple[Any, ...], _draw: Callable[[], Figure]) -> bytes:
    """:func:`png` of the figure ``_draw()`` makes, drawn once per ``key``.

    ``key`` must fix the figure (a page's inputs, or the digest of uploaded files); ``_draw``
    is not hashed (its leading underscore). A rerun of inputs drawn before sends the image it
    sent then instead of drawing it again (0.3-0.4 s a figure).
    """
    return png(_draw())


def fmt(x: float | None, unit: str = "") -> str:
    """``x`` to 4 significant digits with its unit; an em dash for None or not finite."""
    if x is None or not math.isfinite(x):
        return "—"
    return f"{x:.4g}" + (f" {unit}" if unit else "")


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
