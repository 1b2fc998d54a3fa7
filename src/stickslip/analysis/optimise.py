"""The shared optimiser: a bounded Nelder-Mead search and its seeding from a grid of starts.

Every tuning objective of :mod:`stickslip.analysis` (the H-infinity peak of
:mod:`~stickslip.analysis.peak_minimiser`, the stick-slip onset of
:mod:`~stickslip.analysis.stick_slip_tuning`, the critical weakening of
:mod:`~stickslip.analysis.stability_tuning`) is a function of a few positive parameters searched
in log coordinates: a coarse grid of seeds picks a basin, Nelder-Mead (derivative-free, so
indifferent to the kinks of a minimax or the steps of a bisected onset) refines it. A fitting
feature can reuse the same two functions. Thin wrappers over :func:`scipy.optimize.minimize`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize

from stickslip.model._validate import positive

FloatArray = NDArray[np.float64]
Objective = Callable[[FloatArray], float]


def ordered_bounds(name: str, bounds: tuple[float, float]) -> tuple[float, float]:
    """A search interval of a positive parameter, checked: ``0 < lower <= upper``.

    Parameters
    ----------
    name : str
        The parameter, for the error message (e.g. ``"mass ratio"``).
    bounds : (float, float)
        Lower and upper bound.

    Returns
    -------
    (float, float)
        The bounds as floats; a ``ValueError`` names a bound that is not positive and finite,
        or bounds in the wrong order.
    """
    lower, upper = (positive(f"{name} bound", b) for b in bounds)
    if lower > upper:
        raise ValueError(f"{name} bounds ({lower!r}, {upper!r}) are in the wrong order")
    return lower, upper


def box_simplex(x0: FloatArray, step: float, lower: FloatArray, upper: FloatArray) -> FloatArray:
    """A starting simplex of edge ``step`` at ``x0`` inside the box ``[lower, upper]``.

    Parameters
    ----------
    x0 : ndarray, shape (n,)
        First vertex, inside the box.
    step : float
        Edge length along each axis, in the units of ``x0``.
    lower, upper : ndarray, shape (n,)
        Bounds of the box.

    Returns
    -------
    ndarray, shape (n + 1, n)
        The vertices ``x0`` and ``x0 + step e_i`` clipped into the box; a vertex that the clip
        put back onto ``x0`` (a start on an upper bound) steps inwards, ``x0 - step e_i``,
        instead of collapsing the simplex.
    """
    simplex = np.clip(np.vstack([x0, x0 + step * np.eye(x0.size)]), lower, upper)
    simplex[1:] = np.where(simplex[1:] == x0, x0 - step, simplex[1:])
    return simplex


def nelder_mead(
    objective: Objective,
    x0: ArrayLike,
    *,
    xatol: float,
    fatol: float,
    bounds: tuple[FloatArray, FloatArray] | None = None,
    initial_step: float | None = None,
    maxiter: int | None = None,
    maxfev: int | None = None,
) -> tuple[FloatArray, float]:
    """Minimise ``objective`` by Nelder-Mead from ``x0``, optionally within a box.

    Parameters
    ----------
    objective : callable
        Maps a parameter vector to a float (``inf`` for an invalid point).
    x0 : array_like, shape (n,)
        Start.
    xatol, fatol : float
        Absolute tolerances on the simplex size and on the objective (scipy's).
    bounds : (ndarray, ndarray), optional
        Lower and upper bound of each parameter.
    initial_step : float, optional
        Edge of the starting simplex (:func:`box_simplex`, needs ``bounds``); scipy's
        default simplex otherwise.
    maxiter, maxfev : int, optional
        Most iterations and objective evaluations (scipy's defaults otherwise).

    Returns
    -------
    x : ndarray, shape (n,)
        The best point found.
    value : float
        ``objective(x)``.
    """
    start = np.asarray(x0, dtype=np.float64)
    options: dict[str, Any] = {"xatol": xatol, "fatol": fatol}
    if maxiter is not None:
        options["maxiter"] = maxiter
    if maxfev is not None:
        options["maxfev"] = maxfev
    box = None
    if bounds is not None:
        lower, upper = bounds
        box = list(zip(lower, upper, strict=True))
        if initial_step is not None:
            options["initial_simplex"] = box_simplex(start, initial_step, lower, upper)
    elif initial_step is not None:
        raise ValueError("initial_step needs bounds")
    res = minimize(objective, start, method="Nelder-Mead", bounds=box, options=options)
    return np.asarray(res.x, dtype=np.float64), float(res.fun)


def best_seed(objective: Objective, seeds: Iterable[ArrayLike]) -> tuple[FloatArray, float]:
    """The seed with the lowest objective (ties: the smallest coordinates), and its value.

    Parameters
    ----------
    objective : callable
        Maps a parameter vector to a float.
    seeds : iterable of array_like
        Candidate starts, evaluated in the given order.

    Returns
    -------
    x : ndarray
        The best seed.
    value : float
        ``objective(x)``.
    """
    points = [np.asarray(x, dtype=np.float64) for x in seeds]
    scored = [(objective(x), tuple(float(v) for v in x)) for x in points]
    if not scored:
        raise ValueError("best_seed needs at least one seed")
    value, x = min(scored)
    return np.array(x), value
