"""The closed-form stick-slip boundaries that apply to a foundation choice (paper Fig. 9).

For the rigid base Eq. (36) (exact) and Eq. (39); with a foundation Eq. (37) with the
equivalent damping ratio ``zeta_eq`` of the equivalent 1DOF system (Fig. 9). For the paper's
fitted optimum (Eqs. 28-30, ``K`` not scaled) ``zeta_eq`` is Eq. (33); for any other
foundation it is Eq. (32), ``1 / (2 H_max)`` with the exact peak of the foundation's frequency
response (:func:`equivalent_damping_ratio` makes that choice, in one place). All quantities
are dimensionless.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.analysis.dva import resolve_dva
from stickslip.analysis.theory import (
    critical_lambda_approx,
    critical_lambda_exact,
    equivalent_damping_fit,
)
from stickslip.model.dva import DvaSpec
from stickslip.model.parameters import Foundation
from stickslip.model.structure import chain_structure

FloatArray = NDArray[np.float64]


ZETA_EQ_FIT = "Eq. (33), fitted optimum"
ZETA_EQ_PEAK = "Eq. (32), 1/(2 H_max) of the frequency response"


@dataclass(frozen=True)
class AnalyticBoundary:
    """One closed-form critical-lambda curve: stick-slip above ``lam`` (dimensionless).

    Attributes
    ----------
    key : str
        ``eq36``, ``eq39`` or ``eq37``.
    label : str
        Legend text naming the equation.
    zeta, lam : ndarray
        Primary damping ratio and critical lambda (``inf`` where no stick-slip is predicted).
    zeta_eq : ndarray or None
        Equivalent damping ratio used by Eq. (37); None for the rigid-base curves.
    """

    key: str
    label: str
    zeta: FloatArray
    lam: FloatArray
    zeta_eq: FloatArray | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (non-finite values become None)."""
        def clean(values: FloatArray) -> list[float | None]:
            return [float(v) if math.isfinite(v) else None for v in values]

        out: dict[str, Any] = {"label": self.label, "zeta": clean(self.zeta), "lambda": clean(self.lam)}
        if self.zeta_eq is not None:
            out["zeta_eq"] = clean(self.zeta_eq)
        return out


def equivalent_damping_ratio(
    dva: DvaSpec, zeta: float, foundation: Foundation | None = None
) -> tuple[float, str] | None:
    """``zeta_eq`` of the equivalent 1DOF model (Fig. 9) at primary damping ``zeta``, and its source.

    Eq. (33) for the fitted optimum (``optimal``, ``K`` unscaled), otherwise Eq. (32),
    ``1 / (2 H_max)``, from the exact frequency response. None for the rigid base (Eq. 39
    uses ``zeta`` itself). ``foundation``, when
    given, is ``dva`` already resolved at ``zeta`` (resolving ``optimal-exact`` is an
    optimisation of several seconds).

    Parameters
    ----------
    dva : DvaSpec
        The foundation choice.
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.
    foundation : Foundation, optional
        ``dva`` already resolved at ``zeta``.

    Returns
    -------
    tuple of (float, str) or None
        ``zeta_eq`` and the equation it comes from; None for the rigid base.
    """
    if dva.kind == "none":
        return None
    if dva.kind == "optimal" and dva.k_scale == 1.0:
        return equivalent_damping_fit(zeta), ZETA_EQ_FIT
    if foundation is None:
        foundation = resolve_dva(dva, zeta)
    assert foundation is not None  # kind is not "none"
    structure = chain_structure(zeta, (foundation,))
    from stickslip.analysis.frequency_response import equivalent_damping  # scipy: load on use

    return float(equivalent_damping(structure)), ZETA_EQ_PEAK


def analytic_boundaries(
    dva: DvaSpec, zetas: ArrayLike, foundations: Sequence[Foundation | None] | None = None
) -> list[AnalyticBoundary]:
    """The closed-form boundaries that apply to ``dva``, evaluated at ``zetas``.

    Parameters
    ----------
    dva : DvaSpec
        ``none`` gives Eq. (36) (exact) and Eq. (39); a foundation gives Eq. (37) with
        ``zeta_eq`` (empty list when ``zeta_eq`` cannot be computed in this build).
    zetas : array_like
        Primary damping ratios, dimensionless, >= 0.
    foundations : sequence of Foundation, optional
        ``dva`` already resolved at each of ``zetas`` (as stored in a map or boundary).

    Returns
    -------
    list of AnalyticBoundary
        One curve per applicable equation (critical ``lambda`` against ``zeta``).
    """
    z = np.asarray(zetas, dtype=np.float64).reshape(-1)
    if dva.kind == "none":
        return [
            AnalyticBoundary("eq36", "Eq. (36), exact", z,
                             np.array([critical_lambda_exact(v) for v in z])),
            AnalyticBoundary("eq39", "Eq. (39)", z,
                             np.array([critical_lambda_approx(v) for v in z])),
        ]
    resolved = list(foundations) if foundations is not None else [None] * z.size
    if len(resolved) != z.size:
        raise ValueError(f"{len(resolved)} foundations given for {z.size} zeta values")
    pairs = [equivalent_damping_ratio(dva, float(v), f) for v, f in zip(z, resolved, strict=True)]
    if any(p is None for p in pairs):
        return []
    zeta_eq = np.array([p[0] for p in pairs if p is not None])
    source = pairs[0][1] if pairs and pairs[0] is not None else ZETA_EQ_FIT
    label = f"Eq. (37), zeta_eq from {source.split(',')[0]}"
    lam = np.array([critical_lambda_approx(v) for v in zeta_eq])
    return [AnalyticBoundary("eq37", label, z, lam, zeta_eq)]
