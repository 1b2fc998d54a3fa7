"""Velocity-dependent friction laws, dimensionless inside.

While the slider slides, the friction force has the magnitude ``W mu(v_r)`` with the sliding
speed ``v_r = |V - x'|``. In the units of the engine (forces over ``V sqrt(m k)``, speeds
over the belt speed ``V``) a law is the dimensionless magnitude

    F(u) = mu(u V) W / (V sqrt(m k)),    u = v_r / V = |1 - xi'|,

so that the kinetic reference is ``F_k = gamma lambda`` (``mu_k``) and the static one
``F_s = (1 + gamma) lambda`` (``mu_s``); stick (Eq. 20) is unchanged. Every law hands the
engine a piecewise-linear band table (:meth:`bands`): band ``b`` covers
``u in [edges[b], edges[b+1])`` with ``F(u) = intercepts[b] + slopes[b] u``, ``edges[0] = 0``,
``edges[-1] = inf``. Each band is a linear mode of the engine, so ``coulomb``, ``linear``
and ``table`` are integrated exactly; ``stribeck`` is replaced by a piecewise-linear
interpolant whose bands are placed so that ``max |F - F_PL| <= tolerance * lambda`` (the law
approximation error; the integration of the interpolant is exact).

Friction never changes sign with speed: ``linear`` and ``stribeck`` are floored at zero
(``F = max(F, 0)``), a ``table`` that would go negative is refused.
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.model._validate import (
    MAX_PARAMETER,
    MIN_RATIO,
    at_most,
    finite,
    non_negative,
    positive,
    within,
)

FloatArray = NDArray[np.float64]


class TableInputError(ValueError):
    """A friction table refused for what it says (its speeds or coefficients), whatever the
    operating point: messages about it name the table, not the speed and load."""
BandTable = tuple[FloatArray, FloatArray, FloatArray]

#: Most bands a law may produce (the engine has two modes per band).
MAX_BANDS = 2000


def _segments_to_table(segments: list[tuple[float, float, float, float]]) -> BandTable:
    """Floor ``(lo, hi, a, s)`` segments at zero, merge equal neighbours, return arrays."""
    floored: list[tuple[float, float, float, float]] = []
    for lo, hi, a, s in segments:
        f_lo = a + s * lo
        if math.isfinite(hi):
            f_hi = a + s * hi
        else:
            f_hi = math.inf if s > 0 else -math.inf if s < 0 else a
        if f_lo >= 0.0 and f_hi >= 0.0:
            floored.append((lo, hi, a, s))
        elif f_lo <= 0.0 and f_hi <= 0.0:
            floored.append((lo, hi, 0.0, 0.0))
        else:
            cross = -a / s
            if f_lo < 0.0:
                floored += [(lo, cross, 0.0, 0.0), (cross, hi, a, s)]
            else:
                floored += [(lo, cross, a, s), (cross, hi, 0.0, 0.0)]
    merged: list[tuple[float, float, float, float]] = []
    for seg in floored:
        if seg[1] <= seg[0]:
            continue
        if merged and merged[-1][2] == seg[2] and merged[-1][3] == seg[3]:
            merged[-1] = (merged[-1][0], seg[1], seg[2], seg[3])
        else:
            merged.append(seg)
    if len(merged) > MAX_BANDS:
        raise ValueError(
            f"the friction law needs {len(merged)} bands, more than {MAX_BANDS}; "
            "loosen the tolerance or smooth the table"
        )
    edges = np.array([seg[0] for seg in merged] + [math.inf])
    edges[0] = 0.0
    intercepts = np.array([seg[2] for seg in merged])
    slopes = np.array([seg[3] for seg in merged])
    return edges, intercepts, slopes


Segment = tuple[float, float, float, float]


def _through_points(u: FloatArray, f: FloatArray, tail_slope: float) -> list[Segment]:
    """Segments of the piecewise-linear function through ``(u_i, f_i)``.

    Constant ``f_0`` below ``u_0``; beyond the last point ``f_last + tail_slope (u - u_last)``.
    """
    segs: list[tuple[float, float, float, float]] = []
    if u[0] > 0.0:
        segs.append((0.0, float(u[0]), float(f[0]), 0.0))
    for i in range(len(u) - 1):
        s = float((f[i + 1] - f[i]) / (u[i + 1] - u[i]))
        segs.append((float(u[i]), float(u[i + 1]), float(f[i] - s * u[i]), s))
    s = float(tail_slope)
    segs.append((float(u[-1]), math.inf, float(f[-1] - s * u[-1]), s))
    return segs


def evaluate_bands(table: BandTable, u: Any) -> FloatArray:
    """The piecewise-linear friction magnitude of a band table at sliding speeds ``u``.

    Parameters
    ----------
    table : BandTable
        A law's band table, as its ``bands(lam, gamma)`` method returns it.
    u : array_like
        Sliding speeds ``1 - xi'``, dimensionless.

    Returns
    -------
    ndarray
        Friction magnitude ``F(u)``, dimensionless.
    """
    edges, intercepts, slopes = table
    uu = np.asarray(u, dtype=np.float64)
    b = np.clip(np.searchsorted(edges, uu, side="right") - 1, 0, len(intercepts) - 1)
    return np.asarray(intercepts[b] + slopes[b] * uu, dtype=np.float64)


@dataclass(frozen=True)
class CoulombFriction:
    """The paper's two-valued law: ``mu = mu_k`` while sliding, ``F = gamma lambda`` (default).

    One band ``[0, inf)``; results are bit for bit those of the engine before friction laws.
    """

    exact = True

    def bands(self, lam: float, gamma: float) -> BandTable:
        """Band table ``(edges, intercepts, slopes)``: ``([0, inf], [gamma lam], [0])``."""
        return np.array([0.0, math.inf]), np.array([gamma * lam]), np.array([0.0])

    def value(self, u: Any, lam: float, gamma: float) -> FloatArray:
        """Exact dimensionless friction magnitude ``F(u)``."""
        return np.full(np.shape(u), gamma * lam)

    def slope_at(self, u: float, lam: float, gamma: float) -> float:
        """Exact ``dF/du`` at the sliding speed ``u`` (0)."""
        return 0.0

    def describe(self) -> str:
        """One line: the law and how it is computed."""
        return "coulomb, exact"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready parameters."""
        return {"law": "coulomb"}


@dataclass(frozen=True)
class LinearFriction:
    """Kinetic friction linear in the sliding speed, ``mu = mu_k - sigma v_r``; floored at zero.

    Parameters
    ----------
    delta : float
        Dimensionless slope ``delta = sigma W / (2 sqrt(m k))`` (``sigma`` in s/m, ``W`` in N,
        ``m`` in kg, ``k`` in N/m); > 0 velocity weakening, < 0 strengthening. In slip it
        acts as a damper ``-2 delta`` on the slider's velocity. ``mu(0+) = mu_k``.

    Notes
    -----
    ``F(u) = gamma lambda - 2 delta u`` is FLOORED at zero: for weakening, beyond
    ``u* = gamma lambda / (2 delta)`` the friction is 0 (a second band). Exact.
    """

    delta: float
    exact = True

    def __post_init__(self) -> None:
        # |delta| <= MAX_PARAMETER like every other dimensionless parameter: the slip damper
        # -2 delta and the products 2 delta u stay finite (linear:-1e308 doubled to -inf and
        # gave the answer of +1e308)
        object.__setattr__(self, "delta", at_most("delta", self.delta))

    def bands(self, lam: float, gamma: float) -> BandTable:
        """Band table: one band, or two for weakening (``F = 0`` beyond ``u*``)."""
        s = -2.0 * self.delta if self.delta != 0.0 else 0.0
        return _segments_to_table([(0.0, math.inf, gamma * lam, s)])

    def value(self, u: Any, lam: float, gamma: float) -> FloatArray:
        """Exact dimensionless friction magnitude ``max(gamma lam - 2 delta u, 0)``."""
        return np.maximum(gamma * lam - 2.0 * self.delta * np.asarray(u, dtype=np.float64), 0.0)

    def slope_at(self, u: float, lam: float, gamma: float) -> float:
        """Exact ``dF/du`` at ``u`` (``-2 delta``, 0 where floored)."""
        return -2.0 * self.delta if gamma * lam - 2.0 * self.delta * u > 0.0 else 0.0

    def describe(self) -> str:
        """One line: the law and how it is computed."""
        return f"linear, delta = {self.delta:g}, exact (floored at zero)"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready parameters."""
        return {"law": "linear", "delta": self.delta}


@dataclass(frozen=True)
class TableFriction:
    """Piecewise-linear friction through points, constant beyond the last one (exact).

    Parameters
    ----------
    u : sequence of float
        Sliding speeds over the belt speed, ``u_i = v_i / V`` (dimensionless), strictly
        increasing, ``u_0 >= 0``. Below ``u_0`` the first value holds.
    f : sequence of float
        Excess friction over kinetic in units of the static-kinetic gap,
        ``f_i = (mu_i - mu_k) / (mu_s - mu_k)``, so ``F = lambda (gamma + f)``. ``f_0 <= 1``
        (``mu(0+) <= mu_s``); ``f_i >= -gamma`` (``mu >= 0``) is checked by :meth:`bands`.
    """

    u: tuple[float, ...]
    f: tuple[float, ...]
    exact = True

    def __post_init__(self) -> None:
        u = tuple(finite("u", x) for x in self.u)
        f = tuple(finite("f", x) for x in self.f)
        if len(u) == 0 or len(u) != len(f):
            raise ValueError(f"friction table needs equally many u and f values, got {len(u)} and {len(f)}")
        if u[0] < 0.0:
            raise ValueError(f"friction table speed u={u[0]!r} must not be negative")
        for a, b in itertools.pairwise(u):
            if not b > a:
                raise ValueError(f"friction table speeds must increase strictly, got {a!r} then {b!r}")
        if f[0] > 1.0:
            raise ValueError(f"friction table f(0+)={f[0]!r} exceeds 1: mu(0+) above mu_s")
        if len(u) + 1 > MAX_BANDS:
            raise ValueError(f"friction table has {len(u)} points, more than {MAX_BANDS - 1}")
        object.__setattr__(self, "u", u)
        object.__setattr__(self, "f", f)

    @classmethod
    def from_physical(
        cls, v_m_per_s: Any, mu: Any, mu_s: float, mu_k: float, speed: float
    ) -> TableFriction:
        """From sliding speeds ``v`` [m/s] and friction coefficients ``mu`` [-].

        ``mu_s``, ``mu_k``: static and kinetic coefficients that define ``lambda`` and
        ``gamma``; ``speed``: belt speed ``V`` [m/s].
        """
        mu_s = non_negative("mu_s", mu_s)
        mu_k = non_negative("mu_k", mu_k)
        if not mu_s > mu_k:
            raise ValueError(f"mu_s={mu_s!r} must exceed mu_k={mu_k!r}")
        speed = positive("speed", speed)
        mus = [finite("mu", x) for x in mu]
        for x in mus:
            if x < 0.0:
                raise TableInputError(f"friction coefficient mu={x!r} is negative")
        v = [finite("v", x) for x in v_m_per_s]
        # said in the table's own units (m/s), before the division by V of the engine's u
        if v and v[0] < 0.0:
            raise TableInputError(f"friction table speed v = {v[0]!r} m/s must not be negative")
        for a, b in itertools.pairwise(v):
            if not b > a:
                raise TableInputError(f"friction table speeds must increase strictly, got {a!r} m/s "
                                 f"then {b!r} m/s")
        if mus and mus[0] > mu_s:
            raise TableInputError(f"friction table mu(0+) = {mus[0]!r} exceeds mu_s = {mu_s!r}: "
                             "sliding would hold more than sticking")
        u = [x / speed for x in v]
        return cls(tuple(u), tuple((x - mu_k) / (mu_s - mu_k) for x in mus))

    def bands(self, lam: float, gamma: float) -> BandTable:
        """Band table; refuses a table with ``f < -gamma`` (negative friction)."""
        for x in self.f:
            if x < -gamma:
                raise ValueError(f"friction table value f={x!r} is below -gamma={-gamma!r}: mu < 0")
        u = np.array(self.u)
        f = lam * (gamma + np.array(self.f))
        return _segments_to_table(_through_points(u, f, 0.0))

    def value(self, u: Any, lam: float, gamma: float) -> FloatArray:
        """Exact dimensionless friction magnitude ``lambda (gamma + f(u))``."""
        return lam * (gamma + np.interp(np.asarray(u, dtype=np.float64), self.u, self.f))

    def slope_at(self, u: float, lam: float, gamma: float) -> float:
        """Exact ``dF/du`` at ``u`` (right derivative at a point)."""
        edges, _, slopes = self.bands(lam, gamma)
        return float(slopes[np.searchsorted(edges, u, side="right") - 1])

    def describe(self) -> str:
        """One line: the law and how it is computed."""
        return f"table, {len(self.u)} points, exact (piecewise linear)"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready parameters."""
        return {"law": "table", "u": list(self.u), "f": list(self.f)}



#: Supported range of each Stribeck parameter, ``field: (low, high, why)``; outside it the
#: law overflows, cannot be tabulated or defeats the engine. ``u_s`` like a mass ratio
#: (``MIN_RATIO`` to ``MAX_PARAMETER``: ``u_s**2`` and ``u / u_s`` stay finite; 1e308 and
#: 1e-308 overflowed). ``n`` from 0.5, the low end of measured exponents (the slope
#: ``dF/du ~ u**(n-1)`` is infinite at ``u = 0`` for ``n < 1``: at ``n = 0.25`` the engine's
#: steps shrink until the step budget is spent, a division by zero at ``v_s/V = 1e-6``; at
#: ``n = 1e-3`` the last node ``U = u_s ln(2 r0 / tol)**(1/n)`` overflowed) to 100 (the law is
#: then a step at ``u_s`` to the tolerance; ``n = 1e6`` overflowed ``x**n``). ``d_v`` and
#: ``r0`` capped at :data:`MAX_PARAMETER` like every dimensionless parameter (``2 d_v u``
#: overflowed at 1e308, ``r0 = -1e308`` made NaN).
STRIBECK_RANGES: dict[str, tuple[float, float, str]] = {
    "velocity_ratio": (MIN_RATIO, MAX_PARAMETER, "v_s / V beyond it overflows the law"),
    "exponent": (0.5, 100.0, "beyond it the law overflows or cannot be tabulated"),
    "viscous": (-MAX_PARAMETER, MAX_PARAMETER, "larger slopes overflow the dimensionless equations"),
    "mu0_ratio": (-MAX_PARAMETER, 1.0, "below it the law overflows; above 1 mu_0 exceeds mu_s"),
    "tolerance": (1e-9, 0.1, "the law approximation error in units of lambda"),
}


def check_stribeck_parameter(field: str, value: float, name: str | None = None) -> float:
    """``value`` of the Stribeck parameter ``field`` as a float within :data:`STRIBECK_RANGES`.

    ``name`` is how the caller calls it in messages (``vs`` on the command line), default the
    field's own name. Raises ``ValueError`` with one line naming it, the value and the range.

    Parameters
    ----------
    field : str
        Field of :class:`StribeckFriction` (a key of :data:`STRIBECK_RANGES`).
    value : float
        The value asked for (dimensionless).
    name : str, optional
        The name used in the error message (the user's key).

    Returns
    -------
    float
        ``value`` as a float, when it lies within the field's range.
    """
    low, high, why = STRIBECK_RANGES[field]
    return within(name or field, value, low, high, why)


@dataclass(frozen=True)
class StribeckFriction:
    """Stribeck curve ``mu = mu_k + (mu_0 - mu_k) exp(-(v_r/v_s)^n) + sigma_v v_r``.

    Dimensionless ``F(u) = lambda (gamma + r0 exp(-(u/u_s)^n)) + 2 d_v u``, floored at zero.
    Integrated exactly on a piecewise-linear interpolant with
    ``max |F - F_PL| <= tolerance * lambda`` (law approximation error, checked on 64 points
    per band); sticking and events stay exact and graze-proof.

    Parameters
    ----------
    velocity_ratio : float
        ``u_s = v_s / V`` (Stribeck velocity over belt speed), > 0.
    exponent : float, default 1
        ``n`` > 0.
    viscous : float, default 0
        ``d_v = sigma_v W / (2 sqrt(m k))`` (``sigma_v`` in s/m), dimensionless.
    mu0_ratio : float, default 1
        ``r0 = (mu_0 - mu_k) / (mu_s - mu_k) <= 1`` (``mu_0 = mu(0+) <= mu_s``).
    tolerance : float, default 1e-4
        Law approximation error in units of ``lambda``, in ``[1e-9, 0.1]``.
    """

    velocity_ratio: float
    exponent: float = 1.0
    viscous: float = 0.0
    mu0_ratio: float = 1.0
    tolerance: float = 1e-4
    exact = False

    def __post_init__(self) -> None:
        positive("velocity_ratio", self.velocity_ratio)
        positive("exponent", self.exponent)
        r0 = finite("mu0_ratio", self.mu0_ratio)
        if r0 > 1.0:
            raise ValueError(f"mu0_ratio={r0!r} exceeds 1: mu_0 above mu_s")
        tol = positive("tolerance", self.tolerance)
        if not 1e-9 <= tol <= 0.1:
            raise ValueError(f"tolerance={tol!r} must lie in [1e-9, 0.1]")
        for name in STRIBECK_RANGES:
            object.__setattr__(self, name, check_stribeck_parameter(name, getattr(self, name)))

    def _excess(self, u: Any) -> FloatArray:
        """``r0 exp(-(u/u_s)^n)`` (the Stribeck term in units of lambda)."""
        x = np.asarray(u, dtype=np.float64) / self.velocity_ratio
        with np.errstate(over="ignore"):  # x**n = inf far beyond u_s: exp(-inf) = 0, exactly
            return np.asarray(self.mu0_ratio * np.exp(-(x**self.exponent)), dtype=np.float64)

    def value(self, u: Any, lam: float, gamma: float) -> FloatArray:
        """Exact dimensionless friction magnitude (floored at zero)."""
        uu = np.asarray(u, dtype=np.float64)
        return np.maximum(lam * (gamma + self._excess(uu)) + 2.0 * self.viscous * uu, 0.0)

    def slope_at(self, u: float, lam: float, gamma: float) -> float:
        """Exact ``dF/du`` at ``u > 0`` (0 where floored)."""
        if float(self.value(u, lam, gamma)) <= 0.0:
            return 0.0
        n, us = self.exponent, self.velocity_ratio
        x = u / us
        try:
            shape = x ** (n - 1.0) * math.exp(-(x**n))
        except OverflowError:  # x**n beyond the float range: exp(-x**n) is 0 to double precision
            shape = 0.0
        return float(-lam * self.mu0_ratio * n / us * shape + 2.0 * self.viscous)

    def nodes(self) -> FloatArray:
        """Interpolation nodes in ``u`` (independent of lambda and gamma; computed once per law).

        The excess ``e(u) = r0 exp(-(u/u_s)^n)`` is interpolated to ``tolerance`` (in units of
        lambda; the viscous term is linear, so exact): nodes equidistribute ``sqrt(|e''|)``
        (the interpolation error of a band of width ``h`` is about ``h^2 |e''| / 8``), then
        every band whose error, sampled on 64 points, exceeds the tolerance is halved. Beyond
        the last node ``U`` (where ``|r0| exp(-(U/u_s)^n) <= tolerance/2``) the excess is
        dropped and the tail is linear.
        """
        return _stribeck_nodes(self).copy()

    def _compute_nodes(self) -> FloatArray:
        tol = self.tolerance
        r0, n, us = abs(self.mu0_ratio), self.exponent, self.velocity_ratio
        if r0 <= 0.5 * tol:
            return np.array([0.0])
        big_u = us * math.log(2.0 * r0 / tol) ** (1.0 / n)
        grid = np.unique(
            np.concatenate([np.linspace(0.0, big_u, 4001), big_u * np.geomspace(1e-9, 1.0, 2001)])
        )
        x = grid / us
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # e'' = r0 exp(-x^n) n x^(n-2) (n x^n - n + 1) / us^2
            d2 = r0 * np.exp(-(x**n)) * n * x ** (n - 2.0) * np.abs(n * x**n - n + 1.0) / us**2
        d2 = np.where(np.isfinite(d2), d2, 0.0)
        dens = np.sqrt(d2 / (8.0 * 0.5 * tol))
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(grid))])
        count = max(1, math.ceil(cum[-1]))
        if count > MAX_BANDS:
            raise ValueError(
                f"the Stribeck law needs about {count} bands, more than {MAX_BANDS}; loosen the tolerance"
            )
        nodes = list(np.interp(np.linspace(0.0, cum[-1], count + 1), cum, grid))
        nodes[0], nodes[-1] = 0.0, big_u
        frac = np.linspace(0.0, 1.0, 66)[1:-1]
        for _ in range(60):
            arr = np.array(nodes)
            lo, hi = arr[:-1], arr[1:]
            pts = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
            e_lo, e_hi = self._excess(lo), self._excess(hi)
            interp = e_lo[:, None] + (e_hi - e_lo)[:, None] * frac[None, :]
            err = np.max(np.abs(self._excess(pts) - interp), axis=1)
            bad = np.nonzero(err > tol)[0]
            if bad.size == 0:
                break
            mids = 0.5 * (lo[bad] + hi[bad])
            nodes = sorted(nodes + list(mids))
            if len(nodes) > MAX_BANDS:
                raise ValueError(f"the Stribeck law needs more than {MAX_BANDS} bands; loosen the tolerance")
        else:
            raise ValueError("the Stribeck interpolant did not reach its tolerance in 60 refinements")
        return np.array(nodes)

    def bands(self, lam: float, gamma: float) -> BandTable:
        """Band table of the floored piecewise-linear interpolant (``<= tolerance * lambda``)."""
        u = self.nodes()
        f = lam * (gamma + self._excess(u)) + 2.0 * self.viscous * u
        if u.size == 1:
            return _segments_to_table([(0.0, math.inf, float(f[0]), 2.0 * self.viscous)])
        return _segments_to_table(_through_points(u, f, 2.0 * self.viscous))

    def describe(self) -> str:
        """One line: the law and how it is computed."""
        return (
            f"stribeck, v_s/V = {self.velocity_ratio:g}, n = {self.exponent:g}, viscous = {self.viscous:g}, "
            f"mu0 ratio = {self.mu0_ratio:g}; piecewise-linear interpolant, law error "
            f"|F - F_PL| <= {self.tolerance:g} lambda, integrated exactly"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready parameters."""
        return {
            "law": "stribeck",
            "velocity_ratio": self.velocity_ratio,
            "exponent": self.exponent,
            "viscous": self.viscous,
            "mu0_ratio": self.mu0_ratio,
            "tolerance": self.tolerance,
        }


FrictionLaw = CoulombFriction | LinearFriction | TableFriction | StribeckFriction




@functools.lru_cache(maxsize=64)
def _stribeck_nodes(law: StribeckFriction) -> FloatArray:
    """The nodes of a Stribeck law, cached: a map or a tuning evaluates the same law many times."""
    return law._compute_nodes()
