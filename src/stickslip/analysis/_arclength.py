"""Pseudo-arclength continuation of fixed points ``G(y, p) = 0`` of a section's return map.

A branch ``{(y, p) : G(y, p) = P(y; p) - y = 0}`` is traced by pseudo-arclength continuation:
predictor along the unit tangent ``t`` (the null vector of ``[D_y G, D_p G]``, ``D_p G`` by
central differences in ``p``), corrector by Newton's method on ``G = 0`` and
``t . ((y, p) - predicted) = 0``. Step-size control: a step is accepted when the corrector
converges in at most :data:`FAST_NEWTON` + 3 iterations, the phase signature (the sequence of
slip-I, slip-II and stick phases) is unchanged and the tangent turns by less than
:data:`MAX_TURN` rad (so a fold is never stepped over: at a fold the tangent turns through
vertical); otherwise the step is halved. Steps grow by 1.5 after a fast convergence.

Events between two accepted points are located by bisection in the arclength step (each trial
point is a converged point of the branch) to :data:`EVENT_TOL`:

* ``fold``: the tangent's parameter component changes sign (a multiplier crosses +1);
* ``period-doubling``: ``det(D P + I)`` changes sign (a real multiplier crosses -1);
* ``torus`` (Neimark-Sacker): the number of complex multipliers outside the unit circle
  changes;
* ``grazing``: the phase signature changes, or the motion ceases to exist (the end of the
  branch, bisected on the step length).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis._periodic_sections import AnySystem, SlipSection, StickSlipSection

FloatArray = NDArray[np.float64]

#: Newton iterations of a fast corrector (the step then grows).
FAST_NEWTON = 3
#: Largest turn of the tangent per accepted step (radians).
MAX_TURN = 0.3
#: Tolerance of event locations (arclength, hence the parameter).
EVENT_TOL = 1e-10
#: Largest ratio of a step's arclength to its parameter advance cap (see :func:`step_cap`).
MAX_STRETCH = 1000.0
#: Relative finite-difference step in the parameter (central differences).
PARAM_STEP = 1e-7


@dataclass
class BranchState:
    p: float
    y: FloatArray
    jac: FloatArray
    tangent: FloatArray
    signature: tuple[int, ...]


class ArclengthTracer:
    """Pseudo-arclength continuation of one branch of one section kind."""

    def __init__(self, system: AnySystem, name: str,
                 make: Callable[[AnySystem], StickSlipSection | SlipSection]) -> None:
        self.system, self.name, self.make = system, name, make
        #: the range continued over (points outside it are not reported)
        self.bounds = (-math.inf, math.inf)
        self._cache: dict[float, StickSlipSection | SlipSection] = {}

    def section(self, p: float) -> StickSlipSection | SlipSection:
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
                ) -> tuple[BranchState, int] | None:
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
                t = unit_tangent(full, tangent)
                return BranchState(float(x[-1]), x[:-1].copy(), dp_map, t, sig), it
            system = np.vstack([full, tangent if anchor is not None else np.eye(x.size)[-1]])
            try:
                dx = np.linalg.solve(system, -res)
            except np.linalg.LinAlgError:
                return None
            x = x + dx
            if not np.all(np.isfinite(x)):
                return None
        return None

    def step(self, at: BranchState, h: float) -> tuple[BranchState, int] | None:
        anchor = np.append(at.y, at.p) + h * at.tangent
        return self.correct(anchor[:-1], float(anchor[-1]), at.tangent, anchor)


def unit_tangent(full: FloatArray, previous: FloatArray) -> FloatArray:
    """Unit null vector of ``[D_y G, D_p G]`` oriented along ``previous``."""
    _, _, vt = np.linalg.svd(full)
    t = vt[-1]
    t = t / np.linalg.norm(t)
    return t if float(t @ previous) >= 0.0 else -t


def bifurcation_tests(pt: BranchState) -> tuple[float, float, int]:
    """Fold (tangent's ``p``), period-doubling (``det(DP + I)``), complex multipliers outside."""
    mult = np.linalg.eigvals(pt.jac) if pt.jac.size else np.zeros(0, dtype=complex)
    pd = float(np.real(np.prod(mult + 1.0))) if mult.size else 1.0
    torus = int(np.sum((np.abs(mult.imag) > 1e-12) & (np.abs(mult) > 1.0)))
    return float(pt.tangent[-1]), pd, torus


def floquet_multipliers(jac: FloatArray) -> NDArray[np.complex128]:
    return (np.asarray(np.linalg.eigvals(jac), dtype=np.complex128) if jac.size
            else np.zeros(0, dtype=np.complex128))


@dataclass
class TracedRun:
    points: list[BranchState]
    events: list[tuple[str, BranchState, str]]
    stop: str


def trace_branch(tracer: ArclengthTracer, start: BranchState, lo: float, hi: float, h0: float, h_max: float,
           max_steps: int) -> TracedRun:
    """Continue from ``start`` along ``start.tangent`` until the range ends or the branch does.

    Steps adapt: they grow by 1.5 after a fast corrector, up to a parameter advance of
    ``h_max`` (:func:`step_cap`), and a branch that leaves the range ends on its end
    (:func:`land_on_bound`).

    A failed step (no convergence, a changed phase signature or too sharp a turn) is halved;
    once it is below ``1e-4`` of the range and still fails, the end of the branch is located by
    bisection on the step length (every success a converged point) to :data:`EVENT_TOL` and the
    branch stops there: ``grazing`` when the phase signature changes or the cycle ceases to
    exist, ``step-too-small`` otherwise. At most ``max_steps`` steps, accepted or not.
    """
    points = [start]
    events: list[tuple[str, BranchState, str]] = []
    h = h0
    h_small = 1e-4 * (hi - lo)
    stop = "max-steps"
    grow = True
    for _ in range(max_steps):
        at = points[-1]
        out = tracer.step(at, h)
        if out is not None and acceptable_step(at, out[0]):
            new, its = out
            if not lo <= new.p <= hi:
                # land on the end of the range itself (the parameter held there), so the
                # branch reaches it instead of stopping one step short
                bound = hi if new.p > hi else lo
                if at.p == bound:  # already on it (a branch started at the end of the range)
                    stop = "range-end"
                    break
                end = land_on_bound(tracer, at, new, bound)
                if end is not None:
                    new = end
                events += located_events(tracer, at, new)
                points.append(new)
                stop = "range-end"
                break
            events += located_events(tracer, at, new)
            points.append(new)
            if its <= FAST_NEWTON and grow:
                h = min(step_cap(new, h_max), 1.5 * h)
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
            if trial is not None and acceptable_step(at, trial[0]):
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
    return TracedRun(points, events, stop)


def step_cap(at: BranchState, h_max: float) -> float:
    """Largest step from ``at``: ``h_max`` of parameter advance, i.e. ``h_max / |t_p|`` of
    arclength (at most :data:`MAX_STRETCH` times ``h_max``). Where the branch's coordinates
    move much faster than the parameter (a machine continued in m/s, a steep branch) a cap on
    the arclength alone would make hundreds of tiny steps; the turn and Newton checks still
    halve any step that goes too far."""
    return h_max / max(abs(float(at.tangent[-1])), 1.0 / MAX_STRETCH)


def land_on_bound(tracer: ArclengthTracer, at: BranchState, beyond: BranchState, bound: float
                  ) -> BranchState | None:
    """The branch's point at ``p = bound``, between the accepted ``at`` (inside the range) and
    ``beyond`` (outside): Newton with the parameter held, from the linear interpolation; None
    when it does not converge or is not a step of the branch (see :func:`acceptable_step`)."""
    w = (bound - at.p) / (beyond.p - at.p)
    guess = at.y + w * (beyond.y - at.y)
    out = tracer.correct(guess, bound, at.tangent, None)
    if out is None or not acceptable_step(at, out[0]):
        return None
    return out[0]


def acceptable_step(at: BranchState, new: BranchState) -> bool:
    """Same phase signature, and the tangent turned by less than :data:`MAX_TURN`."""
    return new.signature == at.signature and float(new.tangent @ at.tangent) >= math.cos(MAX_TURN)


def located_events(tracer: ArclengthTracer, a: BranchState, b: BranchState
                   ) -> list[tuple[str, BranchState, str]]:
    """Events between the accepted points ``a`` and ``b``, each located by bisection."""
    ta, tb = bifurcation_tests(a), bifurcation_tests(b)
    found: list[tuple[str, BranchState, str]] = []
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
            tm = bifurcation_tests(pt)
            same = (tm[idx] * ta[idx] > 0.0) if idx < 2 else (tm[2] == ta[2])
            if same:
                lo_h = mid
            else:
                hi_h, best = mid, pt
        found.append((name, best, ""))
    return found
