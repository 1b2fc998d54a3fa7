"""Bounds of a sampled nominal function over its sample intervals (the cycle tube's checks).

Shared by :mod:`stickslip.analysis._cycle_tube` (the event checks) and
:mod:`stickslip.analysis._band_variation` (the time a nominal speed spends near a band edge).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def interval_floor(values: FloatArray, curvature: FloatArray) -> FloatArray:
    """Per sample interval: a lower bound of ``|v|`` over it; negative where ``v`` may vanish.

    ``v`` is sampled at the interval's ends; ``curvature`` bounds ``|v''| h^2 / 8`` on each
    interval, the error of the linear interpolant. With end values of one sign, ``|v| >=
    min(|v_j|, |v_{j+1}|) - curvature`` there; an interval whose ends differ in sign gets -1.
    """
    same = np.sign(values[:-1]) * np.sign(values[1:]) > 0
    low = np.minimum(np.abs(values[:-1]), np.abs(values[1:])) - curvature
    return np.where(same, low, -1.0)


def clear_of_zero(g: FloatArray, curvature: FloatArray, eps: FloatArray) -> NDArray[np.bool_]:
    """Per sample interval: ``|g*| > eps`` on all of it (see :func:`interval_floor`)."""
    return interval_floor(g, curvature) > eps


def end_drift(nv: FloatArray, a: FloatArray, f_star: FloatArray, f_norm: float, norm_a: float,
              t_dev: float) -> float:
    """Bound of ``|g*(t* + u) - g*(t*)|`` for ``0 <= u <= t_dev`` along the nominal flow.

    With ``g = n . z - g0`` and ``z' = A z + c``, ``g*' = n . f`` and ``f(z*(t* + s)) =
    expm(A s) f*`` (``f*`` the field at the phase's end). ``expm(A s) - I = int_0^s A
    expm(A r) dr`` gives ``|n . (expm(A s) - I) f*| <= ||n^T A|| s exp(||A|| s) ||f*||``, so

    ``|g*(t* + u) - g*(t*)| <= u |n . f*| + ||n^T A|| ||f*|| u^2 exp(||A|| u) / 2``,

    increasing in ``u``: its value at ``t_dev`` bounds the window. Tighter than ``||n|| ||f*||
    exp(||A|| T) T`` when the surface's rate ``n . f*`` is small (a band edge of the same
    velocity near the one the phase ends on).

    Parameters
    ----------
    nv : ndarray
        The surface's normal ``n``.
    a : ndarray
        The mode's matrix ``A``.
    f_star : ndarray
        ``f*``: the nominal field at the phase's end.
    f_norm : float
        ``||f*||_2``.
    norm_a : float
        A bound of ``||A||_2`` (the Frobenius norm).
    t_dev : float
        ``T``: the window past ``t*``.

    Returns
    -------
    float
        The bound.
    """
    return (t_dev * abs(float(nv @ f_star))
            + float(np.linalg.norm(nv @ a)) * f_norm * t_dev ** 2 * math.exp(norm_a * t_dev) / 2.0)
