"""Reproduction steps from single simulations: Figs. 7, 12-15, Eqs. (34)-(36), (39)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from stickslip.analysis.simulation import simulate
from stickslip.analysis.theory import (
    critical_lambda_approx,
    critical_lambda_exact,
    stick_slip_amplitude_ratio,
    stick_slip_period,
)
from stickslip.analysis.verdict import Verdict
from stickslip.model import Slider, rigid_base
from stickslip.reproduction import histories
from stickslip.reproduction.claims import Claim
from stickslip.reproduction.outputs import save_columns, save_figure
from stickslip.reproduction.quality import Quality
from stickslip.reproduction.report import FigureRecord


def time_history_figures(out_dir: Path, quality: Quality) -> tuple[list[FigureRecord], list[Claim]]:
    """Figs. 7, 12, 13, 14, 15 and the claims read off them."""
    data_dir = out_dir / "data"
    figures: list[FigureRecord] = []
    claims: list[Claim] = []

    runs7 = histories.fig7_runs()
    csv7 = save_columns(histories.history_table(runs7, quality.history_points), data_dir / "fig07.csv")
    figures.append(save_figure(histories.fig7_figure(runs7, quality.history_points), out_dir, "fig07",
                               "Fig. 7: time histories, tuned and detuned foundation", [csv7]))
    tuned = {r.lam: r.verdict.value for r in runs7 if r.k_scale == 1.0}
    detuned = {r.lam: r.verdict.value for r in runs7 if r.k_scale == 2.0}
    differs_at = [lam for lam in tuned if tuned[lam] != detuned[lam]]
    claims.append(Claim(
        "fig7", "Fig. 7",
        "At zeta = 0.1 the DVA setting decides occurrence: some lambda stick-slip with "
        "K = 2 K_opt but not with the tuned foundation.",
        "verdicts (tuned / 2 K_opt): " + "; ".join(
            f"lambda={lam:g}: {tuned[lam]} / {detuned[lam]}" for lam in sorted(tuned)),
        "confirmed" if differs_at else "differs",
        {"tuned": tuned, "detuned": detuned},
    ))

    runs12 = histories.fig12_runs()
    csv12 = save_columns(histories.history_table(runs12, quality.history_points),
                         data_dir / "fig12-15.csv")
    for lam in (1.0, 10.0):
        number = 12 if lam == 1.0 else 13
        figures.append(save_figure(histories.fig12_figure(runs12, lam, quality.history_points), out_dir,
                                   f"fig{number}", f"Fig. {number}: both masses at lambda = {lam:g}",
                                   [csv12]))
    for lam in (1.0, 10.0):
        number = 14 if lam == 1.0 else 15
        figures.append(save_figure(histories.phase_figure(runs12, lam, quality.history_points), out_dir,
                                   f"fig{number}", f"Fig. {number}: phase plane at lambda = {lam:g}",
                                   [csv12]))
    v = {(r.lam, r.k_scale): r.verdict for r in runs12}
    expected = {(1.0, 0.5): Verdict.STEADY_SLIDING, (1.0, 2.0): Verdict.STEADY_SLIDING,
                (10.0, 0.5): Verdict.STEADY_SLIDING, (10.0, 2.0): Verdict.STICK_SLIP}
    ok = all(v[key] is expected[key] for key in expected)
    claims.append(Claim(
        "fig12-13", "Figs. 12-15",
        "zeta = 0.01: no stick-slip at lambda = 1 for K_opt/2 and 2 K_opt; at lambda = 10 "
        "stick-slip only with 2 K_opt (a limit cycle, Fig. 15b).",
        "; ".join(f"lambda={lam:g}, K x {s:g}: {v[(lam, s)].value}" for lam, s in expected),
        "confirmed" if ok else "differs",
        {f"{lam:g}/{s:g}": v[(lam, s)].value for lam, s in expected},
    ))
    phase_half = histories.modal_phase_deg(histories.FIG12_ZETA, 0.5)
    phase_double = histories.modal_phase_deg(histories.FIG12_ZETA, 2.0)
    opposite = abs(phase_half) > 90.0 and abs(phase_double) < 45.0
    claims.append(Claim(
        "phase", "Figs. 12-13, Section 4",
        "With K_opt/2 the two masses oscillate nearly in opposite phase; with 2 K_opt in phase.",
        f"phase of xi_a relative to xi in the least-damped slip-I mode: {phase_half:.0f} deg "
        f"(K_opt/2) and {phase_double:.0f} deg (2 K_opt); opposite would be 180 deg",
        "partly confirmed" if opposite and abs(phase_half) < 150.0 else
        ("confirmed" if opposite else "differs"),
        {"phase_deg_K_half": phase_half, "phase_deg_K_double": phase_double},
    ))
    return figures, claims


def closed_form_claims() -> list[Claim]:
    """Eqs. (34)-(35) and the simplified boundary Eq. (39) against the exact Eq. (36)."""
    claims = []
    errors = []
    for lam in (0.5, 2.0, 10.0):
        r = simulate(rigid_base(0.0), Slider(lam))
        errors.append(max(abs(r.period / stick_slip_period(lam) - 1.0),
                          abs(r.amplitude / stick_slip_amplitude_ratio(lam) - 1.0)))
    claims.append(Claim(
        "eq34-35", "Eqs. (34)-(35)",
        "Undamped 1DOF stick-slip: f_ss/f_n = 1/(1 + (lambda - atan lambda)/pi), "
        "A_ss/A_n = sqrt(1 + lambda^2).",
        f"simulated period and amplitude at lambda = 0.5, 2, 10 match to {max(errors):.1e} (relative)",
        "confirmed" if max(errors) < 1e-9 else "differs",
        {"max_relative_error": max(errors)},
    ))
    zetas = np.linspace(0.005, 0.4, 80)
    rel = np.array([critical_lambda_approx(z) / critical_lambda_exact(z) - 1.0 for z in zetas])
    worst = int(np.argmax(np.abs(rel)))
    small = zetas <= 0.1
    claims.append(Claim(
        "eq39-vs-36", "Eqs. (36), (37), (39)",
        "The simplified boundary (Eq. 37/39) approximates Nakano's exact Eq. (36).",
        f"Eq. (39) / Eq. (36) - 1 over zeta in [0.005, 0.4]: within "
        f"{100 * np.abs(rel[small]).max():.1f}% for zeta <= 0.1, worst "
        f"{100 * rel[worst]:+.1f}% at zeta = {zetas[worst]:.3f}",
        "confirmed" if np.abs(rel[small]).max() < 0.05 else "differs",
        {"zeta": zetas.tolist(), "relative_difference": rel.tolist()},
    ))
    return claims


def fmt_lambda(x: float) -> str:
    """``inf`` as a readable bound."""
    return "none up to the scan limit" if math.isinf(x) else f"{x:.4g}"
