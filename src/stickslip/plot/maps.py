"""Occurrence maps and boundary curves drawn as the paper draws them (Figs. 8 and 11).

``zeta`` is on the horizontal axis and ``lambda`` on the vertical one (log scale when the
grid is log-spaced). Small grids show one marker per cell: filled circles stick-slip, open
circles steady sliding (the paper's convention) and crosses for undetermined cells; dense
grids show a categorical image. The closed-form boundaries are overlaid: Eq. (36) exact and
Eq. (39) for the rigid base, Eq. (37) with ``zeta_eq`` for a foundation.

A (lambda, delta) map (linear friction law of slope ``delta`` at one ``zeta``) has
``lambda`` on the horizontal axis and ``delta`` on the vertical one; the overlays are the
linear-stability threshold ``delta = delta_crit`` of steady sliding and, on the rigid base,
the exact boundary ``lambda_c = critical_lambda_linear(zeta, delta)`` (Eq. 36 at
``zeta - delta``).

Follows the plotting contract of :mod:`stickslip.plot.figure`: every ``*_plot`` takes the
data first and keyword-only options with ``ax=None``, draws, and returns a
:class:`~stickslip.plot.figure.PlotResult`.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.patches import Patch
from numpy.typing import NDArray

from stickslip.analysis.analytic_boundary import analytic_boundaries
from stickslip.analysis.stability import critical_weakening
from stickslip.analysis.theory import critical_lambda_linear
from stickslip.analysis.verdict import VERDICTS
from stickslip.model.dva import DvaSpec
from stickslip.model.parameters import Foundation
from stickslip.model.structure import chain_structure
from stickslip.plot.figure import PlotResult, new_axes
from stickslip.sweep.map_config import dva_from_config
from stickslip.sweep.map_data import stored_foundations
from stickslip.sweep.occurrence import OccurrenceMap

if TYPE_CHECKING:
    import xarray as xr

    from stickslip.sweep.boundary import BoundaryResult

FloatArray = NDArray[np.float64]

#: Marker style of each verdict (paper Fig. 8: filled = stick-slip, open = steady sliding).
MARKERS: dict[str, dict[str, Any]] = {
    "steady-sliding": {"marker": "o", "markerfacecolor": "none", "markeredgecolor": "black"},
    "stick-slip": {"marker": "o", "markerfacecolor": "black", "markeredgecolor": "black"},
    "undetermined": {"marker": "x", "markerfacecolor": "tab:red", "markeredgecolor": "tab:red"},
    "slip-oscillation": {"marker": "D", "markerfacecolor": "tab:purple", "markeredgecolor": "tab:purple"},
}
#: Colours of the categorical image, in verdict-code order.
COLORS = {"steady-sliding": "#dceaf7", "stick-slip": "#303030", "undetermined": "#e4572e",
          "slip-oscillation": "#8e6bb8"}
CURVE_STYLES: dict[str, dict[str, Any]] = {
    "eq36": {"color": "tab:blue", "ls": "-", "lw": 1.6},
    "eq39": {"color": "tab:green", "ls": "--", "lw": 1.6},
    "eq37": {"color": "tab:blue", "ls": "-", "lw": 1.6},
    "eq36_linear": {"color": "tab:blue", "ls": "-", "lw": 1.6},
    "delta_crit": {"color": "tab:orange", "ls": ":", "lw": 1.6},
}
#: Grids with more cells than this are drawn as an image by default.
MAX_MARKERS = 2500


MAP_SIZE = (7.0, 4.8)


def _is_log(values: FloatArray, spacing: str, requested: bool | None, lists: bool = False) -> bool:
    """Log axis if requested, else for log-spaced grids (and, with ``lists``, wide lists)."""
    if requested is not None:
        return requested
    if values.size == 0 or values.min() <= 0.0:
        return False
    if spacing == "log":
        return True
    return lists and spacing == "list" and values.size > 1 and values.max() / values.min() >= 20.0


def cell_edges(values: FloatArray, log: bool) -> FloatArray:
    """Cell edges around grid values: geometric midpoints on a log axis, arithmetic otherwise."""
    v = np.asarray(values, dtype=np.float64)
    if v.size == 1:
        if log:
            return np.array([v[0] / 1.1, v[0] * 1.1])
        half = max(0.05 * abs(v[0]), 0.005)
        return np.array([v[0] - half, v[0] + half])
    if log:
        mid = np.sqrt(v[1:] * v[:-1])
        return np.concatenate([[v[0] ** 2 / mid[0]], mid, [v[-1] ** 2 / mid[-1]]])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])


def _dense(lo: float, hi: float, log: bool, n: int = 300) -> FloatArray:
    if log and lo > 0.0:
        return np.geomspace(lo, hi, n)
    return np.linspace(lo, hi, n)


def analytic_curves_plot(
    dva: DvaSpec,
    zeta_range: tuple[float, float],
    *,
    ax: Axes | None = None,
    log: bool = False,
    n_points: int = 300,
    resolved: tuple[FloatArray, Sequence[Foundation | None]] | None = None,
) -> PlotResult:
    """Draw the closed-form critical lambda against zeta for ``dva``.

    Rigid base: Eq. (36) exact (solid) and Eq. (39) (dashed). Foundation: Eq. (37) with
    ``zeta_eq`` from Eq. (33) for the fitted optimum, or ``1/(2 H_max)`` (Eq. 32) for other
    foundations; when ``zeta_eq`` is not available a note says so instead.

    Parameters
    ----------
    dva : DvaSpec
    zeta_range : (float, float)
        Interval of ``zeta`` (dimensionless) to draw over.
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    log : bool
        Sample ``zeta`` geometrically (for a log ``zeta`` axis).
    n_points : int
        Samples along ``zeta``.
    resolved : (zetas, foundations), optional
        ``dva`` already resolved at some ``zeta`` (a map's grid). For ``optimal-exact``,
        whose resolution is a numerical optimisation of seconds, the curve is drawn
        through these points instead of ``n_points`` new ones.

    Returns
    -------
    PlotResult
        The curves (or the note) as artists; none for an empty ``zeta_range``.
    """
    fig, ax = new_axes(ax, figsize=MAP_SIZE)
    lo, hi = zeta_range
    if lo == hi:
        return PlotResult(fig, [ax], [])
    zetas = _dense(lo, hi, log, n_points)
    foundations = None
    if resolved is not None and dva.kind == "optimal-exact":
        zetas, foundations = np.asarray(resolved[0], dtype=np.float64), resolved[1]
    artists: list[Any] = []
    curves = analytic_boundaries(dva, zetas, foundations)
    if not curves:
        artists.append(ax.text(0.99, 0.01, "Eq. (37) not drawn: $\\zeta_{eq}$ = 1/(2 $H_{max}$) "
                               "unavailable for this foundation", transform=ax.transAxes,
                               ha="right", va="bottom", fontsize="x-small", color="0.3"))
    for curve in curves:
        ok = np.isfinite(curve.lam) & (curve.lam > 0.0)
        label = curve.label.replace("zeta_eq", r"$\zeta_{eq}$")
        artists += ax.plot(curve.zeta[ok], curve.lam[ok], label=label,
                           **CURVE_STYLES.get(curve.key, {}))
    return PlotResult(fig, [ax], artists)


def _delta_overlays(
    zeta: float,
    foundation: Foundation | None,
    delta_range: tuple[float, float],
    *,
    ax: Axes | None = None,
    n_points: int = 300,
) -> PlotResult:
    """Overlays of a (lambda, delta) map: the stability threshold and the closed-form boundary.

    ``delta = delta_crit`` (horizontal line): steady sliding is linearly stable below it
    (:func:`stickslip.analysis.stability.critical_weakening`; ``delta_crit = zeta`` on the rigid
    base). Rigid base only: the exact stick-slip boundary ``lambda_c(delta)`` of the linear law,
    :func:`stickslip.analysis.theory.critical_lambda_linear` (Eq. 36 at ``zeta - delta``),
    drawn where it is finite and positive.

    Parameters
    ----------
    zeta : float
        The map's fixed primary damping ratio.
    foundation : Foundation or None
        The map's foundation at ``zeta`` (``None``: rigid base).
    delta_range : (float, float)
        Interval of ``delta`` to draw the boundary over.
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    n_points : int
        Samples along ``delta``.

    Returns
    -------
    PlotResult
        The threshold line, then the boundary curve (rigid base).
    """
    fig, ax = new_axes(ax, figsize=MAP_SIZE)
    structure = chain_structure(float(zeta), () if foundation is None else (foundation,))
    d_crit = critical_weakening(structure)
    artists: list[Any] = [ax.axhline(d_crit, label=f"$\\delta_{{crit}}$ = {d_crit:.4g}: steady "
                                     "sliding unstable above", **CURVE_STYLES["delta_crit"])]
    lo, hi = delta_range
    if foundation is None and hi > lo:
        deltas = np.linspace(lo, hi, n_points)
        lam_c = np.array([critical_lambda_linear(float(zeta), float(d)) for d in deltas])
        ok = np.isfinite(lam_c) & (lam_c > 0.0)
        if ok.any():
            artists += ax.plot(lam_c[ok], deltas[ok], label="Eq. (36) at $\\zeta - \\delta$ (exact)",
                               **CURVE_STYLES["eq36_linear"])
    return PlotResult(fig, [ax], artists)


def occurrence_map_plot(
    data: OccurrenceMap | xr.Dataset,
    *,
    ax: Axes | None = None,
    style: Literal["auto", "markers", "image"] = "auto",
    analytic: bool = True,
    legend: bool = True,
    lam_log: bool | None = None,
    zeta_log: bool | None = None,
    marker_size: float | None = None,
    max_markers: int = MAX_MARKERS,
    title: str | None = None,
) -> PlotResult:
    """Draw a stick-slip occurrence map as in the paper's Figs. 8 and 11.

    Parameters
    ----------
    data : OccurrenceMap or xarray.Dataset
        A map from :func:`stickslip.sweep.occurrence_map` (or read back from netCDF).
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    style : {"auto", "markers", "image"}
        ``markers``: filled circle stick-slip, open circle steady sliding, red cross
        undetermined (paper Fig. 8); ``image``: a categorical image for dense grids;
        ``auto``: markers up to ``max_markers`` cells.
    analytic : bool
        Overlay the closed-form boundaries (Eqs. 36 and 39, or Eq. 37 with ``zeta_eq``); for a
        (lambda, delta) map the linear-stability threshold ``delta = delta_crit`` of steady
        sliding and, on the rigid base, Eq. (36) at ``zeta - delta``
        (:func:`~stickslip.analysis.theory.critical_lambda_linear`).
    legend : bool
        Add a legend (outside the axes, on the right).
    lam_log, zeta_log : bool, optional
        Log scale of each axis; by default log when the grid is log-spaced (for lambda
        also when an explicit list spans more than a factor of 20). ``zeta_log`` sets the
        ``delta`` axis of a (lambda, delta) map.
    marker_size : float, optional
        Marker size in points (chosen from the grid density by default).
    max_markers : int
        Threshold of ``style="auto"``.
    title : str, optional
        Axes title; by default the foundation and ``gamma`` of the map.

    Returns
    -------
    PlotResult
        The artists are the markers (or the image), the closed-form curves and the legend.
    """
    if style not in ("auto", "markers", "image"):
        raise ValueError(f"style={style!r} must be 'auto', 'markers' or 'image'")
    ds = data.dataset if isinstance(data, OccurrenceMap) else data
    fig, ax = new_axes(ax, figsize=MAP_SIZE)
    by_delta = "delta" in ds.dims
    # (lambda, zeta): zeta across, lambda up (the paper's Figs. 8, 11); (lambda, delta): lambda
    # across, delta up
    x_name, y_name = ("lambda", "delta") if by_delta else ("zeta", "lambda")
    log_requests = {"lambda": lam_log, "zeta": zeta_log, "delta": zeta_log}
    x = np.asarray(ds[x_name].values, dtype=np.float64)
    y = np.asarray(ds[y_name].values, dtype=np.float64)
    verdict = np.asarray(ds["verdict"].transpose(y_name, x_name).values)
    x_log, y_log = (_is_log(values, str(ds[name].attrs.get("spacing", "list")), log_requests[name],
                            lists=name == "lambda")
                    for name, values in ((x_name, x), (y_name, y)))
    if style == "auto":
        style = "markers" if verdict.size <= max_markers else "image"
    artists, handles, x_edges, y_edges = _draw_cells(ax, x, y, verdict, style, marker_size,
                                                     x_log, y_log)
    _set_scales(ax, x_log, y_log)
    if analytic:
        curves = _map_overlays(ds, x, y, x_log, ax)
        artists += curves
        handles += curves
    _set_limits(ax, x, x_edges, y_edges, x_log, style)
    if by_delta:
        ax.set_xlabel(r"$\lambda$")
        ax.set_ylabel(r"friction slope $\delta$ (> 0 velocity weakening)")
        default_title = (f"{ds.attrs.get('dva', '')}, $\\zeta$ = {float(ds.attrs['zeta']):g}, "
                         f"$\\gamma$ = {ds.attrs.get('gamma', '')}, linear law")
    else:
        ax.set_xlabel(r"damping ratio $\zeta$")
        ax.set_ylabel(r"$\lambda$")
        default_title = f"{ds.attrs.get('dva', '')}, $\\gamma$ = {ds.attrs.get('gamma', '')}"
    ax.set_title(default_title if title is None else title, fontsize="medium")
    if legend and handles:
        artists.append(ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                                 fontsize="small", frameon=False))
    return PlotResult(fig, [ax], artists)


def _map_overlays(ds: xr.Dataset, x: FloatArray, y: FloatArray, x_log: bool, ax: Axes) -> list[Any]:
    """The closed-form curves of a map: Eqs. 36/39 (or 37) over zeta, or the delta thresholds."""
    if "delta" in ds.dims:
        (foundation,) = stored_foundations(ds)
        return list(_delta_overlays(float(ds.attrs["zeta"]), foundation, (float(y[0]), float(y[-1])),
                                    ax=ax).artists)
    if "configuration" not in ds.attrs:
        return []
    dva = dva_from_config(json.loads(ds.attrs["configuration"]))
    return list(analytic_curves_plot(dva, (float(x[0]), float(x[-1])), ax=ax, log=x_log,
                                     resolved=(x, stored_foundations(ds))).artists)


def _set_scales(ax: Axes, x_log: bool, y_log: bool) -> None:
    if y_log:
        ax.set_yscale("log")
    if x_log:
        ax.set_xscale("log")


def _set_limits(ax: Axes, x: FloatArray, x_edges: FloatArray, y_edges: FloatArray, x_log: bool,
                style: str) -> None:
    if style == "markers":
        pad_x = 0.02 * (x_edges[-1] - x_edges[0])
        ax.set_xlim(x[0] - pad_x if not x_log else x_edges[0],
                    x[-1] + pad_x if not x_log else x_edges[-1])
    else:
        ax.set_xlim(x_edges[0], x_edges[-1])
    ax.set_ylim(y_edges[0], y_edges[-1])


def _draw_cells(ax: Axes, x: FloatArray, y: FloatArray, verdict: NDArray[Any], style: str,
                marker_size: float | None, x_log: bool, y_log: bool
                ) -> tuple[list[Any], list[Any], FloatArray, FloatArray]:
    """Markers or the categorical image of ``verdict`` (shape ``(y.size, x.size)``)."""
    artists: list[Any] = []
    handles: list[Any] = []
    x_edges, y_edges = cell_edges(x, x_log), cell_edges(y, y_log)
    if style == "markers":
        size = marker_size or float(np.clip(160.0 / max(x.size, y.size), 2.0, 7.0))
        xx, yy = np.meshgrid(x, y)
        for v in VERDICTS:
            mask = verdict == v.code
            if not mask.any():
                continue
            (line,) = ax.plot(xx[mask], yy[mask], ls="none", ms=size, mew=0.8, label=v.value,
                              **MARKERS[v.value])
            artists.append(line)
            handles.append(line)
    else:
        cmap = ListedColormap([COLORS[v.value] for v in VERDICTS])
        norm = BoundaryNorm(np.arange(len(VERDICTS) + 1) - 0.5, len(VERDICTS))
        artists.append(ax.pcolormesh(x_edges, y_edges, verdict, cmap=cmap, norm=norm,
                                     shading="flat", rasterized=True))
        present = set(np.unique(verdict).tolist())
        handles += [Patch(facecolor=COLORS[v.value], edgecolor="0.4", label=v.value)
                    for v in VERDICTS if v.code in present]
    return artists, handles, x_edges, y_edges


def boundary_plot(
    result: BoundaryResult,
    *,
    ax: Axes | None = None,
    analytic: bool = True,
    legend: bool = True,
    lam_log: bool = True,
    zeta_log: bool | None = None,
    title: str | None = None,
) -> PlotResult:
    """Draw simulated critical lambdas against zeta, every verdict change (paper Fig. 11a).

    Onsets (stick-slip above) are filled up-triangles joined by a line through the lowest
    one of each ``zeta``; ends (steady sliding above) are open down-triangles. Crossings
    whose bisection stopped on an undetermined run are drawn in red.

    Parameters
    ----------
    result : BoundaryResult
        From :func:`stickslip.sweep.boundary.stick_slip_boundary`.
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    analytic : bool
        Overlay the closed-form boundaries of the foundation.
    legend : bool
    lam_log : bool
        Log scale for lambda.
    zeta_log : bool, optional
        Log scale for zeta (by default when the zeta grid is log-spaced).
    title : str, optional

    Returns
    -------
    PlotResult
        The artists are the simulated points, the closed-form curves and the legend.
    """
    fig, ax = new_axes(ax, figsize=MAP_SIZE)
    zeta = np.asarray(result.zeta.values, dtype=np.float64)
    x_log = _is_log(zeta, result.zeta.spacing, zeta_log)
    artists: list[Any] = []
    lowest = result.critical_lambda
    ok = np.isfinite(lowest)
    if ok.any():
        artists += ax.plot(zeta[ok], lowest[ok], color="black", lw=1.0, marker="^", ms=5,
                           label="simulated onset (lowest)")
    groups: dict[str, tuple[list[float], list[float], dict[str, Any]]] = {
        "other onsets": ([], [], {"marker": "^", "mfc": "black", "mec": "black"}),
        "simulated end of stick-slip": ([], [], {"marker": "v", "mfc": "none", "mec": "black"}),
        "not converged (undetermined run)": ([], [], {"marker": "s", "mfc": "none",
                                                      "mec": "tab:red"}),
    }
    for z, crossings in zip(zeta, result.crossings, strict=True):
        first_onset = True
        for c in crossings:
            if not c.converged:
                key = "not converged (undetermined run)"
            elif c.onset and first_onset:
                first_onset = False
                continue  # on the line already
            else:
                key = "other onsets" if c.onset else "simulated end of stick-slip"
            groups[key][0].append(float(z))
            groups[key][1].append(c.lam)
    for label, (xs, ys, style) in groups.items():
        if xs:
            artists += ax.plot(xs, ys, ls="none", ms=6, label=label, **style)
    if lam_log:
        ax.set_yscale("log")
    if x_log:
        ax.set_xscale("log")
    if analytic and zeta.size:
        artists += analytic_curves_plot(result.dva, (float(zeta[0]), float(zeta[-1])), ax=ax,
                                        log=x_log, resolved=(zeta, result.foundations)).artists
    ax.set_ylim(result.lam_min, result.lam_max)
    ax.set_xlabel(r"damping ratio $\zeta$")
    ax.set_ylabel(r"critical $\lambda$")
    if title is None:
        title = f"{result.dva.describe()}, $\\gamma$ = {result.gamma:g}"
    ax.set_title(title, fontsize="medium")
    if legend and artists:
        artists.append(ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small",
                                 frameon=False))
    return PlotResult(fig, [ax], artists)
