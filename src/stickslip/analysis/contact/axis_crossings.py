r"""Every friction coefficient where an eigenvalue of steady sliding can cross the imaginary axis.

The first-order matrix ``A(mu)`` of :mod:`stickslip.analysis.contact.friction_coupling` has an
eigenvalue on the imaginary axis only where

* a pair ``s = \pm i\omega`` sits there (flutter, a Hopf crossing): then ``s_i + s_j = 0`` for
  two of its eigenvalues, and ``det(2A \odot I) = 0``, where ``2A \odot I`` is the bialternate
  sum of ``A`` with itself, the ``m(m-1)/2``-square matrix whose eigenvalues are the sums
  ``s_i + s_j`` (``i < j``) of ``A``'s ``m`` eigenvalues (Stephanos 1900; Fuller 1968;
  Govaerts, *Numerical methods for bifurcations of dynamical equilibria*, SIAM 2000, section
  4.4.4);
* or ``s = 0`` (divergence): ``det A = 0``.

Both products are linear in ``A``, and ``A`` depends on ``mu`` in a known way. With the
Coulomb law (no slope) ``A(mu) = A_0 + mu A_1``: the coupling entries ``mu k_n`` and
``mu c_n`` are linear in ``mu``. With a slope ``mu'``, the damping entry ``mu' N_0(mu)``
follows the steady normal force, and by the Sherman-Morrison formula on
``(K_0 + mu k_n e_t e_n^T) q_0 = mu W e_t``,

.. math::

    q_{0,n} = \frac{\mu W G_{nt}}{1 + \mu k_n G_{nt}}, \qquad
    N_0(\mu) = W - k_n q_{0,n} = \frac{W}{1 + a \mu}, \qquad a = k_n G_{nt},

with ``G = K_0^{-1}``. So ``(1 + a mu) A(mu) = P_0 + mu P_1 + mu^2 P_2`` with
``P_0 = A_0 + mu' W A_2``, ``P_1 = A_1 + a A_0``, ``P_2 = a A_1`` (``A_2`` the slope's unit
entry). The crossings are therefore among the real eigenvalues of two matrix polynomials in
``mu`` of degree one or two, ``2 D(mu) \odot I`` and ``D(mu)`` with ``D = (1 + a mu) A``, plus
the pole ``mu = -1/a`` where ``N_0`` changes sign (the contact lifts off). A polynomial
eigenvalue problem is solved by its companion pencil and the QZ algorithm; its real
eigenvalues in ``(0, mu_max)`` cut the range into intervals on each of which the number of
eigenvalues in the right half plane is constant (eigenvalues move continuously with ``mu``
and cannot reach the axis inside an interval). One eigenvalue check per interval then decides
the whole interval, and the first interval proven unstable gives the critical ``mu`` exactly:
its left end.

The search fails (``None``: the caller scans instead) where it cannot prove: a singular
pencil (``det(2A \odot I)`` vanishes for every ``mu``: an undamped structure, whose spectrum
is on the axis below the coalescence, or a mode that friction never touches), or a pencil
beyond :data:`MAX_PENCIL` rows (the bialternate sum grows as ``2 n^2`` for ``n`` DOF).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.contact.friction_coupling import (
    FrictionCoupledSystem,
    first_order_matrix,
    jenkins_state_matrix,
    reference_rate,
)

FloatArray = NDArray[np.float64]

#: Largest pencil (rows) solved by QZ; beyond it the caller scans. QZ costs ~ 30 rows^3 flops:
#: a whole search took 2.0 s for 22 DOF (Coulomb, 946 rows) and 2.3 s for 16 DOF with a slope
#: (992 rows) here. 1000 rows: up to 22 DOF with the Coulomb law, 16 with a slope.
MAX_PENCIL = 1000
#: A computed eigenvalue ``mu`` counts as real when ``|Im mu| <= REAL_TOL max(1, |mu|)``; a
#: double real root (a tangency) splits into a pair ``O(sqrt(eps))`` off the axis, far inside.
REAL_TOL = 1e-6
#: A pencil is singular when ``Q(mu)`` is, to this relative smallest singular value, at every
#: one of three unrelated values of ``mu``.
SINGULAR_TOL = 1e-12


def bialternate_sum(a: FloatArray) -> FloatArray:
    r"""``2A \odot I``: the matrix whose eigenvalues are the sums ``s_i + s_j``, ``i < j``, of ``A``'s.

    Rows and columns are indexed by the pairs ``(p, q)``, ``p > q``, in lexicographic order;
    the entry at ``((p, q), (r, s))`` is ``a_pp + a_qq`` on the diagonal, ``a_pr`` for
    ``s = q, r != p``, ``a_qs`` for ``r = p, s != q``, ``-a_ps`` for ``r = q`` and ``-a_qr``
    for ``s = p`` (Govaerts 2000, section 4.4.4).

    Parameters
    ----------
    a : ndarray, shape (m, m)
        Real matrix, m >= 2.

    Returns
    -------
    ndarray, shape (m (m - 1) / 2, m (m - 1) / 2)
        The bialternate sum (linear in ``a``).
    """
    m = a.shape[0]
    p, q = (np.asarray(v) for v in zip(*[(i, j) for i in range(1, m) for j in range(i)], strict=True))
    P, Q = p[:, None], q[:, None]
    R, S = p[None, :], q[None, :]
    out = np.where((R == P) & (S == Q), a[P, P] + a[Q, Q], 0.0)
    out = out + np.where((S == Q) & (R != P), a[P, R], 0.0)
    out = out + np.where((R == P) & (S != Q), a[Q, S], 0.0)
    out = out - np.where(R == Q, a[P, S], 0.0)
    out = out - np.where(S == P, a[Q, R], 0.0)
    return np.asarray(out, dtype=float)


def steady_normal_force_pole(system: FrictionCoupledSystem) -> float:
    """``a = k_n (K_0^{-1})_{nt}``: ``N_0(mu) = W / (1 + a mu)`` (module docstring).

    Parameters
    ----------
    system : FrictionCoupledSystem
        The linearisation's data.

    Returns
    -------
    float
        ``a`` (dimensionless); 0 without a normal DOF.
    """
    if system.normal_dof is None:
        return 0.0
    g = np.linalg.solve(system.contact_stiffness(), np.eye(system.n_dof)[:, system.tangential_dof])
    return float(system.normal_stiffness * g[system.normal_dof])


def matrix_coefficients(system: FrictionCoupledSystem,
                        ) -> tuple[FloatArray, FloatArray, FloatArray | None, FloatArray] | None:
    """``P_0, P_1, P_2`` and breakpoints: ``f(mu) A(mu) = P_0 + mu P_1 + mu^2 P_2`` (module docstring).

    ``A`` is the scaled first-order matrix of
    :func:`~stickslip.analysis.contact.friction_coupling.first_order_matrix` (the same
    eigenvalues as the unscaled one) and ``f`` a scalar polynomial of degree at most one: 1
    without a slope (``A`` affine, ``P_2`` None), ``1 + a mu`` with one. With a Jenkins element
    (:func:`~stickslip.analysis.contact.friction_coupling.jenkins_state_matrix`) ``A`` is
    affine in ``mu`` when ``N_0`` is constant in it (no slope, or no normal DOF): then
    ``P_0 = A(0)``, ``P_1 = A(1) - A(0)``. With a slope and a normal DOF, ``N_0 = W / (1 + a
    mu)`` enters the massless point's lag ``c_t + mu' N_0`` and the massive point's friction:
    ``f = c_t (1 + a mu) + mu' W`` (massless) or ``1 + a mu`` (massive) makes ``f A``
    quadratic, whose coefficients come from three values of ``mu`` (Lagrange interpolation,
    exact to rounding).

    Parameters
    ----------
    system : FrictionCoupledSystem
        The linearisation's data.

    Returns
    -------
    tuple or None
        ``P_0``, ``P_1``, ``P_2`` (1/s, shape (2n, 2n) or larger; ``P_2`` None when ``A`` is
        affine) and the breakpoints (the zeros of ``f`` and ``1 + a mu``, where ``A`` has a
        pole: the contact lifts off or the point's lag vanishes); None where ``A`` is not of
        that form.
    """
    if system.tangential_stiffness is not None:
        return _jenkins_coefficients(system)
    n, t, nd = system.n_dof, system.tangential_dof, system.normal_dof
    m = np.asarray(system.mass, dtype=float)
    k0 = system.contact_stiffness()
    c0 = np.array(system.damping, dtype=float)
    k1, c1, c2 = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n))
    if nd is not None:
        c0[nd, nd] += system.normal_damping
        k1[t, nd] = system.normal_stiffness
        c1[t, nd] = system.normal_damping
    c2[t, t] = 1.0
    w_ref = reference_rate(m, k0)
    a0 = first_order_matrix(m, c0, k0, w_ref)
    a1 = first_order_matrix(m, c1, k1, w_ref, identity=False)
    a2 = first_order_matrix(m, c2, np.zeros((n, n)), w_ref, identity=False)
    pole = steady_normal_force_pole(system) if system.slope != 0.0 else 0.0
    p0 = a0 + system.slope * system.load * a2
    if pole == 0.0:
        return p0, a1, None, np.array([])
    return p0, a1 + pole * a0, pole * a1, np.array([-1.0 / pole])


def _jenkins_coefficients(system: FrictionCoupledSystem,
                          ) -> tuple[FloatArray, FloatArray, FloatArray | None, FloatArray] | None:
    """:func:`matrix_coefficients` for a Jenkins element (its docstring)."""
    w_ref = reference_rate(system.mass, system.contact_stiffness())
    if system.slope != 0.0 and system.normal_dof is not None:
        a = steady_normal_force_pole(system)
        load_slope = system.slope * system.load
        ct = system.tangential_damping

        def f(mu: float) -> float:
            massive = system.contact_mass is not None
            return (1.0 + a * mu) if massive else ct * (1.0 + a * mu) + load_slope

        usable = [x for x in (0.0, 1.0, 2.0, 3.0, 4.0) if f(x) != 0.0 and 1.0 + a * x != 0.0][:3]
        samples = []
        for x in usable:
            sample = jenkins_state_matrix(system, x, w_ref)
            if sample is None:
                return None
            samples.append(f(x) * sample)
        values = np.stack(samples)
        coefficients = np.linalg.solve(np.vander(usable, 3, increasing=True),
                                       values.reshape(3, -1)).reshape(values.shape)
        breaks = [-1.0 / a] if a != 0.0 else []
        if system.contact_mass is None and ct * a != 0.0:
            breaks.append(-(ct + load_slope) / (ct * a))
        return coefficients[0], coefficients[1], coefficients[2], np.array(breaks)
    a0, a1 = jenkins_state_matrix(system, 0.0, w_ref), jenkins_state_matrix(system, 1.0, w_ref)
    if a0 is not None and a1 is not None:
        return a0, a1 - a0, None, np.array([])
    if system.tangential_damping == 0.0 and system.slope == 0.0:
        # the extension follows the load: the rigid contact's spectrum (FrictionCoupledSystem)
        return matrix_coefficients(replace(system, tangential_stiffness=None, contact_mass=None))
    return None


def polynomial_real_roots(b0: FloatArray, b1: FloatArray, b2: FloatArray | None,
                          lo: float, hi: float) -> FloatArray | None:
    """Real ``mu`` in ``[lo, hi]`` with ``det(b0 + mu b1 + mu^2 b2) = 0`` (QZ on the companion pencil).

    Parameters
    ----------
    b0, b1 : ndarray, shape (N, N)
        Coefficients of the matrix polynomial.
    b2 : ndarray or None
        Its quadratic coefficient (None: a pencil).
    lo, hi : float
        The range of ``mu``.

    Returns
    -------
    ndarray or None
        The roots, sorted; None when the polynomial is singular (its determinant vanishes
        for every ``mu``) or the pencil has more than :data:`MAX_PENCIL` rows.
    """
    import scipy.linalg

    size = b0.shape[0]
    if size * (1 if b2 is None else 2) > MAX_PENCIL:
        return None
    rng = np.random.default_rng(0)
    probes = [lo + (hi - lo) * x for x in rng.uniform(0.1, 0.9, 3)]
    ratios = []
    for mu in probes:
        sv = np.linalg.svd(b0 + mu * b1 + (0.0 if b2 is None else mu * mu * b2), compute_uv=False)
        ratios.append(sv[-1] / sv[0] if sv[0] > 0.0 else 0.0)
    if max(ratios) <= SINGULAR_TOL:
        return None
    if b2 is None:
        left, right = b0, -b1
    else:
        eye, zero = np.eye(size), np.zeros((size, size))
        left = np.block([[zero, eye], [-b0, -b1]])
        right = np.block([[eye, zero], [zero, b2]])
    alpha, beta = scipy.linalg.eig(left, right, right=False, homogeneous_eigvals=True)
    finite = np.abs(beta) > 0.0
    mus = alpha[finite] / beta[finite]
    real = mus[np.abs(mus.imag) <= REAL_TOL * np.maximum(1.0, np.abs(mus))].real
    return np.sort(real[(real >= lo) & (real <= hi)])


def crossing_candidates(system: FrictionCoupledSystem, mu_max: float) -> FloatArray | None:
    """Every ``mu`` in ``(0, mu_max)`` where an eigenvalue can reach the imaginary axis.

    Parameters
    ----------
    system : FrictionCoupledSystem
        The linearisation's data (damped: an undamped spectrum sits on the axis).
    mu_max : float
        End of the range, dimensionless.

    Returns
    -------
    ndarray or None
        Increasing values, merged where closer than ``1e-9 max(1, mu)`` (module docstring);
        None when the search cannot prove (a singular pencil or one too large).
    """
    coefficients = matrix_coefficients(system)
    if coefficients is None:
        return None
    p0, p1, p2, breaks = coefficients
    found = [breaks]
    for transform in (bialternate_sum, None):
        b0, b1 = (p if transform is None else transform(p) for p in (p0, p1))
        b2 = None if p2 is None else (p2 if transform is None else transform(p2))
        roots = polynomial_real_roots(b0, b1, b2, 0.0, mu_max)
        if roots is None:
            return None
        found.append(roots)
    return _merged(np.concatenate(found), mu_max)


def _merged(values: FloatArray, mu_max: float) -> FloatArray:
    """The values in ``(0, mu_max)``, sorted, merged where closer than ``1e-9 max(1, mu)``."""
    values = np.sort(values)
    values = values[(values > 0.0) & (values < mu_max)]
    merged: list[float] = []
    for v in values:
        if not merged or v - merged[-1] > 1e-9 * max(1.0, abs(v)):
            merged.append(float(v))
    return np.array(merged)


def coalescence_candidates(system: FrictionCoupledSystem, mu_max: float) -> FloatArray | None:
    r"""Every ``mu`` in ``(0, mu_max)`` where the undamped spectrum can change its kind.

    Undamped, the squared frequencies ``\lambda = \omega^2`` solve ``g(\lambda) = -1 /
    (\mu k_n)`` with ``g(\lambda) = \sum_i \alpha_i \beta_i / (\lambda_i - \lambda)`` (the
    mass-normalised modes of ``K_0``; module docstring of
    :mod:`~stickslip.analysis.contact.critical_coefficient`), plus the modes friction does not
    couple (``\alpha_i \beta_i = 0``), which stay. As ``\mu`` grows the level
    ``-1 / (\mu k_n)`` moves monotonically; two real roots merge (flutter) or part only where
    it passes a stationary value of ``g`` (``g' = 0``: a double root), and a root changes sign
    only where it passes ``g(0)`` (divergence); roots never cross a pole. So the kind of
    spectrum is constant between the values ``\mu = -1 / (k_n g(\lambda^*))`` for the
    stationary points ``\lambda^*`` and ``\mu = -1 / (k_n g(0))``. The stationary points are
    the zeros of ``g'(\lambda) = \sum_i w_i / (\lambda_i - \lambda)^2``, the transfer
    function of the Jordan blocks ``[[\lambda_i, 1], [0, \lambda_i]]`` with input ``e_2`` and
    output ``w_i e_1``: the finite eigenvalues of its Rosenbrock pencil (QZ), polished by
    Newton's method on ``g'``.

    Parameters
    ----------
    system : FrictionCoupledSystem
        Undamped, with a normal DOF and a rigid tangential contact (or a massless element
        that follows the load).
    mu_max : float
        End of the range, dimensionless.

    Returns
    -------
    ndarray or None
        Increasing values in ``(0, mu_max)``; None beyond :data:`MAX_PENCIL` rows.
    """
    import scipy.linalg

    t, nd = system.tangential_dof, system.normal_dof
    assert nd is not None
    lam, phi = scipy.linalg.eigh(system.contact_stiffness(), system.mass)
    w = phi[t, :] * phi[nd, :]
    scale = float(np.max(np.abs(w))) if w.size else 0.0
    keep = np.abs(w) > 1e-14 * scale
    lam, w = lam[keep], w[keep]
    m = lam.size
    if 2 * m + 1 > MAX_PENCIL or m == 0:
        return None if m else np.array([])
    a = np.zeros((2 * m + 1, 2 * m + 1))
    for i in range(m):
        a[2 * i, 2 * i] = a[2 * i + 1, 2 * i + 1] = lam[i]
        a[2 * i, 2 * i + 1] = 1.0
        a[2 * i + 1, 2 * m] = 1.0  # input into the block's second state
        a[2 * m, 2 * i] = w[i]  # output from its first
    e = np.eye(2 * m + 1)
    e[2 * m, 2 * m] = 0.0
    alpha, beta = scipy.linalg.eig(a, e, right=False, homogeneous_eigvals=True)
    finite = np.abs(beta) > 1e-12 * np.abs(alpha)
    zeros = alpha[finite] / beta[finite]
    stationary = zeros[np.abs(zeros.imag) <= REAL_TOL * np.maximum(1.0, np.abs(zeros))].real

    def g(x: float, power: int) -> float:
        return float(np.sum(w / (lam - x) ** power))

    polished = []
    for x in stationary:
        for _ in range(8):  # Newton on g' (g'' = 2 sum w / (lambda_i - x)^3), bounded
            step = g(x, 2) / (2.0 * g(x, 3)) if g(x, 3) != 0.0 else 0.0
            if not np.isfinite(step):
                break
            x = x - step
        polished.append(x)
    levels = [g(x, 1) for x in polished] + ([g(0.0, 1)] if np.all(lam != 0.0) else [])
    kn = system.normal_stiffness
    mus = np.array([-1.0 / (kn * v) for v in levels if np.isfinite(v) and kn * v < 0.0])
    return _merged(mus, mu_max)


def interval_points(candidates: FloatArray, mu_max: float) -> FloatArray:
    """One point inside each interval between 0, the candidates and ``mu_max``: their midpoints.

    Parameters
    ----------
    candidates : ndarray
        Increasing values in ``(0, mu_max)``.
    mu_max : float
        End of the range.

    Returns
    -------
    ndarray
        ``len(candidates) + 1`` midpoints.
    """
    ends = np.concatenate(([0.0], candidates, [mu_max]))
    return 0.5 * (ends[:-1] + ends[1:])

