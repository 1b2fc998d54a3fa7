"""The paper's Fig. 16 as a flowchart: the design procedure with a worked example's numbers.

Follows the plotting contract of :mod:`stickslip.plot.figure`: :func:`design_flowchart_plot`
takes the :class:`~stickslip.analysis.design.DesignReport` first and keyword-only options
with ``ax=None``, draws, and returns a :class:`~stickslip.plot.figure.PlotResult`.

The chart is laid out in inches (the axes' data units on a new figure, equal aspect), so the
text, set in points, fits its boxes whatever the numbers.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.patches import FancyBboxPatch, Polygon

from stickslip.plot.figure import PlotResult, new_axes

if TYPE_CHECKING:
    from stickslip.analysis.design import DesignReport

#: Size of a new figure, inches; the chart's coordinates are inches of this figure.
FLOWCHART_SIZE = (10.0, 10.6)
FONT_SIZE = 9.0
LINE = 0.21  # inches per line of body text at FONT_SIZE with the line spacing used

_STYLES: dict[str, dict[str, Any]] = {
    "step": {"facecolor": "#eef3f9", "edgecolor": "#3b6ea5"},
    "decision": {"facecolor": "#fff4d6", "edgecolor": "#b7860b"},
    "result": {"facecolor": "#e7f4ea", "edgecolor": "#2e7d32"},
    "stop": {"facecolor": "#f8e4e1", "edgecolor": "#b03a2e"},
    "note": {"facecolor": "#f6f6f6", "edgecolor": "0.6", "linestyle": (0, (3, 2))},
}
_ARROW = {"arrowstyle": "-|>", "color": "0.25", "lw": 1.2, "shrinkA": 0, "shrinkB": 0,
          "mutation_scale": 12}


def _num(x: float | None, unit: str = "") -> str:
    """Four significant digits, no exponent (``47920``, ``0.03162``); ``none`` when undefined."""
    if x is None or not math.isfinite(x):
        return "none"
    text = np.format_float_positional(x, precision=4, unique=False, fractional=False, trim="-")
    return f"{text} {unit}".rstrip()


@dataclass(frozen=True)
class _Box:
    """A box of the chart: centre ``x``, top ``top``, ``width`` and ``height`` (inches)."""

    x: float
    top: float
    width: float
    height: float

    @property
    def bottom(self) -> float:
        return self.top - self.height

    @property
    def left(self) -> float:
        return self.x - self.width / 2

    @property
    def right(self) -> float:
        return self.x + self.width / 2

    @property
    def middle(self) -> float:
        return self.top - self.height / 2


class _Chart:
    """Draws boxes, diamonds and arrows into one axes and keeps the artists."""

    def __init__(self, ax: Axes) -> None:
        self.ax = ax
        self.artists: list[Any] = []

    def box(self, box: _Box, header: str, lines: list[str], style: str) -> None:
        pad = 0.08
        patch = FancyBboxPatch((box.left + pad, box.bottom + pad), box.width - 2 * pad,
                               box.height - 2 * pad, boxstyle=f"round,pad={pad}", lw=1.2,
                               **_STYLES[style])
        self.ax.add_patch(patch)
        self.artists.append(patch)
        self.artists.append(self.ax.text(box.x, box.top - 0.14, header, ha="center", va="top",
                                         fontsize=FONT_SIZE + 0.5, weight="bold"))
        if lines:
            self.artists.append(self.ax.text(box.x, box.top - 0.14 - LINE * 1.35, "\n".join(lines),
                                             ha="center", va="top", fontsize=FONT_SIZE,
                                             linespacing=1.55))

    def diamond(self, box: _Box, header: str, lines: list[str]) -> None:
        corners = [(box.x, box.top), (box.right, box.middle), (box.x, box.bottom),
                   (box.left, box.middle)]
        patch = Polygon(corners, closed=True, lw=1.2, **_STYLES["decision"])
        self.ax.add_patch(patch)
        self.artists.append(patch)
        self.artists.append(self.ax.text(box.x, box.middle + 0.12, header, ha="center",
                                         va="bottom", fontsize=FONT_SIZE + 0.5, weight="bold"))
        self.artists.append(self.ax.text(box.x, box.middle + 0.06, "\n".join(lines), ha="center",
                                         va="top", fontsize=FONT_SIZE, linespacing=1.6))

    def arrow(self, start: tuple[float, float], end: tuple[float, float], label: str = "",
              bold: bool = True) -> None:
        props = dict(_ARROW, lw=1.6 if bold else 1.0, color="0.15" if bold else "0.55")
        self.artists.append(self.ax.annotate("", xy=end, xytext=start, arrowprops=props))
        if label:
            horizontal = start[1] == end[1]
            x = (start[0] + end[0]) / 2 if horizontal else start[0] + 0.1
            y = start[1] + 0.1 if horizontal else (start[1] + end[1]) / 2
            self.artists.append(self.ax.text(x, y, label, ha="center" if horizontal else "left",
                                             va="bottom" if horizontal else "center",
                                             fontsize=FONT_SIZE, style="italic",
                                             color="0.15" if bold else "0.55"))

    def down(self, upper: _Box, lower: _Box, label: str = "", bold: bool = True) -> None:
        self.arrow((upper.x, upper.bottom), (lower.x, lower.top), label, bold)

    def right(self, left: _Box, right: _Box, label: str = "", bold: bool = True) -> None:
        self.arrow((left.right, left.middle), (right.left, left.middle), label, bold)


# Over 120 lines on purpose: the flowchart of Fig. 16 is drawn box by box and arrow by arrow in
# reading order, so that each box sits next to the step it shows; cut into helpers it would be
# harder to check against the figure.
def design_flowchart_plot(
    report: DesignReport,
    *,
    ax: Axes | None = None,
    title: str | None = "Design procedure of the paper's Fig. 16",
) -> PlotResult:
    """Draw the design procedure of the paper's Fig. 16 with the numbers of ``report``.

    Steps down the main column: model the machine as a 1DOF sliding system (seven
    parameters, SI units); the dimensionless ``lambda`` and ``zeta``; ``zeta_eq`` from
    Eq. (33) (or Eq. 32 for a given foundation); the decision of Eq. (38),
    ``(1 - zeta_eq)^5 lambda^2 / zeta_eq < 4 pi``; ``M_opt``, ``K_opt``, ``zeta_a,opt``
    from Eqs. (28)-(30); the foundation ``m_a`` (kg), ``k_a`` (N/m), ``c_a`` (N s/m); the
    critical belt speed (m/s) and normal load (N) for the redesign. Notes on the right give
    the rigid base (Eq. 39), the branch where Eq. (38) fails, and the simulated check.

    Parameters
    ----------
    report : DesignReport
        From :func:`stickslip.analysis.design.design_foundation`.
    ax : matplotlib Axes, optional
        Drawn into (its axis lines are switched off); a new figure of
        :data:`FLOWCHART_SIZE` inches is made when omitted, where the text fits its boxes.
    title : str or None
        Axes title; None for none.

    Returns
    -------
    PlotResult
        One axes; the artists are the boxes, the arrows and the texts.
    """
    fig, ax = new_axes(ax, figsize=FLOWCHART_SIZE)
    d = report.to_dict()
    s, f, crit_speed, crit_load = d["system"], d["foundation"], d["critical_speed"], d["critical_load"]
    verdicts = d["verdict"]
    lam, zeta, zeta_eq = d["lambda"], d["zeta"], d["zeta_eq"]
    criterion = (1.0 - zeta_eq) ** 5 * lam**2 / zeta_eq if zeta_eq > 0.0 else math.inf
    holds = criterion < 4.0 * math.pi
    given = not str(f["source"]).startswith("recommended")

    width, height = FLOWCHART_SIZE
    main_x, main_w = 3.2, 5.9
    side_x, side_w = 8.3, 3.2
    gap = 0.42
    chart = _Chart(ax)

    def below(box: _Box, h: float, w: float = main_w) -> _Box:
        return _Box(main_x, box.bottom - gap, w, h)

    model = _Box(main_x, height - 0.35, main_w, 1.05)
    chart.box(model, "1. Model the machine as a 1DOF sliding system", [
        f"$m$ = {_num(s['m'], 'kg')},   $k$ = {_num(s['k'], 'N/m')},   $c$ = {_num(s['c'], 'N s/m')}",
        rf"$\mu_s$ = {_num(s['mu_s'])},   $\mu_k$ = {_num(s['mu_k'])},   "
        f"$W$ = {_num(s['load'], 'N')},   $V$ = {_num(s['speed'], 'm/s')}",
    ], "step")
    groups = below(model, 1.05)
    chart.box(groups, "2. Dimensionless parameters", [
        rf"$\lambda = (\mu_s - \mu_k)\,W / (V\sqrt{{mk}})$ = {_num(lam)}",
        rf"$\zeta = c / (2\sqrt{{mk}})$ = {_num(zeta)},   $\gamma$ = {_num(d['gamma'])}",
    ], "step")
    equivalent = below(groups, 0.85)
    source = "Eq. (32)" if given else "Eq. (33)"
    chart.box(equivalent, f"3. Equivalent damping ratio, {source}",
              [rf"$\zeta_{{eq}}$ = {_num(zeta_eq)}"], "step")
    decision = below(equivalent, 1.75, 4.9)
    relation = "<" if holds else r"\geq"
    chart.diamond(decision, "4. Does Eq. (38) hold?", [
        r"$(1-\zeta_{eq})^5\,\lambda^2/\zeta_{eq} < 4\pi$",
        rf"${_num(criterion)} {relation} 4\pi = {_num(4.0 * math.pi)}$",
    ])
    optimum = below(decision, 0.85)
    header = "5. Given foundation, dimensionless" if given else "5. Optimal foundation, Eqs. (28)-(30)"
    symbols = (r"$M$", r"$K$", r"$\zeta_a$") if given else (
        r"$M_{opt}$", r"$K_{opt}$", r"$\zeta_{a,opt}$")
    chart.box(optimum, header, ["   ".join(
        f"{symbol} = {_num(f[key])}," for symbol, key in zip(symbols, ("M", "K", "zeta_a"), strict=True)
    ).rstrip(",")], "step")
    physical = below(optimum, 0.85)
    chart.box(physical, "6. Foundation in SI units", [
        f"$m_a$ = {_num(f['m_a'], 'kg')},   $k_a$ = {_num(f['k_a'], 'N/m')},   "
        f"$c_a$ = {_num(f['c_a'], 'N s/m')}",
    ], "step")
    redesign = below(physical, 1.5)
    rows = (("rigid base, Eq. (39)", "rigid_theory"), ("rigid base, simulated", "rigid_simulation"),
            ("with foundation, Eq. (37)", "foundation_theory"),
            ("with foundation, simulated", "foundation_simulation"))
    chart.box(redesign, "7. Redesign: stick-slip for $V < V_c$ or $W > W_c$", [
        f"{label}:   $V_c$ = {_num(crit_speed[key], 'm/s')},   $W_c$ = {_num(crit_load[key], 'N')}"
        for label, key in rows
    ], "result")

    for upper, lower in ((model, groups), (groups, equivalent), (equivalent, decision),
                         (optimum, physical), (physical, redesign)):
        chart.down(upper, lower)
    chart.down(decision, optimum, "yes", bold=holds)

    rigid = _Box(side_x, groups.top + 0.1, side_w, 1.25)
    chart.box(rigid, "Rigid base, Eq. (39)", [
        rf"$\lambda_c$ = {_num(d['critical_lambda']['rigid_theory'])},   $\lambda$ = {_num(lam)}",
        f"theory: {verdicts['rigid']['theory']}",
        f"simulation: {verdicts['rigid']['simulation']}",
    ], "note")
    chart.arrow((groups.right, groups.middle), (rigid.left, groups.middle), bold=False)
    stop = _Box(side_x, decision.middle + 0.6, side_w, 1.2)
    chart.box(stop, "Eq. (38) fails", ["the foundation cannot",
                                       "suppress stick-slip: redesign",
                                       r"the machine ($\lambda$, $\zeta$)"], "stop")
    chart.right(decision, stop, "no", bold=not holds)
    check = _Box(side_x, redesign.top, side_w, redesign.height)
    chart.box(check, "Check by simulation", [
        f"at $W$ = {_num(s['load'], 'N')}, $V$ = {_num(s['speed'], 'm/s')}:",
        f"rigid base: {verdicts['rigid']['simulation']}",
        f"with foundation: {verdicts['foundation']['simulation']}",
    ], "note")
    chart.right(redesign, check, bold=False)
    bottom = redesign.bottom - 0.3
    if d["warnings"]:
        lines = [line for warning in d["warnings"] for line in textwrap.wrap(warning, 120)]
        chart.artists.append(ax.text(0.3, redesign.bottom - 0.15, "\n".join(lines), ha="left",
                                     va="top", fontsize=FONT_SIZE - 1, color="#b03a2e"))
        bottom -= 0.2 * len(lines)

    ax.set_xlim(0.0, width)
    ax.set_ylim(bottom, height)
    ax.set_aspect("equal")
    ax.axis("off")
    if title:
        chart.artists.append(ax.set_title(title, fontsize="large"))
    return PlotResult(fig, [ax], chart.artists)
