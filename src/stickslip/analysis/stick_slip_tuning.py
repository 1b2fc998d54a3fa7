"""The stick-slip optimum of the elastic foundation (beyond the paper).

The paper tunes the foundation as a vibration absorber and notes (Figs. 11a, 12-15) that a
foundation detuned to ``K_opt/2`` suppresses stick-slip far better; here the objective is the
simulated stick-slip onset ``lambda_crit`` itself (:func:`stickslip.analysis.critical.lowest_onset`),
maximised over ``(M, K, zeta_a)`` with the shared optimiser of :mod:`stickslip.analysis.optimise`.
All quantities are dimensionless.

Friction law: the Coulomb law of the paper (``mu = mu_k`` while sliding), whatever the
machine's. Decision: a law that moves with the belt speed (Stribeck, linear, table) has no
single ``lambda_crit``; its onset is a critical belt speed found by an exact boundary search
of some 40 simulations (:func:`stickslip.analysis.critical.speed_and_load_onsets`), and the
optimiser needs about a hundred of them, minutes where this search takes seconds. So the
tuning stays Coulomb, and ``stickslip design`` states beside the result that it assumes
Coulomb friction (:func:`stickslip.analysis.design.coulomb_tuning_note`) and assesses the
result once with the machine's law (one boundary search, its critical speed and load).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from stickslip.analysis.critical import lowest_onset
from stickslip.analysis.optimise import best_seed, nelder_mead, ordered_bounds
from stickslip.analysis.theory import optimal_foundation_fit
from stickslip.model._validate import non_negative, positive
from stickslip.model.parameters import Foundation
from stickslip.model.structure import elastic_foundation


@dataclass(frozen=True)
class StickSlipTuning:
    """Result of :func:`optimal_foundation_stick_slip` (all dimensionless).

    Attributes
    ----------
    foundation : Foundation
        The best foundation found.
    lambda_crit : float
        Its stick-slip onset; ``inf`` means no stick-slip up to ``lam_max``.
    reference : Foundation
        The absorber optimum it is compared with (Eqs. 28-30 unless given).
    reference_lambda_crit : float
        Onset of the reference.
    gain : float
        ``lambda_crit / reference_lambda_crit``.
    """

    zeta: float
    gamma: float
    foundation: Foundation
    lambda_crit: float
    reference: Foundation
    reference_lambda_crit: float
    mass_ratio_bounds: tuple[float, float]
    lam_max: float
    evaluations: int

    @property
    def gain(self) -> float:
        return self.lambda_crit / self.reference_lambda_crit

    def to_dict(self) -> dict[str, Any]:
        def num(x: float) -> float | None:
            return x if math.isfinite(x) else None

        f, r = self.foundation, self.reference
        return {
            "objective": "stick-slip",
            "zeta": self.zeta,
            "gamma": self.gamma,
            "M": f.mass_ratio,
            "K": f.stiffness_ratio,
            "zeta_a": f.damping_ratio,
            "lambda_crit": num(self.lambda_crit),
            "lambda_crit_at_least": self.lam_max if math.isinf(self.lambda_crit) else None,
            "absorber_optimum": {
                "M": r.mass_ratio,
                "K": r.stiffness_ratio,
                "zeta_a": r.damping_ratio,
                "lambda_crit": num(self.reference_lambda_crit),
                "source": "fitted Eqs. (28)-(30)",
            },
            "gain": num(self.gain),
            "mass_ratio_bounds": list(self.mass_ratio_bounds),
            "lam_max": self.lam_max,
            "evaluations": self.evaluations,
        }


def optimal_foundation_stick_slip(
    zeta: float,
    gamma: float = 2.0,
    *,
    mass_ratio_bounds: tuple[float, float] | None = None,
    reference: Foundation | None = None,
    lam_max: float = 100.0,
    rtol: float = 1e-4,
    maxiter: int = 60,
) -> StickSlipTuning:
    """Maximise the simulated stick-slip onset over ``(M, K, zeta_a)``.

    Parameters
    ----------
    zeta : float
        Primary damping ratio, dimensionless.
    gamma : float
        ``mu_k / (mu_s - mu_k)``.
    mass_ratio_bounds : (float, float), optional
        Allowed ``M``; defaults to ``(M_opt / 20, M_opt)`` with ``M_opt`` of Eq. (28).
    reference : Foundation, optional
        The absorber optimum to compare with; defaults to Eqs. (28)-(30).
    lam_max : float
        Onsets above this count as "no stick-slip" (the objective saturates there).
    rtol : float
        Relative tolerance of each onset.
    maxiter : int
        Iterations of the Nelder-Mead refinement.

    Returns
    -------
    StickSlipTuning
        The best foundation, its onset and the reference's.

    Notes
    -----
    A coarse grid over ``(K, zeta_a)`` at the largest allowed ``M`` (and at the smallest)
    seeds a Nelder-Mead search in log coordinates, clipped to the bounds. The objective
    is piecewise constant at the scale of ``rtol``, so the result is a good design, not a
    certified global optimum; the comparison with the reference is exact for both points.
    """
    zeta = non_negative("zeta", zeta)
    gamma = non_negative("gamma", gamma)
    lam_max = positive("lam_max", lam_max)
    reference = optimal_foundation_fit(zeta) if reference is None else reference
    if mass_ratio_bounds is None:
        mass_ratio_bounds = (reference.mass_ratio / 20.0, reference.mass_ratio)
    m_lo, m_hi = ordered_bounds("mass ratio", mass_ratio_bounds)
    count = 0

    def onset(f: Foundation, tol: float = rtol) -> float:
        nonlocal count
        count += 1
        return lowest_onset(elastic_foundation(zeta, f), gamma=gamma, lam_max=lam_max, rtol=tol)

    def objective(x: np.ndarray) -> float:
        m = float(np.clip(np.exp(x[0]), m_lo, m_hi))
        k = float(np.exp(np.clip(x[1], -4.0, 4.0)))
        za = float(np.exp(np.clip(x[2], -7.0, 3.0)))
        value = onset(Foundation(m, k, za))
        return -min(value, lam_max)

    ref_onset = onset(reference, 1e-6)
    k_ref, za_ref = reference.stiffness_ratio, reference.damping_ratio
    seeds = [np.log([m, k, za])
             for m in sorted({m_hi, math.sqrt(m_lo * m_hi)})
             for k in k_ref * np.array([0.35, 0.5, 0.7, 1.0])
             for za in za_ref * np.array([0.25, 0.5, 1.0])]
    best_x, best_val = best_seed(objective, seeds)
    if best_val > -lam_max:
        x, value = nelder_mead(objective, best_x, xatol=1e-3, fatol=1e-4 * lam_max, maxiter=maxiter)
        if value < best_val:
            best_x, best_val = x, value
    m = float(np.clip(np.exp(best_x[0]), m_lo, m_hi))
    k = float(np.exp(np.clip(best_x[1], -4.0, 4.0)))
    za = float(np.exp(np.clip(best_x[2], -7.0, 3.0)))
    best = Foundation(m, k, za)
    best_onset = onset(best, 1e-6)
    return StickSlipTuning(zeta, gamma, best, best_onset, reference, ref_onset, (m_lo, m_hi),
                           lam_max, count)
