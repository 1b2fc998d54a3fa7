"""Closed forms of the paper, each with its equation number.

All quantities are dimensionless. The fitted formulas (Eqs. 28-31, 33) are the paper's
cubic fits to Harik and Issa's numerical optimum; :mod:`stickslip.analysis.absorber_tuning`
computes the optimum itself. Eqs. (34)-(36) are exact for the 1DOF Coulomb system
(Nakano); Eqs. (37)-(39) are the paper's simplified boundary. The ranges on which the fits
hold (:data:`FITTED_ZETA_RANGE`, :data:`MAX_DESIGN_ZETA`) live here with them.

Which of these boundaries apply to a foundation choice is
:func:`stickslip.analysis.analytic_boundary.analytic_boundaries`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from stickslip.model._validate import non_negative, positive
from stickslip.model.parameters import Foundation

FloatArray = NDArray[np.float64]

MAX_DESIGN_ZETA = 0.9
"""Largest primary damping ratio at which the fitted forms (Eqs. 28-33) are used at all, by the
design procedure, the tuning and ``optimal`` foundations; above it they are refused."""
FITTED_ZETA_RANGE = 0.4
"""Upper end of ``0 <= zeta <= 0.4``, the range on which Eqs. (28)-(33) are fitted; results
between it and :data:`MAX_DESIGN_ZETA` are extrapolations and carry a warning."""
MAX_TUNING_ZETA = MAX_DESIGN_ZETA
"""Largest primary damping ratio accepted by the tuning (the frequency response itself takes any
``zeta``): the same bound as the design procedure's."""


def check_fitted_zeta(zeta: float) -> float:
    """Refuse ``zeta`` above :data:`MAX_DESIGN_ZETA` for the fitted optimum (Eqs. 28-30).

    The fit is defined on ``0 <= zeta <= FITTED_ZETA_RANGE`` (0.4); between that and
    ``MAX_DESIGN_ZETA`` (0.9) it is extrapolated and callers warn
    (:func:`stickslip.analysis.dva.fitted_zeta_warning`), above it is refused, as the tuning and
    the design procedure do.

    Parameters
    ----------
    zeta : float
        Primary damping ratio, dimensionless.

    Returns
    -------
    float
        ``zeta`` as a float, when ``0 <= zeta <= MAX_DESIGN_ZETA``; otherwise ``ValueError``.
    """
    z = non_negative("zeta", zeta)
    if z > MAX_DESIGN_ZETA:
        raise ValueError(
            f"zeta={zeta!r} is above {MAX_DESIGN_ZETA}: the fitted optimal foundation "
            "(Eqs. 28-30, fitted for zeta <= 0.4) is not defined there"
        )
    return z


def _cubic(zeta: float, a3: float, a2: float, a1: float, a0: float) -> float:
    z = non_negative("zeta", zeta)
    return ((a3 * z + a2) * z + a1) * z + a0


def optimal_mass_ratio_fit(zeta: float) -> float:
    """Fitted optimal mass ratio ``M_opt = 330 z^3 - 43.6 z^2 + 14.5 z + 1.48``, Eq. (28).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    float
        The fitted value of Eq. (28), dimensionless.
    """
    return _cubic(zeta, 330.0, -43.6, 14.5, 1.48)


def optimal_stiffness_ratio_fit(zeta: float) -> float:
    """Fitted optimal stiffness ratio ``K_opt = 7.72 z^3 + 1.13 z^2 + 1.38 z + 0.934``, Eq. (29).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    float
        The fitted value of Eq. (29), dimensionless.
    """
    return _cubic(zeta, 7.72, 1.13, 1.38, 0.934)


def optimal_damping_ratio_fit(zeta: float) -> float:
    """Fitted optimal damping ratio ``zeta_a,opt = 61.1 z^3 - 4.40 z^2 + 3.91 z + 1.09``, Eq. (30).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    float
        The fitted value of Eq. (30), dimensionless.
    """
    return _cubic(zeta, 61.1, -4.40, 3.91, 1.09)


def optimal_foundation_fit(zeta: float) -> Foundation:
    """The paper's fitted optimal foundation ``(M_opt, K_opt, zeta_a,opt)``, Eqs. (28)-(30).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    Foundation
        ``(M_opt, K_opt, zeta_a,opt)``, dimensionless.
    """
    return Foundation(
        optimal_mass_ratio_fit(zeta),
        optimal_stiffness_ratio_fit(zeta),
        optimal_damping_ratio_fit(zeta),
    )


def peak_response_fit(zeta: float) -> float:
    """Fitted peak response at the optimum ``H_max = 2.31 z^3 + 0.70 z^2 - 3.08 z + 2.24``, Eq. (31).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    float
        The fitted value of Eq. (31), dimensionless.
    """
    return _cubic(zeta, 2.31, 0.70, -3.08, 2.24)


def equivalent_damping_from_peak(peak: float) -> float:
    """Equivalent damping ratio of a 1DOF system with the same peak, ``1 / (2 H_max)``, Eq. (32).

    Parameters
    ----------
    peak : float
        Peak response ``H_max = k |X| / f``, dimensionless, > 0.

    Returns
    -------
    float
        ``zeta_eq``, dimensionless.
    """
    return 1.0 / (2.0 * positive("H_max", peak))


def equivalent_damping_fit(zeta: float) -> float:
    """``zeta_eq = 1 / (4.62 z^3 + 1.40 z^2 - 6.16 z + 4.48)``, Eq. (33) (Eqs. 31 and 32).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    float
        The fitted value of Eq. (33), dimensionless.
    """
    return 1.0 / _cubic(zeta, 4.62, 1.40, -6.16, 4.48)


def stick_slip_frequency_ratio(lam: float) -> float:
    """Undamped 1DOF stick-slip frequency ``f_ss / f_n = 1 / (1 + (lam - atan lam)/pi)``, Eq. (34).

    Parameters
    ----------
    lam : float
        ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``, dimensionless, > 0.

    Returns
    -------
    float
        ``f_ss / f_n``, dimensionless.
    """
    lam = positive("lambda", lam)
    return 1.0 / (1.0 + (lam - math.atan(lam)) / math.pi)


def stick_slip_period(lam: float) -> float:
    """Undamped 1DOF stick-slip period in dimensionless time, ``2 pi / (f_ss/f_n)`` from Eq. (34).

    Parameters
    ----------
    lam : float
        ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``, dimensionless, > 0.

    Returns
    -------
    float
        The period in dimensionless time ``tau = omega_n t``.
    """
    return 2.0 * math.pi / stick_slip_frequency_ratio(lam)


def stick_slip_amplitude_ratio(lam: float) -> float:
    """Undamped 1DOF stick-slip amplitude ``A_ss / A_n = sqrt(1 + lam^2)``, Eq. (35).

    ``A_n = V / omega_n``, so this is also the dimensionless amplitude of ``xi``.

    Parameters
    ----------
    lam : float
        ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``, dimensionless, > 0.

    Returns
    -------
    float
        ``A_ss / A_n``, dimensionless.
    """
    lam = positive("lambda", lam)
    return math.sqrt(1.0 + lam * lam)


def nakano_boundary_residual(lam: float, zeta: float) -> float:
    """Left minus right side of Nakano's exact 1DOF boundary, Eq. (36).

    ``ln(1 - 2 z lam + lam^2) - z/sqrt(1-z^2) (3 pi + 2 atan((1 - z lam)/(lam sqrt(1-z^2))))``.
    Positive: stick-slip; negative: steady sliding. ``zeta`` is ``zeta_eq`` for the
    equivalent 1DOF model (Fig. 9) or ``zeta`` for the rigid base. Requires ``0 <= zeta < 1``.

    Parameters
    ----------
    lam : float
        ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``, dimensionless, > 0.
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, 0 <= zeta < 1 (or ``zeta_eq``).

    Returns
    -------
    float
        Positive: stick-slip; negative: steady sliding.
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

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    float
        Critical ``lambda``: 0 for ``zeta = 0``, ``inf`` for ``zeta >= 1``.
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

    Parameters
    ----------
    zeta : float
        ``zeta_eq`` for Eq. (37) or ``zeta`` for Eq. (39), dimensionless, >= 0.

    Returns
    -------
    float
        Critical ``lambda`` (``inf`` for ``zeta >= 1``).
    """
    zeta = non_negative("zeta", zeta)
    if zeta >= 1.0:
        return math.inf
    return math.sqrt(4.0 * math.pi * zeta / (1.0 - zeta) ** 5)


def stick_slip_predicted(lam: float, zeta: float) -> bool:
    """True when the criterion of Eq. (38) fails, i.e. ``(1 - z)^5 lam^2 / z >= 4 pi``.

    Parameters
    ----------
    lam : float
        ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``, dimensionless, > 0.
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    bool
        True when Eq. (38) predicts stick-slip.
    """
    return positive("lambda", lam) >= critical_lambda_approx(zeta)


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

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.
    delta : float
        Dimensionless weakening ``sigma W / (2 sqrt(m k))`` of the linear law (< 0: strengthening).

    Returns
    -------
    float
        Critical ``lambda``: 0 when ``zeta - delta <= 0``, ``inf`` when it is >= 1.
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
