"""Periodic orbits of a machine with friction with memory, continued in the drive speed.

The bifurcation diagram of ``stickslip continue --config`` for rate-and-state and LuGre:

* **Hopf points**: the speeds where steady sliding changes stability, from its linearisation
  with the state variable (:func:`stickslip.analysis.memory.stability.critical_speeds`, bisected
  to 1e-10), with the growth rate along the range.
* **Branches**: orbits found by runs from kicked steady sliding
  (:func:`~stickslip.analysis.memory.cycle_search.find_memory_cycles`) at :data:`SEED_POINTS`
  speeds of the range, and the orbit born at each Hopf point that no such branch reached
  (:func:`~stickslip.analysis.memory.arclength.hopf_seed`: shooting from the critical
  eigenvector just beside the Hopf point; at a subcritical Hopf point this is the *unstable*
  orbit that bounds the basin of steady sliding). Each is continued both ways by
  pseudo-arclength steps in ``(orbit, ln V)``
  (:mod:`stickslip.analysis.memory.arclength`), which pass folds (named with their speed). A
  failed step is halved; after a success the step grows by 1.5 up to :data:`MAX_STEP` of the
  range. A branch stops at the range's end, or where the step falls below :data:`MIN_STEP` of
  the range: where the orbit shrinks into a Hopf point, or turns sharper than the smallest
  step follows (with LuGre's stiff bristles a stick-slip orbit ends at a corner where its
  stick phase vanishes, a fold too sharp for the steps); the stop is named with the speed.
  Every point has its Floquet multipliers (stable: every nontrivial one inside the unit
  circle) and its amplitude (half the peak-to-peak contact displacement over one period,
  :data:`AMPLITUDE_SAMPLES` samples).

Unstable orbits are found where a Hopf point gives birth to them or a fold turns a branch
into them; an unstable orbit connected to neither is not searched for, and the summary says
what was searched.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.memory.arclength import (
    FOLD_MIN_SIZE,
    SectionOrbit,
    arclength_step,
    fold_speed,
    hopf_seed,
    tangent_at,
)
from stickslip.analysis.memory.cycle_search import find_memory_cycles
from stickslip.analysis.memory.cycles import MULTIPLIER_RESOLUTION, PeriodicOrbit, shoot_cycle
from stickslip.analysis.memory.friction import (
    integrate_run,
    observables,
    state_scales,
    steady_state,
)
from stickslip.analysis.memory.stability import critical_speeds, growth_rate
from stickslip.model.state_friction import MemorySystem, SpeedSchedule

FloatArray = NDArray[np.float64]

#: Speeds of the range (log-spaced, ends included) where orbits are searched for.
SEED_POINTS = 3
#: Kicks of those searches (stuck to the drive, and thrown forward).
SEED_KICKS = (-1.0, 2.0)
#: Largest and smallest step in ln V, as shares of the range's ln(B / A).
MAX_STEP = 0.05
MIN_STEP = 1e-4
FIRST_STEP = 0.01
#: Bound on the steps of one direction of one branch.
MAX_STEPS = 400
#: What the diagram searched, in its output.
SEARCHED = (f"stable orbits from kicked steady sliding at {SEED_POINTS} speeds, and the orbit "
            "born at each Hopf point no branch reached (stable or not), each continued both "
            "ways by pseudo-arclength steps")
#: A start this close (ratio of speeds) beyond a branch's end is checked against it too (a
#: Hopf seed lies just beyond the last point continued towards its Hopf point).
ON_BRANCH_MARGIN = 1.05
#: Samples of one period for the amplitude.
AMPLITUDE_SAMPLES = 401
#: Points of the growth-rate grid along the range.
STEADY_POINTS = 101




@dataclass(frozen=True)
class OrbitPoint:
    """One orbit on a branch (SI)."""

    speed: float
    period: float
    amplitude: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    orbit: PeriodicOrbit = field(repr=False)

    @property
    def stable(self) -> bool:
        """Every nontrivial Floquet multiplier inside the unit circle (see
        :attr:`stability_resolved`)."""
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    @property
    def stability_resolved(self) -> bool:
        """The largest multiplier's modulus is more than
        :data:`~stickslip.analysis.memory.cycles.MULTIPLIER_RESOLUTION` from 1,
        so :attr:`stable` is not decided by the monodromy's own error."""
        return self.orbit.stability_resolved

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"speed_m_per_s": self.speed, "period_s": self.period, "amplitude_m": self.amplitude,
                "stable": self.stable, "stability_resolved": self.stability_resolved,
                "multiplier_moduli": [float(abs(m)) for m in self.multipliers]}


@dataclass(frozen=True)
class OrbitBranch:
    """A continued branch: its points in increasing speed and why each end stopped."""

    points: tuple[OrbitPoint, ...]
    low_end: str
    high_end: str
    folds: tuple[float, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"low_end": self.low_end, "high_end": self.high_end,
                "folds_m_per_s": list(self.folds),
                "points": [p.to_dict() for p in self.points]}


@dataclass(frozen=True)
class MemoryContinuation:
    """The diagram (see module notes)."""

    system: MemorySystem = field(repr=False)
    speed_range: tuple[float, float]
    branches: tuple[OrbitBranch, ...]
    hopf: tuple[float, ...]
    steady_speed: FloatArray = field(repr=False)
    steady_growth: FloatArray = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI), the keys of ``continue --config --json`` for a law with memory."""
        return {"param": "speed", "param_units": "m/s", "range": list(self.speed_range),
                "law": self.system.friction.to_dict(), "hopf_speeds_m_per_s": list(self.hopf),
                "branches": [b.to_dict() for b in self.branches],
                "steady": [{"speed": float(v), "growth_rate_per_s": float(g), "stable": bool(g < 0)}
                           for v, g in zip(self.steady_speed, self.steady_growth, strict=True)],
                "searched": SEARCHED}

    def summary(self) -> str:
        """A few lines: the Hopf points and each branch."""
        lo, hi = self.speed_range
        lines = [f"continuation in speed over [{lo:g}, {hi:g}] m/s (friction with memory): "
                 f"{len(self.branches)} branch(es), {len(self.hopf)} Hopf point(s)"]
        for v in self.hopf:
            lines.append(f"  hopf at speed = {v:.10g} m/s (steady sliding changes stability)")
        for i, b in enumerate(self.branches):
            stable = sum(p.stable for p in b.points if p.stability_resolved)
            unresolved = sum(not p.stability_resolved for p in b.points)
            open_ = (f", {unresolved} unresolved (a multiplier within {MULTIPLIER_RESOLUTION:g} "
                     "of the unit circle)" if unresolved else "")
            speeds = [p.speed for p in b.points]
            folds = "".join(f"; fold at {v:.8g} m/s" for v in b.folds)
            lines.append(f"  branch {i}: {len(b.points)} points, speed in "
                         f"[{min(speeds):.6g}, {max(speeds):.6g}] m/s, {stable} stable{open_}{folds}; "
                         f"one end: {b.low_end}; other end: {b.high_end}")
        lines.append(f"  searched: {SEARCHED}")
        return "\n".join(lines)

    def plot(self, **kwargs: Any) -> Any:
        """The diagram, a ``PlotResult`` (:func:`stickslip.plot.continuation.memory_continuation_plot`)."""
        from stickslip.plot.continuation import memory_continuation_plot

        return memory_continuation_plot(self, **kwargs)


def _at_speed(system: MemorySystem, speed: float) -> MemorySystem:
    return MemorySystem(system.mass, system.damping, system.stiffness, system.contact_dof,
                        system.load, system.friction, SpeedSchedule.constant(float(speed)))


def _point(system: MemorySystem, speed: float, orbit: PeriodicOrbit) -> OrbitPoint:
    one = _at_speed(system, speed)
    times = np.linspace(0.0, orbit.period, AMPLITUDE_SAMPLES)
    run = integrate_run(one, orbit.y0, orbit.period, history_times=times)
    assert run.history is not None
    x = observables(one, run.history, np.full(times.size, speed))["x"]
    amplitude = 0.5 * float(np.nanmax(x) - np.nanmin(x))
    return OrbitPoint(speed, orbit.period, amplitude, orbit.multipliers, orbit)


def _direction(system: MemorySystem, start: OrbitPoint, lo: float, hi: float, sign: int
               ) -> tuple[list[OrbitPoint], str, list[float]]:
    """Continue from ``start`` by pseudo-arclength steps, leaving it towards ``hi`` (``sign =
    1``) or ``lo`` (``-1``): the points, why the direction stopped, and the folds passed."""

    def system_at(speed: float) -> MemorySystem:
        return _at_speed(system, speed)

    span = math.log(hi / lo)
    tangent = tangent_at(system_at, start.orbit.y0, start.speed, start.period, sign)
    if tangent is None:
        return [], f"no return to the section near {start.speed:.8g} m/s", []
    scale = state_scales(system_at(start.speed), start.speed)
    size = float(np.max(np.abs(start.orbit.y0 - steady_state(system_at(start.speed), start.speed))
                        / scale))
    at = SectionOrbit(start.speed, start.orbit.y0, start.period, start.multipliers, tangent, size)
    step = FIRST_STEP * span
    points: list[OrbitPoint] = []
    folds: list[float] = []
    trail = [(0.0, math.log(start.speed))]  # (arclength, ln V) of the points so far
    s = 0.0
    for _ in range(MAX_STEPS):
        nxt = arclength_step(system_at, at, step)
        if nxt is None:
            step *= 0.5
            if step < MIN_STEP * span:
                return points, (f"the orbit ceases to exist near {at.speed:.6g} m/s (it shrinks "
                                "into a Hopf point, or turns sharper than the smallest step "
                                "follows)"), folds
            continue
        if not lo <= nxt.speed <= hi:  # land on the range's end by a shooting there
            end = hi if nxt.speed > hi else lo
            orbit = shoot_cycle(_at_speed(system, end), at.y0, at.period)
            if orbit is not None:
                points.append(_point(system, end, orbit))
            return points, "range end", folds
        s += step
        trail.append((s, math.log(nxt.speed)))
        if nxt.tangent[-1] * at.tangent[-1] < 0.0 and min(at.size, nxt.size) >= FOLD_MIN_SIZE:
            # dp/ds changed sign away from a Hopf point: a fold passed
            if len(trail) >= 3:
                folds.append(fold_speed(trail[-3:]))
            else:
                folds.append(math.exp(max(trail, key=lambda q: sign * q[1])[1]))
        orbit = PeriodicOrbit(nxt.y0, nxt.period, 0.0, nxt.multipliers, complex(1.0), 0)
        points.append(_point(system, nxt.speed, orbit))
        at = nxt
        step = min(1.5 * step, MAX_STEP * span)
    return points, "step bound", folds


def _on_branch(system: MemorySystem, branches: list[OrbitBranch], point: OrbitPoint) -> bool:
    """Whether ``point`` lies on a branch found before: shooting at its speed from the branch's
    nearest orbit lands on the same orbit (period to 1e-6, amplitude to 1e-4)."""
    for b in branches:
        speeds = [p.speed for p in b.points]
        if not min(speeds) * ON_BRANCH_MARGIN ** -1 <= point.speed <= max(speeds) * ON_BRANCH_MARGIN:
            continue
        nearest = min(b.points, key=lambda p: abs(math.log(p.speed / point.speed)))
        orbit = shoot_cycle(_at_speed(system, point.speed), nearest.orbit.y0, nearest.period)
        if orbit is None or abs(orbit.period - point.period) > 1e-6 * point.period:
            continue
        scale = state_scales(_at_speed(system, point.speed), point.speed)
        if float(np.max(np.abs(orbit.y0 - point.orbit.y0) / scale)) <= 1e-4:
            return True  # the same start on the section
        if abs(_point(system, point.speed, orbit).amplitude - point.amplitude) <= (
                1e-4 * max(point.amplitude, 1e-300)):
            return True
    return False


def _add_branch(system: MemorySystem, branches: list[OrbitBranch], start: OrbitPoint, lo: float,
                hi: float) -> None:
    """Continue ``start`` both ways and add its branch, unless it lies on one found before."""
    if _on_branch(system, branches, start):
        return
    down, low_end, low_folds = _direction(system, start, lo, hi, -1)
    up, high_end, high_folds = _direction(system, start, lo, hi, 1)
    points = [*reversed(down), start, *up]
    branches.append(OrbitBranch(tuple(points), low_end, high_end,
                                tuple(sorted(low_folds + high_folds))))


def _reaches(branch: OrbitBranch, hopf: float) -> bool:
    """Whether ``branch`` ends at the Hopf point ``hopf`` (m/s): an end point within 1 % of
    its speed, with an amplitude below 1 % of the branch's largest."""
    largest = max(p.amplitude for p in branch.points)
    return any(abs(math.log(p.speed / hopf)) < 0.01 and p.amplitude < 0.01 * largest
               for p in (branch.points[0], branch.points[-1]))


def continue_memory_orbits(system: MemorySystem, speed_range: tuple[float, float]
                           ) -> MemoryContinuation:
    """The bifurcation diagram in drive speed of a machine with friction with memory.

    Parameters
    ----------
    system : MemorySystem
        The machine (SI, with the slider's mass); its own speed is not used.
    speed_range : (float, float)
        ``(A, B)``, ``0 < A < B``, m/s.

    Returns
    -------
    MemoryContinuation
        Hopf points, the growth rate of steady sliding along the range and the branches.
    """
    lo, hi = float(speed_range[0]), float(speed_range[1])
    if not (0.0 < lo < hi and math.isfinite(hi)):
        raise ValueError(f"speed range {lo!r}:{hi!r} m/s must be positive and increasing")
    if system.quasi_static:
        raise ValueError("the quasi-static slider (m = 0) cannot be kicked onto its orbits: "
                         "continuation needs the slider's mass")
    hopf, _ = critical_speeds(system, lo, hi)
    grid = np.geomspace(lo, hi, STEADY_POINTS)
    rates = np.array([growth_rate(system, float(v)) for v in grid])
    branches: list[OrbitBranch] = []
    for speed in np.geomspace(lo, hi, SEED_POINTS).tolist():
        seeded = find_memory_cycles(_at_speed(system, speed), kicks=SEED_KICKS)
        for cycle in seeded.cycles:
            assert cycle.run.orbit is not None
            _add_branch(system, branches, _point(system, speed, cycle.run.orbit), lo, hi)
    for speed in hopf:  # the orbit born at each Hopf point no branch reached, stable or not
        if any(_reaches(b, speed) for b in branches):
            continue
        found = hopf_seed(lambda v: _at_speed(system, v), speed)
        if found is not None and lo <= found[0] <= hi:
            _add_branch(system, branches, _point(system, found[0], found[1]), lo, hi)
    return MemoryContinuation(system, (lo, hi), tuple(branches), tuple(hopf), grid, rates)


__all__ = ["MemoryContinuation", "OrbitBranch", "OrbitPoint", "continue_memory_orbits"]
