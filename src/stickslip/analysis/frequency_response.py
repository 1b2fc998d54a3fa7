"""Frequency response of the slider on its structure, and its exact peak (paper Fig. 5).

The elastic foundation of the paper's Fig. 1 acts as a dynamic vibration absorber (DVA).
Harik and Issa (paper ref. [20], Fig. 3) drive the slider with a harmonic force
``f sin(omega t)`` instead of friction; the dimensionless receptance of DOF 0 is

    H(Omega) = k |X| / f = |[(Stiffness - Omega^2 Mass + i Omega Damping)^-1]_00|,

with ``Omega = omega / omega_n`` (paper Fig. 5), for any :class:`~stickslip.model.Structure`.
``H(Omega)`` and its peak ``H_max`` are computed exactly: every local maximum is a root of
``d|H|^2/dOmega``, bracketed and refined with Brent's method (never read off a grid). The
equivalent damping ratio ``zeta_eq = 1 / (2 H_max)`` is the paper's Eq. (32). The tuning that
minimises ``H_max`` lives in :mod:`stickslip.analysis.absorber_tuning`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.polynomial import polynomial as P
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from stickslip.model._validate import non_negative
from stickslip.model.parameters import Foundation
from stickslip.model.structure import Structure, elastic_foundation, rigid_base

FloatArray = NDArray[np.float64]

# Poles with |Re p| below this fraction of |p| count as undamped (an infinite peak).
_UNDAMPED = 1e-13


def _dynamic_solution(
    structure: Structure, omega: FloatArray
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """``H = [D^-1]_cc`` (``c`` the contact DOF) and ``dH/dOmega`` at every ``omega``."""
    structure = structure.contact_first()[0]  # the receptance at the contact, now DOF 0
    w = omega[:, None, None]
    dyn = structure.stiffness - w**2 * structure.mass + 1j * w * structure.damping
    e0 = np.zeros((omega.size, structure.n_dof, 1), dtype=np.complex128)
    e0[:, 0, 0] = 1.0
    try:
        x = np.linalg.solve(dyn, e0)[:, :, 0]
    except np.linalg.LinAlgError:  # exactly at an undamped resonance: H is infinite there
        x = np.empty((omega.size, structure.n_dof), dtype=np.complex128)
        for k in range(omega.size):
            try:
                x[k] = np.linalg.solve(dyn[k], e0[k])[:, 0]
            except np.linalg.LinAlgError:
                x[k] = complex(math.inf, 0.0)
    h = np.asarray(x[:, 0], dtype=np.complex128)
    # D is complex symmetric, so e0^T D^-1 = x^T and dH/dOmega = -x^T D'(Omega) x.
    d_dyn = -2.0 * w * structure.mass + 1j * structure.damping
    with np.errstate(invalid="ignore"):  # inf * 0 at an undamped resonance
        dh = np.asarray(-np.einsum("ki,kij,kj->k", x, d_dyn, x), dtype=np.complex128)
    return h, dh


def receptance(structure: Structure, omega: ArrayLike) -> NDArray[np.complex128]:
    """Complex receptance of DOF 0, ``[(Stiffness - Omega^2 Mass + i Omega Damping)^-1]_00``.

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices; the force acts on DOF 0 (the slider, paper Fig. 3).
    omega : array_like
        Forcing frequency ratio ``Omega = omega / omega_n``, dimensionless, >= 0.

    Returns
    -------
    ndarray of complex
        ``k X / f`` (dimensionless), same shape as ``omega``.
    """
    om = np.asarray(omega, dtype=np.float64)
    h, _ = _dynamic_solution(structure, om.reshape(-1))
    return h.reshape(om.shape)


def frequency_response(structure: Structure, omega: ArrayLike) -> FloatArray:
    """Amplitude ``H(Omega) = k|X|/f`` of the slider under a harmonic force (paper Fig. 5).

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices; the force acts on DOF 0.
    omega : array_like
        Forcing frequency ratio ``Omega = omega / omega_n``, dimensionless.

    Returns
    -------
    ndarray
        ``H(Omega)``, dimensionless, same shape as ``omega``.
    """
    return np.abs(receptance(structure, omega))


def _squared_slope(structure: Structure, omega: FloatArray) -> FloatArray:
    """``d|H|^2/dOmega = 2 Re(conj(H) dH/dOmega)`` (vectorised, exact)."""
    h, dh = _dynamic_solution(structure, omega)
    return 2.0 * np.real(np.conj(h) * dh)


def _state_eigenvalues(mass: FloatArray, damping: FloatArray, stiffness: FloatArray) -> Any:
    n = mass.shape[0]
    if n == 0:
        return np.zeros(0, dtype=np.complex128)
    m_inv = np.linalg.inv(mass)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-m_inv @ stiffness, -m_inv @ damping]])
    return np.linalg.eigvals(a)


def _abs2_polynomial(roots: NDArray[np.complex128]) -> FloatArray:
    """Coefficients (ascending in Omega) of ``prod |i Omega - r|^2``."""
    coef = np.array([1.0])
    for r in roots:
        coef = P.polymul(coef, [abs(r) ** 2, -2.0 * r.imag, 1.0])
    return np.asarray(coef, dtype=np.float64)


@dataclass(frozen=True)
class ResponsePeak:
    """Peak of the frequency response ``H(Omega)`` (paper Fig. 5, ``H_max``).

    Unpacks as ``h_max, omega_peak = peak``.

    Attributes
    ----------
    h_max : float
        ``max H(Omega)`` over ``Omega >= 0``, dimensionless; ``inf`` for an undamped
        resonance.
    omega_peak : float
        Frequency ratio ``Omega`` of that maximum, dimensionless.
    local_maxima : tuple of (float, float)
        ``(Omega, H)`` of every local maximum, in increasing ``Omega`` (``Omega = 0``
        included when the static response is a local maximum).
    """

    h_max: float
    omega_peak: float
    local_maxima: tuple[tuple[float, float], ...]

    def __iter__(self) -> Iterator[float]:
        return iter((self.h_max, self.omega_peak))

    @property
    def equivalent_damping(self) -> float:
        """``zeta_eq = 1 / (2 H_max)``, Eq. (32); 0 for an infinite peak."""
        return 0.0 if math.isinf(self.h_max) else 1.0 / (2.0 * self.h_max)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary with the command-line keys ``H_max`` and ``Omega_peak``."""
        out = {
            "H_max": self.h_max,
            "Omega_peak": self.omega_peak,
            "zeta_eq": self.equivalent_damping,
            "local_maxima": [{"Omega": w, "H": h} for w, h in self.local_maxima],
        }
        if math.isinf(self.h_max):  # JSON has no infinity: it prints null, said here
            out["H_max_note"] = "unbounded: an undamped resonance at each local maximum"
        return out


def _bracketing_grid(
    poles: NDArray[np.complex128], zeros: NDArray[np.complex128], candidates: FloatArray
) -> FloatArray:
    """Frequencies between which ``d|H|^2/dOmega`` changes sign at most once.

    Three ingredients, each sufficient in the generic case and together robust:
    the approximate stationary points (real roots of the critical-point polynomial) and
    the midpoints between them; points around each pole and zero spaced by a fraction of
    its half-power width ``|Re p|``; a uniform grid up to twice the largest ``|p|``.
    """
    scale = float(max(np.abs(poles).max(initial=0.0), np.abs(zeros).max(initial=0.0), 1e-300))
    top = 2.0 * scale
    pieces = [np.linspace(0.0, top, 65)]
    t = np.arange(-4.0, 4.01, 0.5)
    for r in np.concatenate([poles, zeros]):
        if r.imag > 0.0:
            pieces.append(r.imag + abs(r.real) * t)
    stationary = np.sort(np.concatenate([[0.0], candidates, [top]]))
    pieces.append(0.5 * (stationary[1:] + stationary[:-1]))
    pieces.append(candidates * (1.0 + 1e-7))
    pieces.append(candidates * (1.0 - 1e-7))
    grid = np.unique(np.concatenate(pieces))
    return grid[(grid >= 0.0) & (grid <= top)]


@dataclass(frozen=True)
class _Stationary:
    """Poles, zeros and approximate stationary points of ``|H|^2`` of one structure."""

    poles: NDArray[np.complex128]
    zeros: NDArray[np.complex128]
    candidates: FloatArray
    undamped: tuple[float, ...]  # frequencies of the uncancelled undamped resonances, ascending


def _stationary(structure: Structure) -> _Stationary:
    """Candidate stationary points of ``|H(Omega)|^2`` from its poles and zeros.

    ``H = [D^-1]_00 = det D_sub / det D``, so the poles ``p`` are the eigenvalues of the
    structure and the zeros ``z`` those of the structure with DOF 0 held fixed, and
    ``|H|^2 = c prod|i Omega - z|^2 / prod|i Omega - p|^2 = c A(Omega) / B(Omega)``. Its
    stationary points are the real roots of the polynomial ``A' B - A B'``: all of them,
    which is what makes the peak search complete. (DOF 0 after
    :meth:`Structure.contact_first`: the contact DOF.)
    """
    structure = structure.contact_first()[0]
    poles = _state_eigenvalues(structure.mass, structure.damping, structure.stiffness)
    zeros = _state_eigenvalues(
        structure.mass[1:, 1:], structure.damping[1:, 1:], structure.stiffness[1:, 1:]
    )
    undamped = sorted(float(p.imag) for p in poles
                      if p.imag > 0.0 and abs(p.real) <= _UNDAMPED * abs(p)
                      and not (zeros.size > 0 and np.min(np.abs(zeros - p)) <= 1e-8 * abs(p)))
    if undamped:  # every one of them an infinite peak
        return _Stationary(poles, zeros, np.zeros(0), tuple(undamped))
    numerator = _abs2_polynomial(zeros)
    denominator = _abs2_polynomial(poles)
    critical = P.polysub(
        P.polymul(P.polyder(numerator), denominator), P.polymul(numerator, P.polyder(denominator))
    )
    roots = P.polyroots(critical) if np.count_nonzero(critical) > 1 else np.zeros(0)
    scale = float(np.abs(poles).max())
    # near-double roots (merging peaks) split into pairs with a small imaginary part
    keep = (roots.real > 1e-6 * scale) & (np.abs(roots.imag) <= 1e-3 * np.abs(roots))
    return _Stationary(poles, zeros, np.sort(roots.real[keep]), ())


def local_maxima_estimate(structure: Structure) -> tuple[FloatArray, FloatArray]:
    """``(Omega_i, H_i)`` of every local maximum, from the polynomial stationary points.

    Between consecutive stationary points ``H`` is monotone, so a stationary point is a
    maximum when ``H`` there is at least ``H`` at its neighbours (``H -> 0`` as
    ``Omega -> inf``). Cheap; :func:`response_peak` gives the bracketed, refined values.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.

    Returns
    -------
    Omega, H : ndarray
        Frequency ratios and heights of the local maxima of ``H(Omega)``.
    """
    st = _stationary(structure)
    if st.undamped:
        return np.array(st.undamped), np.full(len(st.undamped), math.inf)
    om = np.concatenate([[0.0], st.candidates])
    h = frequency_response(structure, om)
    left = np.concatenate([[-math.inf], h[:-1]])
    right = np.concatenate([h[1:], [0.0]])
    is_max = (h >= left) & (h >= right)
    return om[is_max], h[is_max]


def peak_estimate(structure: Structure) -> float:
    """``H_max`` from :func:`local_maxima_estimate`: the optimiser's objective.

    An error ``d`` in a stationary point changes ``H`` there by ``O(d^2)``, so this agrees
    with :func:`response_peak` to rounding.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.

    Returns
    -------
    float
        The largest local maximum ``H_max``, dimensionless.
    """
    return float(local_maxima_estimate(structure)[1].max())


def response_peak(structure: Structure) -> ResponsePeak:
    """Exact peak ``H_max`` of the frequency response and where it occurs (paper Fig. 5).

    Every local maximum of ``H(Omega)`` is a root of ``d|H|^2/dOmega``. Candidate stationary
    points come from the poles ``p`` and zeros ``z`` of the receptance
    (``|H|^2 = c prod|i Omega - z|^2 / prod|i Omega - p|^2``, a rational function whose
    critical points are the real roots of a polynomial); together with points around
    every pole and zero they bracket each sign change of the exact slope, computed from the
    matrices, which Brent's method then refines to about ``1e-13`` in ``Omega``.

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices; the harmonic force acts on DOF 0.

    Returns
    -------
    ResponsePeak
        ``H_max`` and ``Omega_peak`` (dimensionless) and every local maximum. For the 1DOF
        system this gives ``Omega_peak = sqrt(1 - 2 zeta^2)``,
        ``H_max = 1 / (2 zeta sqrt(1 - zeta^2))`` for ``zeta < 1/sqrt(2)``, else
        ``Omega_peak = 0``, ``H_max = 1``.
    """
    st = _stationary(structure)
    if st.undamped:  # Omega_peak: the lowest of the infinite peaks
        return ResponsePeak(math.inf, st.undamped[0], tuple((w, math.inf) for w in st.undamped))
    grid = _bracketing_grid(st.poles, st.zeros, st.candidates)
    slope = _squared_slope(structure, grid)

    def scalar_slope(om: float) -> float:
        return float(_squared_slope(structure, np.array([om]))[0])

    maxima: list[float] = []
    if slope[1] < 0.0:
        maxima.append(0.0)
    sign = np.sign(slope[1:])
    nonzero = np.flatnonzero(sign)
    for a, b in itertools.pairwise(nonzero):
        if sign[a] > 0.0 and sign[b] < 0.0:
            if b > a + 1:  # the slope vanished exactly on a grid point in between
                maxima.append(float(grid[2 + a]))
                continue
            lo, hi = grid[1 + a], grid[1 + b]
            try:
                root = brentq(scalar_slope, lo, hi, xtol=1e-15, rtol=4.0 * np.finfo(float).eps)
            except ValueError:  # the slope is NaN in the bracket: refuse rather than guess
                raise ValueError(
                    f"the response peak near Omega={lo:.3g} cannot be located: the slope of "
                    "H is not finite there (a nearly undamped resonance; add damping)"
                ) from None
            maxima.append(float(root))
    if not maxima:  # monotone decreasing from the static value
        maxima.append(0.0)
    om = np.array(maxima)
    h = frequency_response(structure, om)
    local = tuple((float(w), float(v)) for w, v in zip(om, h, strict=True))
    best = int(np.argmax(h))
    return ResponsePeak(float(h[best]), float(om[best]), local)


def equivalent_damping(structure: Structure) -> float:
    """Equivalent damping ratio ``zeta_eq = 1 / (2 H_max)``, Eq. (32), for any structure.

    The damping ratio of the 1DOF system of the paper's Fig. 9 whose small-damping peak
    ``1 / (2 zeta_eq)`` equals the exact ``H_max`` of ``structure`` (tuned or not). For the
    fitted optimum the paper's Eq. (33) approximates it
    (:func:`stickslip.analysis.theory.equivalent_damping_fit`).

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices; the harmonic force acts on DOF 0.

    Returns
    -------
    float
        ``zeta_eq``, dimensionless; 0 for an undamped resonance (infinite peak).
    """
    return response_peak(structure).equivalent_damping


@dataclass(frozen=True)
class ResponseCurves:
    """Frequency-response curves of the paper's Fig. 5 for one ``zeta`` and foundation.

    Attributes
    ----------
    omega : ndarray
        Frequency ratio ``Omega``, dimensionless.
    rigid : ndarray
        ``H`` of the slider on the rigid base (no foundation).
    foundation : ndarray or None
        ``H`` with the foundation (None without one).
    equivalent : ndarray or None
        ``H`` of the equivalent 1DOF system with ``zeta_eq`` (Fig. 9, dashed in Fig. 5).
    zeta : float
        Primary damping ratio.
    dva : Foundation or None
        The foundation drawn.
    peak : ResponsePeak
        Exact peak of the curve with the foundation (of the rigid base without one).
    zeta_eq : float or None
        ``1 / (2 H_max)``, Eq. (32), of the foundation curve.
    """

    omega: FloatArray
    rigid: FloatArray
    foundation: FloatArray | None
    equivalent: FloatArray | None
    zeta: float
    dva: Foundation | None
    peak: ResponsePeak
    zeta_eq: float | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary of the curves."""
        dva = self.dva
        return {
            "zeta": self.zeta,
            "foundation": None
            if dva is None
            else {"M": dva.mass_ratio, "K": dva.stiffness_ratio, "zeta_a": dva.damping_ratio},
            "Omega": self.omega.tolist(),
            "H_rigid": self.rigid.tolist(),
            "H_foundation": None if self.foundation is None else self.foundation.tolist(),
            "H_equivalent": None if self.equivalent is None else self.equivalent.tolist(),
            "zeta_eq": self.zeta_eq,
            **{k: v for k, v in self.peak.to_dict().items() if k != "zeta_eq"},
        }

    def plot(self, **kwargs: Any) -> Any:
        """Draw the curves (paper Fig. 5), a ``PlotResult``.

        Delegates to :func:`stickslip.plot.absorber.frequency_response_plot` (its keywords).
        """
        from stickslip.plot.absorber import frequency_response_plot

        return frequency_response_plot(self, **kwargs)


def response_curves(
    zeta: float, foundation: Foundation | None, omega: ArrayLike | None = None
) -> ResponseCurves:
    """Data of the paper's Fig. 5: ``H(Omega)`` with and without the foundation and the
    equivalent 1DOF curve with ``zeta_eq`` of Eq. (32).

    Parameters
    ----------
    zeta : float
        Primary damping ratio, dimensionless, >= 0.
    foundation : Foundation or None
        The elastic foundation; None draws the rigid base only.
    omega : array_like, optional
        Frequency ratios; default 2001 points on ``[0, 2]`` plus the exact peak frequency.

    Returns
    -------
    ResponseCurves
        The curves and their peaks.
    """
    zeta = non_negative("zeta", zeta)
    structure = rigid_base(zeta) if foundation is None else elastic_foundation(zeta, foundation)
    peak = response_peak(structure)
    if omega is None:
        extra = [peak.omega_peak] if math.isfinite(peak.h_max) else []
        om = np.unique(np.concatenate([np.linspace(0.0, 2.0, 2001), extra]))
    else:
        om = np.asarray(omega, dtype=np.float64).reshape(-1)
        if om.size == 0 or not np.all(np.isfinite(om)) or np.any(om < 0.0):
            raise ValueError("omega must be non-empty, finite and >= 0")
    rigid = frequency_response(rigid_base(zeta), om)
    if foundation is None:
        return ResponseCurves(om, rigid, None, None, zeta, None, peak, None)
    zeta_eq = peak.equivalent_damping
    with_dva = frequency_response(structure, om)
    equivalent = frequency_response(rigid_base(zeta_eq), om) if zeta_eq > 0.0 else None
    return ResponseCurves(om, rigid, with_dva, equivalent, zeta, foundation, peak, zeta_eq)
