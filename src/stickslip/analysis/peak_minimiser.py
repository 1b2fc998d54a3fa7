"""The H-infinity (minimax) peak minimiser: ``min H_max`` of a structure's frequency response.

The objective, the largest local maximum of the frequency response ``H(Omega)`` of
:mod:`stickslip.analysis.frequency_response`, is continuous but not smooth where two peaks are
equal, which is exactly where optimal absorbers sit (equal-peak designs, paper Section 3.1).
:func:`minimise_peak` combines the shared Nelder-Mead search (:mod:`stickslip.analysis.optimise`)
with a smooth epigraph polish (SLSQP, envelope-theorem gradients). The absorber tuning
(:mod:`stickslip.analysis.absorber_tuning`) applies it to the elastic foundation. All
quantities are dimensionless.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize

from stickslip.analysis.frequency_response import (
    ResponsePeak,
    frequency_response,
    local_maxima_estimate,
    peak_estimate,
    response_peak,
)
from stickslip.analysis.optimise import nelder_mead
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class PeakMinimum:
    """Result of :func:`minimise_peak`.

    Attributes
    ----------
    params : ndarray
        The optimal parameters (the builder's arguments).
    peak : ResponsePeak
        The frequency-response peak of the optimal structure.
    at_bound : tuple of bool
        Whether each parameter ended within ``1e-6`` (relative, in log scale) of a bound.
    n_evaluations : int
        Number of structures built.
    """

    params: FloatArray
    peak: ResponsePeak
    at_bound: tuple[bool, ...]
    n_evaluations: int


class _PeakProblem:
    """The minimax problem on ``y = log x``: peak values and their gradients, counted."""

    def __init__(
        self, build: Callable[[FloatArray], Structure], lo: FloatArray, hi: FloatArray
    ) -> None:
        self.build, self.lo, self.hi = build, lo, hi
        self.count = 0

    def structure(self, y: FloatArray) -> Structure | None:
        self.count += 1
        try:
            return self.build(np.exp(np.clip(y, self.lo, self.hi)))
        except ValueError:
            return None

    def objective(self, y: FloatArray) -> float:
        st = self.structure(y)
        return math.inf if st is None else peak_estimate(st)

    def peaks(self, y: FloatArray) -> tuple[FloatArray, FloatArray]:
        st = self.structure(y)
        if st is None:
            return np.zeros(0), np.zeros(0)
        return local_maxima_estimate(st)

    def peak_gradients(self, y: FloatArray, omegas: FloatArray, step: float = 1e-6) -> FloatArray:
        """``d H_i / d y`` at fixed ``Omega_i`` (envelope theorem), central differences."""
        grad = np.zeros((omegas.size, y.size))
        for j in range(y.size):
            e = np.zeros(y.size)
            e[j] = step
            plus, minus = self.structure(y + e), self.structure(y - e)
            if plus is None or minus is None:
                return np.full((omegas.size, y.size), np.nan)
            grad[:, j] = (
                frequency_response(plus, omegas) - frequency_response(minus, omegas)
            ) / (2.0 * step)
        return grad


def _nelder_mead(
    problem: _PeakProblem, y0: FloatArray, size: float, xatol: float, fatol: float
) -> tuple[FloatArray, float]:
    """Nelder-Mead on the peak within the box, from a simplex of edge ``size`` at ``y0``."""
    return nelder_mead(problem.objective, y0, xatol=xatol, fatol=fatol,
                       bounds=(problem.lo, problem.hi), initial_step=size, maxfev=400 * y0.size)


def _equal_peak_polish(problem: _PeakProblem, y0: FloatArray) -> tuple[FloatArray, float]:
    """Smooth reformulation: minimise ``t`` subject to ``t >= H_i(y)`` for every peak ``i``.

    Each local maximum ``H_i`` is a smooth function of the parameters while it exists (its
    gradient is that of ``H`` at fixed ``Omega_i``, by the envelope theorem), so SLSQP
    converges to the equal-peak optimum where Nelder-Mead crawls along the ridge. Peaks are
    matched by frequency order; their number is the one at ``y0``.
    """
    om0, h0 = problem.peaks(y0)
    m = om0.size
    if m == 0:
        return y0, math.inf
    cache: dict[bytes, tuple[FloatArray, FloatArray]] = {}

    def peaks(y: FloatArray) -> tuple[FloatArray, FloatArray]:
        key = y.tobytes()
        if key not in cache:
            om, h = problem.peaks(y)
            if om.size == 0:
                om, h = om0, np.full(m, math.inf)
            elif om.size != m:  # a peak appeared or vanished: keep the m highest
                keep = np.sort(np.argsort(h)[::-1][:m])
                om, h = om[keep], h[keep]
                if om.size < m:
                    om = np.pad(om, (0, m - om.size), mode="edge")
                    h = np.pad(h, (0, m - h.size), mode="edge")
            cache[key] = (om, h)
        return cache[key]

    def cons(z: FloatArray) -> FloatArray:
        return z[-1] - peaks(z[:-1])[1]

    def cons_jac(z: FloatArray) -> FloatArray:
        y = z[:-1]
        grad = problem.peak_gradients(y, peaks(y)[0])
        return np.hstack([-grad, np.ones((m, 1))])

    z0 = np.append(y0, h0.max())
    bounds = [*zip(problem.lo, problem.hi, strict=True), (None, None)]
    e_t = np.zeros(z0.size)
    e_t[-1] = 1.0
    with np.errstate(invalid="ignore"):
        res = minimize(
            lambda z: z[-1],
            z0,
            jac=lambda z: e_t,
            method="SLSQP",
            bounds=bounds,
            constraints=[{"type": "ineq", "fun": cons, "jac": cons_jac}],
            options={"ftol": 1e-16, "maxiter": 200},
        )
    y = np.clip(np.asarray(res.x[:-1], dtype=np.float64), problem.lo, problem.hi)
    return y, problem.objective(y)


def minimise_peak(
    build: Callable[[FloatArray], Structure],
    x0s: Sequence[ArrayLike],
    bounds: Sequence[tuple[float, float]],
    *,
    rtol: float = 1e-13,
    max_rounds: int = 4,
) -> PeakMinimum:
    """Minimise ``H_max`` of ``build(x)`` over positive parameters ``x`` (minimax tuning).

    The objective, the largest local maximum of ``H(Omega)``, is continuous but not smooth
    where two peaks are equal, which is exactly where optimal absorbers sit (equal-peak
    designs). The search runs on ``log x`` within ``bounds``:

    1. Nelder-Mead (derivative-free, indifferent to the kinks) from every start in ``x0s``
       to a loose tolerance, to find the basin;
    2. from the best point, the smooth epigraph form ``min t`` subject to ``t >= H_i(x)`` for
       every local maximum ``H_i`` (SLSQP, gradients by the envelope theorem): it lands on
       the equal-peak optimum quickly and precisely;
    3. a tight Nelder-Mead restart from the result; steps 2-3 repeat until a round improves
       ``H_max`` by less than ``rtol`` (relative).

    Parameters
    ----------
    build : callable
        Maps a parameter vector (positive floats) to a :class:`Structure`. A ``ValueError``
        from it (an invalid structure) counts as an infinite peak.
    x0s : sequence of array_like
        Starting points (clipped into ``bounds``).
    bounds : sequence of (float, float)
        Positive lower and upper bound of each parameter.
    rtol : float
        Relative tolerance on ``H_max`` between rounds.
    max_rounds : int
        Most polishing rounds (steps 2-3).

    Returns
    -------
    PeakMinimum
        Optimal parameters, the verified peak there (:func:`response_peak`), bound flags
        and the number of structures built.
    """
    box = np.array(bounds, dtype=np.float64).reshape(-1, 2)
    if not (np.all(np.isfinite(box)) and np.all(box > 0.0) and np.all(box[:, 0] < box[:, 1])):
        raise ValueError(f"bounds {list(bounds)!r} must be positive, finite, increasing pairs")
    lo, hi = np.log(box[:, 0]), np.log(box[:, 1])
    raw = [np.asarray(x0, dtype=np.float64) for x0 in x0s]
    if not raw or any(x.shape != lo.shape or not np.all(x > 0.0) for x in raw):
        raise ValueError(f"need at least one start with {lo.size} positive entries")
    starts = [np.clip(np.log(x), lo, hi) for x in raw]
    problem = _PeakProblem(build, lo, hi)

    explored = [_nelder_mead(problem, y0, 0.2, 1e-3, 1e-7) for y0 in starts]
    best_y, best_f = min(explored, key=lambda r: r[1])
    for _ in range(max_rounds):
        before = best_f
        for step in (_equal_peak_polish, _restart):
            y, f = step(problem, best_y)
            if f < best_f:
                best_y, best_f = y, f
        if before - best_f <= rtol * best_f:
            break
    x = np.exp(best_y)
    peak = response_peak(build(x))
    at_bound = tuple(
        bool(min(b - lo_, hi_ - b) <= 1e-6 * (hi_ - lo_))
        for b, lo_, hi_ in zip(best_y, lo, hi, strict=True)
    )
    return PeakMinimum(x, peak, at_bound, problem.count)


def _restart(problem: _PeakProblem, y0: FloatArray) -> tuple[FloatArray, float]:
    """A tight Nelder-Mead run from ``y0`` with a fresh simplex (checks the polish)."""
    f0 = problem.objective(y0)
    return _nelder_mead(problem, y0, 1e-3, 1e-9, 1e-14 * max(1.0, abs(f0)))
