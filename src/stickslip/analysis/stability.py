"""Linear stability of steady sliding under a velocity-dependent friction law.

At steady sliding the slider rests in the moving frame of the structure (``xi' = 0``), so
the sliding speed is the belt speed, ``u = 1``. A small motion about it stays in slip-I,
where the friction force on DOF 0 is ``F(1 - xi') - gamma lambda``; linearised,
``F(1) - gamma lambda - F'(1) xi'``: the friction slope ``s = dF/du`` at ``u = 1`` adds to the
damping ``C_00`` (velocity weakening, ``s < 0``, is negative damping). With the local
weakening ``delta_loc = -s / 2`` (for the linear law ``delta_loc = delta``) the linearisation
is

    Mass q'' + (C - 2 delta_loc e_0 e_0') q' + K q = 0,

and steady sliding is linearly stable iff every eigenvalue of its first-order matrix has a
negative real part; the growth rate is the largest real part (per unit ``tau``). All
quantities are dimensionless.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]

#: Round-off bound of a computed growth rate, in units of ``eps ||A||_F``.
ROUND_OFF_FACTOR = 1000.0


@dataclass(frozen=True)
class SteadySlidingStability:
    """Linear stability of steady sliding.

    Attributes
    ----------
    slope : float
        ``dF/du`` at ``u = 1`` (exact derivative of the law; dimensionless).
    delta_local : float
        ``-slope / 2``, the local velocity weakening.
    eigenvalues : ndarray of complex
        Of the linearisation (per unit ``tau``).
    growth_rate : float
        Largest real part of the eigenvalues.
    stable : bool
        ``growth_rate < -round_off``: asymptotically stable beyond round-off.
    routh_hurwitz : bool or None
        The closed-form Routh-Hurwitz verdict for 1 and 2 DOF, None otherwise.
    kink : bool
        The law has a kink at ``u = 1`` (e.g. a table point at the belt speed): the
        linearisation is not unique; the worse of the two one-sided slopes is reported (both
        sides stable is necessary for stability; the engine's certificate decides).
    """

    slope: float
    delta_local: float
    eigenvalues: NDArray[np.complex128]
    growth_rate: float
    stable: bool
    routh_hurwitz: bool | None
    kink: bool = False
    round_off: float = 0.0

    @property
    def neutral(self) -> bool:
        """``|growth_rate| <= round_off``: neither growing nor decaying, to round-off.

        ``round_off`` (:func:`growth_round_off`: ``ROUND_OFF_FACTOR * eps * ||B||_F``, per
        unit ``tau``, ``B`` the balanced first-order matrix) bounds the round-off error of a
        computed growth rate: a backward-stable eigensolver returns the eigenvalues of
        ``B + E`` with ``||E|| ~ n eps ||B||``, and the factor leaves room for non-normal
        matrices. Neutral
        is marginally stable: an undamped structure, or a weakening that exactly cancels the
        damping.
        """
        return abs(self.growth_rate) <= self.round_off


def linearised_damping(structure: Structure, slope: float) -> FloatArray:
    """Damping matrix of the linearisation: ``C + slope e_c e_c'`` (``c`` the contact DOF).

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on ``structure.contact_dof``.
    slope : float
        Friction slope ``dF/du`` at the belt speed (``u = 1``), dimensionless; it adds to the
        damping of the contact DOF.

    Returns
    -------
    ndarray
        The damping matrix with the friction slope on the contact DOF.
    """
    c = np.array(structure.damping, dtype=np.float64)
    c[structure.contact_dof, structure.contact_dof] += slope
    return c


def slip_matrix(structure: Structure, slope: float) -> FloatArray:
    """First-order matrix ``[[0, I], [-M^-1 K, -M^-1 (C + slope e_c e_c')]]`` of slip-I.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on ``structure.contact_dof``.
    slope : float
        Friction slope ``dF/du`` at the belt speed (``u = 1``), dimensionless; it adds to the
        damping of the contact DOF.

    Returns
    -------
    ndarray, shape (2n, 2n)
        The first-order system matrix.
    """
    n = structure.n_dof
    minv = np.linalg.inv(structure.mass)
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -minv @ structure.stiffness
    a[n:, n:] = -minv @ linearised_damping(structure, slope)
    return a


def routh_hurwitz_1dof(zeta: float, delta_local: float) -> bool:
    """Rigid base: ``xi'' + 2 (zeta - delta_loc) xi' + xi = 0`` is stable iff ``zeta > delta_loc``.

    The characteristic polynomial ``s^2 + 2 (zeta - delta_loc) s + 1`` is Hurwitz iff all its
    coefficients are positive (Routh-Hurwitz for degree 2).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.
    delta_local : float
        Local weakening at the belt speed, dimensionless.

    Returns
    -------
    bool
        True when steady sliding is asymptotically stable.
    """
    return zeta - delta_local > 0.0


def quartic_coefficients(mass: FloatArray, damping: FloatArray, stiffness: FloatArray) -> FloatArray:
    """Coefficients ``(a4, a3, a2, a1, a0)`` of ``det(M s^2 + C s + K)`` for 2 DOF.

    With ``P_ij(s) = M_ij s^2 + C_ij s + K_ij`` (symmetric matrices),
    ``det P = P_00 P_11 - P_01^2``, so

    * ``a4 = M00 M11 - M01^2``
    * ``a3 = M00 C11 + C00 M11 - 2 M01 C01``
    * ``a2 = M00 K11 + C00 C11 + K00 M11 - 2 M01 K01 - C01^2``
    * ``a1 = C00 K11 + K00 C11 - 2 C01 K01``
    * ``a0 = K00 K11 - K01^2``.

    Parameters
    ----------
    mass, damping, stiffness : ndarray, shape (2, 2)
        Dimensionless matrices.

    Returns
    -------
    ndarray, shape (5,)
        ``(a4, a3, a2, a1, a0)``.
    """
    m, c, k = mass, damping, stiffness
    return np.array([
        m[0, 0] * m[1, 1] - m[0, 1] ** 2,
        m[0, 0] * c[1, 1] + c[0, 0] * m[1, 1] - 2.0 * m[0, 1] * c[0, 1],
        m[0, 0] * k[1, 1] + c[0, 0] * c[1, 1] + k[0, 0] * m[1, 1] - 2.0 * m[0, 1] * k[0, 1] - c[0, 1] ** 2,
        c[0, 0] * k[1, 1] + k[0, 0] * c[1, 1] - 2.0 * c[0, 1] * k[0, 1],
        k[0, 0] * k[1, 1] - k[0, 1] ** 2,
    ])


def routh_hurwitz_quartic(coefficients: FloatArray) -> bool:
    """Hurwitz test of ``a4 s^4 + a3 s^3 + a2 s^2 + a1 s + a0`` with ``a4 > 0``.

    Routh's array of the quartic has the first column ``a4, a3, b1, c1, a0`` with
    ``b1 = (a3 a2 - a4 a1) / a3`` and ``c1 = (b1 a1 - a3 a0) / b1``; all roots lie in the
    open left half plane iff the column has no sign change, i.e. iff

    * ``a_i > 0`` for all ``i``,
    * ``a3 a2 - a4 a1 > 0`` (Hurwitz determinant ``D2``),
    * ``a1 (a3 a2 - a4 a1) - a3^2 a0 > 0`` (``D3``).

    Parameters
    ----------
    coefficients : ndarray, shape (5,)
        ``(a4, a3, a2, a1, a0)``.

    Returns
    -------
    bool
        True when every root has a negative real part.
    """
    a4, a3, a2, a1, a0 = (float(x) for x in coefficients)
    if min(a4, a3, a2, a1, a0) <= 0.0:
        return False
    d2 = a3 * a2 - a4 * a1
    d3 = a1 * d2 - a3 * a3 * a0
    return d2 > 0.0 and d3 > 0.0


def routh_hurwitz_2dof(structure: Structure, slope: float) -> bool:
    """Routh-Hurwitz verdict for a 2DOF structure (elastic foundation) with friction slope ``slope``.

    For the foundation in the paper's form (``M = diag(1, M_a)``, ``C_00 = 2 zeta``,
    ``C_01 = -2 zeta`` ...) the quartic is that of :func:`quartic_coefficients` with
    ``C_00 -> C_00 + slope = C_00 - 2 delta_loc``.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.
    slope : float
        Friction slope ``dF/du`` at the belt speed (``u = 1``), dimensionless; it adds to the
        damping of DOF 0.

    Returns
    -------
    bool
        True when steady sliding is asymptotically stable.
    """
    if structure.n_dof != 2:
        raise ValueError(f"routh_hurwitz_2dof needs 2 degrees of freedom, got {structure.n_dof}")
    return routh_hurwitz_quartic(
        quartic_coefficients(structure.mass, linearised_damping(structure, slope), structure.stiffness)
    )


def one_sided_slopes(slider: Slider) -> tuple[float, float]:
    """``dF/du`` just below and just above ``u = 1``: the exact derivative for smooth laws,
    the band slopes for the exact piecewise-linear ones (they differ at a kink).

    Parameters
    ----------
    slider : Slider
        The frictional contact: ``lambda``, ``gamma`` and the friction law.

    Returns
    -------
    tuple of float
        ``dF/du`` below and above ``u = 1``, dimensionless.
    """
    law = slider.friction
    if not law.exact:
        s = float(law.slope_at(1.0, slider.lam, slider.gamma))
        return s, s
    edges, _, slopes = law.bands(slider.lam, slider.gamma)
    b = int(np.searchsorted(edges, 1.0, side="right") - 1)
    right = float(slopes[b])
    left = float(slopes[b - 1]) if b > 0 and edges[b] == 1.0 else right
    return left, right


def steady_sliding_stability(structure: Structure, slider: Slider) -> SteadySlidingStability:
    """Eigenvalues, growth rate and Routh-Hurwitz verdict of steady sliding.

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices, contact on DOF 0.
    slider : Slider
        ``lambda``, ``gamma`` and the friction law; the slope is the law's exact derivative
        at ``u = 1`` (for Stribeck not the piecewise-linear one; at a kink of a table the
        worse side, see :func:`one_sided_slopes`).

    Returns
    -------
    SteadySlidingStability
        Eigenvalues, growth rate, stability and local weakening.
    """
    left, right = one_sided_slopes(slider)
    slope, eig, growth, round_off = right, np.zeros(0, dtype=np.complex128), -np.inf, 0.0
    for s in (right, left) if left != right else (right,):
        matrix = slip_matrix(structure, s)
        e = np.asarray(np.linalg.eigvals(matrix), dtype=np.complex128)
        g = float(np.max(e.real))
        if g > growth:
            slope, eig, growth = s, e, g
            round_off = growth_round_off(matrix)
    rh: bool | None = None
    if structure.n_dof == 1:
        scale = float(np.sqrt(structure.mass[0, 0] * structure.stiffness[0, 0]))
        zeta = 0.5 * float(structure.damping[0, 0]) / scale
        rh = routh_hurwitz_1dof(zeta, -0.5 * slope / scale)
    elif structure.n_dof == 2:
        rh = routh_hurwitz_2dof(structure, slope)
    return SteadySlidingStability(slope, -0.5 * slope + 0.0, eig, growth, growth < -round_off, rh,
                                  left != right, round_off)


def growth_round_off(matrix: FloatArray) -> float:
    """Round-off bound of the growth rate computed from ``matrix``: ``1000 eps ||B||_F``.

    ``B = T^-1 A T`` is ``A`` balanced (diagonal ``T``, the similarity LAPACK's eigensolver
    applies before its QR iteration, ``scipy.linalg.matrix_balance``), so the computed
    eigenvalues are exact for ``B + E`` with ``||E|| ~ n eps ||B||``, and the factor
    (:data:`ROUND_OFF_FACTOR`) leaves room for non-normal matrices. ``||A||_F`` bounds the
    same error but, on a badly scaled structure, by far too much: a foundation ``10^6`` times
    stiffer than the slider (``||A||_F ~ 10^12``, ``||B||_F ~ 10^6``) made a growth rate of
    -0.1 "neutral".

    Parameters
    ----------
    matrix : ndarray, shape (2n, 2n)
        First-order matrix (:func:`slip_matrix`), per unit ``tau``.

    Returns
    -------
    float
        The bound, per unit ``tau``.
    """
    from scipy.linalg import matrix_balance

    balanced, _ = matrix_balance(matrix)
    return ROUND_OFF_FACTOR * float(np.finfo(float).eps * np.linalg.norm(balanced))


def growth_rate(structure: Structure, delta: float) -> float:
    """Largest real part of the eigenvalues of slip-I with uniform weakening ``delta`` (per ``tau``).

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.
    delta : float
        Uniform weakening, dimensionless.

    Returns
    -------
    float
        Largest real part of the eigenvalues, per unit ``tau``.
    """
    return float(np.max(np.linalg.eigvals(slip_matrix(structure, -2.0 * delta)).real))


def _characteristic_polynomial(mass: FloatArray, damping: FloatArray, stiffness: FloatArray
                               ) -> FloatArray:
    """Coefficients (highest power first) of ``det(M s^2 + C s + K)``, real.

    ``det(M s^2 + C s + K) = det(M) prod_i (s - s_i)`` over the ``2 n`` eigenvalues ``s_i`` of
    the first-order matrix ``[[0, I], [-M^-1 K, -M^-1 C]]``; an empty structure gives ``1``.
    """
    n = mass.shape[0]
    if n == 0:
        return np.ones(1)
    minv = np.linalg.inv(mass)
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -minv @ stiffness
    a[n:, n:] = -minv @ damping
    return np.asarray(np.real(np.poly(np.linalg.eigvals(a))) * np.linalg.det(mass))


#: Largest structure whose Hopf weakenings come from the characteristic polynomial (degree
#: ``4 n - 1`` in ``omega``); larger ones use the zeros of a pencil.
POLYNOMIAL_MAX_DOF = 4


def hopf_weakenings(structure: Structure) -> FloatArray:
    """Every weakening ``delta > 0`` at which steady sliding has a root on the imaginary axis.

    With the weakening ``delta`` the characteristic polynomial of the slip-I linearisation is
    affine in ``delta`` (only ``C_00`` changes, by ``-2 delta``; expansion of the determinant
    along row 0):

        ``p(s; delta) = p_0(s) - 2 delta s q(s)``,

    ``p_0(s) = det(M s^2 + C s + K)`` and ``q(s)`` the same determinant without row and
    column 0 (``q = 1`` on the rigid base). ``s = 0`` is never a root (``p(0) = det K > 0``),
    so stability can change only where a pair ``s = +-i omega``, ``omega > 0``, crosses:
    ``p_0(i omega) = 2 delta i omega q(i omega)``. Writing ``P(omega) = p_0(i omega)`` and
    ``Q(omega) = i omega q(i omega)`` (polynomials in ``omega`` with complex coefficients),
    ``delta = P / (2 Q)`` is real iff ``Im(P conj(Q)) = 0``: a real polynomial in ``omega``
    of degree at most ``4 n - 1``. Its positive roots (polished by Newton's method on that
    polynomial) give the candidate ``delta = Re(P conj(Q)) / (2 |Q|^2)``; those with
    ``delta > 0`` are returned, sorted, each once. Rigid base: ``p_0 = s^2 + 2 zeta s + 1``,
    ``q = 1``, so ``omega = 1`` and ``delta = zeta``. Beyond :data:`POLYNOMIAL_MAX_DOF`
    DOFs the polynomial's coefficients lose their accuracy, and the same crossings come from
    the zeros of ``G(s) - G(-s)`` (``G`` the contact's mobility; see
    :func:`_hopf_weakenings_from_zeros`).

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices; the contact's DOF carries the weakening.

    Returns
    -------
    ndarray of float
        The Hopf weakenings ``delta > 0`` (dimensionless), sorted ascending, each once;
        empty when none exists.
    """
    contact_first, _ = structure.contact_first()  # the minor q drops the contact's row and column
    m, c, k = (np.asarray(x, dtype=np.float64) for x in
               (contact_first.mass, contact_first.damping, contact_first.stiffness))
    if m.shape[0] > POLYNOMIAL_MAX_DOF:
        return _unique_sorted(_hopf_weakenings_from_zeros(m, c, k))
    p0 = _characteristic_polynomial(m, c, k)
    q = _characteristic_polynomial(m[1:, 1:], c[1:, 1:], k[1:, 1:])
    q = np.append(q, 0.0)  # s q(s)
    # a polynomial a(s) = sum a_j s^j evaluated at s = i omega: coefficient a_j i^j of omega^j
    big_p = np.polynomial.Polynomial(p0[::-1] * (1j ** np.arange(p0.size)))
    big_q = np.polynomial.Polynomial(q[::-1] * (1j ** np.arange(q.size)))
    pr, pi = (np.polynomial.Polynomial(big_p.coef.real), np.polynomial.Polynomial(big_p.coef.imag))
    qr, qi = (np.polynomial.Polynomial(big_q.coef.real), np.polynomial.Polynomial(big_q.coef.imag))
    cross = (pi * qr - pr * qi).trim()
    numer = pr * qr + pi * qi
    denom = qr * qr + qi * qi
    dcross = cross.deriv()
    found: list[float] = []
    for root in np.asarray(cross.roots(), dtype=np.complex128):
        if abs(root.imag) > 1e-6 * max(1.0, abs(root.real)) or root.real <= 0.0:
            continue
        w = float(root.real)
        for _ in range(8):  # Newton polish on the real polynomial
            slope = float(dcross(w))
            if slope == 0.0:
                break
            step = float(cross(w)) / slope
            w -= step
            if abs(step) <= 1e-16 * w:
                break
        d2 = float(denom(w))
        if w <= 0.0 or d2 <= 0.0:
            continue
        delta = 0.5 * float(numer(w)) / d2
        if delta > 0.0 and math.isfinite(delta):
            found.append(delta)
    return _unique_sorted(found)


def _unique_sorted(found: list[float]) -> FloatArray:
    """``found`` sorted, values within ``1e-12`` (relative) of the previous one dropped."""
    unique: list[float] = []
    for d in sorted(found):
        if not unique or d - unique[-1] > 1e-12 * max(1.0, d):
            unique.append(d)
    return np.array(unique)


def _hopf_weakenings_from_zeros(m: FloatArray, c: FloatArray, k: FloatArray) -> list[float]:
    """:func:`hopf_weakenings` beyond :data:`POLYNOMIAL_MAX_DOF` DOFs, without polynomials.

    With the weakening, slip-I is ``A(delta) = A_0 + 2 delta b e'`` (``b = [0; M^-1 e_0]``,
    ``e`` picks the contact's velocity), so ``s`` is an eigenvalue iff ``2 delta G(s) = 1``
    with ``G(s) = e' (s I - A_0)^-1 b`` (the contact's mobility). On ``s = i omega``, ``delta``
    is real iff ``G(i omega)`` is: a zero of ``Phi(s) = G(s) - G(-s)``, whose realisation is
    ``(diag(A_0, -A_0), [b; b], [e', e'])``. Its zeros are the finite generalised eigenvalues
    of the Rosenbrock pencil (QZ, backward stable); those near the positive imaginary axis are
    polished by Newton's method on ``Im G(i omega)`` (``G`` from the modes of ``A_0``), and
    ``delta = 1 / (2 Re G(i omega))``. The coefficients of the characteristic polynomial lose
    all accuracy beyond a few DOFs (a 50-DOF reduced frame gave no crossing at all in one run
    and one 1 % off in the next, from matrices equal to round-off).
    """
    from scipy.linalg import eig, eigvals

    n = m.shape[0]
    minv = np.linalg.inv(m)
    a0 = np.zeros((2 * n, 2 * n))
    a0[:n, n:] = np.eye(n)
    a0[n:, :n] = -minv @ k
    a0[n:, n:] = -minv @ c
    b = np.zeros(2 * n)
    b[n:] = minv[:, 0]
    size = 4 * n + 1
    pencil = np.zeros((size, size))
    pencil[: 2 * n, : 2 * n] = a0
    pencil[2 * n: 4 * n, 2 * n: 4 * n] = -a0
    pencil[: 4 * n, 4 * n] = np.r_[b, b]
    pencil[4 * n, [n, 3 * n]] = 1.0
    unit = np.eye(size)
    unit[4 * n, 4 * n] = 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        zeros = eigvals(pencil, unit)
    lam, vec = eig(a0)
    residues = np.linalg.solve(vec, b) * vec[n, :]  # G(s) = sum_j residues_j / (s - lam_j)
    found: list[float] = []
    for z in zeros[np.isfinite(zeros)]:
        if z.imag <= 0.0 or abs(z.real) > 1e-6 * abs(z):
            continue
        w = float(z.imag)
        for _ in range(8):  # Newton on Im G(i w), with dG/dw = -i sum r / (i w - lam)^2
            gap = 1j * w - lam
            f = float(np.sum(residues / gap).imag)
            slope = float(np.sum(-1j * residues / gap**2).imag)
            if slope == 0.0:
                break
            step = f / slope
            w -= step
            if abs(step) <= 1e-15 * w:
                break
        g = complex(np.sum(residues / (1j * w - lam)))
        if w <= 0.0 or abs(g.imag) > 1e-8 * abs(g) or g.real <= 0.0:
            continue  # no real crossing there (a zero off the axis), or a negative weakening
        found.append(0.5 / g.real)
    return found


def critical_weakening(structure: Structure) -> float:
    """Largest friction weakening ``delta_crit`` for which steady sliding stays stable.

    Steady sliding of ``structure`` under a law with local slope ``dF/du = -2 delta`` at the
    belt speed is stable for ``0 <= delta < delta_crit`` (dimensionless, ``delta = sigma W /
    (2 sqrt(m k))`` for the linear law): ``delta_crit`` is the first loss of stability, exactly.
    Closed form on the rigid base: ``delta_crit = zeta`` (Routh-Hurwitz of
    ``s^2 + 2 (zeta - delta) s + 1``, :func:`routh_hurwitz_1dof`).

    Method: no scan. Stability can change only where a root crosses the imaginary axis, at the
    Hopf weakenings of :func:`hopf_weakenings` (roots of a polynomial); between two of them the
    verdict is constant. Steady sliding stable at ``delta = 0`` stays stable up to the smallest
    one, which is returned (a window of instability above it and a return to stability, as on
    some foundations, is therefore never stepped over). Returns 0 when steady sliding is not
    stable even without weakening, and ``inf`` when no crossing exists.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.

    Returns
    -------
    float
        ``delta_crit``, dimensionless; 0 when steady sliding is unstable without weakening,
        ``inf`` when no crossing exists.
    """
    if growth_rate(structure, 0.0) >= 0.0:
        return 0.0
    hopf = hopf_weakenings(structure)
    return float(hopf[0]) if hopf.size else float("inf")


def stability_intervals(structure: Structure) -> list[tuple[float, float, bool]]:
    """Steady sliding's stability for every weakening ``delta >= 0``, exactly.

    Returns the intervals ``(lo, hi, stable)`` between consecutive Hopf weakenings
    (:func:`hopf_weakenings`; ``hi = inf`` for the last), the verdict of each taken from the
    eigenvalues at its midpoint (at ``lo + 1`` for the last).

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices.

    Returns
    -------
    list of (float, float, bool)
        ``(lo, hi, stable)`` for each interval of ``delta`` between consecutive Hopf
        weakenings, from 0 to infinity.
    """
    edges = [0.0, *hopf_weakenings(structure).tolist(), float("inf")]
    out: list[tuple[float, float, bool]] = []
    for lo, hi in itertools.pairwise(edges):
        probe = lo + 1.0 if not np.isfinite(hi) else 0.5 * (lo + hi)
        out.append((lo, hi, growth_rate(structure, probe) < 0.0))
    return out
