"""Figs. 7 and 12-15: time histories and phase portraits of the sliding system."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from stickslip.analysis.simulation import EngineOptions, SimulationResult, simulate
from stickslip.analysis.theory import optimal_foundation_fit
from stickslip.analysis.verdict import Verdict
from stickslip.model import Slider, elastic_foundation
from stickslip.plot.figure import new_grid
from stickslip.plot.simulation import phase_portrait_plot, time_history_plot

FIG7_ZETA = 0.1
FIG7_LAMS = (1.0, 3.0, 6.0, 12.0)
FIG7_T_MAX = 150.0
FIG12_ZETA = 0.01
FIG12_T_MAX = 300.0


@dataclass(frozen=True)
class Run:
    """A labelled simulation used by a figure."""

    label: str
    k_scale: float
    lam: float
    zeta: float
    result: SimulationResult  # the drawn window, simulated up to its end
    verdict: Verdict  # certified verdict of the same case (default horizon)


def run_case(lam: float, zeta: float, k_scale: float, t_max: float, gamma: float = 2.0) -> Run:
    """Simulate the fitted optimal foundation (Eqs. 28-30) with ``K`` scaled by ``k_scale``."""
    structure = elastic_foundation(zeta, optimal_foundation_fit(zeta).scaled(k_scale))
    slider = Slider(lam, gamma=gamma)
    result = simulate(structure, slider, options=EngineOptions(t_max=t_max), run_to_t_max=True)
    verdict = simulate(structure, slider, record=False).verdict
    tag = {1.0: "K_opt", 2.0: "2 K_opt", 0.5: "K_opt/2"}.get(k_scale, f"{k_scale:g} K_opt")
    return Run(f"{tag}, lambda={lam:g}", k_scale, lam, zeta, result, verdict)


def fig7_runs() -> list[Run]:
    """Paper Fig. 7: zeta = 0.1, gamma = 2; (a) tuned foundation, (b) K = 2 K_opt."""
    return [run_case(lam, FIG7_ZETA, scale, FIG7_T_MAX) for scale in (1.0, 2.0) for lam in FIG7_LAMS]


def fig12_runs() -> list[Run]:
    """Paper Figs. 12-15: zeta = 0.01; lambda = 1 and 10; K = K_opt/2 (a) and 2 K_opt (b)."""
    return [run_case(lam, FIG12_ZETA, scale, FIG12_T_MAX) for lam in (1.0, 10.0) for scale in (0.5, 2.0)]


def fig7_figure(runs: list[Run], n_points: int) -> Figure:
    """Displacement histories, one row per lambda, tuned (left) and detuned (right)."""
    lams = sorted({r.lam for r in runs})
    fig, axes = new_grid(len(lams), 2, figsize=(11.0, 2.2 * len(lams) + 0.6), sharex=True)
    for col, scale in enumerate((1.0, 2.0)):
        for row, lam in enumerate(lams):
            run = next(r for r in runs if r.lam == lam and r.k_scale == scale)
            drawn = time_history_plot(run.result, ax=axes[2 * row + col], n_points=n_points,
                                      show_foundation=False, legend=False)
            drawn.ax.set_title(f"{run.label}: {run.verdict.value}", fontsize="small")
    # one legend for the eight panels, below them: inside, the stick shading leaves no room
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=len(labels), fontsize="small",
               frameon=False)
    fig.suptitle(r"Fig. 7: $\xi(\tau)$ at $\zeta$ = 0.1, $\gamma$ = 2; "
                 r"(a) optimal foundation, (b) $K = 2K_{opt}$")
    return fig


def fig12_figure(runs: list[Run], lam: float, n_points: int) -> Figure:
    """Displacements and velocities of both masses (paper Figs. 12 and 13)."""
    fig, axes = new_grid(2, 2, figsize=(11.0, 5.5), sharex=True)
    for col, scale in enumerate((0.5, 2.0)):
        run = next(r for r in runs if r.lam == lam and r.k_scale == scale)
        time_history_plot(run.result, ax=axes[col], quantity="position", n_points=n_points)
        time_history_plot(run.result, ax=axes[2 + col], quantity="velocity", n_points=n_points)
        axes[col].set_title(f"({'ab'[col]}) {run.label}: {run.verdict.value}",
                               fontsize="small")
    number = 12 if lam == 1.0 else 13
    fig.suptitle(f"Fig. {number}: both masses at $\\lambda$ = {lam:g}, $\\zeta$ = 0.01")
    return fig


def phase_figure(runs: list[Run], lam: float, n_points: int) -> Figure:
    """Phase portraits (paper Figs. 14 and 15)."""
    fig, axes = new_grid(1, 2, figsize=(10.0, 4.2))
    for col, scale in enumerate((0.5, 2.0)):
        run = next(r for r in runs if r.lam == lam and r.k_scale == scale)
        phase_portrait_plot(run.result, ax=axes[col], n_points=n_points)
        axes[col].set_title(f"({'ab'[col]}) {run.label}: {run.verdict.value}",
                            fontsize="small")
    number = 14 if lam == 1.0 else 15
    fig.suptitle(f"Fig. {number}: phase plane at $\\lambda$ = {lam:g}, $\\zeta$ = 0.01")
    return fig


def history_table(runs: list[Run], n_points: int) -> dict[str, np.ndarray]:
    """Columns for a CSV: tau and xi, xi', xi_a, xi_a' of every run."""
    columns: dict[str, np.ndarray] = {}
    for run in runs:
        t = np.linspace(0.0, run.result.t_end, n_points)
        q, v, _ = run.result.state_at(t)
        key = run.label.replace(" ", "").replace(",", "_")
        columns.setdefault("tau", t)
        columns[f"{key}:xi"] = q[:, 0]
        columns[f"{key}:xi_dot"] = v[:, 0]
        columns[f"{key}:xi_a"] = q[:, 1]
        columns[f"{key}:xi_a_dot"] = v[:, 1]
    return columns


def modal_phase_deg(zeta: float, k_scale: float) -> float:
    """Phase of ``xi_a`` relative to ``xi`` in the least-damped oscillatory slip-I mode, degrees.

    0 means in phase, +-180 opposite phase; the paper reads Figs. 12a-b as "nearly opposite"
    for ``K_opt/2`` and "in phase" for ``2 K_opt``.
    """
    st = elastic_foundation(zeta, optimal_foundation_fit(zeta).scaled(k_scale))
    n = st.n_dof
    minv = np.linalg.inv(st.mass)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ st.stiffness, -minv @ st.damping]])
    eigval, eigvec = np.linalg.eig(a)
    oscillatory = [k for k in range(2 * n) if eigval[k].imag > 1e-9]
    k = min(oscillatory, key=lambda i: -eigval[i].real / abs(eigval[i]))
    return float(np.degrees(np.angle(eigvec[1, k] / eigvec[0, k])))
