"""Figures of the absorber theory: the paper's Figs. 4, 5, 6 and 10.

Follows the plotting contract of :mod:`stickslip.plot.figure`: every ``*_plot`` takes the
data first and keyword-only options with ``ax=None``, draws, and returns a
:class:`~stickslip.plot.figure.PlotResult`. The data come from
:mod:`stickslip.analysis.absorber_tuning` (:func:`~stickslip.analysis.absorber_tuning.tuning_curve`,
:func:`~stickslip.analysis.frequency_response.response_curves`); these functions only draw.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes

from stickslip.analysis.theory import (
    equivalent_damping_fit,
    optimal_damping_ratio_fit,
    optimal_mass_ratio_fit,
    optimal_stiffness_ratio_fit,
    peak_response_fit,
)
from stickslip.plot.figure import PlotResult, new_axes, new_grid

if TYPE_CHECKING:
    from stickslip.analysis.absorber_tuning import TuningCurve
    from stickslip.analysis.frequency_response import ResponseCurves

EXACT_STYLE: dict[str, Any] = {"color": "black", "marker": "o", "ms": 4, "mfc": "white", "lw": 0.8}
FIT_STYLE: dict[str, Any] = {"color": "tab:red", "lw": 1.4}

# attribute of TuningCurve, fitted formula, axis label, equation
_PARAMETERS = {
    "M": ("mass_ratio", optimal_mass_ratio_fit, r"$M_{opt}$", "Eq. (28)"),
    "K": ("stiffness_ratio", optimal_stiffness_ratio_fit, r"$K_{opt}$", "Eq. (29)"),
    "zeta_a": ("damping_ratio", optimal_damping_ratio_fit, r"$\zeta_{a,opt}$", "Eq. (30)"),
}


PANEL_SIZE = (4.5, 3.4)


def _fit_grid(zeta: np.ndarray) -> np.ndarray:
    """A fine grid over the range of ``zeta`` for the smooth fitted curves."""
    lo, hi = float(np.min(zeta)), float(np.max(zeta))
    return np.linspace(lo, hi if hi > lo else lo + 0.4, 200)


def optimal_parameter_plot(
    curve: TuningCurve,
    parameter: str,
    *,
    ax: Axes | None = None,
    show_fit: bool = True,
) -> PlotResult:
    """One panel of the paper's Fig. 4: an optimal foundation parameter against ``zeta``.

    Parameters
    ----------
    curve : TuningCurve
        Exact optimum over a ``zeta`` grid (:func:`stickslip.analysis.absorber_tuning.tuning_curve`).
    parameter : {"M", "K", "zeta_a"}
        ``M_opt`` (Eq. 28), ``K_opt`` (Eq. 29) or ``zeta_a,opt`` (Eq. 30), dimensionless.
        Part of the data (which curve), so it may be given by position.
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    show_fit : bool
        Draw the paper's fitted cubic over the exact values.

    Returns
    -------
    PlotResult
    """
    if parameter not in _PARAMETERS:
        raise ValueError(f"parameter={parameter!r} must be one of {', '.join(_PARAMETERS)}")
    attr, fit, label, eq = _PARAMETERS[parameter]
    fig, ax = new_axes(ax, figsize=PANEL_SIZE)
    artists: list[Any] = ax.plot(
        curve.zeta, getattr(curve, attr), label="exact optimum", **EXACT_STYLE
    )
    if show_fit:
        z = _fit_grid(curve.zeta)
        artists += ax.plot(z, [fit(v) for v in z], label=f"paper fit, {eq}", **FIT_STYLE)
    ax.set_xlabel(r"$\zeta$")
    ax.set_ylabel(label)
    ax.legend(fontsize="small", frameon=False)
    return PlotResult(fig, [ax], artists)


def optimal_tuning_plot(
    curve: TuningCurve,
    *,
    ax: Sequence[Axes] | None = None,
    show_fit: bool = True,
    title: str | None = None,
) -> PlotResult:
    """The paper's Fig. 4: ``M_opt``, ``K_opt`` and ``zeta_a,opt`` against ``zeta``, three panels.

    Parameters
    ----------
    curve : TuningCurve
    ax : sequence of three matplotlib Axes, optional
        Axes for ``M``, ``K`` and ``zeta_a``; by default a new figure with one row of three.
    show_fit : bool
        Draw Eqs. (28)-(30) over the exact optimum.
    title : str, optional
        Figure title; by default (on a new figure) a line naming Fig. 4.

    Returns
    -------
    PlotResult
        Axes in the order ``M``, ``K``, ``zeta_a``.
    """
    if ax is None and title is None:
        title = "Optimal foundation (Fig. 4): exact optimum and the paper's fits"
    fig, axes = new_grid(1, 3, axes=ax, figsize=(12.0, 3.6))
    artists: list[Any] = []
    for panel, name in zip(axes, _PARAMETERS, strict=True):
        artists += optimal_parameter_plot(curve, name, ax=panel, show_fit=show_fit).artists
    if title is not None:
        artists.append(fig.suptitle(title))
    return PlotResult(fig, axes, artists)


def frequency_response_plot(
    curves: ResponseCurves,
    *,
    ax: Axes | None = None,
    show_rigid: bool = True,
    show_equivalent: bool = True,
) -> PlotResult:
    """The paper's Fig. 5: ``H = k|X|/f`` against ``Omega`` with and without the foundation.

    Parameters
    ----------
    curves : ResponseCurves
        From :func:`stickslip.analysis.frequency_response.response_curves`.
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    show_rigid : bool
        Draw the slider on the rigid base (no foundation), thin grey.
    show_equivalent : bool
        Draw the equivalent 1DOF system with ``zeta_eq = 1/(2 H_max)`` (Eq. 32), dashed.

    Returns
    -------
    PlotResult
    """
    fig, ax = new_axes(ax, figsize=(5.5, 3.8))
    artists: list[Any] = []
    peak = curves.peak
    if curves.foundation is not None and curves.dva is not None:
        d = curves.dva
        label = f"foundation M={d.mass_ratio:.4g}, K={d.stiffness_ratio:.4g}, " + (
            rf"$\zeta_a$={d.damping_ratio:.4g}"
        )
        artists += ax.plot(curves.omega, curves.foundation, color="black", lw=1.5, label=label)
        if show_equivalent and curves.equivalent is not None and curves.zeta_eq is not None:
            artists += ax.plot(
                curves.omega, curves.equivalent, color="black", ls="--", lw=1.0,
                label=rf"equivalent 1DOF, $\zeta_{{eq}}$={curves.zeta_eq:.4g} (Eq. 32)",
            )
    if show_rigid or curves.foundation is None:
        artists += ax.plot(curves.omega, curves.rigid, color="0.55", lw=1.0, label="rigid base")
    if math.isfinite(peak.h_max):
        artists += ax.plot(
            [peak.omega_peak], [peak.h_max], "v", color="tab:red", ms=6,
            label=f"$H_{{max}}$={peak.h_max:.4g}",
        )
        drawn = np.concatenate([np.ravel(a.get_ydata()) for a in artists]).astype(float)
        top = float(np.max(drawn[np.isfinite(drawn)]))
        # an undamped rigid base (zeta = 0) would flatten everything else
        ax.set_ylim(0.0, 1.1 * min(top, 4.0 * peak.h_max))
    ax.set_xlim(float(curves.omega.min()), float(curves.omega.max()))
    ax.set_xlabel(r"$\Omega = \omega/\omega_n$")
    ax.set_ylabel(r"$H = kX/f$")
    ax.set_title(rf"$\zeta$ = {curves.zeta:.4g}")
    ax.legend(fontsize="small", frameon=False)
    return PlotResult(fig, [ax], artists)


def peak_response_plot(
    curve: TuningCurve, *, ax: Axes | None = None, show_fit: bool = True
) -> PlotResult:
    """The paper's Fig. 6: ``H_max`` at the optimum against ``zeta``, exact and Eq. (31).

    Parameters
    ----------
    curve : TuningCurve
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    show_fit : bool
        Draw Eq. (31).

    Returns
    -------
    PlotResult
    """
    return _exact_against_fit(curve.zeta, curve.h_max, "exact optimum", peak_response_fit,
                              "paper fit, Eq. (31)", r"$H_{max}$", ax=ax, show_fit=show_fit)


def equivalent_damping_plot(
    curve: TuningCurve, *, ax: Axes | None = None, show_fit: bool = True
) -> PlotResult:
    """The paper's Fig. 10: ``zeta_eq = 1/(2 H_max)`` (Eq. 32) against ``zeta``, and Eq. (33).

    Parameters
    ----------
    curve : TuningCurve
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    show_fit : bool
        Draw Eq. (33).

    Returns
    -------
    PlotResult
    """
    result = _exact_against_fit(curve.zeta, curve.zeta_eq, r"exact optimum, $1/(2H_{max})$",
                                equivalent_damping_fit, "paper fit, Eq. (33)", r"$\zeta_{eq}$",
                                ax=ax, show_fit=show_fit)
    # Eq. (32) applied to the rigid base itself: 1/(2 H_max) = zeta sqrt(1 - zeta^2)
    z = _fit_grid(curve.zeta)
    result.artists += result.ax.plot(z, z * np.sqrt(np.clip(1.0 - z * z, 0.0, None)), color="0.6",
                                     lw=0.8, ls=":", label=r"rigid base, $\zeta\sqrt{1-\zeta^2}$")
    result.ax.legend(fontsize="small", frameon=False)
    return result


def _exact_against_fit(zeta: np.ndarray, exact: np.ndarray, exact_label: str,
                       fit: Callable[[float], float], fit_label: str, ylabel: str, *,
                       ax: Axes | None, show_fit: bool) -> PlotResult:
    """One quantity of the exact optimum against ``zeta``, with the paper's fitted formula."""
    fig, ax = new_axes(ax, figsize=PANEL_SIZE)
    artists: list[Any] = ax.plot(zeta, exact, label=exact_label, **EXACT_STYLE)
    if show_fit:
        z = _fit_grid(zeta)
        artists += ax.plot(z, [fit(v) for v in z], label=fit_label, **FIT_STYLE)
    ax.set_xlabel(r"$\zeta$")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize="small", frameon=False)
    return PlotResult(fig, [ax], artists)
