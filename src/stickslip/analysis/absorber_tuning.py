"""The absorber tuning of the elastic foundation: the exact H-infinity optimum (paper Figs. 3-6, 10).

The dynamic-vibration-absorber optimum (paper Section 3.1, Eqs. 28-31): the minimax problem
``min H_max`` over the foundation ``(M, K, zeta_a)`` at a given primary damping ``zeta``
(:func:`stickslip.analysis.peak_minimiser.minimise_peak`), to be compared with the paper's
fitted Eqs. (28)-(31). The other objectives are :mod:`stickslip.analysis.stick_slip_tuning`
(the simulated onset) and :mod:`stickslip.analysis.stability_tuning` (steady-sliding stability).

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

Friction law: none enters. The objective is the receptance of the linear structure, the
same under any friction law; the law enters only the onset of stick-slip, which
:mod:`stickslip.analysis.stick_slip_tuning` tunes for (with the Coulomb law, stated there).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.analysis.frequency_response import peak_estimate, response_peak
from stickslip.analysis.peak_minimiser import minimise_peak
from stickslip.analysis.theory import (
    MAX_TUNING_ZETA,
    equivalent_damping_fit,
    optimal_foundation_fit,
    peak_response_fit,
)
from stickslip.model._validate import non_negative, ratio
from stickslip.model.parameters import Foundation
from stickslip.model.structure import Structure, elastic_foundation

FloatArray = NDArray[np.float64]


DEFAULT_MASS_BOUNDS: tuple[float, float] = (0.01, 100.0)
"""Default search interval of the mass ratio ``M = m_a/m`` (dimensionless)."""
STIFFNESS_BOUNDS: tuple[float, float] = (1e-3, 1e3)
"""Search interval of the stiffness ratio ``K = sqrt(k_a/k)`` (dimensionless)."""
DAMPING_BOUNDS: tuple[float, float] = (1e-4, 1e3)
"""Search interval of the foundation damping ratio ``zeta_a`` (dimensionless)."""


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


def check_tuning_zeta(zeta: float) -> float:
    """``zeta`` as a float when the tuning is defined there, ``0 <= zeta <= MAX_TUNING_ZETA``.

    Parameters
    ----------
    zeta : float
        Primary damping ratio, dimensionless.

    Returns
    -------
    float
        ``zeta``; a ``ValueError`` above :data:`~stickslip.analysis.theory.MAX_TUNING_ZETA`.
    """
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
    zeta = check_tuning_zeta(zeta)
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


@lru_cache(maxsize=4096)  # a map's zeta axis (hundreds) tuned once, then reused by its cells
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

    Returns
    -------
    Foundation
        The exact optimum ``(M, K, zeta_a)``, dimensionless.
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
