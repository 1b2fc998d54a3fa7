"""Continuation of periodic motions in one parameter: bifurcation diagrams (DESIGN.md section 12).

Periodic motions are fixed points of an exact return map on a Poincare section:

* **stick-slip cycles** on the breakaway section of :mod:`stickslip.analysis.cycles`
  (``xi' = 1``, ``S = lambda``; unknowns ``b``, the foundation's coordinates, ``2 n - 2`` of
  them), ``P^k(b) = b`` with the exact Jacobian of saltation matrices
  (:meth:`stickslip.analysis.cycles._ReturnMap.linearise`);
* **slip oscillations** (never sticking, velocity-dependent friction) on the section of a
  velocity maximum of the slider, ``xi'' = 0`` with ``xi''' < 0``: the unknowns are the slider's
  peak velocity ``xi'`` and the foundation's coordinates (``2 n - 1``), ``xi`` follows from
  ``xi'' = 0``. The map is evaluated exactly by the engine (the next velocity maximum is the
  root of ``xi''`` on the recorded run); its Jacobian by central differences (the section is
  crossed transversally, the flow is smooth in slip: a piecewise-linear friction law is
  continuous across its band edges).

A branch ``{(y, p) : G(y, p) = P(y; p) - y = 0}`` is traced by pseudo-arclength continuation:
predictor along the unit tangent ``t`` (the null vector of ``[D_y G, D_p G]``, ``D_p G`` by
central differences in ``p``), corrector by Newton's method on ``G = 0`` and
``t . ((y, p) - predicted) = 0``. Step-size control: a step is accepted when the corrector
converges in at most :data:`FAST_NEWTON` + 3 iterations, the phase signature (the sequence of
slip-I, slip-II and stick phases) is unchanged and the tangent turns by less than
:data:`MAX_TURN` rad (so a fold is never stepped over: at a fold the tangent turns through
vertical); otherwise the step is halved. Steps grow by 1.5 after a fast convergence.

Events between two accepted points are located by bisection in the arclength step (each trial
point is a converged point of the branch) to :data:`EVENT_TOL` in the parameter:

* ``fold``: the tangent's parameter component changes sign (a multiplier crosses +1);
* ``period-doubling``: ``det(D P + I)`` changes sign (a real multiplier crosses -1);
* ``torus`` (Neimark-Sacker): the number of complex multipliers outside the unit circle
  changes;
* ``grazing``: the phase signature changes (a stick phase appears or vanishes, or a slip
  oscillation touches the belt speed); the branch of that cycle ends there;
* ``hopf``: steady sliding gains or loses stability (:mod:`stickslip.analysis.stability`).

On the rigid base a stick-slip cycle has no free coordinate (the breakaway state is unique), so
its branch is the interval of the parameter where the run from that state returns to a
breakaway; its end, the grazing point, is located by bisection on that exact, graze-proof
predicate (Eq. 36 for the Coulomb law).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.cycles import _ReturnMap, find_cycles
from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.analysis.stability import growth_rate, hopf_weakenings, one_sided_slopes, slip_matrix
from stickslip.analysis.verdict import Verdict
from stickslip.kernel.system import SLIP_I, SLIP_II
from stickslip.model.friction import CoulombFriction, FrictionLaw, LinearFriction, evaluate_bands
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Foundation, Slider
from stickslip.model.structure import Structure, chain_structure

FloatArray = NDArray[np.float64]

#: Parameters a branch can be continued in (``delta`` needs the linear law; ``K``, ``M``,
#: ``zeta_a`` a foundation).
PARAMETERS = ("lam", "zeta", "gamma", "delta", "K", "M", "zeta_a")
#: Newton iterations of a fast corrector (the step then grows).
FAST_NEWTON = 3
#: Largest turn of the tangent per accepted step (radians).
MAX_TURN = 0.3
#: Tolerance of event locations in the parameter.
EVENT_TOL = 1e-10
#: Peak velocity of the first slip oscillation computed next to a Hopf point.
SLIP_START = 0.02
#: Relative finite-difference step in the parameter (central differences).
PARAM_STEP = 1e-7


@dataclass(frozen=True)
class ContinuationSystem:
    """The system continued: the options of ``stickslip cycles`` as one value.

    Parameters
    ----------
    lam, zeta, gamma : float
        The slider (Eqs. 19-27, dimensionless).
    foundation : Foundation or None
        The elastic foundation (None: rigid base).
    friction : FrictionLaw
        The friction law (section 8 of DESIGN.md).
    """

    lam: float
    zeta: float
    gamma: float = 2.0
    foundation: Foundation | None = None
    friction: FrictionLaw = field(default_factory=CoulombFriction)

    def value(self, name: str) -> float:
        """The current value of parameter ``name`` (one of :data:`PARAMETERS`)."""
        check_parameter(self, name)
        if name in ("lam", "zeta", "gamma"):
            return float(getattr(self, name))
        if name == "delta":
            assert isinstance(self.friction, LinearFriction)
            return float(self.friction.delta)
        f = self.foundation
        assert f is not None
        return float({"K": f.stiffness_ratio, "M": f.mass_ratio, "zeta_a": f.damping_ratio}[name])

    def with_value(self, name: str, value: float) -> ContinuationSystem:
        """The same system with parameter ``name`` set to ``value``."""
        check_parameter(self, name)
        if name == "lam":
            return replace(self, lam=float(value))
        if name == "zeta":
            return replace(self, zeta=float(value))
        if name == "gamma":
            return replace(self, gamma=float(value))
        if name == "delta":
            return replace(self, friction=LinearFriction(float(value)))
        f = self.foundation
        assert f is not None
        if name == "K":
            return replace(self, foundation=replace(f, stiffness_ratio=float(value)))
        if name == "M":
            return replace(self, foundation=replace(f, mass_ratio=float(value)))
        return replace(self, foundation=replace(f, damping_ratio=float(value)))

    def build(self) -> tuple[Structure, Slider]:
        """The engine's structure and slider."""
        structure = chain_structure(self.zeta, () if self.foundation is None else (self.foundation,))
        return structure, Slider(self.lam, gamma=self.gamma, friction=self.friction)


def check_parameter(system: ContinuationSystem, name: str) -> None:
    """Refuse a parameter the system cannot be continued in (``ValueError``, one line)."""
    if name not in PARAMETERS:
        raise ValueError(f"parameter {name!r} is not one of {', '.join(PARAMETERS)}")
    if name == "delta" and not isinstance(system.friction, LinearFriction):
        raise ValueError("parameter 'delta' needs the linear friction law (--friction linear:DELTA)")
    if name in ("K", "M", "zeta_a") and system.foundation is None:
        raise ValueError(f"parameter {name!r} needs a foundation (--dva), not the rigid base")


# --------------------------------------------------------------------------- sections


class _StickSlipSection:
    """``G(b) = P^k(b) - b`` on the breakaway section, exact Jacobian."""

    kind = "stick-slip"

    def __init__(self, system: ContinuationSystem, k: int, options: EngineOptions,
                 direction: int = SLIP_I) -> None:
        self.structure, self.slider = system.build()
        self.k = k
        self.pmap = _ReturnMap(self.structure, self.slider, options, direction)
        self.dim = 2 * self.structure.n_dof - 2

    def residual(self, y: FloatArray) -> tuple[FloatArray, FloatArray] | None:
        if self.dim == 0:
            return (np.zeros(0), np.zeros((0, 0))) if self.pmap(np.zeros(0), self.k) is not None else None
        out = self.pmap.linearise(y, self.k)
        if out is None:
            return None
        pb, jac = out
        return pb - y, jac

    def gap(self, y: FloatArray) -> FloatArray | None:
        """``P^k(y) - y`` without the Jacobian."""
        py = self.pmap(y, self.k)
        return None if py is None else py - y

    def signature(self, y: FloatArray) -> tuple[int, ...] | None:
        return self.pmap.signature(y, self.k)

    def full_state(self, y: FloatArray) -> FloatArray:
        return self.pmap.state(y)

    def measure(self, y: FloatArray) -> tuple[float, float, float] | None:
        """Period, amplitude and stick ratio of the cycle, from a certifying run."""
        n = self.structure.n_dof
        z = self.full_state(y)
        run = simulate(self.structure, self.slider, initial=InitialState(z[:n], z[n:]),
                       options=self.pmap.options, record=False)
        if run.verdict is not Verdict.STICK_SLIP or run.period is None or run.amplitude is None:
            return None
        return float(run.period), float(run.amplitude), float(run.stick_ratio or 0.0)


class _SlipSection:
    """``G(y) = P(y) - y`` on the section of a velocity maximum, ``y = (xi', foundation)``."""

    kind = "slip-oscillation"

    def __init__(self, system: ContinuationSystem, options: EngineOptions) -> None:
        self.structure, self.slider = system.build()
        st = self.structure
        self.n = st.n_dof
        self.dim = 2 * self.n - 1
        self.minv = np.linalg.inv(st.mass)
        self.bands = self.slider.friction.bands(float(self.slider.lam), float(self.slider.gamma))
        self.f_ref = float(self.slider.lam * self.slider.gamma)
        self.options = EngineOptions(t_max=options.t_max, max_events=min(
            100_000, 400 * len(self.bands[1]) + 400))
        self.last: tuple[float, float, float] | None = None

    def _force(self, v0: float) -> float:
        """Friction on the slider in slip-I in shifted coordinates, ``F(1 - xi') - gamma lambda``."""
        return float(evaluate_bands(self.bands, 1.0 - v0)) - self.f_ref

    def accel(self, z: FloatArray) -> FloatArray:
        n, st = self.n, self.structure
        f = np.zeros(n)
        f[0] = self._force(float(z[n]))
        return np.asarray(self.minv @ (f - st.damping @ z[n:] - st.stiffness @ z[:n]))

    def full_state(self, y: FloatArray) -> FloatArray:
        """The state with ``xi'' = 0`` (solved for ``xi``, linear in it)."""
        n, st = self.n, self.structure
        q = np.zeros(n)
        v = np.zeros(n)
        v[0] = y[0]
        q[1:], v[1:] = y[1:n], y[n:]
        # row 0 of M^-1 (f - C v - K q) = 0, linear in q0
        r = self.minv[0]
        rest = r @ (np.eye(n)[0] * self._force(v[0]) - st.damping @ v - st.stiffness @ q)
        coef = float(r @ st.stiffness[:, 0])
        q[0] = rest / coef
        return np.concatenate([q, v])

    def reduce(self, z: FloatArray) -> FloatArray:
        n = self.n
        return np.concatenate([z[n:n + 1], z[1:n], z[n + 1:]])

    def step(self, y: FloatArray) -> FloatArray | None:
        """The next velocity maximum (reduced), or None when the slider sticks or no maximum.

        Also keeps ``(period, amplitude, max velocity)`` of the run in :attr:`last`.
        """
        n = self.n
        z0 = self.full_state(y)
        if not np.all(np.isfinite(z0)) or z0[n] >= 1.0:
            return None
        # a period of the slowest mode bounds the search for the next maximum
        omega = np.abs(np.linalg.eigvals(slip_matrix(self.structure, 0.0)).imag)
        omega = omega[omega > 1e-9]
        horizon = 3.0 * 2.0 * math.pi / float(omega.min()) if omega.size else 60.0
        run = simulate(self.structure, self.slider, initial=InitialState(z0[:n], z0[n:]),
                       options=self.options.with_t_max(horizon), record=True, run_to_t_max=True)
        t_end = float(run.t_end)
        grid = np.linspace(0.0, t_end, 400)
        q, v, modes = run.state_at(grid)
        if np.any(modes != 0):
            return None  # it sticks or slides faster than the belt: not a slip oscillation
        st = self.structure
        force = np.zeros_like(q)
        force[:, 0] = evaluate_bands(self.bands, 1.0 - v[:, 0]) - self.f_ref
        acc = ((force - v @ st.damping.T - q @ st.stiffness.T) @ self.minv.T)[:, 0]
        start = int(np.argmax(grid > 1e-6 * t_end + 1e-9))
        for i in range(max(start, 1), grid.size - 1):
            if acc[i] > 0.0 >= acc[i + 1]:
                t_peak = _root(lambda t: self._accel_at(run, t), grid[i], grid[i + 1])
                zq, zv, _ = run.state_at(np.array([t_peak]))
                z1 = np.concatenate([zq[0], zv[0]])
                x_ext = self._xi_extrema(run, t_peak)
                self.last = (t_peak, 0.5 * (max(x_ext) - min(x_ext)), float(z1[n]))
                return self.reduce(z1)
        return None

    def _accel_at(self, run: Any, t: float) -> float:
        q, v, _ = run.state_at(np.array([t]))
        return float(self.accel(np.concatenate([q[0], v[0]]))[0])

    def _xi_extrema(self, run: Any, t_end: float) -> list[float]:
        """``xi`` at the roots of ``xi'`` in ``[0, t_end]`` (and at the ends)."""
        grid = np.linspace(0.0, t_end, 200)
        q, v, _ = run.state_at(grid)
        out = [float(q[0, 0]), float(q[-1, 0])]
        for i in range(grid.size - 1):
            if v[i, 0] * v[i + 1, 0] < 0.0:
                t = _root(lambda s: float(run.state_at(np.array([s]))[1][0, 0]), grid[i], grid[i + 1])
                out.append(float(run.state_at(np.array([t]))[0][0, 0]))
        return out

    def residual(self, y: FloatArray) -> tuple[FloatArray, FloatArray] | None:
        py = self.step(y)
        if py is None:
            return None
        last = self.last
        jac = np.zeros((self.dim, self.dim))
        for j in range(self.dim):
            h = 1e-6 * max(1.0, abs(float(y[j])))
            e = np.zeros(self.dim)
            e[j] = h
            plus, minus = self.step(y + e), self.step(y - e)
            if plus is None or minus is None:
                return None
            jac[:, j] = (plus - minus) / (2.0 * h)
        self.last = last
        return py - y, jac

    def gap(self, y: FloatArray) -> FloatArray | None:
        """``P(y) - y`` without the Jacobian."""
        py = self.step(y)
        return None if py is None else py - y

    def signature(self, y: FloatArray) -> tuple[int, ...] | None:
        return (0,) if self.step(y) is not None else None

    def measure(self, y: FloatArray) -> tuple[float, float, float] | None:
        if self.step(y) is None or self.last is None:
            return None
        return self.last[0], self.last[1], 0.0


def _root(f: Callable[[float], float], a: float, b: float) -> float:
    from scipy.optimize import brentq

    return float(brentq(f, a, b, xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=200))


# --------------------------------------------------------------------------- results


@dataclass(frozen=True)
class BranchPoint:
    """One periodic motion on a branch (dimensionless: ``tau``, ``V/omega_n``)."""

    param: float
    period: float
    amplitude: float
    stick_ratio: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    stable: bool
    state: FloatArray = field(repr=False)

    @property
    def multiplier(self) -> float:
        """Largest Floquet multiplier modulus (0 for the rigid base's stick-slip cycle)."""
        return float(np.max(np.abs(self.multipliers))) if self.multipliers.size else 0.0

    def to_dict(self, name: str) -> dict[str, Any]:
        return {name: self.param, "period": self.period, "amplitude": self.amplitude,
                "stick_ratio": self.stick_ratio, "multiplier": self.multiplier, "stable": self.stable}


@dataclass(frozen=True)
class Branch:
    """A continued branch: its kind, points in order of arclength and why it stopped."""

    kind: str
    stick_phases: int
    points: tuple[BranchPoint, ...]
    stop_reason: str

    def to_dict(self, name: str) -> dict[str, Any]:
        return {"kind": self.kind, "stick_phases": self.stick_phases, "stop_reason": self.stop_reason,
                "points": [p.to_dict(name) for p in self.points]}


@dataclass(frozen=True)
class Event:
    """A named point: ``type`` is fold, period-doubling, torus, grazing or hopf."""

    type: str
    param: float
    amplitude: float
    branch: int | None
    detail: str = ""

    def to_dict(self, name: str) -> dict[str, Any]:
        return {"type": self.type, name: self.param, "amplitude": self.amplitude,
                "branch": self.branch, "detail": self.detail}


@dataclass(frozen=True)
class ContinuationResult:
    """Outcome of :func:`continue_cycles`: branches, steady sliding along the range, events."""

    system: ContinuationSystem
    param: str
    param_range: tuple[float, float]
    branches: tuple[Branch, ...]
    steady_param: FloatArray = field(repr=False)
    steady_growth: FloatArray = field(repr=False)
    events: tuple[Event, ...]

    @property
    def steady_stable(self) -> NDArray[np.bool_]:
        return np.asarray(self.steady_growth < 0.0)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, the keys of ``stickslip continue --json``."""
        name = self.param
        s = self.system
        return {
            "param": name,
            "range": list(self.param_range),
            "system": {"lam": s.lam, "zeta": s.zeta, "gamma": s.gamma,
                       "foundation": None if s.foundation is None else {
                           "M": s.foundation.mass_ratio, "K": s.foundation.stiffness_ratio,
                           "zeta_a": s.foundation.damping_ratio},
                       "friction": s.friction.describe()},
            "branches": [b.to_dict(name) for b in self.branches],
            "steady": [{name: float(p), "growth_rate": float(g), "stable": bool(g < 0.0)}
                       for p, g in zip(self.steady_param, self.steady_growth, strict=True)],
            "events": [e.to_dict(name) for e in self.events],
        }

    def summary(self) -> str:
        """A few lines: the branches, their ranges and the events."""
        lines = [f"continuation in {self.param} over [{self.param_range[0]:g}, {self.param_range[1]:g}]: "
                 f"{len(self.branches)} branch(es), {len(self.events)} event(s)"]
        for i, b in enumerate(self.branches):
            ps = [p.param for p in b.points]
            lines.append(f"  branch {i}: {b.kind}, {b.stick_phases} stick phase(s), {len(ps)} points, "
                         f"{self.param} in [{min(ps):.6g}, {max(ps):.6g}], stopped: {b.stop_reason}")
        for e in self.events:
            lines.append(f"  {e.type} at {self.param} = {e.param:.10g} "
                         f"(amplitude {e.amplitude:.6g}) {e.detail}")
        return "\n".join(lines)

    def to_xarray(self) -> Any:
        """Points of every branch along one ``point`` dimension, steady sliding, events (CF attrs)."""
        import xarray as xr

        rows = [(i, p) for i, b in enumerate(self.branches) for p in b.points]
        ds = xr.Dataset(
            {
                "branch": ("point", np.array([i for i, _ in rows], dtype=np.int64)),
                self.param: ("point", np.array([p.param for _, p in rows])),
                "period": ("point", np.array([p.period for _, p in rows])),
                "amplitude": ("point", np.array([p.amplitude for _, p in rows])),
                "stick_ratio": ("point", np.array([p.stick_ratio for _, p in rows])),
                "multiplier": ("point", np.array([p.multiplier for _, p in rows])),
                "stable": ("point", np.array([p.stable for _, p in rows], dtype=np.int8),
                           {"flag_values": [0, 1], "flag_meanings": "unstable stable"}),
                "steady_" + self.param: ("steady", np.asarray(self.steady_param)),
                "steady_growth_rate": ("steady", np.asarray(self.steady_growth),
                                       {"units": "1", "long_name": "largest real part, per tau"}),
                "event_type": ("event", np.array([e.type for e in self.events], dtype=str)),
                "event_" + self.param: ("event", np.array([e.param for e in self.events])),
                "event_amplitude": ("event", np.array([e.amplitude for e in self.events])),
            },
            attrs={"branch_kinds": " ".join(b.kind for b in self.branches),
                   "branch_stop_reasons": "; ".join(b.stop_reason for b in self.branches),
                   "parameter": self.param},
        )
        return ds

    def plot(self, **kwargs: Any) -> Any:
        """The bifurcation diagram (:func:`stickslip.plot.continuation.continuation_plot`)."""
        from stickslip.plot.continuation import continuation_plot

        return continuation_plot(self, **kwargs)


# --------------------------------------------------------------------------- continuation


@dataclass
class _Point:
    p: float
    y: FloatArray
    jac: FloatArray
    tangent: FloatArray
    signature: tuple[int, ...]


class _Tracer:
    """Pseudo-arclength continuation of one branch of one section kind."""

    def __init__(self, system: ContinuationSystem, name: str,
                 make: Callable[[ContinuationSystem], _StickSlipSection | _SlipSection]) -> None:
        self.system, self.name, self.make = system, name, make
        #: the range continued over (points outside it are not reported)
        self.bounds = (-math.inf, math.inf)
        self._cache: dict[float, _StickSlipSection | _SlipSection] = {}

    def section(self, p: float) -> _StickSlipSection | _SlipSection:
        if p not in self._cache:
            if len(self._cache) > 64:
                self._cache.clear()
            self._cache[p] = self.make(self.system.with_value(self.name, p))
        return self._cache[p]

    def valid(self, p: float) -> bool:
        """Whether the parameter value makes a valid system (e.g. ``lambda > 0``)."""
        try:
            self.section(p)
        except ValueError:
            return False
        return True

    def jacobians(self, y: FloatArray, p: float) -> tuple[FloatArray, FloatArray, FloatArray] | None:
        """``G``, ``[D_y G, D_p G]`` and ``D P`` at ``(y, p)``."""
        h = PARAM_STEP * max(1.0, abs(p))
        if not (self.valid(p) and self.valid(p + h) and self.valid(p - h)):
            return None
        out = self.section(p).residual(y)
        if out is None:
            return None
        g, dp_map = out
        plus, minus = self.section(p + h).gap(y), self.section(p - h).gap(y)
        if plus is None or minus is None:
            return None
        gp = (plus - minus) / (2.0 * h)
        full = np.column_stack([dp_map - np.eye(y.size), gp])
        return g, full, dp_map

    def correct(self, y: FloatArray, p: float, tangent: FloatArray, anchor: FloatArray | None
                ) -> tuple[_Point, int] | None:
        """Newton on ``G = 0`` plus ``t . (x - anchor) = 0`` (or ``p`` fixed when anchor is None)."""
        x = np.append(y, p)
        for it in range(FAST_NEWTON + 4):
            ev = self.jacobians(x[:-1], float(x[-1]))
            if ev is None:
                return None
            g, full, dp_map = ev
            extra = float(tangent @ (x - anchor)) if anchor is not None else 0.0
            res = np.append(g, extra)
            scale = max(1.0, float(np.max(np.abs(x))))
            if np.max(np.abs(g)) <= 1e-11 * scale and abs(extra) <= 1e-11 * scale and it > 0:
                sig = self.section(float(x[-1])).signature(x[:-1])
                if sig is None:
                    return None
                t = _tangent(full, tangent)
                return _Point(float(x[-1]), x[:-1].copy(), dp_map, t, sig), it
            system = np.vstack([full, tangent if anchor is not None else np.eye(x.size)[-1]])
            try:
                dx = np.linalg.solve(system, -res)
            except np.linalg.LinAlgError:
                return None
            x = x + dx
            if not np.all(np.isfinite(x)):
                return None
        return None

    def step(self, at: _Point, h: float) -> tuple[_Point, int] | None:
        anchor = np.append(at.y, at.p) + h * at.tangent
        return self.correct(anchor[:-1], float(anchor[-1]), at.tangent, anchor)


def _tangent(full: FloatArray, previous: FloatArray) -> FloatArray:
    """Unit null vector of ``[D_y G, D_p G]`` oriented along ``previous``."""
    _, _, vt = np.linalg.svd(full)
    t = vt[-1]
    t = t / np.linalg.norm(t)
    return t if float(t @ previous) >= 0.0 else -t


def _tests(pt: _Point) -> tuple[float, float, int]:
    """Fold (tangent's ``p``), period-doubling (``det(DP + I)``), complex multipliers outside."""
    mult = np.linalg.eigvals(pt.jac) if pt.jac.size else np.zeros(0, dtype=complex)
    pd = float(np.real(np.prod(mult + 1.0))) if mult.size else 1.0
    torus = int(np.sum((np.abs(mult.imag) > 1e-12) & (np.abs(mult) > 1.0)))
    return float(pt.tangent[-1]), pd, torus


def _multipliers(jac: FloatArray) -> NDArray[np.complex128]:
    return (np.asarray(np.linalg.eigvals(jac), dtype=np.complex128) if jac.size
            else np.zeros(0, dtype=np.complex128))


@dataclass
class _BranchRun:
    points: list[_Point]
    events: list[tuple[str, _Point, str]]
    stop: str


def _trace(tracer: _Tracer, start: _Point, lo: float, hi: float, h0: float, h_max: float,
           max_steps: int) -> _BranchRun:
    """Continue from ``start`` along ``start.tangent`` until the range ends or the branch does.

    A failed step (no convergence, a changed phase signature or too sharp a turn) is halved;
    once it is below ``1e-4`` of the range and still fails, the end of the branch is located by
    bisection on the step length (every success a converged point) to :data:`EVENT_TOL` and the
    branch stops there: ``grazing`` when the phase signature changes or the cycle ceases to
    exist, ``step-too-small`` otherwise. At most ``max_steps`` steps, accepted or not.
    """
    points = [start]
    events: list[tuple[str, _Point, str]] = []
    h = h0
    h_small = 1e-4 * (hi - lo)
    stop = "max-steps"
    grow = True
    for _ in range(max_steps):
        at = points[-1]
        out = tracer.step(at, h)
        if out is not None and _acceptable(at, out[0]):
            new, its = out
            events += _located_events(tracer, at, new)
            points.append(new)
            if not lo <= new.p <= hi:
                stop = "range-end"
                break
            if its <= FAST_NEWTON and grow:
                h = min(h_max, 1.5 * h)
            grow = True
            continue
        grow = False
        if h > h_small:
            h *= 0.5
            continue
        # the end of the branch: bisection on the step length
        changed = out is not None and out[0].signature != at.signature
        ok_h, bad_h, last = 0.0, h, at
        while bad_h - ok_h > EVENT_TOL:
            mid = 0.5 * (ok_h + bad_h)
            trial = tracer.step(at, mid)
            if trial is not None and _acceptable(at, trial[0]):
                ok_h, last = mid, trial[0]
            else:
                changed = changed or (trial is not None and trial[0].signature != at.signature)
                bad_h = mid
        if last is not at:
            points.append(last)
        if changed or out is None:
            events.append(("grazing", last, "a phase appears or vanishes (phase signature changes)"
                           if changed else "the periodic motion ceases to exist"))
            stop = "grazing"
        else:
            stop = "step-too-small"
        break
    return _BranchRun(points, events, stop)


def _acceptable(at: _Point, new: _Point) -> bool:
    """Same phase signature, and the tangent turned by less than :data:`MAX_TURN`."""
    return new.signature == at.signature and float(new.tangent @ at.tangent) >= math.cos(MAX_TURN)


def _located_events(tracer: _Tracer, a: _Point, b: _Point) -> list[tuple[str, _Point, str]]:
    """Events between the accepted points ``a`` and ``b``, each located by bisection."""
    ta, tb = _tests(a), _tests(b)
    found: list[tuple[str, _Point, str]] = []
    span = float(np.linalg.norm(np.append(b.y - a.y, b.p - a.p)))
    for name, idx in (("fold", 0), ("period-doubling", 1), ("torus", 2)):
        if idx < 2 and ta[idx] * tb[idx] >= 0.0:
            continue
        if idx == 2 and ta[2] == tb[2]:
            continue
        lo_h, hi_h, best = 0.0, span, b
        for _ in range(60):
            if abs(best.p - a.p) >= 0 and hi_h - lo_h <= EVENT_TOL:
                break
            mid = 0.5 * (lo_h + hi_h)
            out = tracer.step(a, mid)
            if out is None:
                break
            pt = out[0]
            tm = _tests(pt)
            same = (tm[idx] * ta[idx] > 0.0) if idx < 2 else (tm[2] == ta[2])
            if same:
                lo_h = mid
            else:
                hi_h, best = mid, pt
        found.append((name, best, ""))
    return found


def _rigid_stick_slip(system: ContinuationSystem, name: str, lo: float, hi: float, n_points: int,
                      options: EngineOptions) -> tuple[list[tuple[float, _StickSlipSection]], list[float]]:
    """Rigid base: where the cycle exists on a grid, and its ends located by bisection."""

    def exists(p: float) -> _StickSlipSection | None:
        sec = _StickSlipSection(system.with_value(name, p), 1, options)
        return sec if sec.residual(np.zeros(0)) is not None else None

    grid = np.linspace(lo, hi, n_points)
    found = [(float(p), exists(float(p))) for p in grid]
    ends: list[float] = []
    for (pa, sa), (pb, sb) in itertools.pairwise(found):
        if (sa is None) != (sb is None):
            a, b = pa, pb
            while b - a > EVENT_TOL * max(1.0, abs(a)):
                mid = 0.5 * (a + b)
                if (exists(mid) is None) == (sa is None):
                    a = mid
                else:
                    b = mid
            ends.append(0.5 * (a + b))
    points = [(p, s) for p, s in found if s is not None]
    for e in ends:  # the branch's end points themselves, on the existing side
        for q in (e - EVENT_TOL, e + EVENT_TOL):
            s = exists(q)
            if s is not None:
                points.append((q, s))
                break
    points.sort(key=lambda x: x[0])
    return points, ends


def _local_slope(system: ContinuationSystem, name: str, p: float) -> float:
    """The friction slope ``dF/du`` at the belt speed (the worse side at a kink)."""
    left, right = one_sided_slopes(system.with_value(name, p).build()[1])
    return min(left, right)


def steady_sliding_along(system: ContinuationSystem, name: str, lo: float, hi: float,
                         n_points: int = 101) -> tuple[FloatArray, FloatArray, list[float]]:
    """Growth rate of steady sliding on a grid of the range, and its Hopf points.

    Hopf points in ``delta`` (linear law) are exact: the roots of the characteristic polynomial
    (:func:`stickslip.analysis.stability.hopf_weakenings`). In any other parameter the local
    slope of the law enters the linearisation; a sign change of the growth rate between two
    grid points is then refined by Brent's method to :data:`EVENT_TOL`.
    """
    grid = np.linspace(lo, hi, n_points)

    def rate(p: float) -> float:
        structure, slider = system.with_value(name, p).build()
        left, right = one_sided_slopes(slider)
        return max(growth_rate(structure, -0.5 * left), growth_rate(structure, -0.5 * right))

    rates = np.array([rate(float(p)) for p in grid])
    hopf: list[float] = []
    if name == "delta":
        structure, _ = system.build()
        hopf = [float(d) for d in hopf_weakenings(structure) if lo <= d <= hi]
    else:
        for i in range(n_points - 1):
            if rates[i] * rates[i + 1] < 0.0:
                hopf.append(_root(rate, float(grid[i]), float(grid[i + 1])))
    return grid, rates, hopf


def continue_cycles(
    system: ContinuationSystem,
    param: str,
    param_range: tuple[float, float],
    *,
    max_period: int = 2,
    seeds: int = 12,
    max_steps: int = 400,
    n_points: int = 41,
    options: EngineOptions | None = None,
) -> ContinuationResult:
    """Bifurcation diagram of periodic motions against one parameter.

    Parameters
    ----------
    system : ContinuationSystem
        The system; its value of ``param`` is ignored (the range decides).
    param : str
        One of :data:`PARAMETERS`.
    param_range : (float, float)
        ``(A, B)``, ``A < B``.
    max_period : int
        Longest stick-slip cycle looked for by :func:`stickslip.analysis.cycles.find_cycles`
        (stick phases) at the seeding points.
    seeds : int
        Random starts of that search at each seeding point (ends and middle of the range).
    max_steps : int
        Bound on the accepted and rejected steps per branch (and the grid of the rigid base).
    n_points : int
        Rigid base: the grid on which the cycle's existence is tested before its ends are
        bisected.
    options : EngineOptions, optional
        Horizon of the runs.

    Returns
    -------
    ContinuationResult
    """
    check_parameter(system, param)
    lo, hi = float(param_range[0]), float(param_range[1])
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"range {lo!r}:{hi!r} must be finite and increasing")
    opts = options or EngineOptions()
    branches: list[Branch] = []
    events: list[Event] = []
    grid, rates, hopf = steady_sliding_along(system, param, lo, hi)
    for p in hopf:
        events.append(Event("hopf", p, 0.0, None, "steady sliding changes stability"))
    structure, _ = system.build()
    if structure.n_dof == 1:
        pts, ends = _rigid_stick_slip(system, param, lo, hi, n_points, opts)
        bps = []
        for p, sec in pts:
            m = sec.measure(np.zeros(0))
            if m is not None:
                bps.append(BranchPoint(p, *m, np.zeros(0, dtype=np.complex128), True,
                                       sec.full_state(np.zeros(0))))
        if bps:
            reason = "grazing" if ends else "range-end"
            branches.append(Branch("stick-slip", 1, tuple(bps), reason))
        for e in ends:
            amp = min(bps, key=lambda b: abs(b.param - e)).amplitude if bps else 0.0
            events.append(Event("grazing", e, amp, 0 if bps else None,
                                "the stick-slip cycle is born / ends: its slip velocity grazes "
                                "the belt speed"))
    else:
        _foundation_branches(system, param, lo, hi, max_period, seeds, max_steps, opts, branches, events)
    if not isinstance(system.friction, (CoulombFriction, LinearFriction)):
        _slip_branches(system, param, lo, hi, hopf, max_steps, opts, branches, events)
    events.sort(key=lambda e: e.param)
    return ContinuationResult(system, param, (lo, hi), tuple(branches), grid, rates, tuple(events))


def _to_branch(tracer: _Tracer, runs: list[_BranchRun], kind: str, k: int) -> tuple[Branch, list[Event]]:
    """Join a backward and a forward run into one branch, measuring every point."""
    back, fwd = runs
    ordered = list(reversed(back.points[1:])) + fwd.points
    lo, hi = tracer.bounds
    ordered = [pt for pt in ordered if lo <= pt.p <= hi]  # the step that left the range: dropped
    bps: list[BranchPoint] = []
    for pt in ordered:
        sec = tracer.section(pt.p)
        if kind == "slip-oscillation" and not np.any(pt.y):  # the Hopf point: steady sliding
            structure = tracer.system.with_value(tracer.name, pt.p).build()[0]
            omega = float(np.max(np.abs(np.linalg.eigvals(slip_matrix(structure, 0.0)).imag)))
            # the linear period there: 2 pi / omega of the critical pair (the Hopf frequency)
            critical = np.linalg.eigvals(slip_matrix(structure, _local_slope(tracer.system, tracer.name,
                                                                             pt.p)))
            omega = float(np.abs(critical[np.argmin(np.abs(critical.real))].imag)) or omega
            bps.append(BranchPoint(pt.p, 2.0 * math.pi / omega, 0.0, 0.0,
                                   np.zeros(0, dtype=np.complex128), False, np.zeros(2 * structure.n_dof)))
            continue
        m = sec.measure(pt.y)
        if m is None:
            continue
        mult = _multipliers(pt.jac)
        bps.append(BranchPoint(pt.p, *m, mult, bool(np.all(np.abs(mult) < 1.0)), sec.full_state(pt.y)))
    if len(bps) > 1 and bps[0].amplitude == 0.0:  # the Hopf end takes its neighbour's stability
        bps[0] = replace(bps[0], stable=bps[1].stable)
    reason = f"backward: {back.stop}; forward: {fwd.stop}"
    evs = []
    for typ, pt, detail in back.events + fwd.events:
        m = tracer.section(pt.p).measure(pt.y)
        evs.append(Event(typ, pt.p, m[1] if m else float("nan"), None, detail))
    return Branch(kind, k, tuple(bps), reason), evs


def _on_branch(branches: list[Branch], p: float, amplitude: float, kind: str) -> bool:
    """Whether ``(p, amplitude)`` lies on a computed branch of ``kind`` (to 1e-6 relative)."""
    for b in branches:
        if b.kind != kind:
            continue
        ps = np.array([q.param for q in b.points])
        amps = np.array([q.amplitude for q in b.points])
        for i in range(ps.size - 1):
            a0, a1 = ps[i], ps[i + 1]
            if min(a0, a1) - 1e-12 <= p <= max(a0, a1) + 1e-12:
                w = 0.0 if a1 == a0 else (p - a0) / (a1 - a0)
                if abs(amps[i] + w * (amps[i + 1] - amps[i]) - amplitude) <= 1e-3 * max(1.0, amplitude):
                    return True
        if np.any((np.abs(ps - p) <= 1e-9) & (np.abs(amps - amplitude) <= 1e-6 * max(1.0, amplitude))):
            return True
    return False


def _stick_slip_factory(k: int, opts: EngineOptions, direction: int
                        ) -> Callable[[ContinuationSystem], _StickSlipSection]:
    def make(s: ContinuationSystem) -> _StickSlipSection:
        return _StickSlipSection(s, k, opts, direction)

    return make


def _foundation_branches(system: ContinuationSystem, name: str, lo: float, hi: float, max_period: int,
                         seeds: int, max_steps: int, opts: EngineOptions, branches: list[Branch],
                         events: list[Event]) -> None:
    """Stick-slip branches with a foundation, seeded by :func:`find_cycles` at three points."""
    h_max = 0.05 * (hi - lo)
    for p0 in (lo, 0.5 * (lo + hi), hi):
        structure, slider = system.with_value(name, p0).build()
        for cycle in find_cycles(structure, slider, seeds=seeds, max_period=max_period,
                                 options=opts).cycles:
            if _on_branch(branches, p0, cycle.amplitude, "stick-slip"):
                continue
            k = cycle.stick_phases
            direction = SLIP_I if cycle.breakaway_onto == "slip-I" else SLIP_II
            tracer = _Tracer(system, name, _stick_slip_factory(k, opts, direction))
            tracer.bounds = (lo, hi)
            sec = tracer.section(p0)
            assert isinstance(sec, _StickSlipSection)
            y0 = sec.pmap.reduce(cycle.breakaway_state)
            ev = tracer.jacobians(y0, p0)
            if ev is None:
                continue
            t0 = _tangent(ev[1], np.eye(y0.size + 1)[-1])
            sig = sec.signature(y0)
            if sig is None:
                continue
            start = _Point(p0, y0, ev[2], t0, sig)
            back_start = _Point(p0, y0, ev[2], -t0, sig)
            runs = [_trace(tracer, back_start, lo, hi, 0.2 * h_max, h_max, max_steps),
                    _trace(tracer, start, lo, hi, 0.2 * h_max, h_max, max_steps)]
            branch, evs = _to_branch(tracer, runs, "stick-slip", k)
            if branch.points:
                index = len(branches)
                branches.append(branch)
                events += [replace(e, branch=index) for e in evs]


def _slip_branches(system: ContinuationSystem, name: str, lo: float, hi: float, hopf: list[float],
                   max_steps: int, opts: EngineOptions, branches: list[Branch], events: list[Event]) -> None:
    """Slip oscillations born at every Hopf point of steady sliding in the range."""
    h_max = 0.05 * (hi - lo)
    for p_h in hopf:
        tracer = _Tracer(system, name, lambda s: _SlipSection(s, opts))
        tracer.bounds = (lo, hi)
        sec = tracer.section(p_h)
        assert isinstance(sec, _SlipSection)
        # a small oscillation (peak velocity SLIP_START), foundation at rest; p from the corrector
        y0 = np.zeros(sec.dim)
        y0[0] = SLIP_START
        fix = np.eye(sec.dim + 1)[0]
        start = None
        for guess in (p_h, p_h - 1e-3 * max(1.0, abs(p_h)), p_h + 1e-3 * max(1.0, abs(p_h))):
            out = tracer.correct(y0, guess, fix, np.append(y0, guess))
            if out is not None:
                start = out[0]
                break
        if start is None:
            events.append(Event("hopf", p_h, 0.0, None, "no slip oscillation could be started here"))
            continue
        # orient towards growing amplitude; the other way the branch ends at the Hopf point
        start.tangent = start.tangent if start.tangent[0] >= 0.0 else -start.tangent
        hopf_end = _Point(p_h, np.zeros(sec.dim), np.eye(sec.dim), start.tangent, start.signature)
        runs = [_BranchRun([start, hopf_end], [], "hopf"),
                _trace(tracer, start, lo, hi, 1e-2 * (hi - lo), h_max, max_steps)]
        branch, evs = _to_branch(tracer, runs, "slip-oscillation", 0)
        if branch.points:
            index = len(branches)
            branches.append(branch)
            events += [replace(e, branch=index) for e in evs]


def slip_oscillation(system: ContinuationSystem, peak_velocity: float, *,
                     options: EngineOptions | None = None) -> BranchPoint | None:
    """The slip oscillation of ``system`` whose peak slider velocity is near ``peak_velocity``.

    Newton's method on the velocity-maximum section at fixed parameters (the corrector of the
    continuation with the parameter held); None when it does not converge.
    """
    opts = options or EngineOptions()
    tracer = _Tracer(system, "lam", lambda s: _SlipSection(s, opts))
    sec = tracer.section(system.lam)
    assert isinstance(sec, _SlipSection)
    y0 = np.zeros(sec.dim)
    y0[0] = peak_velocity
    out = tracer.correct(y0, system.lam, np.eye(sec.dim + 1)[-1], None)
    if out is None:
        return None
    pt = out[0]
    m = sec.measure(pt.y)
    if m is None or pt.y[0] <= 1e-9:  # peak velocity 0: steady sliding, not an oscillation
        return None
    mult = _multipliers(pt.jac)
    return BranchPoint(pt.p, *m, mult, bool(np.all(np.abs(mult) < 1.0)), sec.full_state(pt.y))
