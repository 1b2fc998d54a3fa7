r"""Steady sliding with normal-load coupling, linearised: matrices, eigenvalues, critical mu.

What finite-element codes call CEA: linearise the equations of motion about steady sliding,
where the friction force depends on the normal force and the normal force on the motion, and
read stability from the eigenvalues. The friction coupling makes the stiffness matrix
non-symmetric, two modes can merge (mode coalescence, flutter) and the pair's growth rate
becomes positive: the mechanism behind brake squeal.

The equations (SI units)
------------------------
``q`` (m) are the structure's DOF, ``t`` the tangential DOF (``contact_dof``, along the belt,
which moves at ``V`` in the positive direction) and ``n`` the normal DOF (``normal_dof``,
positive away from the belt). ``M``, ``C``, ``K`` (kg, N s/m, N/m) are the structure's own;
the contact spring ``k_n`` and damper ``c_n`` act on ``n``; the preload ``W`` (``load``, N)
pushes ``n`` towards the belt. With ``q`` measured from where the contact spring carries
exactly ``W``, the normal force and the friction force on ``t`` while sliding are

.. math::

    N = W - k_n q_n - c_n \dot q_n, \qquad F_t = \mu(v_r)\, N, \qquad v_r = V - \dot q_t,

so that

.. math::

    M \ddot q + C \dot q + K q + (k_n q_n + c_n \dot q_n - W) e_n + W e_n
        = \mu(v_r) N e_t .

The preload and the contact force's share ``W`` cancel on ``n``. Steady sliding is the
equilibrium ``q_0`` of ``(K + k_n e_n e_n^T + \mu k_n e_t e_n^T) q_0 = \mu W e_t`` with
``\mu = \mu(V)``, and ``N_0 = W - k_n q_{0,n}`` must be positive (else the contact has lifted
off). For a small motion ``x = q - q_0``, ``\delta F_t = -\mu k_n x_n - \mu c_n \dot x_n
- \mu'(V) N_0 \dot x_t`` (``\mu' = d\mu/dv_r``, s/m), and moving it to the left side:

.. math::

    M \ddot x + \big(C + c_n e_n e_n^T + \mu c_n e_t e_n^T + \mu'(V) N_0 e_t e_t^T\big) \dot x
        + \big(K + k_n e_n e_n^T + \mu k_n e_t e_n^T\big) x = 0 .

* ``+\mu k_n`` in the stiffness entry ``(t, n)`` (N/m) is the friction coupling: moving away
  from the belt (``x_n > 0``) lowers ``N`` and the friction that pulls ``t`` forward. It makes
  the stiffness non-symmetric: a circulatory force that can do work around a closed orbit.
  (With the normal coordinate positive *towards* the belt, as in Hoffmann et al. 2002, the
  same entry reads ``-\mu k_n``.)
* ``+\mu c_n`` in the damping entry ``(t, n)`` (N s/m) is the same coupling through the
  contact damper.
* ``\mu'(V) N_0`` (N s/m) on ``(t, t)`` is the friction law's slope: a velocity-weakening law
  (``\mu' < 0``, a falling Stribeck curve) is a negative damper on the tangential DOF. Speed
  and load enter the linearisation only through this term: with the Coulomb law
  (``\mu' = 0``) the eigenvalues depend on neither.

Eigenvalues ``s`` (1/s) are those of the first-order form ``[[0, I], [-M^{-1}K, -M^{-1}C]]``;
a mode with ``s = \sigma + i\omega`` has frequency ``\omega / 2\pi`` Hz and damping ratio
``-\sigma / |s|``. Steady sliding is asymptotically stable when every ``\sigma < 0``.

The Jenkins element
-------------------
The Jenkins element (``[contact] tangential_stiffness``) puts a contact point ``p`` between the
tangential DOF ``q_t`` and the belt: a spring ``k_t`` and damper ``c_t`` act on the extension
``e = q_t - p`` (m), and the belt's friction acts on the point. Its force on the structure is
``F_e = -(k_t e + c_t \dot e)``, and the point, of mass ``m_c`` (or massless), slides at
``v_p = \dot q_t - \dot e`` with the relative velocity ``v_r = V - v_p``:

.. math::

    m_c \dot v_p = \mu(v_r) N + k_t e + c_t \dot e
    \qquad (m_c = 0:\ k_t e + c_t \dot e = -\mu(v_r) N),

the equations of the contact engine's slip modes
(:mod:`stickslip.analysis.contact.engine`). In steady sliding the structure and the point are
at rest (``v_p = 0``, ``v_r = V``), ``k_t e_0 = -\mu N_0`` and ``F_e = \mu N_0``: the same
equilibrium and ``N_0`` as the rigid contact. For a small motion, with
``\delta N = -k_n x_n - c_n \dot x_n`` and ``\delta(\mu N) = \mu \delta N + \mu' N_0 \delta v_r``:

* **massive point** (states ``x, \dot x, \delta e, \delta v_p``): ``\delta\dot e = \dot x_t -
  \delta v_p``, ``\delta F_e = -(k_t \delta e + c_t \delta\dot e)`` and ``m_c \delta\dot v_p =
  \mu \delta N - \mu' N_0 \delta v_p - \delta F_e``;
* **massless point** (states ``x, \dot x, \delta e``): ``(c_t + \mu' N_0) \delta\dot e =
  -k_t \delta e - \mu \delta N + \mu' N_0 \dot x_t``. When ``c_t + \mu' N_0 = 0`` the extension
  is not a state: with ``c_t = 0`` and the Coulomb law it follows the load, ``k_t \delta e =
  -\mu \delta N``, ``\delta F_e = \mu \delta N``, and the eigenvalues are the rigid contact's
  (:meth:`FrictionCoupledSystem.eigenvalues` takes that path); a damper that cancels the
  slope exactly leaves no linearisation (NaN eigenvalues, neutral within no bound);

and the structure ``M \ddot x + (C + c_n e_n e_n^T) \dot x + (K + k_n e_n e_n^T) x = e_t
\delta F_e``. The friction coupling ``\mu \delta N`` reaches the structure through the point,
and the law's slope damps (or feeds) the point's motion rather than the tangential DOF's.
As ``k_t`` grows the spectrum tends to the rigid contact's with the point's mass added to the
tangential DOF, plus the element's own fast eigenvalues (tested: the gap closes like
``1 / k_t``).

The critical friction coefficient, where steady sliding first turns unstable as ``\mu`` grows,
is :mod:`stickslip.analysis.contact.critical_coefficient`.

The analysis of a machine file (eigenvalues, verdict, both critical coefficients) is
:func:`stickslip.analysis.contact.eigenvalues.complex_eigenvalue_analysis`; the minimal model
of Hoffmann et al. (2002), whose undamped flutter boundary has a closed form, is
:mod:`stickslip.analysis.contact.squeal_minimal_model`; root loci and maps over (mu, speed) or
(mu, load) are :mod:`stickslip.analysis.contact.eigenvalue_maps`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.blas_threads import one_blas_thread
from stickslip.model.contact import check_contact_stiffness

if TYPE_CHECKING:
    from stickslip.model.contact import Contact
    from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True)
class FrictionCoupledSystem:
    """The structure, its contact and the friction law's slope: steady sliding's linearisation.

    Parameters
    ----------
    mass, damping, stiffness : ndarray, shape (n, n)
        The structure's own matrices, kg, N s/m, N/m (symmetric; mass positive definite).
    tangential_dof : int
        DOF along the belt (the belt moves at V in its positive direction).
    normal_dof : int or None
        DOF across the belt, positive away from it; None: a constant normal load.
    normal_stiffness, normal_damping : float
        Contact spring ``k_n`` (N/m) and damper ``c_n`` (N s/m) on ``normal_dof``.
    load : float
        Preload ``W``, N.
    slope : float
        ``d mu / d v_r`` of the friction law at the sliding speed, s/m (0: Coulomb).
    tangential_stiffness : float or None
        ``k_t`` of a Jenkins element between ``tangential_dof`` and the belt, N/m; None: a
        rigid tangential contact (:func:`jenkins_state_matrix`).
    tangential_damping : float
        Its damper ``c_t``, N s/m.
    contact_mass : float or None
        Mass of its contact point, kg; None: massless.
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    tangential_dof: int
    normal_dof: int | None = None
    normal_stiffness: float = 0.0
    normal_damping: float = 0.0
    load: float = 1.0
    slope: float = 0.0
    tangential_stiffness: float | None = None
    tangential_damping: float = 0.0
    contact_mass: float | None = None

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom."""
        return int(self.mass.shape[0])

    @property
    def n_eigenvalues(self) -> int:
        """How many eigenvalues :meth:`eigenvalues` gives: ``2n``, one more for a Jenkins element
        whose massless point's extension is a state, two more for a massive point."""
        if self.tangential_stiffness is None:
            return 2 * self.n_dof
        if self.contact_mass is not None:
            return 2 * self.n_dof + 2
        follows_load = self.tangential_damping == 0.0 and self.slope == 0.0
        return 2 * self.n_dof + (0 if follows_load else 1)

    def undamped(self) -> FrictionCoupledSystem:
        """The same system without any velocity term (``C = 0``, ``c_n = 0``, ``c_t = 0``, slope 0)."""
        return replace(self, damping=np.zeros_like(self.damping), normal_damping=0.0, slope=0.0,
                       tangential_damping=0.0)

    def point_as_dof(self) -> FrictionCoupledSystem:
        """A massive contact point as one more DOF of the structure, with a rigid contact there.

        The point (mass ``m_c``) is joined to ``tangential_dof`` by the element (``k_t``,
        ``c_t``) and slides on the belt: its equations are those of a DOF ``p`` with
        ``m_c x_p'' = k_t (x_t - x_p) + c_t (x_t' - x_p') + mu N`` and ``N = W - k_n q_n -
        c_n q_n'``, which is the rigid contact of this class on the structure with ``M + m_c
        e_p e_p^T``, ``C + c_t d d^T`` and ``K + k_t d d^T`` (``d = e_t - e_p``), friction on
        ``p``. The law's slope then acts on ``x_p'``, as in :func:`jenkins_state_matrix`. In
        steady sliding the element carries ``mu N_0``, so ``N_0`` is unchanged.

        Returns
        -------
        FrictionCoupledSystem
            ``n + 1`` DOF, ``tangential_dof = n`` (the point), no element.
        """
        assert self.tangential_stiffness is not None and self.contact_mass is not None
        n, t = self.n_dof, self.tangential_dof
        d = np.zeros(n + 1)
        d[t], d[n] = 1.0, -1.0

        def grown(matrix: FloatArray, point: float, element: float) -> FloatArray:
            out = np.zeros((n + 1, n + 1))
            out[:n, :n] = matrix
            out[n, n] = point
            return out + element * np.outer(d, d)

        return replace(self, mass=grown(self.mass, self.contact_mass, 0.0),
                       damping=grown(self.damping, 0.0, self.tangential_damping),
                       stiffness=grown(self.stiffness, 0.0, self.tangential_stiffness),
                       tangential_dof=n, tangential_stiffness=None, tangential_damping=0.0,
                       contact_mass=None)

    def contact_stiffness(self) -> FloatArray:
        """``K_0 = K + k_n e_n e_n^T`` (N/m): the structure pressed on the belt, without friction."""
        k0 = np.array(self.stiffness, dtype=float)
        if self.normal_dof is not None:
            k0[self.normal_dof, self.normal_dof] += self.normal_stiffness
        return k0

    def normal_force(self, mu: float) -> float:
        """``N_0 = W - k_n q_{0,n}`` (N) of steady sliding at the friction coefficient ``mu``."""
        if self.normal_dof is None:
            return self.load
        t, n = self.tangential_dof, self.normal_dof
        k = self.contact_stiffness()
        k[t, n] += mu * self.normal_stiffness
        rhs = np.zeros(self.n_dof)
        rhs[t] = mu * self.load
        try:
            q0 = np.linalg.solve(k, rhs)
        except np.linalg.LinAlgError:
            return math.nan  # the divergence point itself: no equilibrium
        return float(self.load - self.normal_stiffness * q0[n])

    def self_locking_mu(self) -> float | None:
        """The friction coefficient where steady sliding self-locks (divergence), or None.

        Derivation: with ``K_0`` the contact stiffness (:meth:`contact_stiffness`) the
        equilibrium is ``(K_0 + mu k_n e_t e_n^T) q_0 = mu W e_t``; by the Sherman-Morrison
        formula ``q_0 = mu W K_0^-1 e_t / (1 + a mu)`` with ``a = k_n (K_0^-1)[n, t]``, so
        ``N_0 = W - k_n q_0[n] = W / (1 + a mu)`` and ``det K(mu) = det K_0 (1 + a mu)``. For
        ``a < 0`` the normal force grows without bound as ``mu -> -1/a`` (the static stiffness
        loses its definiteness: divergence) and beyond it the equilibrium would need ``N_0 <
        0``: the friction wedges the slider into the belt (self-locking, sprag), it does not
        lift it off. For ``a >= 0`` (or no normal DOF) no coefficient self-locks.

        Returns
        -------
        float or None
            ``-1 / a``, dimensionless; None when ``a >= 0`` or without a normal DOF.
        """
        if self.normal_dof is None:
            return None
        e_t = np.zeros(self.n_dof)
        e_t[self.tangential_dof] = 1.0
        a = self.normal_stiffness * float(np.linalg.solve(self.contact_stiffness(), e_t)[
            self.normal_dof])
        return -1.0 / a if a < 0.0 else None

    def matrices(self, mu: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``(M, C(mu), K(mu))`` of the linearisation about steady sliding (module docstring).

        The rigid tangential contact's; a Jenkins element adds states
        (:meth:`eigenvalues`).

        Parameters
        ----------
        mu : float
            Friction coefficient at the sliding speed, dimensionless.

        Returns
        -------
        tuple of ndarray
            Mass (kg), damping (N s/m) and the non-symmetric stiffness (N/m).
        """
        t, n = self.tangential_dof, self.normal_dof
        c = np.array(self.damping, dtype=float)
        k = self.contact_stiffness()
        if n is not None:
            c[n, n] += self.normal_damping
            c[t, n] += mu * self.normal_damping
            k[t, n] += mu * self.normal_stiffness
        if self.slope != 0.0:
            c[t, t] += self.slope * self.normal_force(mu)
        return np.array(self.mass, dtype=float), c, k

    def eigenvalues(self, mu: float) -> tuple[ComplexArray, FloatArray]:
        """Eigenvalues (1/s) of the linearisation at ``mu`` and their error bounds (1/s).

        Parameters
        ----------
        mu : float
            Friction coefficient, dimensionless.

        Returns
        -------
        values : ndarray of complex, shape (2n,)
            ``s = sigma + i omega``, sorted by ``omega`` then ``sigma`` (a Jenkins element
            adds one, or two with a massive contact point).
        bounds : ndarray, shape (2n,)
            First-order bound on each eigenvalue's round-off error (module docstring).
        """
        if self.tangential_stiffness is not None:
            a = jenkins_state_matrix(self, mu, reference_rate(self.mass, self.contact_stiffness()))
            if a is not None:
                return bounded_eigenvalues(a)
            if self.tangential_damping != 0.0 or self.slope != 0.0:
                # the damper cancels the slope: no linearisation (neutral, never proven)
                return (np.full(self.n_eigenvalues, np.nan, dtype=complex),
                        np.full(self.n_eigenvalues, np.inf))
        return _eigen(*self.matrices(mu))


def jenkins_state_matrix(system: FrictionCoupledSystem, mu: float, w_ref: float) -> FloatArray | None:
    """The first-order matrix of steady sliding on the Jenkins element (module docstring).

    Parameters
    ----------
    system : FrictionCoupledSystem
        With ``tangential_stiffness`` set.
    mu : float
        Friction coefficient at the sliding speed, dimensionless.
    w_ref : float
        The state's scale ``w``, 1/s
        (:func:`~stickslip.analysis.contact.friction_coupling.reference_rate`).

    Returns
    -------
    ndarray, shape (2n + 1, 2n + 1) or (2n + 2, 2n + 2), or None
        ``A`` (1/s) in the state ``(w x, \\dot x, w \\delta e[, \\delta v_p])`` (a diagonal
        similarity of the SI state, the same eigenvalues); None
        for a massless point whose extension is not a state (``c_t + \\mu' N_0 = 0``).
    """
    assert system.tangential_stiffness is not None
    n, t, nd = system.n_dof, system.tangential_dof, system.normal_dof
    kt, ct, mc = system.tangential_stiffness, system.tangential_damping, system.contact_mass
    slope_force = system.slope * system.normal_force(mu) if system.slope != 0.0 else 0.0
    d = 2 * n + (1 if mc is None else 2)
    ie, ivp = 2 * n, 2 * n + 1

    def unit(i: int, value: float = 1.0) -> FloatArray:
        row = np.zeros(d)
        row[i] = value
        return row

    normal = np.zeros(d) if nd is None else -(unit(nd, system.normal_stiffness)
                                              + unit(n + nd, system.normal_damping))
    a = np.zeros((d, d))
    if mc is None:
        lag = ct + slope_force
        if lag == 0.0:
            return None
        a[ie] = (-unit(ie, kt) - mu * normal + unit(n + t, slope_force)) / lag
    else:
        a[ie] = unit(n + t) - unit(ivp)
    element = -(unit(ie, kt) + ct * a[ie])  # delta F_e on the structure
    if mc is not None:
        a[ivp] = (mu * normal - unit(ivp, slope_force) - element) / mc
    m = np.asarray(system.mass, dtype=float)
    c0 = np.array(system.damping, dtype=float)
    if nd is not None:
        c0[nd, nd] += system.normal_damping
    k0 = system.contact_stiffness()
    force = np.zeros((n, d))
    force[:, :n], force[:, n:2 * n] = -k0, -c0
    force[t] += element
    a[:n, n:2 * n] = np.eye(n)
    a[n:2 * n] = np.linalg.solve(m, force)
    scale = np.ones(d)
    scale[:n] = w_ref
    scale[ie] = w_ref
    return np.asarray(scale[:, None] * a / scale[None, :], dtype=float)


def reference_rate(m: FloatArray, k: FloatArray) -> float:
    """``omega_ref = sqrt(max |diag(M^-1 K)|)`` (1/s): the scale of :func:`first_order_matrix`.

    Parameters
    ----------
    m, k : ndarray, shape (n, n)
        Mass (kg) and stiffness (N/m).

    Returns
    -------
    float
        The reference rate, 1/s.
    """
    mk = np.linalg.solve(m, k)
    return math.sqrt(max(float(np.max(np.abs(np.diag(mk)))), 1e-300))


def first_order_matrix(m: FloatArray, c: FloatArray, k: FloatArray, w_ref: float, *,
                       identity: bool = True) -> FloatArray:
    """``A = [[0, w I], [-M^-1 K / w, -M^-1 C]]``: the first-order form in the state ``(w q, q')``.

    The same eigenvalues as ``[[0, I], [-M^-1 K, -M^-1 C]]`` (a diagonal similarity), with
    entries of the size of the frequencies. Linear in ``(K, C)`` apart from the identity block.

    Parameters
    ----------
    m, c, k : ndarray, shape (n, n)
        Mass (kg), damping (N s/m) and stiffness (N/m).
    w_ref : float
        The scale ``w``, 1/s (:func:`reference_rate`).
    identity : bool
        Include the block ``w I`` (False: the part linear in ``K`` and ``C`` alone).

    Returns
    -------
    ndarray, shape (2n, 2n)
        The matrix, 1/s.
    """
    n = m.shape[0]
    a = np.zeros((2 * n, 2 * n))
    if identity:
        a[:n, n:] = w_ref * np.eye(n)
    a[n:, :n] = -np.linalg.solve(m, k) / w_ref
    a[n:, n:] = -np.linalg.solve(m, c)
    return a


def _eigen(m: FloatArray, c: FloatArray, k: FloatArray) -> tuple[ComplexArray, FloatArray]:
    return bounded_eigenvalues(first_order_matrix(m, c, k, reference_rate(m, k)))


def bounded_eigenvalues(a: FloatArray) -> tuple[ComplexArray, FloatArray]:
    """Eigenvalues of ``a`` with a first-order bound on each one's round-off error.

    LAPACK's eigenvalues are exact for a matrix within ``O(eps) ||a||`` of ``a``; an
    eigenvalue moves by at most its condition number ``kappa = ||x|| ||y|| / |y^H x|`` (right
    and left eigenvectors ``x``, ``y``) times that: the bound is ``kappa 2 m eps ||a||_F`` for
    an ``m x m`` matrix (Wilkinson; Golub and Van Loan, section 7.2.2). With unit right
    eigenvectors (the columns of ``X``) the left ones are the rows of ``X^-1`` scaled so that
    ``y^H x = 1``, so ``kappa`` is the norm of a row of ``X^-1``. A matrix whose entries differ
    by orders of magnitude should be balanced (a diagonal similarity) first.

    Parameters
    ----------
    a : ndarray, shape (..., m, m)
        Real matrices (1/s); a stack is done at once.

    Returns
    -------
    values : ndarray of complex, shape (..., m)
        Sorted by imaginary part, then real part.
    bounds : ndarray, shape (..., m)
        Their error bounds (same unit).
    """
    if a.ndim > 2 and a.shape[0] == 0:
        return np.zeros(a.shape[:-1], dtype=np.complex128), np.zeros(a.shape[:-1])
    values, right = np.linalg.eig(a)
    try:
        kappa = np.linalg.norm(np.linalg.inv(right), axis=-1)
    except np.linalg.LinAlgError:
        if a.ndim > 2:  # one defective matrix in the stack: the others keep their bounds
            parts = [bounded_eigenvalues(m) for m in a.reshape(-1, *a.shape[-2:])]
            return (np.stack([p[0] for p in parts]).reshape(values.shape),
                    np.stack([p[1] for p in parts]).reshape(values.shape))
        kappa = np.full(values.shape, np.inf)  # defective: no bound, the eigenvalue is unreliable
    kappa = np.where(np.isfinite(kappa), kappa, np.inf)
    norm = np.linalg.norm(a, axis=(-2, -1))[..., None]
    bounds = kappa * 2 * a.shape[-1] * np.finfo(float).eps * norm
    order = np.lexsort((values.real, values.imag), axis=-1)
    return np.take_along_axis(values, order, -1), np.take_along_axis(bounds, order, -1)


def verdict_of(values: ComplexArray, bounds: FloatArray) -> int:
    """Sign of the spectrum, read only beyond each eigenvalue's error bound.

    Parameters
    ----------
    values : ndarray of complex
        Eigenvalues, 1/s.
    bounds : ndarray
        Their error bounds, 1/s (:meth:`FrictionCoupledSystem.eigenvalues`).

    Returns
    -------
    int
        +1 proven unstable, -1 proven asymptotically stable, 0 undecided (neutral within bounds).
    """
    if np.any(values.real - bounds > 0.0):
        return 1
    if np.all(values.real + bounds < 0.0):
        return -1
    return 0


@one_blas_thread
def track_branches(system: FrictionCoupledSystem, mus: FloatArray) -> ComplexArray:
    """Eigenvalues along ``mus``, each column one branch followed by nearest matching.

    Parameters
    ----------
    system : FrictionCoupledSystem
        The linearisation's data.
    mus : ndarray
        Increasing friction coefficients, dimensionless.

    Returns
    -------
    ndarray of complex, shape (len(mus), 2n)
        Row ``i`` the eigenvalues (1/s) at ``mus[i]``, matched to row ``i - 1`` by the least
        total distance (an assignment problem).
    """
    from scipy.optimize import linear_sum_assignment

    out = np.empty((len(mus), system.n_eigenvalues), dtype=complex)
    for i, mu in enumerate(mus):
        values, _ = system.eigenvalues(float(mu))
        if i:
            cost = np.abs(out[i - 1][:, None] - values[None, :])
            _, cols = linear_sum_assignment(cost)
            values = values[cols]
        out[i] = values
    return out


def friction_at(machine: Machine, speed: float | None = None) -> tuple[float, float]:
    """``(mu(V), d mu / d v_r at V)`` of the machine's friction law at the sliding speed ``V``.

    Parameters
    ----------
    machine : Machine
        Its law, ``mu_s``, ``mu_k`` and operating point.
    speed : float, optional
        Sliding speed, m/s (default the machine's).

    Returns
    -------
    tuple of float
        The coefficient (dimensionless) and its slope (s/m): the law's exact value and slope
        (the Stribeck law's, not its piecewise-linear tabulation).
    """
    at = machine if speed is None else machine.with_operating_point(speed=speed)
    slider = at.slider()
    unit = (at.mu_s - at.mu_k) / slider.lam  # mu per unit of the dimensionless friction F
    mu = float(slider.friction.value(1.0, slider.lam, slider.gamma)) * unit
    slope = float(slider.friction.slope_at(1.0, slider.lam, slider.gamma)) * unit / at.speed
    return mu, slope


def coupled_system(machine: Machine, contact: Contact | None, *, normal_dof: int | None = None,
                   speed: float | None = None, load: float | None = None,
                   ) -> tuple[FrictionCoupledSystem, float]:
    """The :class:`FrictionCoupledSystem` of a machine and its contact, and ``mu(V)``.

    Parameters
    ----------
    machine : Machine
        Structure (SI), contact DOF, law and operating point.
    contact : Contact or None
        The ``[contact]``; None or without a normal DOF: a constant normal load.
    normal_dof : int, optional
        The normal DOF's index in ``machine`` when it differs from ``contact.normal_dof``
        (a reduced model).
    speed, load : float, optional
        Sliding speed (m/s) and preload (N) instead of the machine's.

    Returns
    -------
    tuple
        The system and the friction coefficient at the sliding speed.
    """
    at = machine.with_operating_point(speed=speed, load=load)
    mu, slope = friction_at(at)
    index = None
    kn = cn = 0.0
    if contact is not None and contact.normal_dof is not None:
        if normal_dof is None:
            contact.check_dofs(at.n_dof, at.contact_dof)
        index = contact.normal_dof if normal_dof is None else normal_dof
        kn, cn = float(contact.normal_stiffness or 0.0), contact.normal_damping
    if contact is not None:
        check_contact_stiffness(contact.normal_stiffness, contact.tangential_stiffness,
                                at.stiffness)
    system = FrictionCoupledSystem(at.mass, at.damping, at.stiffness, at.contact_dof, index,
                                   normal_stiffness=kn, normal_damping=cn, load=at.load,
                                   slope=slope)
    if contact is not None and contact.has_tangential_compliance:
        system = replace(system, tangential_stiffness=contact.tangential_stiffness,
                         tangential_damping=contact.tangential_damping,
                         contact_mass=contact.mass)
    return system, mu

