"""Continuation of periodic motions in one parameter: bifurcation diagrams.

Periodic motions are fixed points of exact return maps on Poincare sections
(:mod:`stickslip.analysis._periodic_sections`: the breakaway section for stick-slip cycles, a
velocity maximum for slip oscillations), traced by pseudo-arclength continuation with events
located on the way (:mod:`stickslip.analysis._arclength`). This module seeds the branches,
joins them into a :class:`ContinuationResult` and adds steady sliding along the range:

* stick-slip branches start from the cycles :func:`stickslip.analysis.cycles.find_cycles`
  finds at :data:`SEARCH_POINTS` points of the range (its ends included), each continued
  both ways, and from its candidates (fixed points no existence proof holds for; such a
  branch is marked and :meth:`ContinuationResult.warnings` says so);
* slip oscillations (velocity-dependent laws other than the linear one, whose Hopf point is
  degenerate) start next to every Hopf point of steady sliding in the range, and from the
  ones :func:`stickslip.analysis.slip_oscillations.find_slip_oscillations` finds at the same
  points, stable or unstable, with or without a Hopf point;
* a branch that leaves the range ends on its end; one seeded twice is kept once;
* a machine in SI (:class:`MachineSystem`, ``--config``) is continued in its belt speed,
  load or friction coefficients like the dimensionless system in its groups;
* ``hopf`` events: steady sliding gains or loses stability (:mod:`stickslip.analysis.stability`).

On the rigid base a stick-slip cycle has no free coordinate (the breakaway state is unique), so
its branch is the interval of the parameter where the run from that state returns to a
breakaway; its end, the grazing point, is located by bisection on that exact, graze-proof
predicate (Eq. 36 for the Coulomb law).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis._arclength import (
    EVENT_TOL,
    ArclengthTracer,
    BranchState,
    TracedRun,
    floquet_multipliers,
    trace_branch,
    unit_tangent,
)
from stickslip.analysis._periodic_sections import (
    MACHINE_PARAMETERS,
    PARAMETERS,
    AnySystem,
    ContinuationSystem,
    MachineSystem,
    ScaledMachine,
    SlipSection,
    StickSlipSection,
    refined_root,
)
from stickslip.analysis.continuation_result import Branch, BranchPoint, ContinuationResult, Event
from stickslip.analysis.cycles import find_cycles
from stickslip.analysis.simulation import EngineOptions
from stickslip.analysis.slip_oscillations import find_slip_oscillations
from stickslip.analysis.stability import growth_rate, hopf_weakenings, one_sided_slopes, slip_matrix
from stickslip.kernel.system import SLIP_I, SLIP_II
from stickslip.model.friction import CoulombFriction, LinearFriction

FloatArray = NDArray[np.float64]

__all__ = ["MACHINE_PARAMETERS", "PARAMETERS", "Branch", "BranchPoint", "ContinuationResult",
           "ContinuationSystem", "Event", "MachineSystem",
           "continue_cycles", "slip_oscillation", "steady_sliding_along"]

#: Peak velocity of the first slip oscillation computed next to a Hopf point.
SLIP_START = 0.02
#: Points of the range (ends included) where slip oscillations are searched for and where
#: a foundation's stick-slip cycles are (:func:`find_cycles`): every branch that exists at one
#: of them is traced, whether or not an event in the range leads to it.
SEARCH_POINTS = 5


def _rigid_stick_slip(system: AnySystem, name: str, lo: float, hi: float, n_points: int,
                      options: EngineOptions) -> tuple[list[tuple[float, StickSlipSection]], list[float]]:
    """Rigid base: where the cycle exists on a grid, and its ends located by bisection."""

    def exists(p: float) -> StickSlipSection | None:
        sec = StickSlipSection(system.with_value(name, p), 1, options)
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


def _local_slope(system: AnySystem, name: str, p: float) -> float:
    """The friction slope ``dF/du`` at the belt speed (the worse side at a kink)."""
    left, right = one_sided_slopes(system.with_value(name, p).build()[1])
    return min(left, right)


def steady_sliding_along(system: AnySystem, name: str, lo: float, hi: float,
                         n_points: int = 101) -> tuple[FloatArray, FloatArray, list[float]]:
    """Growth rate of steady sliding on a grid of the range, and its Hopf points.

    Hopf points in ``delta`` (linear law) are exact: the roots of the characteristic polynomial
    (:func:`stickslip.analysis.stability.hopf_weakenings`). In any other parameter the local
    slope of the law enters the linearisation; a sign change of the growth rate between two
    grid points (across any nodes where it is exactly zero) is then refined by Brent's method to
    :data:`EVENT_TOL`.

    Parameters
    ----------
    system : ContinuationSystem
        The machine and friction law continued.
    name : str
        The parameter varied (one of :data:`PARAMETERS`).
    lo, hi : float
        The range of the parameter.
    n_points : int
        Points of the grid over the range.

    Returns
    -------
    tuple of (ndarray, ndarray, list of float)
        The grid of parameter values, the growth rate of steady sliding there (1/tau, dimensionless;
        negative: stable) and the Hopf points in the range.
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
        # a node whose rate is exactly 0 (on the Hopf point) changes no sign with either
        # neighbour: bracket across it, between the nearest nodes with a sign
        signed = np.flatnonzero(rates != 0.0)
        for i, j in itertools.pairwise(signed):
            if rates[i] * rates[j] < 0.0:
                hopf.append(refined_root(rate, float(grid[i]), float(grid[j])))
    return grid, rates, hopf


def continue_cycles(
    system: AnySystem,
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
    system.check(param)
    lo, hi = float(param_range[0]), float(param_range[1])
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"range {lo!r}:{hi!r} must be finite and increasing")
    if isinstance(system, MachineSystem):  # SI: continued in units of the range (ScaledMachine)
        scale = max(abs(lo), abs(hi))
        scaled = _continue(ScaledMachine(system, scale), param, lo / scale, hi / scale,
                           max_period, seeds, max_steps, n_points, options)
        return _unscaled(scaled, system, (lo, hi), scale)
    return _continue(system, param, lo, hi, max_period, seeds, max_steps, n_points, options)


def _unscaled(result: ContinuationResult, system: MachineSystem, param_range: tuple[float, float],
              scale: float) -> ContinuationResult:
    """``result`` of a :class:`ScaledMachine` with every parameter value back in SI (the
    range's ends exactly: a branch that reaches an end lands on it)."""
    lo, hi = param_range
    ends = {result.param_range[0]: lo, result.param_range[1]: hi}

    def back(p: float) -> float:
        return ends.get(p, p * scale)

    branches = tuple(replace(b, points=tuple(replace(q, param=back(q.param)) for q in b.points))
                     for b in result.branches)
    events = tuple(replace(e, param=back(e.param)) for e in result.events)
    steady = np.array([back(float(p)) for p in result.steady_param])
    return replace(result, system=system, param_range=param_range, branches=branches,
                   steady_param=steady, events=events)


def _continue(system: AnySystem, param: str, lo: float, hi: float, max_period: int, seeds: int,
              max_steps: int, n_points: int, options: EngineOptions | None) -> ContinuationResult:
    """:func:`continue_cycles` on ``[lo, hi]`` of ``system`` as given (no rescaling)."""
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
        _searched_slip_branches(system, param, lo, hi, seeds, max_steps, opts, branches, events)
    events.sort(key=lambda e: e.param)
    return ContinuationResult(system, param, (lo, hi), tuple(branches), grid, rates, tuple(events))


def _to_branch(tracer: ArclengthTracer, runs: list[TracedRun], kind: str, k: int
               ) -> tuple[Branch, list[Event]]:
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
        mult = floquet_multipliers(pt.jac)
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
    """Whether ``(p, amplitude)`` lies on a computed branch of ``kind``: on the linear
    interpolation between two points (or its extension by one segment past either end) to
    1e-3 relative or a tenth of the segment's change of amplitude, or at a point to 1e-6."""
    for b in branches:
        if b.kind != kind:
            continue
        ps = np.array([q.param for q in b.points])
        amps = np.array([q.amplitude for q in b.points])
        last = ps.size - 2
        for i in range(ps.size - 1):
            a0, a1 = ps[i], ps[i + 1]
            reach = abs(a1 - a0) if i in (0, last) else 0.0
            if min(a0, a1) - 1e-12 - reach <= p <= max(a0, a1) + 1e-12 + reach:
                w = 0.0 if a1 == a0 else (p - a0) / (a1 - a0)
                # a coarse step on a curved branch: the chord is off by a share of the change
                tol = max(1e-3 * max(1.0, amplitude), 0.1 * abs(amps[i + 1] - amps[i]))
                if abs(amps[i] + w * (amps[i + 1] - amps[i]) - amplitude) <= tol:
                    return True
        if np.any((np.abs(ps - p) <= 1e-9) & (np.abs(amps - amplitude) <= 1e-6 * max(1.0, amplitude))):
            return True
    return False


def _duplicate(branches: list[Branch], new: Branch) -> bool:
    """Whether ``new`` retraces a branch already computed: the same kind and a point at the
    same parameter value (the ends of the range, where every branch that reaches them lands
    exactly, or a branch end bisected to :data:`EVENT_TOL`) with the same amplitude to 1e-6."""
    for b in branches:
        if b.kind != new.kind or b.stick_phases != new.stick_phases:
            continue
        for q in new.points:
            for r in b.points:
                if (abs(q.param - r.param) <= 100.0 * EVENT_TOL * max(1.0, abs(q.param))
                        and abs(q.amplitude - r.amplitude) <= 1e-6 * max(1e-9, abs(q.amplitude))):
                    return True
    return False


def _stick_slip_factory(k: int, opts: EngineOptions, direction: int
                        ) -> Callable[[AnySystem], StickSlipSection]:
    def make(s: AnySystem) -> StickSlipSection:
        return StickSlipSection(s, k, opts, direction)

    return make


def _foundation_branches(system: AnySystem, name: str, lo: float, hi: float, max_period: int,
                         seeds: int, max_steps: int, opts: EngineOptions, branches: list[Branch],
                         events: list[Event]) -> None:
    """Stick-slip branches with a foundation, seeded by :func:`find_cycles` at
    :data:`SEARCH_POINTS` points of the range."""
    h_max = 0.05 * (hi - lo)
    for p0 in (float(p) for p in np.linspace(lo, hi, SEARCH_POINTS)):
        structure, slider = system.with_value(name, p0).build()
        search = find_cycles(structure, slider, seeds=seeds, max_period=max_period, options=opts)
        for cycle in (*search.cycles, *search.candidates):
            if _on_branch(branches, p0, cycle.amplitude, "stick-slip"):
                continue
            k = cycle.stick_phases
            direction = SLIP_I if cycle.breakaway_onto == "slip-I" else SLIP_II
            tracer = ArclengthTracer(system, name, _stick_slip_factory(k, opts, direction))
            tracer.bounds = (lo, hi)
            sec = tracer.section(p0)
            assert isinstance(sec, StickSlipSection)
            y0 = sec.pmap.reduce(cycle.breakaway_state)
            ev = tracer.jacobians(y0, p0)
            if ev is None:
                continue
            t0 = unit_tangent(ev[1], np.eye(y0.size + 1)[-1])
            sig = sec.signature(y0)
            if sig is None:
                continue
            start = BranchState(p0, y0, ev[2], t0, sig)
            back_start = BranchState(p0, y0, ev[2], -t0, sig)
            runs = [trace_branch(tracer, back_start, lo, hi, 0.2 * h_max, h_max, max_steps),
                    trace_branch(tracer, start, lo, hi, 0.2 * h_max, h_max, max_steps)]
            branch, evs = _to_branch(tracer, runs, "stick-slip", k)
            branch = replace(branch, from_candidate=bool(cycle.not_proven))
            if branch.points and not _duplicate(branches, branch):
                index = len(branches)
                branches.append(branch)
                events += [replace(e, branch=index) for e in evs]


def _slip_branches(system: AnySystem, name: str, lo: float, hi: float, hopf: list[float],
                   max_steps: int, opts: EngineOptions, branches: list[Branch], events: list[Event]) -> None:
    """Slip oscillations born at every Hopf point of steady sliding in the range."""
    h_max = 0.05 * (hi - lo)
    for p_h in hopf:
        tracer = ArclengthTracer(system, name, lambda s: SlipSection(s, opts))
        tracer.bounds = (lo, hi)
        sec = tracer.section(p_h)
        assert isinstance(sec, SlipSection)
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
        hopf_end = BranchState(p_h, np.zeros(sec.dim), np.eye(sec.dim), start.tangent, start.signature)
        runs = [TracedRun([start, hopf_end], [], "hopf"),
                trace_branch(tracer, start, lo, hi, 1e-2 * (hi - lo), h_max, max_steps)]
        branch, evs = _to_branch(tracer, runs, "slip-oscillation", 0)
        if branch.points:
            index = len(branches)
            branches.append(branch)
            events += [replace(e, branch=index) for e in evs]


def _searched_slip_branches(system: AnySystem, name: str, lo: float, hi: float, seeds: int,
                            max_steps: int, opts: EngineOptions, branches: list[Branch],
                            events: list[Event]) -> None:
    """Slip oscillations found by :func:`find_slip_oscillations` at :data:`SEARCH_POINTS`
    points of the range (whether or not a Hopf point is near), each not yet on a branch
    continued both ways."""
    h_max = 0.05 * (hi - lo)
    for p0 in np.linspace(lo, hi, SEARCH_POINTS):
        structure, slider = system.with_value(name, float(p0)).build()
        for osc in find_slip_oscillations(structure, slider, seeds=seeds, options=opts):
            if _on_branch(branches, float(p0), osc.amplitude, "slip-oscillation"):
                continue
            tracer = ArclengthTracer(system, name, lambda s: SlipSection(s, opts))
            tracer.bounds = (lo, hi)
            sec = tracer.section(float(p0))
            assert isinstance(sec, SlipSection)
            y0 = sec.reduce(osc.state)
            ev = tracer.jacobians(y0, float(p0))
            sig = sec.signature(y0)
            if ev is None or sig is None:
                continue
            t0 = unit_tangent(ev[1], np.eye(y0.size + 1)[-1])
            runs = [trace_branch(tracer, BranchState(float(p0), y0, ev[2], -t0, sig), lo, hi,
                                 0.2 * h_max, h_max, max_steps),
                    trace_branch(tracer, BranchState(float(p0), y0, ev[2], t0, sig), lo, hi,
                                 0.2 * h_max, h_max, max_steps)]
            branch, evs = _to_branch(tracer, runs, "slip-oscillation", 0)
            if branch.points and not _duplicate(branches, branch):
                index = len(branches)
                branches.append(branch)
                events += [replace(e, branch=index) for e in evs]


def slip_oscillation(system: ContinuationSystem, peak_velocity: float, *,
                     options: EngineOptions | None = None) -> BranchPoint | None:
    """The slip oscillation of ``system`` whose peak slider velocity is near ``peak_velocity``.

    Newton's method on the velocity-maximum section at fixed parameters (the corrector of the
    continuation with the parameter held); None when it does not converge.

    Parameters
    ----------
    system : ContinuationSystem
        The machine and friction law, at fixed parameters.
    peak_velocity : float
        Guess of the largest slider velocity over the oscillation (dimensionless, belt speed 1).
    options : EngineOptions, optional
        Engine options of the section's runs.

    Returns
    -------
    BranchPoint or None
        The converged slip oscillation, or None when Newton's method does not converge.
    """
    opts = options or EngineOptions()
    tracer = ArclengthTracer(system, "lam", lambda s: SlipSection(s, opts))
    sec = tracer.section(system.lam)
    assert isinstance(sec, SlipSection)
    y0 = np.zeros(sec.dim)
    y0[0] = peak_velocity
    out = tracer.correct(y0, system.lam, np.eye(sec.dim + 1)[-1], None)
    if out is None:
        return None
    pt = out[0]
    m = sec.measure(pt.y)
    if m is None or pt.y[0] <= 1e-9:  # peak velocity 0: steady sliding, not an oscillation
        return None
    mult = floquet_multipliers(pt.jac)
    return BranchPoint(pt.p, *m, mult, bool(np.all(np.abs(mult) < 1.0)), sec.full_state(pt.y))
