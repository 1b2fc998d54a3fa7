"""The basin of attraction in the slider's phase plane, with the certified safe region."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from stickslip.analysis.verdict import VERDICTS, Verdict
from stickslip.plot.figure import PlotResult, new_axes
from stickslip.plot.maps import COLORS

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from stickslip.sweep.basin import BasinResult
    from stickslip.sweep.basin_maps import BasinMap


def basin_plot(
    data: BasinResult,
    *,
    ax: Axes | None = None,
    safe_region: bool = True,
    marker_size: float = 4.0,
    title: str | None = None,
) -> PlotResult:
    """Initial states coloured by their certified verdict, in the ``(xi, xi')`` plane.

    Parameters
    ----------
    data : BasinResult
        From :func:`stickslip.sweep.basin.basin_stability`.
    ax : matplotlib Axes, optional
        Drawn into; a new figure otherwise.
    safe_region : bool
        Draw the certified safe region of :func:`stickslip.analysis.disturbance.safe_disturbance`:
        the states whose deviation from steady sliding has mechanical energy below ``E*`` (in this
        plane, with every other coordinate at its steady-sliding value, an ellipse
        ``(K_00 dxi^2 + M_00 dv^2) / 2 = E*``): no state inside it can start stick-slip.
    marker_size : float
        Scatter marker size (points squared).
    title : str, optional
        Axes title; by default the system and the fractions.
    """
    from stickslip.analysis.disturbance import safe_disturbance
    from stickslip.sweep.basin import equilibrium_state

    fig, ax = new_axes(ax)
    n = data.structure.n_dof
    artists: list[Any] = []
    for verdict in VERDICTS:
        mask = data.verdict == verdict.code
        if np.any(mask):
            artists.append(ax.scatter(data.states[mask, 0], data.states[mask, n], s=marker_size,
                                      color=COLORS[verdict.value], label=verdict.value,
                                      edgecolors="0.4" if verdict.value == "steady-sliding" else "none",
                                      linewidths=0.2))
    eq = equilibrium_state(data.structure, data.slider)
    artists += ax.plot([eq[0]], [eq[n]], marker="*", color="tab:green", markersize=8, ls="none",
                       label="steady sliding")
    if safe_region:
        margin = safe_disturbance(data.structure, data.slider)
        if margin.energy > 0.0:
            theta = np.linspace(0.0, 2.0 * np.pi, 400)
            k00, m00 = data.structure.stiffness[0, 0], data.structure.mass[0, 0]
            dx = np.sqrt(2.0 * margin.energy / k00) * np.cos(theta)
            dv = np.sqrt(2.0 * margin.energy / m00) * np.sin(theta)
            artists += ax.plot(eq[0] + dx, eq[n] + dv, color="tab:green", lw=1.8,
                               label=f"certified safe: energy < {margin.energy:.3g} m V$^2$")
    artists.append(ax.axhline(1.0, color="tab:red", ls="--", lw=0.9, label="belt speed"))
    ax.set_xlabel(r"$\xi$ (from the kinetic-friction equilibrium, $V/\omega_n$)")
    ax.set_ylabel(r"$\xi'$ (units of the belt speed $V$)")
    if title is None:
        fr = data.fractions
        title = (f"{data.structure.name}, $\\lambda$={data.slider.lam:.3g}, "
                 f"$\\zeta$={data.structure.zeta:.3g}: stick-slip {fr['stick-slip']:.1%} of {data.n}")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), markerscale=1.5)
    return PlotResult(fig, [ax], artists)


#: Axis label of the grid's second coordinate of a basin map.
_SECOND_LABELS = {
    "zeta": r"damping ratio $\zeta$",
    "delta": r"friction slope $\delta$ of the linear law (> 0: velocity weakening)",
}


def basin_map_plot(
    data: BasinMap,
    *,
    ax: Axes | None = None,
    title: str | None = None,
) -> PlotResult:
    """Stick-slip fraction of the disturbance sample per cell, with the start-up region outlined.

    ``lambda`` is drawn upwards (on a log scale when the grid spans more than a factor 20),
    the second axis of the grid (``zeta``, or ``delta`` for a map over the slope of the linear
    friction law at one ``zeta``) across.

    Parameters
    ----------
    data : BasinMap
        From :func:`stickslip.sweep.basin.basin_map`.
    ax : matplotlib Axes, optional
        Drawn into; a new figure otherwise.
    title : str, optional
        Axes title; by default it names the disturbed starts (and the fixed ``zeta`` of a
        ``(lambda, delta)`` map).
    """
    fig, ax = new_axes(ax)
    ds = data.dataset
    second = str(ds["stick_slip_fraction"].dims[1])
    lam = np.asarray(ds["lambda"].values)
    across = np.asarray(ds[second].values)
    fraction = np.asarray(ds["stick_slip_fraction"].transpose("lambda", second).values)
    startup = np.asarray(ds["startup_verdict"].transpose("lambda", second).values)
    mesh = ax.pcolormesh(across, lam, fraction, shading="nearest", cmap="magma_r", vmin=0.0, vmax=1.0)
    bar = fig.colorbar(mesh, ax=ax)
    bar.set_label("fraction of disturbed starts ending in stick-slip")
    artists: list[Any] = [mesh]
    if len(across) > 1 and len(lam) > 1:
        sticks = (startup == Verdict.STICK_SLIP.code).astype(float)
        artists.append(ax.contour(across, lam, sticks, levels=[0.5], colors="tab:cyan", linewidths=1.6))
        artists += ax.plot([], [], color="tab:cyan", label="start-up: stick-slip above")
        ax.legend(fontsize=8, loc="lower right")
    if len(lam) > 2 and np.all(lam > 0) and lam[-1] / lam[0] > 20:
        ax.set_yscale("log")
    ax.set_xlabel(_SECOND_LABELS.get(second, second))
    ax.set_ylabel(r"$\lambda$")
    if title is None:
        title = "basin stability: disturbed starts"
        if second == "delta":
            title += f", $\\zeta$ = {float(ds.attrs['zeta']):g}"
    ax.set_title(title, fontsize=10)
    return PlotResult(fig, [ax], artists)
