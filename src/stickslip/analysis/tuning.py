"""Tuning the elastic foundation: the absorber optimum and the stick-slip optimum.

Two objectives over the foundation ``(M, K, zeta_a)`` at a given primary damping ``zeta``:

* the dynamic-vibration-absorber optimum (paper Section 3.1, Eqs. 28-31): the minimax problem
  ``min H_max`` of the frequency response of :mod:`stickslip.analysis.frequency_response`,
  to be compared with the paper's fitted Eqs. (28)-(31);
* the stick-slip optimum (beyond the paper): the foundation that maximises the simulated
  stick-slip onset ``lambda_crit`` itself (:func:`optimal_foundation_stick_slip`).

All quantities are dimensionless (Section 2.3 definitions: ``M = m_a/m``,
``K = sqrt(k_a/k)``, ``zeta = c/(2 sqrt(mk))``, ``zeta_a = c_a/(2 sqrt(mk))``).

The optimiser searches over the logarithms of positive parameters with bounds. For the
foundation the default mass-ratio bounds are ``0.01 <= M <= 100``
(:data:`DEFAULT_MASS_BOUNDS`), ``1e-3 <= K <= 1e3`` and ``1e-4 <= zeta_a <= 1e3``; a result
on a bound is flagged (``at_bound``). With ``M`` free the optimum is interior for
``0 <= zeta <= 0.5``: ``H_max`` grows again for large ``M`` (the heavy foundation stops
moving and the slider sees a rigid base) and for small ``M`` (the massless foundation is
only a spring and a dashpot in series). ``M_opt`` grows steeply with ``zeta`` (25.8 at 0.4,
82 at 0.5) and meets the upper bound 100 between ``zeta = 0.50`` and ``0.52``; by
``zeta = 0.58`` no foundation within the bounds beats the rigid base and the search ends
at ``K -> 1e3`` (a rigid foundation). At ``zeta = 0`` the optimum is ``M = 25/16``,
``K^2 = 7/8``, ``zeta_a = 25/(16 sqrt 2)``, ``H_max = sqrt 5`` (see ``docs/absorber.md``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize

from stickslip.analysis.critical import lowest_onset
from stickslip.analysis.design import MAX_DESIGN_ZETA
from stickslip.analysis.frequency_response import (
    ResponsePeak,
    frequency_response,
    local_maxima_estimate,
    peak_estimate,
    response_peak,
)
from stickslip.analysis.theory import (
    equivalent_damping_fit,
    optimal_foundation_fit,
    peak_response_fit,
)
from stickslip.model._validate import non_negative, positive, ratio
from stickslip.model.parameters import Foundation
from stickslip.model.structure import Structure, elastic_foundation

FloatArray = NDArray[np.float64]

DEFAULT_MASS_BOUNDS: tuple[float, float] = (0.01, 100.0)
"""Default search interval of the mass ratio ``M = m_a/m`` (dimensionless)."""
STIFFNESS_BOUNDS: tuple[float, float] = (1e-3, 1e3)
"""Search interval of the stiffness ratio ``K = sqrt(k_a/k)`` (dimensionless)."""
DAMPING_BOUNDS: tuple[float, float] = (1e-4, 1e3)
"""Search interval of the foundation damping ratio ``zeta_a`` (dimensionless)."""
MAX_TUNING_ZETA = MAX_DESIGN_ZETA
"""Largest primary damping ratio accepted by the tuning (the FRF itself takes any zeta);
the same bound as the design procedure's (one home: :mod:`stickslip.analysis.design`)."""



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
    lo, hi = problem.lo, problem.hi
    simplex = np.clip(np.vstack([y0, y0 + size * np.eye(y0.size)]), lo, hi)
    # a start on an upper bound steps inwards instead of collapsing the simplex
    simplex[1:] = np.where(simplex[1:] == y0, y0 - size, simplex[1:])
    options = {"xatol": xatol, "fatol": fatol, "maxfev": 400 * y0.size, "initial_simplex": simplex}
    res = minimize(
        problem.objective,
        y0,
        method="Nelder-Mead",
        bounds=list(zip(lo, hi, strict=True)),
        options=options,
    )
    return np.asarray(res.x, dtype=np.float64), float(res.fun)


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


@dataclass(frozen=True)
class TuningResult:
    """Optimal elastic foundation (DVA) for one primary damping ratio (paper Figs. 4 and 6).

    Attributes
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless.
    foundation : Foundation
        The exact optimum ``(M, K, zeta_a)``, dimensionless.
    h_max : float
        Its peak response ``H_max``, dimensionless.
    omega_peak : float
        Where the peak is, ``Omega = omega/omega_n``.
    local_maxima : tuple of (float, float)
        ``(Omega, H)`` of every local maximum at the optimum (two equal peaks).
    mass_ratio_fixed : bool
        True when ``M`` was fixed by the user and only ``K``, ``zeta_a`` were optimised.
    mass_bounds : (float, float)
        Search interval of ``M`` (when free).
    at_bound : tuple of bool
        For each free parameter, whether the optimum lies on its search bound.
    fitted : Foundation
        The paper's fitted optimum, Eqs. (28)-(30).
    fitted_h_max : float
        The paper's fitted peak, Eq. (31).
    fitted_h_max_exact : float
        The exact ``H_max`` of the structure with the fitted parameters of Eqs. (28)-(30).
    """

    zeta: float
    foundation: Foundation
    h_max: float
    omega_peak: float
    local_maxima: tuple[tuple[float, float], ...]
    mass_ratio_fixed: bool
    mass_bounds: tuple[float, float]
    at_bound: tuple[bool, ...]
    fitted: Foundation = field(repr=False)
    fitted_h_max: float = field(repr=False)
    fitted_h_max_exact: float = field(repr=False)

    @property
    def zeta_eq(self) -> float:
        """Equivalent damping ratio ``1 / (2 H_max)`` of the exact optimum, Eq. (32)."""
        return 1.0 / (2.0 * self.h_max)

    @property
    def fitted_zeta_eq(self) -> float:
        """The paper's fitted equivalent damping ratio, Eq. (33)."""
        return equivalent_damping_fit(self.zeta)

    def relative_differences(self) -> dict[str, float]:
        """``fitted / exact - 1`` for ``M``, ``K``, ``zeta_a`` (Eqs. 28-30), ``H_max`` (Eq. 31)
        and ``zeta_eq`` (Eq. 33)."""
        f, e = self.fitted, self.foundation
        return {
            "M": f.mass_ratio / e.mass_ratio - 1.0,
            "K": f.stiffness_ratio / e.stiffness_ratio - 1.0,
            "zeta_a": f.damping_ratio / e.damping_ratio - 1.0,
            "H_max": self.fitted_h_max / self.h_max - 1.0,
            "zeta_eq": self.fitted_zeta_eq / self.zeta_eq - 1.0,
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (keys of ``stickslip tune --json``)."""
        f = self.fitted
        return {
            "zeta": self.zeta,
            "M": self.foundation.mass_ratio,
            "K": self.foundation.stiffness_ratio,
            "zeta_a": self.foundation.damping_ratio,
            "H_max": self.h_max,
            "Omega_peak": self.omega_peak,
            "zeta_eq": self.zeta_eq,
            "local_maxima": [{"Omega": w, "H": h} for w, h in self.local_maxima],
            "mass_ratio_fixed": self.mass_ratio_fixed,
            "mass_bounds": list(self.mass_bounds),
            "at_bound": list(self.at_bound),
            "fitted": {
                "M": f.mass_ratio,
                "K": f.stiffness_ratio,
                "zeta_a": f.damping_ratio,
                "H_max": self.fitted_h_max,
                "H_max_exact_at_fitted": self.fitted_h_max_exact,
                "zeta_eq": self.fitted_zeta_eq,
                "source": "Eqs. (28)-(31) and (33)",
            },
            "relative_difference": self.relative_differences(),
        }

    def plot(self, **kwargs: Any) -> Any:
        """Frequency response of the tuned foundation against the rigid base (Fig. 5), a ``PlotResult``.

        Delegates to :func:`stickslip.plot.absorber.frequency_response_plot` (its keywords)
        with the curves of :func:`stickslip.analysis.frequency_response.response_curves`.
        """
        from stickslip.analysis.frequency_response import response_curves
        from stickslip.plot.absorber import frequency_response_plot

        return frequency_response_plot(response_curves(self.zeta, self.foundation), **kwargs)


def _check_tuning_zeta(zeta: float) -> float:
    zeta = non_negative("zeta", zeta)
    if zeta > MAX_TUNING_ZETA:
        raise ValueError(
            f"zeta={zeta!r} is above {MAX_TUNING_ZETA}: the tuning is not defined there "
            "(the slider alone barely resonates)"
        )
    return zeta


def _check_mass_bounds(bounds: tuple[float, float]) -> tuple[float, float]:
    lo, hi = ratio("lower mass bound", bounds[0]), ratio("upper mass bound", bounds[1])
    if lo >= hi:
        raise ValueError(f"mass bounds {bounds!r} must be increasing")
    return lo, hi


def tune_foundation(
    zeta: float,
    *,
    mass_ratio: float | None = None,
    mass_bounds: tuple[float, float] = DEFAULT_MASS_BOUNDS,
) -> TuningResult:
    """Exact optimal foundation: ``(M, K, zeta_a)`` minimising ``H_max`` (paper Figs. 3-6).

    The numerical counterpart of Harik and Issa's optimum that the paper fits with
    Eqs. (28)-(31). Results are cached per argument set.

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, ``0 <= zeta <= 0.9``.
    mass_ratio : float, optional
        Fix ``M = m_a/m`` (dimensionless, > 0) and optimise only ``K`` and ``zeta_a``.
    mass_bounds : (float, float)
        Search interval of ``M`` when it is free; default ``(0.01, 100)``.

    Returns
    -------
    TuningResult
        The optimum, its peak and the paper's fitted values side by side.
    """
    zeta = _check_tuning_zeta(zeta)
    if mass_ratio is not None:
        mass_ratio = ratio("mass ratio M", mass_ratio)
    return _tune_cached(zeta, mass_ratio, _check_mass_bounds(mass_bounds))


def _best_of_grid(
    build: Callable[[FloatArray], Structure], axes: Sequence[FloatArray], n_best: int
) -> list[FloatArray]:
    """The ``n_best`` points of a coarse tensor grid with the lowest ``H_max`` (seeds)."""
    points = np.stack([g.ravel() for g in np.meshgrid(*axes, indexing="ij")], axis=1)
    values = np.array([peak_estimate(build(x)) for x in points])
    return [points[i] for i in np.argsort(values, kind="stable")[:n_best]]


def _foundation_starts(
    build: Callable[[FloatArray], Structure], zeta: float, mass_free: bool
) -> list[FloatArray]:
    """Starts: the paper's fitted optimum and the best points of a coarse log grid.

    The landscape has several local minima (e.g. at fixed ``M`` far from ``M_opt``), so a
    coarse scan of ``K`` (0.2 ... 10), ``zeta_a`` (0.03 ... 100) and, when free, ``M``
    (0.01 ... 100) seeds the search.
    """
    fit = optimal_foundation_fit(min(zeta, 0.4))
    k_axis = np.geomspace(0.2, 10.0, 9 if mass_free else 13)
    z_axis = np.geomspace(0.03, 100.0, 9 if mass_free else 13)
    if mass_free:
        axes = [np.geomspace(0.01, 100.0, 9), k_axis, z_axis]
        first = np.array([fit.mass_ratio, fit.stiffness_ratio, fit.damping_ratio])
    else:
        axes = [k_axis, z_axis]
        first = np.array([fit.stiffness_ratio, fit.damping_ratio])
    return [first, *_best_of_grid(build, axes, 3)]


@lru_cache(maxsize=256)
def _tune_cached(
    zeta: float, mass_ratio: float | None, mass_bounds: tuple[float, float]
) -> TuningResult:
    if mass_ratio is None:

        def build(x: FloatArray) -> Structure:
            return elastic_foundation(zeta, Foundation(x[0], x[1], x[2]))

        bounds = [mass_bounds, STIFFNESS_BOUNDS, DAMPING_BOUNDS]
    else:
        fixed = mass_ratio

        def build(x: FloatArray) -> Structure:
            return elastic_foundation(zeta, Foundation(fixed, x[0], x[1]))

        bounds = [STIFFNESS_BOUNDS, DAMPING_BOUNDS]
    starts = _foundation_starts(build, zeta, mass_ratio is None)
    result = minimise_peak(build, starts, bounds)
    x = [float(v) for v in result.params]
    foundation = Foundation(*x) if mass_ratio is None else Foundation(mass_ratio, *x)
    fitted = optimal_foundation_fit(zeta)
    return TuningResult(
        zeta=zeta,
        foundation=foundation,
        h_max=result.peak.h_max,
        omega_peak=result.peak.omega_peak,
        local_maxima=result.peak.local_maxima,
        mass_ratio_fixed=mass_ratio is not None,
        mass_bounds=mass_bounds,
        at_bound=result.at_bound,
        fitted=fitted,
        fitted_h_max=peak_response_fit(zeta),
        fitted_h_max_exact=response_peak(elastic_foundation(zeta, fitted)).h_max,
    )


def optimal_foundation_exact(zeta: float) -> Foundation:
    """Exact optimal foundation ``(M, K, zeta_a)`` for primary damping ``zeta`` (cached).

    The numerical optimum of :func:`tune_foundation` with ``M`` free in
    :data:`DEFAULT_MASS_BOUNDS`; the exact counterpart of Eqs. (28)-(30). Used by
    ``--dva optimal-exact``.

    Parameters
    ----------
    zeta : float
        Primary damping ratio, dimensionless, ``0 <= zeta <= 0.9``.
    """
    return tune_foundation(zeta).foundation



@dataclass(frozen=True)
class TuningCurve:
    """Exact optimum and the paper's fits over a grid of ``zeta`` (Figs. 4, 6 and 10).

    Every array has the shape of ``zeta``; all values are dimensionless. ``*_fit`` arrays are
    Eqs. (28)-(31) and (33).
    """

    zeta: FloatArray
    mass_ratio: FloatArray
    stiffness_ratio: FloatArray
    damping_ratio: FloatArray
    h_max: FloatArray
    omega_peak: FloatArray
    zeta_eq: FloatArray
    mass_ratio_fit: FloatArray
    stiffness_ratio_fit: FloatArray
    damping_ratio_fit: FloatArray
    h_max_fit: FloatArray
    zeta_eq_fit: FloatArray
    mass_ratio_fixed: bool = False

    _NAMES: ClassVar[dict[str, tuple[str, str]]] = {
        "mass_ratio": ("M_opt", "optimal mass ratio m_a/m, exact"),
        "stiffness_ratio": ("K_opt", "optimal stiffness ratio sqrt(k_a/k), exact"),
        "damping_ratio": ("zeta_a_opt", "optimal foundation damping ratio, exact"),
        "h_max": ("H_max", "peak response k|X|/f at the optimum, exact"),
        "omega_peak": ("Omega_peak", "frequency ratio of the peak, exact"),
        "zeta_eq": ("zeta_eq", "equivalent damping ratio 1/(2 H_max), Eq. (32)"),
        "mass_ratio_fit": ("M_opt_fit", "Eq. (28)"),
        "stiffness_ratio_fit": ("K_opt_fit", "Eq. (29)"),
        "damping_ratio_fit": ("zeta_a_opt_fit", "Eq. (30)"),
        "h_max_fit": ("H_max_fit", "Eq. (31)"),
        "zeta_eq_fit": ("zeta_eq_fit", "Eq. (33)"),
    }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary of lists keyed by the paper's symbols."""
        out: dict[str, Any] = {"zeta": self.zeta.tolist()}
        for attr, (key, _) in self._NAMES.items():
            out[key] = getattr(self, attr).tolist()
        out["mass_ratio_fixed"] = self.mass_ratio_fixed
        return out

    def to_xarray(self) -> Any:
        """An ``xarray.Dataset`` with coordinate ``zeta`` and one variable per array."""
        import xarray as xr

        data = {
            key: ("zeta", getattr(self, attr), {"long_name": text, "units": "1"})
            for attr, (key, text) in self._NAMES.items()
        }
        return xr.Dataset(
            data,
            coords={"zeta": ("zeta", self.zeta, {"long_name": "primary damping ratio"})},
            attrs={"mass_ratio_fixed": int(self.mass_ratio_fixed)},
        )

    def plot(self, kind: str = "parameters", **kwargs: Any) -> Any:
        """Draw the curve, a ``PlotResult``.

        Parameters
        ----------
        kind : {"parameters", "peak", "equivalent-damping"}
            ``M_opt``, ``K_opt``, ``zeta_a,opt`` in three panels (Fig. 4,
            :func:`~stickslip.plot.absorber.optimal_tuning_plot`); ``H_max`` (Fig. 6,
            :func:`~stickslip.plot.absorber.peak_response_plot`); ``zeta_eq`` (Fig. 10,
            :func:`~stickslip.plot.absorber.equivalent_damping_plot`).
        **kwargs
            Keywords of that plotting function.
        """
        from stickslip.plot import absorber

        plots: dict[str, Callable[..., Any]] = {
            "parameters": absorber.optimal_tuning_plot,
            "peak": absorber.peak_response_plot,
            "equivalent-damping": absorber.equivalent_damping_plot,
        }
        if kind not in plots:
            raise ValueError(f"kind={kind!r} must be one of {', '.join(map(repr, plots))}")
        return plots[kind](self, **kwargs)


def tuning_curve(zetas: ArrayLike, *, mass_ratio: float | None = None) -> TuningCurve:
    """Exact optimal tuning at every ``zeta`` of a grid, with Eqs. (28)-(31) and (33).

    Parameters
    ----------
    zetas : array_like
        Primary damping ratios, dimensionless, in ``[0, 0.9]``.
    mass_ratio : float, optional
        Fixed mass ratio ``M`` (only ``K`` and ``zeta_a`` optimised).

    Returns
    -------
    TuningCurve
        Arrays for the paper's Figs. 4 (parameters), 6 (``H_max``) and 10 (``zeta_eq``).
    """
    z = np.atleast_1d(np.asarray(zetas, dtype=np.float64))
    if z.ndim != 1 or z.size == 0:
        raise ValueError("zetas must be a non-empty one-dimensional sequence")
    results = [tune_foundation(float(v), mass_ratio=mass_ratio) for v in z]

    def arr(values: Sequence[float]) -> FloatArray:
        return np.array(values, dtype=np.float64)

    return TuningCurve(
        zeta=z,
        mass_ratio=arr([r.foundation.mass_ratio for r in results]),
        stiffness_ratio=arr([r.foundation.stiffness_ratio for r in results]),
        damping_ratio=arr([r.foundation.damping_ratio for r in results]),
        h_max=arr([r.h_max for r in results]),
        omega_peak=arr([r.omega_peak for r in results]),
        zeta_eq=arr([r.zeta_eq for r in results]),
        mass_ratio_fit=arr([r.fitted.mass_ratio for r in results]),
        stiffness_ratio_fit=arr([r.fitted.stiffness_ratio for r in results]),
        damping_ratio_fit=arr([r.fitted.damping_ratio for r in results]),
        h_max_fit=arr([r.fitted_h_max for r in results]),
        zeta_eq_fit=arr([r.fitted_zeta_eq for r in results]),
        mass_ratio_fixed=mass_ratio is not None,
    )


# The stick-slip optimum (beyond the paper): the paper tunes the foundation as a vibration
# absorber and notes (Figs. 11a, 12-15) that a foundation detuned to K_opt/2 suppresses
# stick-slip far better; here the objective is the onset itself.


@dataclass(frozen=True)
class StickSlipTuning:
    """Result of :func:`optimal_foundation_stick_slip` (all dimensionless).

    Attributes
    ----------
    foundation : Foundation
        The best foundation found.
    lambda_crit : float
        Its stick-slip onset; ``inf`` means no stick-slip up to ``lam_max``.
    reference : Foundation
        The absorber optimum it is compared with (Eqs. 28-30 unless given).
    reference_lambda_crit : float
        Onset of the reference.
    gain : float
        ``lambda_crit / reference_lambda_crit``.
    """

    zeta: float
    gamma: float
    foundation: Foundation
    lambda_crit: float
    reference: Foundation
    reference_lambda_crit: float
    mass_ratio_bounds: tuple[float, float]
    lam_max: float
    evaluations: int

    @property
    def gain(self) -> float:
        return self.lambda_crit / self.reference_lambda_crit

    def to_dict(self) -> dict[str, Any]:
        def num(x: float) -> float | None:
            return x if math.isfinite(x) else None

        f, r = self.foundation, self.reference
        return {
            "objective": "stick-slip",
            "zeta": self.zeta,
            "gamma": self.gamma,
            "M": f.mass_ratio,
            "K": f.stiffness_ratio,
            "zeta_a": f.damping_ratio,
            "lambda_crit": num(self.lambda_crit),
            "lambda_crit_at_least": self.lam_max if math.isinf(self.lambda_crit) else None,
            "absorber_optimum": {
                "M": r.mass_ratio,
                "K": r.stiffness_ratio,
                "zeta_a": r.damping_ratio,
                "lambda_crit": num(self.reference_lambda_crit),
                "source": "fitted Eqs. (28)-(30)",
            },
            "gain": num(self.gain),
            "mass_ratio_bounds": list(self.mass_ratio_bounds),
            "lam_max": self.lam_max,
            "evaluations": self.evaluations,
        }


def optimal_foundation_stick_slip(
    zeta: float,
    gamma: float = 2.0,
    *,
    mass_ratio_bounds: tuple[float, float] | None = None,
    reference: Foundation | None = None,
    lam_max: float = 100.0,
    rtol: float = 1e-4,
    maxiter: int = 60,
) -> StickSlipTuning:
    """Maximise the simulated stick-slip onset over ``(M, K, zeta_a)``.

    Parameters
    ----------
    zeta : float
        Primary damping ratio, dimensionless.
    gamma : float
        ``mu_k / (mu_s - mu_k)``.
    mass_ratio_bounds : (float, float), optional
        Allowed ``M``; defaults to ``(M_opt / 20, M_opt)`` with ``M_opt`` of Eq. (28).
    reference : Foundation, optional
        The absorber optimum to compare with; defaults to Eqs. (28)-(30).
    lam_max : float
        Onsets above this count as "no stick-slip" (the objective saturates there).
    rtol : float
        Relative tolerance of each onset.
    maxiter : int
        Iterations of the Nelder-Mead refinement.

    Notes
    -----
    A coarse grid over ``(K, zeta_a)`` at the largest allowed ``M`` (and at the smallest)
    seeds a Nelder-Mead search in log coordinates, clipped to the bounds. The objective
    is piecewise constant at the scale of ``rtol``, so the result is a good design, not a
    certified global optimum; the comparison with the reference is exact for both points.
    """
    zeta = non_negative("zeta", zeta)
    gamma = non_negative("gamma", gamma)
    lam_max = positive("lam_max", lam_max)
    reference = optimal_foundation_fit(zeta) if reference is None else reference
    if mass_ratio_bounds is None:
        mass_ratio_bounds = (reference.mass_ratio / 20.0, reference.mass_ratio)
    m_lo, m_hi = (positive("mass ratio bound", b) for b in mass_ratio_bounds)
    if m_lo > m_hi:
        raise ValueError(f"mass ratio bounds ({m_lo!r}, {m_hi!r}) are in the wrong order")
    count = 0

    def onset(f: Foundation, tol: float = rtol) -> float:
        nonlocal count
        count += 1
        return lowest_onset(elastic_foundation(zeta, f), gamma=gamma, lam_max=lam_max, rtol=tol)

    def objective(x: np.ndarray) -> float:
        m = float(np.clip(np.exp(x[0]), m_lo, m_hi))
        k = float(np.exp(np.clip(x[1], -4.0, 4.0)))
        za = float(np.exp(np.clip(x[2], -7.0, 3.0)))
        value = onset(Foundation(m, k, za))
        return -min(value, lam_max)

    ref_onset = onset(reference, 1e-6)
    k_ref, za_ref = reference.stiffness_ratio, reference.damping_ratio
    seeds = []
    for m in sorted({m_hi, math.sqrt(m_lo * m_hi)}):
        for k in k_ref * np.array([0.35, 0.5, 0.7, 1.0]):
            for za in za_ref * np.array([0.25, 0.5, 1.0]):
                x = np.log([m, k, za])
                seeds.append((objective(x), tuple(x)))
    seeds.sort()
    best_x = np.array(seeds[0][1])
    best_val = seeds[0][0]
    if best_val > -lam_max:
        res = minimize(objective, best_x, method="Nelder-Mead",
                       options={"maxiter": maxiter, "xatol": 1e-3, "fatol": 1e-4 * lam_max})
        if res.fun < best_val:
            best_x, best_val = res.x, float(res.fun)
    m = float(np.clip(np.exp(best_x[0]), m_lo, m_hi))
    k = float(np.exp(np.clip(best_x[1], -4.0, 4.0)))
    za = float(np.exp(np.clip(best_x[2], -7.0, 3.0)))
    best = Foundation(m, k, za)
    best_onset = onset(best, 1e-6)
    return StickSlipTuning(zeta, gamma, best, best_onset, reference, ref_onset, (m_lo, m_hi),
                           lam_max, count)


# The stability optimum (beyond the paper): with velocity-weakening friction steady sliding
# itself can lose stability; the foundation's second job is to keep it stable for the largest
# friction slope.


#: Default largest static deflection of the foundation under the kinetic friction force, as a
#: multiple of the slider spring's deflection under it (``1 / K^2``); see
#: :func:`optimal_foundation_stability`.
MAX_FOUNDATION_DEFLECTION_RATIO = 4.0


@dataclass(frozen=True)
class StabilityTuning:
    """Result of :func:`optimal_foundation_stability` (all dimensionless).

    Attributes
    ----------
    foundation : Foundation
        The foundation with the largest critical weakening found.
    delta_crit : float
        Its critical friction slope: steady sliding is linearly stable for every law whose
        weakening at the belt speed, ``delta = -(dF/du) / 2``, is below it.
    reference, reference_delta_crit :
        The absorber optimum (Eqs. 28-30 unless given) and its critical slope.
    """

    zeta: float
    foundation: Foundation
    delta_crit: float
    reference: Foundation
    reference_delta_crit: float
    mass_ratio_bounds: tuple[float, float]
    stiffness_ratio_bounds: tuple[float, float]
    evaluations: int

    @property
    def gain(self) -> float:
        """``delta_crit / reference_delta_crit``."""
        return self.delta_crit / self.reference_delta_crit if self.reference_delta_crit > 0 else math.inf

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, with the keys of ``stickslip tune --objective stability --json``."""
        f, r = self.foundation, self.reference
        return {
            "objective": "stability",
            "zeta": self.zeta,
            "M": f.mass_ratio,
            "K": f.stiffness_ratio,
            "zeta_a": f.damping_ratio,
            "delta_crit": self.delta_crit,
            "rigid_base_delta_crit": self.zeta,
            "absorber_optimum": {
                "M": r.mass_ratio,
                "K": r.stiffness_ratio,
                "zeta_a": r.damping_ratio,
                "delta_crit": self.reference_delta_crit,
                "source": "fitted Eqs. (28)-(30)",
            },
            "gain": self.gain if math.isfinite(self.gain) else None,
            "mass_ratio_bounds": list(self.mass_ratio_bounds),
            "stiffness_ratio_bounds": list(self.stiffness_ratio_bounds),
            # static deflection of the foundation under mu_k W over the slider spring's: 1 / K^2
            "foundation_deflection_ratio": 1.0 / f.stiffness_ratio ** 2,
            "evaluations": self.evaluations,
        }


def optimal_foundation_stability(
    zeta: float,
    *,
    mass_ratio_bounds: tuple[float, float] | None = None,
    stiffness_ratio_bounds: tuple[float, float] | None = None,
    reference: Foundation | None = None,
    maxiter: int = 400,
    max_deflection_ratio: float = MAX_FOUNDATION_DEFLECTION_RATIO,
) -> StabilityTuning:
    """Maximise the critical friction weakening ``delta_crit`` over ``(M, K, zeta_a)``.

    Parameters
    ----------
    zeta : float
        Primary damping ratio, dimensionless.
    mass_ratio_bounds : (float, float), optional
        Allowed ``M``; by default ``(M_opt / 20, M_opt)`` with ``M_opt`` of Eq. (28), so that
        the design adds no more mass than the absorber optimum (as for the stick-slip objective).
    stiffness_ratio_bounds : (float, float), optional
        Allowed ``K``; by default ``(1 / sqrt(max_deflection_ratio), 10 K_opt)`` with ``K_opt``
        of Eq. (29). A lower bound is needed: as ``K -> 0`` the foundation hangs on its damper
        alone, ``delta_crit`` tends to ``zeta_a`` while the static drift ``gamma lambda / K^2``
        of the foundation grows without bound and its slowest mode stops decaying, which is no
        design.
    max_deflection_ratio : float
        Largest static deflection of the foundation under the kinetic friction force
        ``mu_k W``, as a multiple of the slider spring's deflection under the same force:
        ``(mu_k W / k_a) / (mu_k W / k) = 1 / K^2``, so ``K >= 1 / sqrt(max_deflection_ratio)``.
        In SI the deflection is ``max_deflection_ratio * mu_k W / k``. Default
        :data:`MAX_FOUNDATION_DEFLECTION_RATIO` (4: a foundation spring at least a quarter as
        stiff as the slider's, i.e. ``K >= 0.5``, the paper's detuning ``K_opt / 2`` of
        Figs. 11-15 at small ``zeta``).
    reference : Foundation, optional
        The absorber optimum compared with; Eqs. (28)-(30) by default.
    maxiter : int
        Nelder-Mead iterations from the best seed.

    Notes
    -----
    ``delta_crit`` comes from the eigenvalues of the linearised slip-I matrix
    (:func:`stickslip.analysis.stability.critical_weakening`), so one evaluation costs
    microseconds; a grid of seeds over ``(K, zeta_a)`` at the largest and the mean allowed ``M``
    starts a Nelder-Mead search in log coordinates. ``K`` and ``zeta_a`` are searched within
    the bounds of the absorber tuning.
    """
    from stickslip.analysis.stability import critical_weakening

    zeta = _check_tuning_zeta(zeta)
    reference = optimal_foundation_fit(zeta) if reference is None else reference
    if mass_ratio_bounds is None:
        mass_ratio_bounds = (reference.mass_ratio / 20.0, reference.mass_ratio)
    m_lo, m_hi = (positive("mass ratio bound", b) for b in mass_ratio_bounds)
    if m_lo > m_hi:
        raise ValueError(f"mass ratio bounds ({m_lo!r}, {m_hi!r}) are in the wrong order")
    if stiffness_ratio_bounds is None:
        ratio_max = positive("largest foundation deflection ratio", max_deflection_ratio)
        stiffness_ratio_bounds = (1.0 / math.sqrt(ratio_max),
                                  max(reference.stiffness_ratio * 10.0, 1.0 / math.sqrt(ratio_max)))
    k_lo, k_hi = (positive("stiffness ratio bound", b) for b in stiffness_ratio_bounds)
    if k_lo > k_hi:
        raise ValueError(f"stiffness ratio bounds ({k_lo!r}, {k_hi!r}) are in the wrong order")
    z_lo, z_hi = DAMPING_BOUNDS
    count = 0

    def foundation(x: FloatArray) -> Foundation:
        return Foundation(float(np.clip(np.exp(x[0]), m_lo, m_hi)),
                          float(np.clip(np.exp(x[1]), k_lo, k_hi)),
                          float(np.clip(np.exp(x[2]), z_lo, z_hi)))

    def objective(x: FloatArray) -> float:
        nonlocal count
        count += 1
        return -critical_weakening(elastic_foundation(zeta, foundation(x)))

    seeds = []
    for m in sorted({m_hi, math.sqrt(m_lo * m_hi)}):
        for k in np.geomspace(k_lo, k_hi, 7):
            for za in reference.damping_ratio * np.array([0.25, 0.5, 1.0, 2.0]):
                x = np.log([m, k, za])
                seeds.append((objective(x), tuple(x)))
    seeds.sort()
    res = minimize(objective, np.array(seeds[0][1]), method="Nelder-Mead",
                   options={"maxiter": maxiter, "xatol": 1e-6, "fatol": 1e-10})
    best_x = res.x if res.fun < seeds[0][0] else np.array(seeds[0][1])
    best = foundation(best_x)
    return StabilityTuning(
        zeta, best, critical_weakening(elastic_foundation(zeta, best)), reference,
        critical_weakening(elastic_foundation(zeta, reference)), (m_lo, m_hi), (k_lo, k_hi), count,
    )
