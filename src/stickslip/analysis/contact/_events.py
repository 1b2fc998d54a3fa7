"""The first event on an exact affine flow ``z' = A z + c``, found so that no root is skipped.

A phase of :mod:`stickslip.analysis.contact.engine` is one linear mode: its solution is
``z(t) = E(t) z_0 + d(t)`` with ``[[E, d], [0, 1]] = expm([[A, c], [0, 0]] t)``, exact but for
rounding. Its events are affine functions ``g(z) = a . z + b`` that are positive while the mode
holds; the event is the first time one reaches zero.

The search samples the exact flow on a uniform grid of step ``h`` and bounds what can happen
between two samples: with ``f = A z + c`` the field, ``g'' = a A f`` and ``f(t_j + s) =
expm(A s) f(t_j)``, so on ``[t_j, t_j + h]``

    |g''| <= ||a A D|| ||D^-1 f(t_j)|| exp(||D^-1 A D|| h)

(``D`` the diagonal balancing of ``A``, which makes metres and metres per second comparable),
or, tighter once ``g''`` is resolved, the larger sampled ``|g''|`` plus the interpolation
error of ``g''`` itself, ``||a A^3 D|| ||D^-1 f(t_j)|| exp(||D^-1 A D|| h) h^2 / 8``
(:class:`_Curvature`). The linear interpolant of the two samples of ``g`` is then within
``max|g''| h^2 / 8`` of ``g``: an interval whose sampled values both exceed that bound holds
no root, and every other interval is halved (the same bounds with ``h / 2``) until it is
cleared or a sign change is found. A sign change is refined by Brent's method on the exact
flow. A root that only touches zero (a graze) is found too: its interval can never be
cleared, and after :data:`MAX_HALVINGS` halvings the touch is taken as the event.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import NDArray
from scipy.optimize import brentq

FloatArray = NDArray[np.float64]

#: ``||D^-1 A D|| h`` of the sampling step.
STEP = 0.25
#: Samples evaluated together (one batched product per chunk): the first chunk, and the
#: largest (each chunk doubles the last).
FIRST_CHUNK = 8
CHUNK = 256
#: Halvings of a sample interval before a touch of zero is taken as a graze.
MAX_HALVINGS = 52
#: Most interval halvings in one search (a budget: beyond it the search gives up).
MAX_REFINEMENTS = 100_000
#: Propagators a flow keeps for the event search's halved steps (then it starts afresh).
KEPT_PROPAGATORS = 128
#: Relative allowance of a surface that the phase starts on (its own rounding).
START_TOLERANCE = 1e-10
#: Multiple of that allowance beyond which the surface counts as left (exact again).
LEFT = 1e3


class AffineFlow:
    """The exact flow of ``z' = A z + c`` (``A`` in 1/s, ``c`` in the state's units per s).

    Parameters
    ----------
    a : ndarray, shape (d, d)
        The mode's matrix, 1/s (entries mix units: the state holds metres and m/s).
    c : ndarray, shape (d,)
        The mode's constant.
    """

    def __init__(self, a: FloatArray, c: FloatArray) -> None:
        self.a = np.asarray(a, dtype=float)
        self.c = np.asarray(c, dtype=float)
        n = self.c.size
        self.aug = np.zeros((n + 1, n + 1))
        self.aug[:n, :n], self.aug[:n, n] = self.a, self.c
        scaled, (scale, _perm) = scipy.linalg.matrix_balance(self.a, permute=False,
                                                              separate=True)
        self.scale = np.where(scale > 0.0, scale, 1.0).astype(float)
        self.norm = max(float(np.linalg.norm(scaled, 2)), 1e-300)
        c_scaled = float(np.max(np.abs(self.c / self.scale), initial=0.0))
        aug_scale = np.append(self.scale, self.norm / c_scaled if c_scaled > 0.0 else 1.0)
        self.aug_balanced = self.aug * aug_scale[None, :] / aug_scale[:, None]
        self.aug_ratio = aug_scale[:, None] / aug_scale[None, :]
        self._kept: dict[float, FloatArray] = {}
        self.sample_step = STEP / self.norm
        self._powers = np.empty((0, n + 1, n + 1))

    def propagator(self, t: float) -> FloatArray:
        """``expm([[A, c], [0, 0]] t)``: the flow's affine map over ``t`` seconds.

        Computed on the balanced matrix (``D^-1 A D``, entries of one size) and scaled back:
        the same exponential, with fewer squarings and no mixing of metres and m/s.
        """
        return np.asarray(scipy.linalg.expm(self.aug_balanced * t)) * self.aug_ratio

    def kept_propagator(self, t: float) -> FloatArray:
        """:meth:`propagator`, kept for the durations the event search uses again and again
        (the sampling step halved, ``h / 2^k``); the same matrix, computed once."""
        p = self._kept.get(t)
        if p is None:
            if len(self._kept) >= KEPT_PROPAGATORS:
                self._kept.clear()
            p = self._kept[t] = self.propagator(t)
        return p

    def step_powers(self, k: int) -> FloatArray:
        """The propagators over ``1..k`` sampling steps (:attr:`sample_step`), kept."""
        made = self._powers.shape[0]
        if made < k:
            grown = np.empty((max(k, min(2 * made, CHUNK)), *self._powers.shape[1:]))
            grown[:made] = self._powers
            if made == 0:
                grown[0] = self.kept_propagator(self.sample_step)
                made = 1
            for j in range(made, grown.shape[0]):
                grown[j] = grown[0] @ grown[j - 1]
            self._powers = grown
        return self._powers[:k]

    def at(self, z0: FloatArray, t: float, *, keep: bool = False) -> FloatArray:
        """The state ``t`` seconds after ``z0`` (exact but for rounding); ``keep``: a duration
        used again (:meth:`kept_propagator`)."""
        p = self.kept_propagator(t) if keep else self.propagator(t)
        n = z0.size
        return np.asarray(p[:n, :n] @ z0 + p[:n, n])

    def field_norm(self, z: FloatArray) -> FloatArray:
        """``||D^-1 (A z + c)||`` of states ``z`` (rows), the scaled speed of the flow."""
        return np.asarray(np.linalg.norm((z @ self.a.T + self.c) / self.scale, axis=-1))


@dataclass(frozen=True)
class Found:
    """The first event: ``dt`` seconds after the phase start, the state there, the surface."""

    dt: float
    z: FloatArray
    index: int
    samples: int


@dataclass(frozen=True)
class Settled:
    """The search stopped because ``stop(z)`` said so (e.g. steady sliding proven)."""

    dt: float
    z: FloatArray
    samples: int


@dataclass(frozen=True)
class Horizon:
    """No event before the horizon; ``samples`` used."""

    z: FloatArray
    samples: int


class SampleBudgetExhausted(RuntimeError):
    """The search used its budget of samples with no event found up to ``dt`` (s) after the
    phase's start, where the state is ``z``; ``samples`` is what it used."""

    def __init__(self, max_samples: int, dt: float, z: FloatArray, samples: int) -> None:
        super().__init__(f"sample budget of {max_samples} exhausted")
        self.dt = dt
        self.z = z
        self.samples = samples


def first_event(flow: AffineFlow, z0: FloatArray, normals: FloatArray, levels: FloatArray,
                horizon: float, *, max_samples: int,
                stop: Callable[[FloatArray], bool] | None = None) -> Found | Settled | Horizon:
    """The first time one of ``g_i(z) = normals[i] . z + levels[i]`` reaches zero.

    Parameters
    ----------
    flow : AffineFlow
        The mode.
    z0 : ndarray
        The state at the phase start.
    normals, levels : ndarray
        The event functions (shape ``(m, d)`` and ``(m,)``), positive while the mode holds.
    horizon : float
        Longest duration searched, s (> 0).
    max_samples : int
        Budget of samples; exceeding it raises :class:`SampleBudgetExhausted` (with how far
        the search got), :data:`MAX_REFINEMENTS` halvings ``RuntimeError`` (the caller
        reports both).
    stop : callable, optional
        Checked at each chunk's end; True ends the search there (:class:`Settled`).

    Returns
    -------
    Found, Settled or Horizon
    """
    z0 = np.asarray(z0, dtype=float)
    n_d = z0.size
    g0 = normals @ z0 + levels
    size = np.abs(levels) + np.abs(normals) @ np.abs(z0) + 1e-300
    # a surface the phase starts on counts from just beyond its own rounding, until the
    # function has clearly left it (then the exact surface again)
    tol = START_TOLERANCE * size
    shift = np.where(g0 <= tol, tol, 0.0)
    if np.any(g0 + shift < 0.0):
        index = int(np.argmin(g0 + shift))
        return Found(0.0, z0, index, 0)
    # one sampling step per mode (its propagators kept across phases), the last sample at or
    # just beyond the horizon; chunks grow from FIRST_CHUNK to CHUNK samples (most phases end
    # within a few samples)
    h = flow.sample_step
    steps = max(1, math.ceil(horizon / h))
    coef = _Curvature.of(flow, normals)
    chunk = min(FIRST_CHUNK, steps)
    done, z, used = 0, z0, 0
    budget = [MAX_REFINEMENTS]
    while done < steps:
        k = min(chunk, steps - done)
        chunk = min(2 * chunk, CHUNK)
        used += k
        if used > max_samples:
            raise SampleBudgetExhausted(max_samples, done * h, z, used - k)
        powers = flow.step_powers(k)
        zs = np.vstack([z[None, :], powers[:, :n_d, :n_d] @ z + powers[:, :n_d, n_d]])
        g = zs @ normals.T + levels
        # the surface is left behind once the function was clearly positive at a sample
        left = np.maximum.accumulate((g > LEFT * tol) | (shift == 0.0)[None, :], axis=0)
        shifts = np.where(left, 0.0, shift[None, :])  # per sample; an interval keeps its start's
        shift = shifts[-1]
        low = np.minimum(g[:-1], g[1:]) + shifts[:-1]
        bound = coef.bound(flow, zs, h)
        suspect = np.flatnonzero(~np.all(low > bound, axis=1))
        for j in suspect.tolist():
            hit = _refine(flow, zs[j], (done + j) * h, h, normals, levels + shifts[j], coef, 0,
                          budget)
            if hit is not None:
                dt, index = hit
                if dt > horizon:  # in the last interval, beyond the horizon
                    break
                return Found(dt, flow.at(z0, dt), index, used)
        done += k
        if done >= steps:  # the horizon lies in the last interval: its state from there
            start = (done - 1) * h
            return Horizon(flow.at(zs[-2], horizon - start), used)
        z = zs[-1]
        if stop is not None and stop(z):
            return Settled(done * h, z, used)
    return Horizon(z, used)  # not reached: the loop returns at its last interval


@dataclass(frozen=True)
class _Curvature:
    """What bounds ``|g''|`` of every event function between two samples ``h`` apart.

    Two bounds, both from ``f(t_j + s) = expm(A s) f(t_j)``, the smaller is used:
    ``||a A D|| F_j exp(||A_s|| h)`` (``F_j = ||D^-1 f(t_j)||``), and the larger of the two
    sampled values of ``g'' = a A f`` plus the error of their linear interpolant,
    ``||a A^3 D|| F_j exp(||A_s|| h) h^2 / 8`` (tight when ``g''`` is well resolved).
    """

    second: FloatArray  # (m, d): g'' = second @ z + second_level
    second_level: FloatArray
    first_norm: FloatArray  # ||a A D||
    fourth_norm: FloatArray  # ||a A^3 D||

    @classmethod
    def of(cls, flow: AffineFlow, normals: FloatArray) -> _Curvature:
        na = normals @ flow.a
        na2 = na @ flow.a
        na3 = na2 @ flow.a
        return cls(na2, na @ flow.c, np.linalg.norm(na * flow.scale, axis=1),
                   np.linalg.norm(na3 * flow.scale, axis=1))

    def bound(self, flow: AffineFlow, zs: FloatArray, h: float) -> FloatArray:
        """``max |g - linear interpolant|`` on each interval of the samples ``zs``: (k, m)."""
        speed = flow.field_norm(zs[:-1]) * math.exp(flow.norm * h)
        sampled = np.abs(zs @ self.second.T + self.second_level)
        second = np.minimum(self.first_norm[None, :] * speed[:, None],
                            np.maximum(sampled[:-1], sampled[1:])
                            + self.fourth_norm[None, :] * speed[:, None] * h * h / 8.0)
        return np.asarray(second * h * h / 8.0)


def _refine(flow: AffineFlow, z_left: FloatArray, t_left: float, h: float, normals: FloatArray,
            levels: FloatArray, coef: _Curvature, depth: int,
            budget: list[int]) -> tuple[float, int] | None:
    """The first root in ``[t_left, t_left + h]`` (time from the phase start), or None.

    ``budget[0]`` counts the halvings left; at zero the search raises ``RuntimeError``.
    """
    budget[0] -= 1
    if budget[0] < 0:
        raise RuntimeError(f"event search budget of {MAX_REFINEMENTS} interval halvings exhausted")
    half = 0.5 * h
    z_mid = flow.at(z_left, half, keep=True)
    z_right = flow.at(z_left, h, keep=True)
    zs = np.vstack([z_left, z_mid, z_right])
    g = zs @ normals.T + levels
    for side in (0, 1):
        lo, hi = g[side], g[side + 1]
        crossing = np.flatnonzero(hi <= 0.0)
        if crossing.size:
            roots = [(_root(flow, zs[side], normals[i], levels[i], half), int(i)) for i in crossing]
            dt, index = min(roots)
            return t_left + side * half + dt, index
        bound = coef.bound(flow, zs[side:side + 2], half)[0]
        unclear = np.minimum(lo, hi) <= bound
        if not np.any(unclear):
            continue
        if depth >= MAX_HALVINGS:  # a touch of zero: the graze is the event
            index = int(np.argmin(np.minimum(lo, hi) - bound))
            return t_left + side * half + (0.0 if lo[index] <= hi[index] else half), index
        hit = _refine(flow, zs[side], t_left + side * half, half, normals, levels, coef,
                      depth + 1, budget)
        if hit is not None:
            return hit
    return None


def _root(flow: AffineFlow, z_left: FloatArray, normal: FloatArray, level: float,
          length: float) -> float:
    """The root of ``normal . z(s) + level`` in ``(0, length]`` (positive at 0, not at ``length``)."""
    def g(s: float) -> float:
        return float(normal @ flow.at(z_left, s) + level)

    at_end = g(length)
    if at_end >= 0.0:  # the sampled value was <= 0: this one differs from it by rounding only
        return length
    if g(0.0) <= 0.0:
        return 0.0
    return float(brentq(g, 0.0, length, xtol=1e-15 * length + 1e-300, rtol=1e-15))
