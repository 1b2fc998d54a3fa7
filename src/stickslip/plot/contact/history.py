"""The time history of a machine with its contact: displacements and normal force, phases marked.

The figure of :func:`contact_history_plot` draws what
:meth:`stickslip.analysis.contact.engine.ContactRun.history` returns (the history of
``stickslip simulate --config ... --history-times``): the tangential displacement of the
contact DOF (m), the normal displacement (m, when the machine has a normal DOF) and the normal
force (N) against time (s), with the stick phases and the separations shaded. It follows the
plotting contract of :mod:`stickslip.plot.figure`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.plot.figure import PlotResult, new_grid

if TYPE_CHECKING:
    from matplotlib.axes import Axes

#: Phase label -> (shading colour, legend text).
PHASE_SHADING: dict[str, tuple[str, str]] = {
    "stick": ("C2", "stick"),
    "separation": ("C3", "separation (N = 0)"),
}


def phase_spans(times: Sequence[float] | NDArray[np.float64], modes: Sequence[str],
                phase: str) -> list[tuple[float, float]]:
    """The time intervals (s) in which the sampled ``modes`` read ``phase``.

    Each run of consecutive samples in ``phase`` becomes one interval, from its first sample to
    the next sample after it (or its last sample at the end of the record).

    Parameters
    ----------
    times : sequence of float or ndarray
        Sample times, s, increasing.
    modes : sequence of str
        The mode at each sample (``stick``, ``slip forward``, ``slip backward``, ``separation``).
    phase : str
        The mode whose intervals are wanted.

    Returns
    -------
    list of (float, float)
        ``(start, end)`` in s.
    """
    spans: list[tuple[float, float]] = []
    start: int | None = None
    for i, mode in enumerate(modes):
        if mode == phase and start is None:
            start = i
        elif mode != phase and start is not None:
            spans.append((float(times[start]), float(times[i])))
            start = None
    if start is not None:
        spans.append((float(times[start]), float(times[-1])))
    return spans


def contact_history_plot(history: Mapping[str, Sequence[Any]], *,
                         ax: Sequence[Axes] | None = None, title: str | None = None,
                         period_s: float | None = None) -> PlotResult:
    """Tangential and normal displacement (m) and normal force (N) against time (s).

    Parameters
    ----------
    history : mapping
        ``t_s`` (s), ``tangential_m`` (m), ``normal_force_N`` (N), ``mode`` (labels) and, for a
        machine with a normal DOF, ``normal_m`` (m): the dictionary of
        :meth:`~stickslip.analysis.contact.engine.ContactRun.history`.
    ax : sequence of Axes, optional
        Three axes (tangential, normal, force), or two without ``normal_m``; a new figure
        when None.
    title : str, optional
        Figure title.
    period_s : float, optional
        The period of the motion, s: said in the title when given.

    Returns
    -------
    PlotResult
        Axes ``[tangential displacement, normal displacement, normal force]`` (the middle one
        absent without ``normal_m``); the stick and separation phases shaded on each.

    Raises
    ------
    ValueError
        A history without samples or without one of the keys above.
    """
    needed = ("t_s", "tangential_m", "normal_force_N", "mode")
    missing = [key for key in needed if key not in history]
    if missing or len(history.get("t_s", ())) == 0:
        raise ValueError(f"the history lacks {', '.join(missing) or 'samples'}")
    t = np.asarray(history["t_s"], dtype=float)
    panels = [("tangential_m", "tangential displacement [m]", "C0")]
    if "normal_m" in history:
        panels.append(("normal_m", "normal displacement [m]", "C1"))
    panels.append(("normal_force_N", "normal force N [N]", "k"))
    fig, axes = new_grid(len(panels), 1, axes=ax, figsize=(7.0, 2.0 + 1.6 * len(panels)),
                         sharex=True)
    artists: list[Any] = []
    modes = [str(m) for m in history["mode"]]
    for a, (key, label, color) in zip(axes, panels, strict=True):
        for phase, (shade, legend) in PHASE_SHADING.items():
            for n, (start, end) in enumerate(phase_spans(t, modes, phase)):
                artists.append(a.axvspan(start, end, color=shade, alpha=0.15, lw=0,
                                         label=legend if n == 0 else None))
        artists += a.plot(t, np.asarray(history[key], dtype=float), color=color, lw=1.3)
        a.set_ylabel(label)
        a.grid(True, alpha=0.3)
    axes[-1].set_xlabel("time t [s]")
    if any(phase_spans(t, modes, phase) for phase in PHASE_SHADING):
        axes[0].legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2, frameon=False,
                       fontsize="small")  # above the top panel, clear of the curves
    heading = title or "Time history with the contact"
    if period_s is not None:
        heading += f" (period {period_s:.6g} s)"
    fig.suptitle(heading)
    return PlotResult(fig, axes, artists)
