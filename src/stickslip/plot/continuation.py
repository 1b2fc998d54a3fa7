"""The bifurcation diagram of a continuation: amplitude against the parameter.

Follows the plotting contract of :mod:`stickslip.plot.figure`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes

from stickslip.plot.figure import PlotResult, new_axes

if TYPE_CHECKING:
    from stickslip.analysis.continuation import ContinuationResult
    from stickslip.analysis.memory.continuation import MemoryContinuation

#: Colour per branch kind.
KIND_COLORS = {"stick-slip": "black", "slip-oscillation": "tab:blue"}
#: Marker per event type.
EVENT_MARKERS = {"fold": ("s", "tab:red"), "period-doubling": ("D", "tab:purple"),
                 "torus": ("^", "tab:green"), "grazing": ("o", "tab:orange"), "hopf": ("*", "tab:blue")}


#: Axis label of each parameter: its symbol (mathtext) and unit.
PARAM_LABELS = {
    "lam": r"friction ratio $\lambda = (\mu_s - \mu_k) W / (V \sqrt{mk})$",
    "zeta": r"damping ratio $\zeta$",
    "gamma": r"$\gamma = \mu_k / (\mu_s - \mu_k)$",
    "delta": r"friction slope $\delta$",
    "K": r"foundation stiffness ratio $K$",
    "M": r"foundation mass ratio $M$",
    "zeta_a": r"foundation damping $\zeta_a$",
    "speed": r"belt speed $V$ (m/s)",
    "load": r"normal load $W$ (N)",
    "mu_s": r"static friction coefficient $\mu_s$",
    "mu_k": r"kinetic friction coefficient $\mu_k$",
}


def system_title(data: ContinuationResult) -> str:
    """The system the diagram is of, in one line (mathtext)."""
    d = data.system.to_dict()
    if "machine" in d:
        m = d["machine"]
        values = ", ".join(text for key, text in (
            ("mu_s", rf"$\mu_s$ = {m['mu_s']:.4g}"), ("mu_k", rf"$\mu_k$ = {m['mu_k']:.4g}"),
            ("load", f"$W$ = {m['load_N']:.4g} N"), ("speed", f"$V$ = {m['speed_m_per_s']:.4g} m/s"))
            if key != data.param)
        law = data.system.friction.describe().split(";")[0]
        return (f"Machine '{m['name']}': {m['n_dof']} DOF, contact on DOF {m['contact_dof']}, {values}"
                f"\nfriction: {law}")
    base = "rigid base" if d["foundation"] is None else (
        f"foundation $M$ = {d['foundation']['M']:.4g}, $K$ = {d['foundation']['K']:.4g}, "
        rf"$\zeta_a$ = {d['foundation']['zeta_a']:.4g}")
    groups = ", ".join(f"{symbol} = {d[key]:.4g}" for key, symbol in
                       (("lam", r"$\lambda$"), ("zeta", r"$\zeta$"), ("gamma", r"$\gamma$"))
                       if key != data.param)
    law = str(d["friction"]).split(";")[0]
    return f"Slider on a moving belt, {base}, {groups}\nfriction: {law}"


def _runs(stable: np.ndarray) -> list[tuple[int, int, bool]]:
    """Maximal runs ``(start, stop, stable)`` of equal stability (``stop`` inclusive, shared)."""
    out: list[tuple[int, int, bool]] = []
    start = 0
    for i in range(1, stable.size + 1):
        if i == stable.size or stable[i] != stable[start]:
            out.append((start, min(i, stable.size - 1), bool(stable[start])))
            start = i
    return out


def continuation_plot(
    data: ContinuationResult,
    *,
    ax: Axes | None = None,
    show_steady: bool = True,
    show_events: bool = True,
) -> PlotResult:
    """Amplitude of every continued branch against the parameter (stable solid, unstable dashed).

    Steady sliding (amplitude 0) is drawn on the axis, solid where it is linearly stable and
    dashed where it is not; named events are marked and listed in the legend.

    Parameters
    ----------
    data : ContinuationResult
        Of :func:`stickslip.analysis.continuation.continue_cycles`.
    ax : Axes, optional
        Draw into it (a new figure otherwise).
    show_steady, show_events : bool
        Draw steady sliding; mark the events.

    Returns
    -------
    PlotResult
        One axes: the diagram (amplitude in ``V/omega_n`` against the parameter).
    """
    fig, ax = new_axes(ax, figsize=(8.0, 4.8))
    artists: list[Any] = []
    machine = data.system.si_scales() is not None
    labelled: set[str] = set()

    def label(text: str) -> str | None:
        if text in labelled:
            return None
        labelled.add(text)
        return text

    def scaled(p: float, amplitude: float) -> float:  # metres for a machine
        return amplitude * data.si_scales(p)[1] if machine else amplitude

    for branch in data.branches:
        p = np.array([q.param for q in branch.points])
        a = np.array([scaled(q.param, q.amplitude) for q in branch.points])
        st = np.array([q.stable for q in branch.points], dtype=bool)
        color = KIND_COLORS.get(branch.kind, "0.3")
        for i, j, stable in _runs(st):
            text = f"{branch.kind}, {'stable' if stable else 'unstable'}"
            (line,) = ax.plot(p[i:j + 1], a[i:j + 1], color=color, lw=1.6,
                              ls="-" if stable else "--", label=label(text))
            artists.append(line)
    if show_steady and data.steady_param.size:
        sp, ok = np.asarray(data.steady_param), np.asarray(data.steady_stable)
        for i, j, stable in _runs(ok):
            text = f"steady sliding, {'stable' if stable else 'unstable'}"
            (line,) = ax.plot(sp[i:j + 1], np.zeros(j + 1 - i), color="tab:gray", lw=2.4,
                              ls="-" if stable else ":", label=label(text))
            artists.append(line)
    if show_events:
        named: list[tuple[float, str]] = []
        width = data.param_range[1] - data.param_range[0]
        for e in sorted(data.events, key=lambda e: e.param):
            if not np.isfinite(e.amplitude):
                continue
            marker, color = EVENT_MARKERS.get(e.type, ("x", "k"))
            y = scaled(e.param, e.amplitude)
            artists.append(ax.plot([e.param], [y], marker=marker, color=color, ls="none",
                                   ms=7, label=label(e.type), zorder=5)[0])
            if any(t == e.type and abs(p - e.param) <= 1e-6 * width for p, t in named):
                continue  # the same event found from two branches: named once
            # names of events close together are stacked, not printed over each other
            near = sum(1 for p, _ in named if abs(p - e.param) <= 0.06 * width)
            named.append((e.param, e.type))
            artists.append(ax.annotate(f"{e.type} {e.param:.5g}", (e.param, y), xytext=(-4, 10 + 11 * near),
                                       textcoords="offset points", fontsize="x-small", color=color,
                                       ha="right" if e.param > data.param_range[0] + 0.5 * width else "left"))
    ax.set_xlabel(PARAM_LABELS.get(data.param, data.param))
    ax.set_ylabel(r"amplitude of $x$, $\frac{1}{2}$ peak to peak (m)" if machine else
                  r"amplitude of $\xi$, $\frac{1}{2}$ peak to peak ($V/\omega_n$)")
    ax.set_title(system_title(data), fontsize="medium")
    ax.set_xlim(*data.param_range)
    top = max([1e-12] + [scaled(q.param, q.amplitude) for b in data.branches for q in b.points])
    ax.set_ylim(-0.02 * top, 1.12 * top)
    # outside the axes: the legend never covers a branch
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small", frameon=False)
    return PlotResult(fig, [ax], artists)


def memory_continuation_plot(data: MemoryContinuation, *, ax: Axes | None = None,
                             title: str | None = None) -> PlotResult:
    """Amplitude of the contact's periodic orbits against the drive speed (friction with memory).

    Stable orbits solid, unstable dashed; steady sliding on the axis (solid grey where it is
    stable, dashed red where not); the Hopf points starred and named. The speed axis is
    logarithmic when the range spans more than a decade; the legend stands outside the axes.

    Parameters
    ----------
    data : MemoryContinuation
        From :func:`stickslip.analysis.memory.continuation.continue_memory_orbits`.
    ax : Axes, optional
        Axes to draw into; new figure when None.
    title : str, optional
        Axes title (default: the law and the structure).

    Returns
    -------
    PlotResult
        One axes.
    """
    fig, axis = new_axes(ax, figsize=(8.4, 4.6))
    artists: list[Any] = []
    labelled: set[str] = set()

    def label(name: str) -> str | None:
        if name in labelled:
            return None
        labelled.add(name)
        return name

    for branch in data.branches:
        speeds = np.array([p.speed for p in branch.points])
        amps = np.array([p.amplitude for p in branch.points])
        stable = np.array([p.stable for p in branch.points])
        for a, b, ok in _runs(stable):
            name = "periodic orbit, " + ("stable" if ok else "unstable")
            artists += axis.plot(speeds[a:b + 1], amps[a:b + 1], "-" if ok else "--", color="black",
                                 lw=1.6, label=label(name))
    for a, b, ok in _runs(np.asarray(data.steady_growth < 0.0)):
        name = "steady sliding, " + ("stable" if ok else "unstable")
        artists += axis.plot(data.steady_speed[a:b + 1], np.zeros(b + 1 - a),
                             "-" if ok else "--", color="0.5" if ok else "tab:red", lw=2.5,
                             label=label(name))
    for v in data.hopf:
        artists += axis.plot([v], [0.0], marker="*", ms=13, color="tab:blue", mec="k", ls="none",
                             label=label("Hopf point"))
        artists.append(axis.annotate(f"Hopf {v:.5g}", (v, 0.0), textcoords="offset points",
                                     xytext=(4, 8), fontsize="small", color="tab:blue"))
    lo, hi = data.speed_range
    if hi / lo > 10.0:
        from matplotlib.ticker import NullFormatter

        axis.set_xscale("log")
        axis.xaxis.set_minor_formatter(NullFormatter())  # labelled minor ticks overlap
    axis.set_xlim(lo, hi)
    axis.set_xlabel(PARAM_LABELS["speed"])
    axis.set_ylabel(r"amplitude of $x_c$, $\frac{1}{2}$ peak to peak (m)")
    law = data.system.friction.to_dict().get("law", "memory")
    axis.set_title(title or f"{data.system.n_dof}-DOF machine, {law} friction, load "
                   f"{data.system.load:g} N\nperiodic orbits against the drive speed")
    axis.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small", frameon=False)
    return PlotResult(fig, [axis], artists)
