"""The slider page's standing charts as Vega-Lite specifications, drawn by the browser.

The time history, the phase portrait and the occurrence maps change with every new operating
point. Drawn by Matplotlib and sent as PNG images they took 1.5-2.2 s of a new point's 2.8 s
(issue 31); as Vega-Lite specifications the server only assembles the data (a few ms) and the
browser draws them, with zoom, pan and tooltips, and a menu to save each as PNG or SVG.

The data and the styles are those of the package's figures: the trajectory of
:meth:`~stickslip.analysis.engine_run.SimulationResult.time_history` and
:meth:`~stickslip.analysis.engine_run.SimulationResult.stick_intervals`, the closed-form
boundaries of :func:`~stickslip.analysis.analytic_boundary.analytic_boundaries`, the cell
edges, verdict colours and curve styles of :mod:`stickslip.plot.maps`, the stick colour of
:mod:`stickslip.plot.simulation`. The Matplotlib figures of the command line and the Python
API (``result.plot()``) are unchanged.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import pyarrow as pa
from matplotlib.colors import to_hex  # Matplotlib colours (grey levels too) as CSS
from numpy.typing import NDArray

from stickslip.analysis.analytic_boundary import analytic_boundaries
from stickslip.analysis.engine_run import SimulationResult
from stickslip.analysis.verdict import VERDICTS
from stickslip.model.physical import PhysicalSystem
from stickslip.plot.maps import COLORS, CURVE_STYLES, cell_edges
from stickslip.plot.simulation import FOUNDATION_COLOR, PRIMARY_COLOR, STICK_COLOR
from stickslip.sweep.map_config import dva_from_config
from stickslip.sweep.map_data import stored_foundations
from stickslip.sweep.occurrence import OccurrenceMap

Spec = dict[str, Any]

#: Samples of the exact trajectory per chart (every mode switch is added to them), and the
#: largest distance of a dropped one from the line drawn, as a fraction of the axes' ranges
#: (:func:`simplified`; a third of a pixel on a chart 640 px wide).
PLOT_POINTS = 1500
TOLERANCE = 5e-4
#: Height of the charts' plotting areas, px (their width is the page column's: "fit-x").
RUN_HEIGHT = 200
MAP_HEIGHT = 300
AUTOSIZE = {"type": "fit-x", "contains": "padding"}
#: Drawn on a canvas, not as SVG: a new operating point redraws the canvas instead of
#: updating hundreds of document nodes (bench_app's cached rerun: 0.52 s with SVG, 0.48 s).
CANVAS = {"embedOptions": {"renderer": "canvas"}}
#: Legends below the charts, long labels (the closed-form curves') in full.
LEGEND = {"orient": "bottom", "direction": "horizontal", "labelLimit": 360, "columns": 2}
#: Matplotlib line styles of :data:`stickslip.plot.maps.CURVE_STYLES` as Vega-Lite dashes.
DASHES = {"-": [1, 0], "--": [6, 3], ":": [2, 2], "-.": [6, 2, 2, 2]}
BELT_COLOR = "#d62728"  # Matplotlib's tab:red, the belt-speed line of the figures
START_COLOR = "#2ca02c"  # tab:green, the start marker
OPERATING_COLOR = "gold"
#: The masses drawn in the time history, and their colours (those of the package's figures).
SERIES = ("slider x", "foundation x_a")
SERIES_COLORS = [to_hex(PRIMARY_COLOR), to_hex(FOUNDATION_COLOR)]
#: A five-pointed star, as an SVG path in the unit square (Vega's shapes have no star).
STAR = "M0,-1L0.24,-0.31L0.95,-0.31L0.38,0.12L0.59,0.81L0,0.38L-0.59,0.81L-0.38,0.12L-0.95,-0.31L-0.24,-0.31Z"


def _tables(**frames: pd.DataFrame) -> dict[str, pa.Table]:
    """The charts' datasets as Arrow tables: Streamlit sends Arrow, and a table made once per
    operating point (the charts are cached) is not converted again at every rerun."""
    return {name: pa.Table.from_pandas(frame, preserve_index=False)
            for name, frame in frames.items()}


def simplified(x: NDArray[np.float64], y: NDArray[np.float64],
               tolerance: float = TOLERANCE) -> NDArray[np.intp]:
    """Indices of the samples of the polyline ``(x, y)`` that draw it within ``tolerance``.

    Ramer-Douglas-Peucker on the axes' ranges scaled to 1: a sample is dropped when it lies
    within ``tolerance`` (a fraction of the ranges) of the straight segment between the kept
    samples around it. The slider's stick phases are straight lines, its slip phases arcs: a
    trajectory of 1500 samples keeps a few hundred, and the browser draws those much faster.
    Every loop is bounded: each pass keeps one new sample or settles one interval.
    """
    n = x.size
    if n < 3:
        return np.arange(n)
    span_x, span_y = float(np.ptp(x)) or 1.0, float(np.ptp(y)) or 1.0
    px, py = (x - x[0]) / span_x, (y - y[0]) / span_y
    keep = np.zeros(n, dtype=bool)
    keep[[0, -1]] = True
    intervals = [(0, n - 1)]
    while intervals:
        a, b = intervals.pop()
        if b - a < 2:
            continue
        dx, dy = px[b] - px[a], py[b] - py[a]
        qx, qy = px[a + 1:b] - px[a], py[a + 1:b] - py[a]
        length = math.hypot(dx, dy)
        distance = (np.abs(qx * dy - qy * dx) / length if length > 0.0
                    else np.hypot(qx, qy))
        worst = int(np.argmax(distance))
        if distance[worst] > tolerance:
            i = a + 1 + worst
            keep[i] = True
            intervals += [(a, i), (i, b)]
    return np.flatnonzero(keep)


def _orbit(result: SimulationResult, si: tuple[float, float, float]) -> pd.DataFrame:
    """The slider's orbit in SI, simplified: ``x`` in m, ``v`` in m/s, ``i`` the sample (in
    time order) of :meth:`~stickslip.analysis.engine_run.SimulationResult.time_history`."""
    _, length_scale, speed = si
    hist = result.time_history(n_points=PLOT_POINTS)
    x, v = hist.position[:, 0] * length_scale, hist.velocity[:, 0] * speed
    kept = simplified(x, v)
    return pd.DataFrame({"i": kept, "x": x[kept], "v": v[kept]})


def _stick_phases(result: SimulationResult, time_scale: float) -> pd.DataFrame:
    """The run's stick phases, ``start`` and ``end`` in s."""
    stick = result.stick_intervals() * time_scale
    return pd.DataFrame({"start": stick[:, 0], "end": stick[:, 1], "series": "stick"})


def _displacements(result: SimulationResult, si: tuple[float, float, float]) -> pd.DataFrame:
    """Slider and foundation displacements in m against time in s, one row per sample and mass
    (the long format the browser draws without transforming it; each curve simplified)."""
    time_scale, length_scale, _ = si
    hist = result.time_history(n_points=PLOT_POINTS)
    t = hist.t * time_scale
    frames = []
    for mass, series in enumerate(SERIES[:hist.position.shape[1]]):
        x = hist.position[:, mass] * length_scale
        kept = simplified(t, x)
        frames.append(pd.DataFrame({"t": t[kept], "x": x[kept], "series": series}))
    return pd.concat(frames, ignore_index=True)


def time_history_chart(result: SimulationResult, si: tuple[float, float, float]) -> Spec:
    """Slider (and foundation) displacement against time in SI, stick phases shaded.

    The chart of :func:`~stickslip.plot.simulation.time_history_plot` with ``si``.

    Parameters
    ----------
    result : SimulationResult
        A recorded run (dimensionless).
    si : (float, float, float)
        ``(1/omega_n [s], V/omega_n [m], V [m/s])`` of the physical system (Eqs. 15-16).

    Returns
    -------
    dict
        The Vega-Lite specification; its ``datasets`` are Arrow tables.
    """
    history, stick = _displacements(result, si), _stick_phases(result, si[0])
    series = list(dict.fromkeys(history["series"]))
    colour = {"field": "series", "type": "nominal", "title": None,
              "scale": {"domain": [*series, "stick"],
                        "range": [*SERIES_COLORS[:len(series)], STICK_COLOR]},
              "legend": LEGEND}
    t_axis = {"field": "t", "type": "quantitative", "title": "time t [s]",
              "scale": {"nice": False}}
    return {
        "datasets": _tables(history=history, stick=stick),
        "height": RUN_HEIGHT, "autosize": AUTOSIZE, "usermeta": CANVAS,
        "layer": [
            {"data": {"name": "stick"}, "mark": {"type": "rect", "opacity": 0.35},
             "encoding": {"x": {**t_axis, "field": "start"}, "x2": {"field": "end"},
                          "color": colour}},
            {"data": {"name": "history"}, "mark": {"type": "line", "strokeWidth": 1, "clip": True},
             "encoding": {"x": t_axis,
                          "y": {"field": "x", "type": "quantitative", "title": "x [m]"},
                          "color": colour}},
        ],
    }


def phase_portrait_chart(result: SimulationResult, si: tuple[float, float, float]) -> Spec:
    """The slider's orbit in the (x [m], v [m/s]) plane, its start and the belt speed.

    The chart of :func:`~stickslip.plot.simulation.phase_portrait_plot` with ``si``; stick
    phases lie on the belt-speed line ``v = V``.

    Parameters and return value as :func:`time_history_chart`.
    """
    history = _orbit(result, si)
    speed = si[2]
    x = {"field": "x", "type": "quantitative", "title": "slider x [m]",
         "axis": {"tickCount": 4}}
    y = {"field": "v", "type": "quantitative", "title": "slider v [m/s]"}
    return {
        "datasets": _tables(history=history, first=history.iloc[:1].assign(what="start"),
                            belt=pd.DataFrame({"v": [speed], "what": ["belt speed"]})),
        "height": RUN_HEIGHT, "autosize": AUTOSIZE, "usermeta": CANVAS,
        "layer": [
            {"data": {"name": "history"}, "mark": {"type": "line", "strokeWidth": 0.9,
                                                   "color": to_hex(PRIMARY_COLOR)},
             "encoding": {"x": x, "y": y, "order": {"field": "i"}}},
            {"data": {"name": "first"}, "mark": {"type": "point", "filled": True, "size": 30,
                                                 "color": START_COLOR},
             "encoding": {"x": x, "y": y, "tooltip": [{"field": "what"}]}},
            {"data": {"name": "belt"}, "mark": {"type": "rule", "color": BELT_COLOR,
                                                "strokeDash": DASHES["--"], "strokeWidth": 0.8},
             "encoding": {"y": y, "tooltip": [{"field": "what"},
                                              {"field": "v", "title": "V [m/s]",
                                               "format": ".4g"}]}},
        ],
    }


def _cells(result: OccurrenceMap) -> pd.DataFrame:
    """The (zeta, lambda) map as rectangles: in each column of ``zeta``, one per run of cells
    of the same verdict (their edges, the column's ``zeta`` and the run's ``lambda`` range).

    A run is drawn as one rectangle: a map of 30 x 12 cells is a few dozen marks for the
    browser instead of 360.
    """
    ds = result.dataset
    zetas = np.asarray(ds["zeta"].values, dtype=np.float64)
    lams = np.asarray(ds["lambda"].values, dtype=np.float64)
    verdict = np.asarray(ds["verdict"].transpose("lambda", "zeta").values)
    z_edges, l_edges = cell_edges(zetas, False), cell_edges(lams, True)
    name = {v.code: v.value for v in VERDICTS}
    rows = []
    for j in range(zetas.size):
        column = verdict[:, j]
        starts = np.flatnonzero(np.r_[True, column[1:] != column[:-1]])
        ends = np.r_[starts[1:], column.size]
        for a, b in zip(starts, ends, strict=True):
            label = name[int(column[a])]
            rows.append((z_edges[j], z_edges[j + 1], l_edges[a], l_edges[b], zetas[j],
                         lams[a], lams[b - 1], label, COLORS[label]))
    return pd.DataFrame(rows, columns=["z0", "z1", "l0", "l1", "zeta", "lambda_from",
                                       "lambda_to", "verdict", "paint"])


def _curves(result: OccurrenceMap, lam_range: tuple[float, float]) -> pd.DataFrame:
    """The closed-form boundaries over the map's zeta range (Eqs. 36, 39 or 37), cut at the
    map's ``lam_range`` (the chart's lambda axis is that of the cells)."""
    ds = result.dataset
    zetas = np.asarray(ds["zeta"].values, dtype=np.float64)
    empty = pd.DataFrame({"zeta": [], "lambda": [], "curve": [], "key": []})
    if "configuration" not in ds.attrs or zetas.size == 0:
        return empty
    dva = dva_from_config(json.loads(ds.attrs["configuration"]))
    dense = np.linspace(float(zetas[0]), float(zetas[-1]), 200)
    resolved = None
    if dva.kind == "optimal-exact":
        dense, resolved = zetas, stored_foundations(ds)
    frames = []
    for curve in analytic_boundaries(dva, dense, resolved):
        ok = np.isfinite(curve.lam) & (curve.lam > 0.0)
        zeta, lam = _inside(curve.zeta[ok], curve.lam[ok], lam_range)
        frames.append(pd.DataFrame({"zeta": zeta, "lambda": lam,
                                    "curve": curve.label.replace("zeta_eq", "ζ_eq"),
                                    "key": curve.key}))
    return pd.concat(frames, ignore_index=True) if frames else empty


def _inside(zeta: NDArray[np.float64], lam: NDArray[np.float64], lam_range: tuple[float, float]
            ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The polyline ``(zeta, lam)`` cut to ``lam_range``: the points inside, and where a segment
    leaves or enters the range, its crossing (interpolated in ``log lam``, as drawn)."""
    lo, hi = math.log(lam_range[0]), math.log(lam_range[1])
    log_lam = np.log(lam)
    out_z: list[float] = []
    out_l: list[float] = []
    for i in range(lam.size):
        if i > 0:
            for edge in (lo, hi):
                a, b = log_lam[i - 1] - edge, log_lam[i] - edge
                if a * b < 0.0:  # the segment crosses this edge
                    w = a / (a - b)
                    out_z.append(float(zeta[i - 1] + w * (zeta[i] - zeta[i - 1])))
                    out_l.append(math.exp(edge))
        if lo <= log_lam[i] <= hi:
            out_z.append(float(zeta[i]))
            out_l.append(float(lam[i]))
    return np.array(out_z), np.array(out_l)


def occurrence_chart(result: OccurrenceMap, title: str, system: PhysicalSystem, lam: float,
                     zeta: float) -> Spec:
    """One occurrence map (paper Figs. 8, 11): verdict cells in (zeta, lambda), the closed-form
    boundaries, the operating point (a star) and SI axes.

    The top axis reads ``zeta`` as the damping coefficient ``c = 2 zeta sqrt(m k)`` [N s/m];
    the right axis reads ``lambda`` as the belt speed ``V = lambda_op V_op / lambda`` at the
    same load (Eq. 22), on a reversed logarithmic scale that lines up with ``lambda``'s.

    Parameters
    ----------
    result : OccurrenceMap
        A (lambda, zeta) map of :func:`~stickslip.sweep.occurrence.occurrence_map`.
    title : str
        The chart's title.
    system : PhysicalSystem
        The machine at the operating point (its mass, stiffness and belt speed give the SI
        axes).
    lam, zeta : float
        The operating point, dimensionless.

    Returns
    -------
    dict
        The Vega-Lite specification; its ``datasets`` are Arrow tables.
    """
    cells = _cells(result)
    z_lo, z_hi = float(cells["z0"].min()), float(cells["z1"].max())
    l_lo, l_hi = float(cells["l0"].min()), float(cells["l1"].max())
    curves = _curves(result, (l_lo, l_hi))
    root_mk = math.sqrt(system.mass * system.stiffness)
    product = lam * system.speed
    # no value of the data in the specification: a new operating point changes the datasets
    # only, which the browser updates in place instead of building the chart again
    x = {"type": "quantitative", "title": "damping ratio ζ",
         "scale": {"nice": False, "zero": False}}
    y = {"type": "quantitative", "title": "λ", "scale": {"type": "log", "nice": False}}
    verdicts = [v.value for v in VERDICTS]
    keys = list(dict.fromkeys(curves["key"])) if len(curves) else []
    labels = list(dict.fromkeys(curves["curve"])) if len(curves) else []
    styles = [CURVE_STYLES.get(k, {}) for k in keys]
    frame = pd.DataFrame({"c": [2.0 * root_mk * z_lo, 2.0 * root_mk * z_hi],
                          "V": [product / l_hi, product / l_lo]})
    # the closed-form curves (colour and dash in one legend); none when no curve applies
    legend = {**LEGEND, "columns": 1}
    curve_layers = [{
        "data": {"name": "curves"}, "mark": {"type": "line", "strokeWidth": 1.6, "clip": True},
        "encoding": {
            "x": {**x, "field": "zeta"}, "y": {**y, "field": "lambda"},
            "color": {"field": "curve", "type": "nominal", "title": None, "legend": legend,
                      "scale": {"domain": labels,
                                "range": [to_hex(s.get("color", "black")) for s in styles]}},
            "strokeDash": {"field": "curve", "type": "nominal", "title": None, "legend": legend,
                           "scale": {"domain": labels,
                                     "range": [DASHES[s.get("ls", "-")] for s in styles]}},
        },
    }] if labels else []
    return {
        "datasets": _tables(cells=cells, curves=curves, frame=frame,
                            point=pd.DataFrame({"zeta": [zeta], "lambda": [lam],
                                                "what": ["operating point"]})),
        "title": title, "height": MAP_HEIGHT, "autosize": AUTOSIZE, "usermeta": CANVAS,
        "layer": [
            {"layer": [
                {"data": {"name": "cells"}, "mark": {"type": "rect"},
                 "encoding": {"x": {**x, "field": "z0"}, "x2": {"field": "z1"},
                              "y": {**y, "field": "l0"}, "y2": {"field": "l1"},
                              "fill": {"field": "verdict", "type": "nominal", "title": None,
                                       "scale": {"domain": verdicts,
                                                 "range": [COLORS[v] for v in verdicts]},
                                       "legend": legend},
                              # the cell's own colour as its outline: no seams between cells
                              "stroke": {"field": "paint", "type": "nominal", "scale": None},
                              "tooltip": [{"field": "zeta", "title": "ζ", "format": ".4g"},
                                          {"field": "lambda_from", "title": "λ from",
                                           "format": ".4g"},
                                          {"field": "lambda_to", "title": "λ to",
                                           "format": ".4g"},
                                          {"field": "verdict"}]}},
                *curve_layers,
                {"data": {"name": "point"}, "mark": {"type": "point", "shape": STAR, "size": 260,
                                                     "filled": True, "color": OPERATING_COLOR,
                                                     "stroke": "black", "strokeWidth": 1},
                 "encoding": {"x": {**x, "field": "zeta"}, "y": {**y, "field": "lambda"},
                              "tooltip": [{"field": "what"},
                                          {"field": "zeta", "title": "ζ", "format": ".4g"},
                                          {"field": "lambda", "title": "λ", "format": ".4g"}]}},
            ]},
            {"data": {"name": "frame"}, "mark": {"type": "point", "opacity": 0},
             "encoding": {
                 "x": {"field": "c", "type": "quantitative", "title": "damping c [N s/m]",
                       "axis": {"orient": "top"},
                       "scale": {"nice": False, "zero": False}},
                 "y": {"field": "V", "type": "quantitative", "title": "belt speed V [m/s]",
                       "axis": {"orient": "right"},
                       "scale": {"type": "log", "nice": False, "reverse": True}}}},
        ],
        "resolve": {"scale": {"x": "independent", "y": "independent"}},
    }


def occurrence_charts(maps: Mapping[str, OccurrenceMap], system: PhysicalSystem, lam: float,
                      zeta: float) -> list[Spec]:
    """:func:`occurrence_chart` of each map, titled with its name."""
    return [occurrence_chart(result, name, system, lam, zeta) for name, result in maps.items()]
