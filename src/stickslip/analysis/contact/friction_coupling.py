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

Critical friction coefficient
-----------------------------
``critical_mu`` is the smallest ``\mu > 0`` at which an eigenvalue crosses into the right
half plane, the law's slope ``\mu'(V)`` held at its value (``N_0`` follows ``\mu``). An
eigenvalue reaches the imaginary axis only at a real root of ``det(2A(\mu) \odot I)`` (a pair
``\pm i\omega``) or of ``det A(\mu)`` (zero), and both are polynomial eigenvalue problems in
``\mu`` (:mod:`stickslip.analysis.contact.axis_crossings`): their real roots cut ``(0,
mu_max]`` into intervals of constant stability, one eigenvalue check decides each, and the
critical value is the root where the first unstable interval begins (exact: no window is
skipped, however narrow). A sign is read only beyond the eigenvalue's error bound: each
eigenvalue's first-order perturbation bound ``kappa_i * 4n * eps * ||A||_F`` (``kappa_i`` its
condition number from the left and right eigenvectors, Wilkinson) is added to its real part.
The bracket comes from bisection between the two intervals' check points: its lower end is
proven stable and its upper end proven unstable. Where the roots cannot prove (an undamped
system, a singular pencil, more than 22 DOF (16 with a slope), an interval neutral within
round-off) the range is scanned at ``n_scan`` steps with bisection, which resolves instability
windows wider than its step (``mu_max / n_scan``), and the method says so.

``critical_mu_undamped`` is the same with every velocity term removed (``C``, ``c_n`` and the
slope): the eigenvalues are then ``\pm i\omega`` until two modes coalesce (flutter) or one
frequency reaches zero (divergence). Below the coalescence the undamped spectrum is on the
imaginary axis (marginal), so only the upper end is proven; the value is then made exact by
the coalescence condition: in the mass-normalised modes ``\Phi`` of
``K_0 = K + k_n e_n e_n^T`` (eigenvalues ``\lambda_i``), the squared frequencies
``\lambda = \omega^2`` of the coupled system solve
``1 + \mu k_n g(\lambda) = 0`` with ``g(\lambda) = \sum_i \alpha_i \beta_i / (\lambda_i - \lambda)``,
``\alpha_i = \Phi_{t i}``, ``\beta_i = \Phi_{n i}`` (the matrix determinant lemma). Two real
roots merge at a stationary point of ``g``: ``g'(\lambda^*) = 0``, found between the two
merging roots (a sign change of ``g'``), and ``\mu^* = -1 / (k_n g(\lambda^*))``.

The analysis of a machine file (eigenvalues, verdict, both critical coefficients) is
:func:`stickslip.analysis.contact.eigenvalues.complex_eigenvalue_analysis`; the minimal model
of Hoffmann et al. (2002), whose undamped flutter boundary has a closed form, is
:mod:`stickslip.analysis.contact.squeal_minimal_model`; root loci and maps over (mu, speed) or
(mu, load) are :mod:`stickslip.analysis.contact.eigenvalue_maps`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.blas_threads import one_blas_thread

if TYPE_CHECKING:
    from stickslip.model.contact import Contact
    from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


#: Default range of the friction coefficient searched for the critical one (dimensionless).
MU_MAX = 2.0
#: Default number of scan steps over ``[0, mu_max]`` before bisection.
N_SCAN = 400
#: Bisection steps (each halves the bracket; 200 steps are far beyond double precision).
MAX_BISECTIONS = 200


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

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom."""
        return int(self.mass.shape[0])

    def undamped(self) -> FrictionCoupledSystem:
        """The same system without any velocity term (``C = 0``, ``c_n = 0``, slope 0)."""
        return replace(self, damping=np.zeros_like(self.damping), normal_damping=0.0, slope=0.0)

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

    def matrices(self, mu: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``(M, C(mu), K(mu))`` of the linearisation about steady sliding (module docstring).

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
            ``s = sigma + i omega``, sorted by ``omega`` then ``sigma``.
        bounds : ndarray, shape (2n,)
            First-order bound on each eigenvalue's round-off error (module docstring).
        """
        return _eigen(*self.matrices(mu))


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


@dataclass(frozen=True)
class CriticalFriction:
    """The smallest friction coefficient at which steady sliding becomes unstable.

    Attributes
    ----------
    mu : float or None
        The critical coefficient (dimensionless); None when stable over the whole range.
    bracket : tuple of float
        ``(lo, hi)``: ``hi`` proven unstable; ``lo`` proven stable (damped) or not proven
        unstable (undamped, marginal below the coalescence).
    kind : str
        ``"flutter"`` (a complex pair crosses: mode coupling), ``"divergence"`` (a real
        eigenvalue crosses zero), ``"unstable at mu = 0"`` or ``"none"``.
    frequency_hz : float or None
        Frequency of the eigenvalue that crosses, Hz.
    modes : tuple of int
        The modes involved, numbered 1, 2, ... by frequency at ``mu = 0`` (the structure
        pressed on the belt, without friction): the crossing branch and, for a coalescence,
        the branch it merges with.
    mu_max : float
        Upper end of the range searched.
    method : str
        How the value was found.
    """

    mu: float | None
    bracket: tuple[float, float] | None
    kind: str
    frequency_hz: float | None
    modes: tuple[int, ...]
    mu_max: float
    method: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``mu``, ``bracket``, ``kind``, ``frequency_hz``, ``modes``, ``mu_max``, ``method``."""
        return {"mu": self.mu, "bracket": None if self.bracket is None else list(self.bracket),
                "kind": self.kind, "frequency_hz": self.frequency_hz, "modes": list(self.modes),
                "mu_max": self.mu_max, "method": self.method}


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

    out = np.empty((len(mus), 2 * system.n_dof), dtype=complex)
    for i, mu in enumerate(mus):
        values, _ = system.eigenvalues(float(mu))
        if i:
            cost = np.abs(out[i - 1][:, None] - values[None, :])
            _, cols = linear_sum_assignment(cost)
            values = values[cols]
        out[i] = values
    return out


def _mode_numbers(start: ComplexArray) -> FloatArray:
    """Mode number (1, 2, ... by frequency) of each branch at ``mu = 0``, 0 for real ones."""
    freq = np.abs(start.imag)
    ranks = np.zeros(len(start))
    distinct = np.unique(np.round(freq[freq > 0.0], 9))
    for j, f in enumerate(start):
        if f.imag != 0.0:
            ranks[j] = 1 + int(np.argmin(np.abs(distinct - round(abs(f.imag), 9))))
    return ranks


@one_blas_thread
def critical_friction(system: FrictionCoupledSystem, *, mu_max: float = MU_MAX,
                      n_scan: int = N_SCAN) -> CriticalFriction:
    """The smallest ``mu`` in ``(0, mu_max]`` where steady sliding turns unstable (module docstring).

    A damped system is searched exactly: every ``mu`` where an eigenvalue can reach the
    imaginary axis is a real root of ``det(2A(mu) (.) I) det A(mu)``
    (:mod:`~stickslip.analysis.contact.axis_crossings`), and one eigenvalue check between
    consecutive roots decides each interval. Where that cannot prove (an undamped system, a
    singular or too large pencil, an interval within round-off of neutral) the range is
    scanned at ``n_scan`` steps and the method says so.

    Parameters
    ----------
    system : FrictionCoupledSystem
        The structure and its contact; pass ``system.undamped()`` for the flutter boundary
        of the undamped structure (then refined by the exact coalescence condition).
    mu_max : float
        Largest friction coefficient searched, dimensionless (> 0).
    n_scan : int
        Scan steps over ``[0, mu_max]`` where the exact search cannot prove (>= 2); also
        sets how finely the branches are followed to name the modes.

    Returns
    -------
    CriticalFriction
        The value, its bracket, the kind of instability and the modes involved.
    """
    if not (math.isfinite(mu_max) and mu_max > 0.0):
        raise ValueError(f"mu_max = {mu_max!r} must be a positive number")
    if not 2 <= n_scan <= 100_000:
        raise ValueError(f"n_scan = {n_scan!r} must be from 2 to 100000")
    undamped = (not np.any(system.damping) and system.normal_damping == 0.0
                and system.slope == 0.0)
    start = system.eigenvalues(0.0)[0]
    if verdict_of(*system.eigenvalues(0.0)) == 1:
        big = start[np.argmax(start.real)]
        return CriticalFriction(0.0, (0.0, 0.0), "unstable at mu = 0",
                                abs(big.imag) / (2 * math.pi), (), mu_max,
                                "unstable without friction coupling (the structure or the "
                                "friction law's slope)")
    exact = None if undamped else _exact_search(system, mu_max)
    if exact is not None and exact[0] is None:
        return CriticalFriction(None, None, "none", None, (), mu_max, exact[1])
    if exact is not None:
        root, lo, hi = exact[0], exact[2], exact[3]
        n_track, below = max(2, math.ceil(4 * n_scan * lo / mu_max)), lo
    else:
        mus = np.linspace(0.0, mu_max, n_scan + 1)
        verdicts = [verdict_of(*system.eigenvalues(float(mu))) for mu in mus]
        if 1 not in verdicts:
            return CriticalFriction(None, None, "none", None, (), mu_max,
                                    f"no eigenvalue proven unstable at {n_scan + 1} values of mu "
                                    f"in [0, {mu_max:g}] (a scan: windows narrower than "
                                    f"{mu_max / n_scan:g} can be missed)")
        first = verdicts.index(1)
        lo, hi = _bisected(system, float(mus[first - 1]), float(mus[first]), undamped)
        root, n_track, below = None, max(first, 2) * 4, float(mus[first - 1])
    proven_lo = verdict_of(*system.eigenvalues(lo)) == -1
    branches = track_branches(system, np.append(np.linspace(0.0, lo, n_track), hi))
    at_hi = branches[-1]
    j = int(np.argmax(at_hi.real + 1e-12 * np.abs(at_hi) * np.sign(at_hi.imag)))
    crossing = at_hi[j]
    numbers = _mode_numbers(branches[0])
    others = [i for i in range(len(at_hi)) if i != j and at_hi[i].real < 0.0
              and at_hi[i].imag * crossing.imag >= 0.0
              and abs(at_hi[i].imag - crossing.imag) <= 0.1 * abs(crossing)]
    modes = [int(numbers[j])] + ([int(numbers[min(others, key=lambda i: abs(at_hi[i] - crossing))])]
                                 if others else [])
    kind = "flutter" if abs(crossing.imag) > 1e-6 * abs(crossing) else "divergence"
    ends = "lower end proven stable, upper end proven unstable" if proven_lo else \
        "upper end proven unstable"
    if exact is not None and root is not None:
        mu, method = root, f"{exact[1]}; bracket by bisection: {ends}"
    else:
        mu, method = 0.5 * (lo + hi), f"scan and bisection: {ends}"
    if undamped and kind == "flutter" and system.normal_dof is not None:
        exact_mu = _coalescence(system, below, crossing)
        if exact_mu is not None and lo - 1e-9 * hi <= exact_mu <= hi:
            mu = exact_mu
            method = ("mode coalescence, g'(lambda*) = 0 (exact), inside the bisection bracket "
                      "whose upper end is proven unstable")
    return CriticalFriction(mu, (lo, hi), kind, abs(crossing.imag) / (2 * math.pi),
                            tuple(sorted({m for m in modes if m > 0})), mu_max, method)


def _bisected(system: FrictionCoupledSystem, lo: float, hi: float,
              undamped: bool) -> tuple[float, float]:
    """``(lo, hi)`` halved while ``hi`` stays proven unstable and ``lo`` not (bounded: 200 steps)."""
    for _ in range(MAX_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        v = verdict_of(*system.eigenvalues(mid))
        if v == 1:
            hi = mid
        elif v == -1 or undamped:  # undamped: below the coalescence it is marginal, never -1
            lo = mid
        else:  # neutral within round-off: the bracket is as tight as the eigenvalues allow
            break
    return lo, hi


def _exact_search(system: FrictionCoupledSystem,
                  mu_max: float) -> tuple[float | None, str, float, float] | None:
    """The exact critical ``mu`` from the axis crossings, or None where they cannot prove.

    Returns ``(mu, method, lo, hi)``: ``mu`` the root where the first interval proven
    unstable begins (None: every interval proven stable), ``(lo, hi)`` its bisection bracket.
    """
    from stickslip.analysis.contact.axis_crossings import crossing_candidates, interval_points

    roots = crossing_candidates(system, mu_max)
    if roots is None:
        return None
    verdicts = [verdict_of(*system.eigenvalues(float(x))) for x in interval_points(roots, mu_max)]
    first = verdicts.index(1) if 1 in verdicts else len(verdicts)
    if 0 in verdicts[:first]:
        return None  # an interval within round-off of neutral: not decided
    counted = (f"{len(roots)} real root{'s' if len(roots) != 1 else ''} of "
               f"det(2A(mu) (.) I) det A(mu) in (0, {mu_max:g})")
    if first == len(verdicts):
        return (None, f"exact: no eigenvalue crosses the imaginary axis in (0, {mu_max:g}] "
                      f"({counted}; each interval between them proven stable)", 0.0, 0.0)
    points = interval_points(roots, mu_max)
    root = float(roots[first - 1]) if first else 0.0
    lo, hi = _bisected(system, float(points[first - 1]) if first else 0.0, float(points[first]),
                       False)
    if not lo - 1e-9 * max(1.0, hi) <= root <= hi + 1e-9 * max(1.0, hi):
        return None  # the roots and the eigenvalues disagree: not proven
    return (root, f"exact: the first real root of det(2A(mu) (.) I) det A(mu) past which the "
                  f"spectrum is unstable ({counted}, one eigenvalue check between each two)", lo, hi)


def _coalescence(system: FrictionCoupledSystem, mu_lo: float, crossing: complex) -> float | None:
    """Exact ``mu*`` of the coalescence near ``crossing`` (undamped; module docstring).

    ``mu_lo`` is a coefficient below the coalescence where the two merging squared
    frequencies are still real and apart: they bracket the stationary point of ``g``.
    """
    import scipy.linalg
    from scipy.optimize import brentq

    t, n = system.tangential_dof, system.normal_dof
    assert n is not None
    lam, phi = scipy.linalg.eigh(system.contact_stiffness(), system.mass)
    ab = phi[t, :] * phi[n, :]
    kn = system.normal_stiffness

    def g(x: float) -> float:
        return float(np.sum(ab / (lam - x)))

    def dg(x: float) -> float:
        return float(np.sum(ab / (lam - x) ** 2))

    coupled = np.linalg.eigvals(np.diag(lam) + mu_lo * kn * np.outer(phi[t, :], phi[n, :]))
    real = coupled[np.abs(coupled.imag) <= 1e-9 * np.abs(coupled)].real
    target = crossing.imag**2
    near = sorted(real, key=lambda x: abs(x - target))[:2]
    if len(near) < 2:
        return None
    a, b = min(near), max(near)
    if not a < b or np.any((lam > a) & (lam < b)) or dg(a) * dg(b) >= 0.0:
        return None
    star = brentq(dg, a, b, xtol=1e-15 * b, rtol=4 * np.finfo(float).eps, maxiter=200)
    value = g(star)
    return None if value >= 0.0 else -1.0 / (kn * value)


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
    if contact is not None and contact.has_tangential_compliance:
        raise ValueError("[contact] tangential_stiffness: the tangential contact compliance is not "
                         "in the complex-eigenvalue analysis of this version (remove it here)")
    at = machine.with_operating_point(speed=speed, load=load)
    mu, slope = friction_at(at)
    index = None
    kn = cn = 0.0
    if contact is not None and contact.normal_dof is not None:
        if normal_dof is None:
            contact.check_dofs(at.n_dof, at.contact_dof)
        index = contact.normal_dof if normal_dof is None else normal_dof
        kn, cn = float(contact.normal_stiffness or 0.0), contact.normal_damping
    system = FrictionCoupledSystem(at.mass, at.damping, at.stiffness, at.contact_dof, index,
                                   normal_stiffness=kn, normal_damping=cn, load=at.load,
                                   slope=slope)
    return system, mu
