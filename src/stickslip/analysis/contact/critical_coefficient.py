r"""The critical friction coefficient of steady sliding: exact where it can be proven, scanned where not.

The linearisation, its matrices and eigenvalues are
:mod:`stickslip.analysis.contact.friction_coupling`.

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
proven stable and its upper end proven unstable. Where the roots cannot prove (a singular
pencil, more than 22 DOF (16 with a slope), an interval neutral within round-off) the range
is scanned at ``n_scan`` steps with bisection, which resolves instability windows wider than
its step (``mu_max / n_scan``), and the method says so.

``critical_mu_undamped`` is the same with every velocity term removed (``C``, ``c_n`` and the
slope): the eigenvalues are then ``\pm i\omega`` until two modes coalesce (flutter) or one
frequency reaches zero (divergence). Below the coalescence the undamped spectrum is on the
imaginary axis (marginal), so only the upper end is proven; the value is then made exact by
the coalescence condition: in the mass-normalised modes ``\Phi`` of
``K_0 = K + k_n e_n e_n^T`` (eigenvalues ``\lambda_i``), the squared frequencies
``\lambda = \omega^2`` of the coupled system solve
``1 + \mu k_n g(\lambda) = 0`` with ``g(\lambda) = \sum_i \alpha_i \beta_i / (\lambda_i - \lambda)``,
``\alpha_i = \Phi_{t i}``, ``\beta_i = \Phi_{n i}`` (the matrix determinant lemma). Two real
roots merge at a stationary point of ``g``: ``g'(\lambda^*) = 0``, and
``\mu^* = -1 / (k_n g(\lambda^*))``. Every stationary point is computed (the zeros of ``g'``,
:func:`~stickslip.analysis.contact.axis_crossings.coalescence_candidates`), and with
``\mu = -1 / (k_n g(0))`` (a frequency reaching zero) they are the only values where the
undamped spectrum can change its kind; one eigenvalue check between each two finds the first
interval proven unstable, and its left end is the exact value (no flutter window skipped).
A massive contact point of a Jenkins element is one more DOF with a rigid contact there
(:meth:`~stickslip.analysis.contact.friction_coupling.FrictionCoupledSystem.point_as_dof`), so
the same search applies to it. Without a normal DOF the friction force is ``mu W``, a
constant, and the undamped eigenvalues do not depend on ``mu``: the check at one ``mu``
decides the whole range. Where the search does not apply (a pencil too large) the range is
scanned and the coalescence found between the two merging roots (a sign change of ``g'``)
makes the value exact inside the scan's bracket.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.blas_threads import one_blas_thread
from stickslip.analysis.contact.axis_crossings import (
    coalescence_candidates,
    crossing_candidates,
    interval_points,
)
from stickslip.analysis.contact.friction_coupling import (
    FrictionCoupledSystem,
    track_branches,
    verdict_of,
)

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

#: Default range of the friction coefficient searched for the critical one (dimensionless).
MU_MAX = 2.0
#: Default number of scan steps over ``[0, mu_max]`` before bisection.
N_SCAN = 400
#: Bisection steps (each halves the bracket; 200 steps are far beyond double precision).
MAX_BISECTIONS = 200



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

    The search is exact: every ``mu`` where an eigenvalue can reach the imaginary axis is a
    real root of ``det(2A(mu) (.) I) det A(mu)`` (damped) or a stationary value of the
    coalescence function (undamped) (:mod:`~stickslip.analysis.contact.axis_crossings`), and
    one eigenvalue check between consecutive roots decides each interval. Where that cannot
    prove (a singular or too large pencil, an interval within round-off of neutral) the range
    is scanned at ``n_scan`` steps and the method says so.

    Parameters
    ----------
    system : FrictionCoupledSystem
        The structure and its contact; pass ``system.undamped()`` for the flutter boundary
        of the undamped structure.
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
                and system.slope == 0.0 and system.tangential_damping == 0.0)
    start = system.eigenvalues(0.0)[0]
    if verdict_of(*system.eigenvalues(0.0)) == 1:
        big = start[np.argmax(start.real)]
        without_slope = replace(system, slope=0.0)
        cause = ("the structure itself (unstable without friction)"
                 if system.slope == 0.0 or verdict_of(*without_slope.eigenvalues(0.0)) == 1 else
                 f"the friction law's slope ({system.slope:.6g} s/m at V: negative damping at the "
                 "contact; the structure alone is stable), before any mode coupling")
        return CriticalFriction(0.0, (0.0, 0.0), "unstable at mu = 0",
                                abs(big.imag) / (2 * math.pi), (), mu_max,
                                f"unstable without friction coupling: {cause}")
    exact = _exact_search(system, mu_max, undamped)
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
    if exact is None and undamped and kind == "flutter" and system.normal_dof is not None:
        exact_mu = _coalescence(_rigid_form(system), below, crossing)
        if exact_mu is not None and lo - 1e-9 * hi <= exact_mu <= hi:
            mu = exact_mu
            method = ("mode coalescence, g'(lambda*) = 0 (exact), inside the bisection bracket "
                      "whose upper end is proven unstable")
    if undamped:  # the lower end is only "not proven unstable": the exact value may lie a
        lo = min(lo, mu)  # rounding below it (an eigenvalue's bound is wide at coalescence)
    return CriticalFriction(mu, (lo, hi), kind, abs(crossing.imag) / (2 * math.pi),
                            tuple(sorted({m for m in modes if m > 0})), mu_max, method)


def _rigid_form(system: FrictionCoupledSystem) -> FrictionCoupledSystem:
    """The undamped system with a rigid tangential contact: itself (a rigid contact, or a
    massless element that follows the load) or, for a massive contact point, the structure
    with the point as one more DOF (:meth:`FrictionCoupledSystem.point_as_dof`)."""
    return system if system.contact_mass is None else system.point_as_dof()


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


def _exact_search(system: FrictionCoupledSystem, mu_max: float,
                  undamped: bool) -> tuple[float | None, str, float, float] | None:
    """The exact critical ``mu`` from the axis crossings, or None where they cannot prove.

    Damped: the real roots of ``det(2A (.) I) det A`` (every interval before the first
    unstable one proven stable). Undamped (a normal DOF; a rigid contact, a massless element
    that follows the load, or a massive point as one more DOF,
    :meth:`~stickslip.analysis.contact.friction_coupling.FrictionCoupledSystem.point_as_dof`):
    the values where the spectrum can change its kind
    (:func:`~stickslip.analysis.contact.axis_crossings.coalescence_candidates`; the intervals
    before the first unstable one are marginal, never proven stable). Returns
    ``(mu, method, lo, hi)``: ``mu`` the value where the first interval proven unstable
    begins (None: none is), ``(lo, hi)`` its bisection bracket.
    """
    if undamped and system.normal_dof is None:
        # the friction force is mu W, a constant: the eigenvalues do not depend on mu
        if verdict_of(*system.eigenvalues(0.5 * mu_max)) != 0:
            return None  # not marginal within round-off: not decided here
        return (None, "exact: without a normal DOF the friction force is mu W and the undamped "
                      "linearisation does not depend on mu: marginal at every mu", 0.0, 0.0)
    if undamped:
        roots = coalescence_candidates(_rigid_form(system), mu_max)
        what, settled = "the stationary values of g and g(0)", 0
    else:
        roots = crossing_candidates(system, mu_max)
        what, settled = "the real roots of det(2A(mu) (.) I) det A(mu)", -1
    if roots is None:
        return None
    points = interval_points(roots, mu_max)
    verdicts = [verdict_of(*system.eigenvalues(float(x))) for x in points]
    first = verdicts.index(1) if 1 in verdicts else len(verdicts)
    if any(v != settled for v in verdicts[:first]):
        return None  # an interval within round-off of neutral: not decided
    counted = f"{len(roots)} of them in (0, {mu_max:g})"
    checked = "proven stable" if settled == -1 else "marginal (undamped)"
    if first == len(verdicts):
        return (None, f"exact: no eigenvalue crosses the imaginary axis in (0, {mu_max:g}] "
                      f"(it can only at {what}: {counted}; each interval between them "
                      f"{checked})", 0.0, 0.0)
    root = float(roots[first - 1]) if first else 0.0
    lo, hi = _bisected(system, float(points[first - 1]) if first else 0.0, float(points[first]),
                       undamped)
    if not lo - 1e-9 * max(1.0, hi) <= root <= hi + 1e-9 * max(1.0, hi):
        return None  # the roots and the eigenvalues disagree: not proven
    return (root, f"exact: the first of {what} past which the spectrum is unstable "
                  f"({counted}, one eigenvalue check between each two)", lo, hi)


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


def critical_text(critical: Mapping[str, Any], operating_mu: float | None = None, *,
                  detail: bool = True) -> str:
    """One critical friction coefficient in words (``stickslip stability`` and the app).

    Parameters
    ----------
    critical : mapping
        :meth:`CriticalFriction.to_dict`.
    operating_mu : float, optional
        The operating ``mu``: named when it lies above the searched range.
    detail : bool
        Add the bracket and the method (the command line's line).

    Returns
    -------
    str
        The value (``-`` when steady sliding is unstable without mode coupling, whose
        critical coefficient is then not defined) and how it was found.
    """
    if critical["mu"] is None:
        above = (f"; the operating mu = {operating_mu:.6g} lies above the searched range: raise "
                 "--mu-max" if operating_mu is not None and operating_mu > critical["mu_max"] else "")
        return f"none up to mu = {critical['mu_max']:g} ({critical['method']}){above}"
    where = f" at {critical['frequency_hz']:.6g} Hz" if critical["frequency_hz"] is not None else ""
    if critical["kind"] == "unstable at mu = 0":
        return f"- (unstable at mu = 0{where}; {critical['method']})"
    modes = " and ".join(str(m) for m in critical["modes"]) or "-"
    text = (f"{critical['mu']:.8g} ({critical['kind']}{where}; "
            f"mode{'s' if len(critical['modes']) > 1 else ''} {modes}")
    if not detail:
        return text + ")"
    return (f"{text}; bracket [{critical['bracket'][0]:.10g}, {critical['bracket'][1]:.10g}]; "
            f"{critical['method']})")
