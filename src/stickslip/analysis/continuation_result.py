"""The result of a continuation: branches of periodic motions, their events, steady sliding.

:func:`stickslip.analysis.continuation.continue_cycles` computes it; it summarises itself,
exports to xarray and plots its bifurcation diagram (:mod:`stickslip.plot.continuation`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis._periodic_sections import MACHINE_PARAMETERS, AnySystem, MachineSystem

FloatArray = NDArray[np.float64]


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
                "stick_ratio": self.stick_ratio, "multiplier": self.multiplier, "stable": self.stable,
                "multipliers": [{"re": float(m.real), "im": float(m.imag), "abs": float(abs(m))}
                                for m in self.multipliers]}


@dataclass(frozen=True)
class Branch:
    """A continued branch: its kind, points in order of arclength and why it stopped."""

    kind: str
    stick_phases: int
    points: tuple[BranchPoint, ...]
    stop_reason: str
    #: seeded from a cycle candidate (:attr:`stickslip.analysis.cycles.CycleSearch.candidates`:
    #: a fixed point no existence proof holds for), not from a proven cycle
    from_candidate: bool = False

    def to_dict(self, name: str) -> dict[str, Any]:
        return {"kind": self.kind, "stick_phases": self.stick_phases, "stop_reason": self.stop_reason,
                "from_candidate": self.from_candidate, "points": [p.to_dict(name) for p in self.points]}


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

    system: AnySystem
    param: str
    param_range: tuple[float, float]
    branches: tuple[Branch, ...]
    steady_param: FloatArray = field(repr=False)
    steady_growth: FloatArray = field(repr=False)
    events: tuple[Event, ...]

    @property
    def steady_stable(self) -> NDArray[np.bool_]:
        return np.asarray(self.steady_growth < 0.0)

    def warnings(self) -> list[str]:
        """What the diagram's numbers may owe to the law's interpolant, in sentences.

        A smooth law (Stribeck) runs as its piecewise-linear interpolant; a slip oscillation
        next to a Hopf point crosses only its few bands nearest the belt speed, where the
        interpolant's kinks can fold the branch and turn its stability. On the published
        bistable case at the default tolerance (1e-4) the small oscillations showed four folds
        and eight "stable" points; at 1e-6 the branch has no fold and every point is unstable,
        as an independent smooth-law integration gives. Said whenever a slip-oscillation
        branch of an interpolated law has a fold or a stable point.

        A stick-slip branch seeded from a cycle candidate (a fixed point of the return map
        that no existence proof holds for, :attr:`Branch.from_candidate`) is said too.
        """
        seeded = [i for i, b in enumerate(self.branches) if b.from_candidate]
        said = ([f"stick-slip branch(es) {', '.join(str(i) for i in seeded)} start from a fixed "
                 "point of the return map that no existence proof holds for (a `stickslip "
                 "cycles` candidate): their points are Newton's fixed points, as every "
                 "branch's, but the cycle they start from is not proven"] if seeded else [])
        friction = getattr(self.system, "friction", None)
        if friction is None or getattr(friction, "exact", True):
            return said
        slip = [i for i, b in enumerate(self.branches) if b.kind == "slip-oscillation"]
        folds = [e for e in self.events if e.type == "fold" and e.branch in slip]
        stable = sum(p.stable for i in slip for p in self.branches[i].points)
        if not folds and not stable:
            return said
        tol = getattr(friction, "tolerance", None)
        return [*said, f"the slip oscillations show {len(folds)} fold(s) and {stable} stable point(s) "
                f"with the law's piecewise-linear interpolant (tolerance {tol:g}); small "
                "oscillations cross only a few of its bands, whose kinks can fold a branch and "
                "turn its stability: check them with a finer tolerance (e.g. tol=1e-6 in "
                "--friction, or tolerance in [friction])"]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, the keys of ``stickslip continue --json``."""
        name = self.param
        branches = [b.to_dict(name) for b in self.branches]
        units = MACHINE_PARAMETERS.get(name) if isinstance(self.system, MachineSystem) else None
        if units is not None:  # seconds and metres at each point's own scales
            for branch in branches:
                for point in branch["points"]:
                    time_s, length_m = self.si_scales(point[name])
                    point["period_s"] = point["period"] * time_s
                    point["amplitude_m"] = point["amplitude"] * length_m
        system = self.system.to_dict()
        if name in system:  # the continued parameter takes the range's values, not this one
            system[name] = None
        return {
            "param": name,
            "param_units": units,
            "range": list(self.param_range),
            "system": system,
            "branches": branches,
            "steady": [{name: float(p), "growth_rate": float(g), "stable": bool(g < 0.0)}
                       for p, g in zip(self.steady_param, self.steady_growth, strict=True)],
            "events": [e.to_dict(name) for e in self.events],
            "warnings": self.warnings(),
        }

    def si_scales(self, value: float) -> tuple[float, float]:
        """``(time_scale_s, length_scale_m)`` at parameter ``value``; ``(1, 1)`` for a
        dimensionless system (its answers stay in ``tau`` and ``V/omega_n``)."""
        scales = self.system.with_value(self.param, value).si_scales()
        return (1.0, 1.0) if scales is None else scales

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
        lines += [f"warning: {w}" for w in self.warnings()]
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
                   "branches_from_candidates": " ".join(
                       str(i) for i, b in enumerate(self.branches) if b.from_candidate),
                   "warnings": " | ".join(self.warnings()),
                   "parameter": self.param},
        )
        if isinstance(self.system, MachineSystem):  # a machine: SI beside the dimensionless
            scales = np.array([self.si_scales(p.param) for _, p in rows]).reshape(-1, 2)
            ds[self.param].attrs["units"] = MACHINE_PARAMETERS[self.param]
            ds["period_s"] = ("point", ds["period"].values * scales[:, 0], {"units": "s"})
            ds["amplitude_m"] = ("point", ds["amplitude"].values * scales[:, 1], {"units": "m"})
        return ds

    def plot(self, **kwargs: Any) -> Any:
        """The bifurcation diagram (:func:`stickslip.plot.continuation.continuation_plot`)."""
        from stickslip.plot.continuation import continuation_plot

        return continuation_plot(self, **kwargs)
