"""Closed forms of the paper, each with its equation number.

All quantities are dimensionless. The fitted formulas (Eqs. 28-31, 33) are the paper's
cubic fits to Harik and Issa's numerical optimum; :mod:`stickslip.analysis.tuning`
computes the optimum itself. Eqs. (34)-(36) are exact for the 1DOF Coulomb system
(Nakano); Eqs. (37)-(39) are the paper's simplified boundary.

:func:`analytic_boundaries` evaluates the boundaries that apply to a foundation choice along
``zeta``: for the rigid base Eq. (36) (exact) and Eq. (39); with a foundation Eq. (37) with
the equivalent damping ratio ``zeta_eq`` of the equivalent 1DOF system (Fig. 9). For the
paper's fitted optimum (Eqs. 28-30, ``K`` not scaled) ``zeta_eq`` is Eq. (33); for any other
foundation it is Eq. (32), ``1 / (2 H_max)`` with the exact peak of the foundation's
frequency response (:func:`equivalent_damping_ratio` makes that choice, in one place).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.model._validate import non_negative, positive
from stickslip.model.parameters import Foundation
from stickslip.model.structure import chain_structure

if TYPE_CHECKING:
    from stickslip.analysis.dva import DvaSpec

FloatArray = NDArray[np.float64]


def _cubic(zeta: float, a3: float, a2: float, a1: float, a0: float) -> float:
    z = non_negative("zeta", zeta)
    return ((a3 * z + a2) * z + a1) * z + a0


def optimal_mass_ratio_fit(zeta: float) -> float:
    """Fitted optimal mass ratio ``M_opt = 330 z^3 - 43.6 z^2 + 14.5 z + 1.48``, Eq. (28)."""
    return _cubic(zeta, 330.0, -43.6, 14.5, 1.48)


def optimal_stiffness_ratio_fit(zeta: float) -> float:
    """Fitted optimal stiffness ratio ``K_opt = 7.72 z^3 + 1.13 z^2 + 1.38 z + 0.934``, Eq. (29)."""
    return _cubic(zeta, 7.72, 1.13, 1.38, 0.934)


def optimal_damping_ratio_fit(zeta: float) -> float:
    """Fitted optimal damping ratio ``zeta_a,opt = 61.1 z^3 - 4.40 z^2 + 3.91 z + 1.09``, Eq. (30)."""
    return _cubic(zeta, 61.1, -4.40, 3.91, 1.09)


def optimal_foundation_fit(zeta: float) -> Foundation:
    """The paper's fitted optimal foundation ``(M_opt, K_opt, zeta_a,opt)``, Eqs. (28)-(30)."""
    return Foundation(
        optimal_mass_ratio_fit(zeta),
        optimal_stiffness_ratio_fit(zeta),
        optimal_damping_ratio_fit(zeta),
    )


def peak_response_fit(zeta: float) -> float:
    """Fitted peak response at the optimum ``H_max = 2.31 z^3 + 0.70 z^2 - 3.08 z + 2.24``, Eq. (31)."""
    return _cubic(zeta, 2.31, 0.70, -3.08, 2.24)


def equivalent_damping_from_peak(peak: float) -> float:
    """Equivalent damping ratio of a 1DOF system with the same peak, ``1 / (2 H_max)``, Eq. (32)."""
    return 1.0 / (2.0 * positive("H_max", peak))


def equivalent_damping_fit(zeta: float) -> float:
    """``zeta_eq = 1 / (4.62 z^3 + 1.40 z^2 - 6.16 z + 4.48)``, Eq. (33) (Eqs. 31 and 32)."""
    return 1.0 / _cubic(zeta, 4.62, 1.40, -6.16, 4.48)


def stick_slip_frequency_ratio(lam: float) -> float:
    """Undamped 1DOF stick-slip frequency ``f_ss / f_n = 1 / (1 + (lam - atan lam)/pi)``, Eq. (34)."""
    lam = positive("lambda", lam)
    return 1.0 / (1.0 + (lam - math.atan(lam)) / math.pi)


def stick_slip_period(lam: float) -> float:
    """Undamped 1DOF stick-slip period in dimensionless time, ``2 pi / (f_ss/f_n)`` from Eq. (34)."""
    return 2.0 * math.pi / stick_slip_frequency_ratio(lam)


def stick_slip_amplitude_ratio(lam: float) -> float:
    """Undamped 1DOF stick-slip amplitude ``A_ss / A_n = sqrt(1 + lam^2)``, Eq. (35).

    ``A_n = V / omega_n``, so this is also the dimensionless amplitude of ``xi``.
    """
    lam = positive("lambda", lam)
    return math.sqrt(1.0 + lam * lam)


def nakano_boundary_residual(lam: float, zeta: float) -> float:
    """Left minus right side of Nakano's exact 1DOF boundary, Eq. (36).

    ``ln(1 - 2 z lam + lam^2) - z/sqrt(1-z^2) (3 pi + 2 atan((1 - z lam)/(lam sqrt(1-z^2))))``.
    Positive: stick-slip; negative: steady sliding. ``zeta`` is ``zeta_eq`` for the
    equivalent 1DOF model (Fig. 9) or ``zeta`` for the rigid base. Requires ``0 <= zeta < 1``.
    """
    lam = positive("lambda", lam)
    zeta = non_negative("zeta", zeta)
    if zeta >= 1.0:
        raise ValueError(f"zeta={zeta!r} must be below 1 for Eq. (36) (no oscillation otherwise)")
    wd = math.sqrt(1.0 - zeta * zeta)
    lhs = math.log(1.0 - 2.0 * zeta * lam + lam * lam)
    rhs = zeta / wd * (3.0 * math.pi + 2.0 * math.atan((1.0 - zeta * lam) / (lam * wd)))
    return lhs - rhs


def critical_lambda_exact(zeta: float) -> float:
    """Critical ``lambda`` of the 1DOF Coulomb system: the root of Eq. (36).

    Stick-slip occurs for ``lambda`` above it. Returns 0 for ``zeta = 0`` (always
    stick-slip) and ``inf`` for ``zeta >= 1`` (an overdamped slider never returns to the
    belt speed).
    """
    zeta = non_negative("zeta", zeta)
    if zeta == 0.0:
        return 0.0
    if zeta >= 1.0:
        return math.inf
    lo, hi = 1e-12, 1.0
    while nakano_boundary_residual(hi, zeta) <= 0.0:
        hi *= 2.0
    from scipy.optimize import brentq  # here, not at import: the command line starts fast

    return float(brentq(nakano_boundary_residual, lo, hi, args=(zeta,), xtol=1e-15, rtol=1e-15))


def critical_lambda_approx(zeta: float) -> float:
    """Boundary of the simplified criterion ``(1 - z)^5 lam^2 / z = 4 pi``, Eqs. (37) and (39).

    Pass ``zeta_eq`` for Eq. (37) (foundation) or ``zeta`` for Eq. (39) (rigid base).
    """
    zeta = non_negative("zeta", zeta)
    if zeta >= 1.0:
        return math.inf
    return math.sqrt(4.0 * math.pi * zeta / (1.0 - zeta) ** 5)


def stick_slip_predicted(lam: float, zeta: float) -> bool:
    """True when the criterion of Eq. (38) fails, i.e. ``(1 - z)^5 lam^2 / z >= 4 pi``."""
    return positive("lambda", lam) >= critical_lambda_approx(zeta)


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
    """
    if dva.kind == "none":
        return None
    if dva.kind == "optimal" and dva.k_scale == 1.0:
        return equivalent_damping_fit(zeta), ZETA_EQ_FIT
    if foundation is None:
        foundation = dva.resolve(zeta)
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


def critical_lambda_linear(zeta: float, delta: float) -> float:
    """Critical ``lambda`` of the rigid base with the linear friction law: Eq. (36) at ``zeta - delta``.

    Derivation. With ``mu = mu_k - sigma v_r`` the dimensionless friction magnitude is
    ``F(u) = gamma lambda - 2 delta u`` (``delta = sigma W / (2 sqrt(m k))``, ``u = 1 - xi'``
    in slip-I). In the shifted coordinates of Eqs. (15)-(16) slip-I (Eq. 22 with this force)
    reads ``xi'' + 2 zeta xi' + xi = F(u) - gamma lambda = -2 delta + 2 delta xi'``, i.e.

        xi'' + 2 (zeta - delta) xi' + (xi + 2 delta) = 0.

    With ``eta = xi + 2 delta`` and ``zeta_e = zeta - delta`` this is Nakano's slip-I
    equation ``eta'' + 2 zeta_e eta' + eta = 0``. The stick force of Eq. (20) at ``xi' = 1``
    is ``S = 2 zeta + xi = 2 (zeta - delta) + (xi + 2 delta) = 2 zeta_e eta' + eta`` at
    ``eta' = 1``: the stick bounds ``-lambda (1 + 2 gamma) <= S <= lambda`` are the same in
    ``eta``. Hence every breakaway happens at ``eta = lambda - 2 zeta_e``, ``eta' = 1``, the
    breakaway state of Nakano's system with damping ``zeta_e``, and the slip-I trajectory
    that follows (whether it returns to the belt speed, which decides stick-slip) is Nakano's.
    The exact boundary is therefore Eq. (36) with ``zeta -> zeta_e``
    (:func:`critical_lambda_exact`).

    Validity:

    * the startup stick phase must last (``S(0) = 2 zeta - gamma lambda <= lambda``, i.e.
      ``2 zeta <= (1 + gamma) lambda_c``), so that the first breakaway is the one above;
    * the floor of the law must not be reached. For ``delta > 0`` the friction is zero beyond
      ``u* = gamma lambda / (2 delta)``; along slip-I from the breakaway the energy
      ``eta^2 + eta'^2`` does not grow (``zeta_e >= 0``), so ``u = 1 - xi' <= 1 +
      sqrt((lambda - 2 zeta_e)^2 + 1)``, and the result holds when ``u*`` exceeds this bound;
    * ``zeta_e <= 0``: the slip-I motion does not decay, the slider returns to the belt speed:
      always stick-slip, ``lambda_c = 0``; ``zeta_e >= 1``: never (``inf``).

    Velocity strengthening (``delta < 0``) simply raises the effective damping.
    """
    zeta = non_negative("zeta", zeta)
    try:
        zeta_e = zeta - float(delta)
    except (TypeError, ValueError):
        raise ValueError(f"delta={delta!r} is not a number") from None
    if not math.isfinite(zeta_e):
        raise ValueError(f"delta={delta!r} must be finite")
    if zeta_e <= 0.0:
        return 0.0
    return critical_lambda_exact(zeta_e)
