"""Pictures of a machine: its verdicts over speed and load, its modes.

Two functions of the plotting contract (:mod:`stickslip.plot.figure`): data in, an optional
``ax``, a :class:`~stickslip.plot.figure.PlotResult` out.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from stickslip.plot.figure import PlotResult, new_axes, new_grid
from stickslip.plot.maps import COLORS

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from stickslip.analysis.reduction import ReducedStructure
    from stickslip.model.machine import Machine
    from stickslip.sweep.operating_map import OperatingMap


def _log_spaced(values: Any) -> bool:
    v = np.asarray(values, dtype=np.float64)
    return bool(v.size > 2 and np.all(v > 0) and v.max() / v.min() > 20.0)


def operating_map_plot(data: OperatingMap, *, ax: Axes | None = None, legend: bool = True,
                       critical_lambda: float | None = None, title: str | None = None) -> PlotResult:
    """Draw the verdict of each (belt speed, normal load) cell of a machine.

    Parameters
    ----------
    data : OperatingMap
        From :func:`stickslip.sweep.operating_map.operating_map`.
    ax : matplotlib Axes, optional
        Drawn into; a new figure is made when omitted.
    legend : bool
        Add a legend of the verdicts.
    critical_lambda : float, optional
        Draw the line ``lambda(V, W) = critical_lambda``, i.e.
        ``W = critical_lambda V sqrt(m_ref k_ref) / (mu_s - mu_k)`` (a straight line on
        log axes): the onset of stick-slip of a Coulomb contact.
    title : str, optional
        Axes title; by default the machine's name.

    Returns
    -------
    PlotResult
        The artists are the cell image and the critical line (if drawn).
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from stickslip.analysis.verdict import VERDICTS

    fig, ax = new_axes(ax)
    names = [v.value for v in VERDICTS]
    codes = np.vectorize(names.index)(data.verdict)
    x_log, y_log = _log_spaced(data.speed), _log_spaced(data.load)
    mesh = ax.pcolormesh(data.speed, data.load, codes.T, cmap=ListedColormap([COLORS[n] for n in names]),
                         vmin=-0.5, vmax=len(names) - 0.5, shading="nearest")
    artists: list[Any] = [mesh]
    if x_log:
        ax.set_xscale("log")
    if y_log:
        ax.set_yscale("log")
    if critical_lambda is not None:
        # lambda = c W / V: W = lambda_c V / c with c = lambda / (W / V) of any cell
        c = float(data.lam[0, 0] * data.speed[0] / data.load[0])
        line, = ax.plot(data.speed, critical_lambda * data.speed / c, color="#e4572e", lw=1.5,
                        label=f"lambda = {critical_lambda:.4g}")
        ax.set_ylim(float(data.load.min()), float(data.load.max()))
        artists.append(line)
    ax.set_xlabel("belt speed V [m/s]")
    ax.set_ylabel("normal load W [N]")
    ax.set_title(title if title is not None else f"{data.machine.get('name')}: verdict over V and W")
    if legend:
        handles = [Patch(facecolor=COLORS[n], edgecolor="0.4", label=n) for n in names
                   if np.any(data.verdict == n)]
        if critical_lambda is not None:
            handles.append(artists[-1])
        ax.legend(handles=handles, loc="upper left", fontsize="small")
    return PlotResult(fig, [ax], artists)


#: Above this many DOF the shapes are drawn as lines without markers, with a few ticks.
MARKED_DOF = 24


def machine_modes_plot(machine: Machine, *, n_modes: int | None = None, ax: Any = None,
                       title: str | None = None,
                       reduction: ReducedStructure | None = None) -> PlotResult:
    """The undamped mode shapes of a machine, with the contact DOF marked.

    Each mode ``phi_i`` (``K phi = w_i^2 M phi``, mass-normalised, scaled to a largest entry
    of 1) is drawn over the DOF index; the contact DOF is a shaded column, and the title of
    each panel gives the frequency [Hz] and ``|phi_i[c]|`` (mass-normalised, 1/sqrt(kg)),
    how strongly the contact takes part in the mode. A reduced machine (``reduction``) is
    drawn over the full model's DOFs (``x = T q``), its contact at the file's DOF.

    Parameters
    ----------
    machine : Machine
        The structure in SI.
    n_modes : int, optional
        Modes drawn, lowest first (default all, at most 6).
    ax : sequence of Axes, optional
        One axes per mode; a new figure is made when omitted.
    title : str, optional
        Figure title; by default the machine's name and contact DOF.
    reduction : ReducedStructure, optional
        The reduction that made ``machine`` (:func:`~stickslip.analysis.reduction.reduce_structure`).

    Returns
    -------
    PlotResult
        One axes per mode; the artists are the mode-shape lines.
    """
    from matplotlib.ticker import MaxNLocator
    from scipy.linalg import eigh

    w2, phi = eigh(machine.stiffness, machine.mass)
    count = min(machine.n_dof, 6) if n_modes is None else max(1, min(int(n_modes), machine.n_dof))
    at_contact = phi[machine.contact_dof, :]
    if reduction is not None:
        shapes, c = reduction.basis @ phi, reduction.kept_dofs[machine.contact_dof]
    else:
        shapes, c = phi, machine.contact_dof
    n = shapes.shape[0]
    cols = min(count, 3)
    rows = math.ceil(count / cols)
    fig, axes_list = new_grid(rows, cols, axes=None if ax is None else list(np.ravel(ax)),
                              figsize=(3.2 * cols, 2.6 * rows))
    dofs = np.arange(n)
    artists = []
    for i in range(count):
        a = axes_list[i]
        shape = shapes[:, i] / np.max(np.abs(shapes[:, i]))
        a.axvspan(c - 0.4, c + 0.4, color="#f2c14e", alpha=0.5, lw=0)
        a.axhline(0.0, color="0.7", lw=0.8)
        line, = a.plot(dofs, shape, "o-" if n <= MARKED_DOF else "-", color="black", ms=4)
        artists.append(line)
        freq = math.sqrt(max(float(w2[i]), 0.0)) / (2.0 * math.pi)
        a.set_title(f"mode {i + 1}: {freq:.4g} Hz, |phi[c]| = {abs(at_contact[i]):.3g}",
                    fontsize="small")
        if n <= MARKED_DOF:
            a.set_xticks(dofs)
        else:  # one tick per DOF would smear into a black band
            a.xaxis.set_major_locator(MaxNLocator(nbins=5, integer=True))
        a.set_ylim(-1.15, 1.15)
        a.set_xlabel("DOF (contact shaded)")
        if i % cols == 0:
            a.set_ylabel("mode shape (largest = 1)")
    for a in axes_list[count:]:
        a.set_visible(False)
    if title is None:
        name = machine.name.replace("$", r"\$")  # a user's name is not mathtext
        title = f"{name}: modes, contact on DOF {c}"
        if reduction is not None:
            title += f" ({reduction.n_full}-DOF model, reduced to {machine.n_dof})"
    fig.suptitle(title)
    return PlotResult(fig, axes_list[:count], artists)
