"""The attractors of a machine with its contact, followed along its speed or load by runs.

``stickslip continue --config`` for a machine with a ``[contact]``. At each of ``points``
values of the parameter, log-spaced from ``A`` to ``B`` (ends included: speed and load are
positive and their effects scale with ratios), two runs of the exact contact engine:

* **continued**: from the previous point's final state (the first point from the start-up
  state), so that the attractor reached at one point is followed to the next;
* **start-up**: from the machine's start-up state at that value.

Each records its verdict, period (s) and amplitude (m; half the peak-to-peak displacement of
the contact DOF over one period). A **branch** is a run of consecutive points of one
sequence whose attractor is continuous (:func:`_continuous`): the same verdict, the same
separation flag and the same events per period of the repeating kind, and neither the period
nor the amplitude changing by more than a factor :data:`MAX_JUMP` from one point to the next
(steady sliding continues steady sliding). The start-up sequence adds the branches of the
points where it reaches another attractor than the continued one (coexisting attractors).

Only attractors (stable orbits, and stable steady sliding) are followed: a run never stays
on an unstable orbit, so unstable orbits and the folds where branches end are not found by
this method. The periodic verdicts are observed (a state repeated to 1e-9), not proven.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from stickslip.analysis.contact._modes import ContactSystem
from stickslip.analysis.contact._pool import ContactOutcome, run_many, run_one
from stickslip.analysis.contact.cycles import OBSERVED

#: The parameters and their units.
PARAMETERS = {"speed": "m/s", "load": "N"}
#: Default number of points, and the bounds on it.
DEFAULT_POINTS = 25
MAX_POINTS = 2000
#: Largest factor between the periods (or amplitudes) of neighbours on one branch.
MAX_JUMP = 1.5
#: Relative tolerance under which the start-up run reaches the continued run's attractor.
SAME_PERIOD = 1e-6
#: What this method finds.
FOLLOWED = ("attractors only (stable orbits and stable steady sliding), followed by runs; "
            "unstable orbits and folds are not found by this method")


@dataclass(frozen=True)
class ContactPoint:
    """One parameter value: the outcomes of the continued and the start-up runs (SI)."""

    value: float
    continued: ContactOutcome = field(repr=False)
    startup: ContactOutcome = field(repr=False)

    @property
    def coexisting(self) -> bool:
        """The start-up run reached another attractor than the continued run."""
        return not _same_attractor(self.continued, self.startup)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        def one(o: ContactOutcome) -> dict[str, Any]:
            return {"verdict": o.verdict, "period_s": o.period_s, "amplitude_m": o.amplitude_m,
                    "separated": o.separated, "stick_phases_per_period": o.stick_phases,
                    "events_per_period": o.event_counts}

        return {"value": self.value, "continued": one(self.continued),
                "startup": one(self.startup), "coexisting": self.coexisting}


@dataclass(frozen=True)
class ContactBranch:
    """Consecutive points of one sequence (``continued`` or ``startup``) on one attractor."""

    source: str
    verdict: str
    indices: tuple[int, ...]

    def to_dict(self, points: tuple[ContactPoint, ...]) -> dict[str, Any]:
        """JSON-ready, with the points' values, periods and amplitudes."""
        outs = [getattr(points[i], self.source) for i in self.indices]
        return {"source": self.source, "verdict": self.verdict, "indices": list(self.indices),
                "values": [points[i].value for i in self.indices],
                "period_s": [o.period_s for o in outs], "amplitude_m": [o.amplitude_m for o in outs]}


@dataclass(frozen=True)
class ContactContinuation:
    """Result of :func:`continue_contact` (module notes)."""

    system: ContactSystem = field(repr=False)
    param: str
    value_range: tuple[float, float]
    points: tuple[ContactPoint, ...]
    branches: tuple[ContactBranch, ...]

    @property
    def units(self) -> str:
        """The parameter's SI unit."""
        return PARAMETERS[self.param]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI)."""
        return {"param": self.param, "param_units": self.units, "range": list(self.value_range),
                "n_points": len(self.points), "spacing": "log",
                "points": [p.to_dict() for p in self.points],
                "branches": [b.to_dict(self.points) for b in self.branches],
                "followed": FOLLOWED, "status": f"periodic verdicts {OBSERVED}",
                "engine": "exact piecewise-affine contact engine"}

    def rows(self) -> list[dict[str, Any]]:
        """One row per point and sequence (the CSV's rows)."""
        out = []
        for i, p in enumerate(self.points):
            for source in ("continued", "startup"):
                o = getattr(p, source)
                out.append({"index": i, f"{self.param}_{_unit_tag(self.units)}": p.value,
                            "source": source, "verdict": o.verdict, "period_s": o.period_s,
                            "amplitude_m": o.amplitude_m, "separated": o.separated,
                            "stick_phases_per_period": o.stick_phases})
        return out

    def to_csv(self) -> str:
        """The rows as CSV text (empty cells where there is no period)."""
        rows = self.rows()
        names = list(rows[0])
        lines = [",".join(names)]
        for r in rows:
            lines.append(",".join("" if r[k] is None else
                                  (repr(r[k]) if isinstance(r[k], float) else str(r[k]).lower()
                                   if isinstance(r[k], bool) else str(r[k])) for k in names))
        return "\n".join(lines) + "\n"

    def summary(self) -> str:
        """A few lines: the points and the branches."""
        lo, hi = self.value_range
        u = self.units
        lines = [f"continuation in {self.param} over [{lo:.6g}, {hi:.6g}] {u}: {len(self.points)} "
                 f"points (log-spaced), {len(self.branches)} branch(es)"]
        for b in self.branches:
            d = b.to_dict(self.points)
            span = f"{d['values'][0]:.6g} to {d['values'][-1]:.6g} {u}"
            periods = [p for p in d["period_s"] if p is not None]
            extra = (f", period {min(periods):.6g} to {max(periods):.6g} s" if periods else "")
            lines.append(f"  branch ({b.source}) {b.verdict}: {len(b.indices)} point(s), "
                         f"{span}{extra}")
        both = [p.value for p in self.points if p.coexisting]
        if both:
            lines.append(f"  coexisting attractors (start-up reaches another) at {len(both)} "
                         f"point(s): " + ", ".join(f"{v:.4g}" for v in both) + f" {u}")
        lines.append(f"  followed: {FOLLOWED}")
        lines.append("  periodic verdicts are observed (a state repeated to 1e-9), not proven")
        return "\n".join(lines)

    def plot(self, **kwargs: Any) -> Any:
        """Period and amplitude against the parameter, a ``PlotResult``
        (:func:`stickslip.plot.contact.continuation.contact_continuation_plot`)."""
        from stickslip.plot.contact.continuation import contact_continuation_plot

        return contact_continuation_plot(self, **kwargs)


def _unit_tag(units: str) -> str:
    return units.replace("/", "_")


def _same_attractor(a: ContactOutcome, b: ContactOutcome) -> bool:
    """The same verdict and, when periodic, the same period (relative :data:`SAME_PERIOD`)."""
    if a.verdict != b.verdict:
        return False
    if a.period_s is None or b.period_s is None:
        return a.period_s is None and b.period_s is None
    return abs(a.period_s - b.period_s) <= SAME_PERIOD * a.period_s


def _continuous(a: ContactOutcome, b: ContactOutcome) -> bool:
    """Neighbouring outcomes on one branch (module notes)."""
    if a.verdict != b.verdict or a.verdict == "undetermined":
        return False
    if a.period_s is None or b.period_s is None:
        return a.period_s is None and b.period_s is None
    if a.separated != b.separated or a.event_counts.get(a.repeat_kind or "") != \
            b.event_counts.get(b.repeat_kind or ""):
        return False
    for x, y in ((a.period_s, b.period_s), (a.amplitude_m, b.amplitude_m)):
        if x is None or y is None or not (x > 0.0 and y > 0.0) or max(x / y, y / x) > MAX_JUMP:
            return False
    return True


def _branches(points: tuple[ContactPoint, ...]) -> tuple[ContactBranch, ...]:
    """Branches of the continued sequence, and of the start-up one where it differs."""
    out: list[ContactBranch] = []
    for source in ("continued", "startup"):
        run: list[int] = []
        for i, p in enumerate(points):
            o = getattr(p, source)
            keep = source == "continued" or p.coexisting
            if keep and o.verdict != "undetermined" and run and i == run[-1] + 1 \
                    and _continuous(getattr(points[run[-1]], source), o):
                run.append(i)
                continue
            if run:
                out.append(ContactBranch(source, getattr(points[run[0]], source).verdict,
                                         tuple(run)))
            run = [i] if keep and o.verdict != "undetermined" else []
        if run:
            out.append(ContactBranch(source, getattr(points[run[0]], source).verdict, tuple(run)))
    return tuple(out)


def continue_contact(system: ContactSystem, param: str, value_range: tuple[float, float], *,
                     points: int = DEFAULT_POINTS, t_max: float | None = None,
                     max_events: int = 100_000, workers: int = 2,
                     progress: Callable[[int, int], None] | None = None) -> ContactContinuation:
    """Follow the attractors along ``param`` by runs (module notes).

    Parameters
    ----------
    system : ContactSystem
        The machine (SI); its own value of ``param`` is not used.
    param : str
        ``speed`` (belt speed, m/s) or ``load`` (preload, N).
    value_range : (float, float)
        ``(A, B)``, ``0 < A < B``, in the parameter's SI unit.
    points : int
        Number of log-spaced values, ends included (2 to :data:`MAX_POINTS`).
    t_max : float, optional
        Horizon of each run, s (default the engine's at each value).
    max_events : int
        Bound on the events of each run.
    workers : int
        Worker processes for the start-up runs (the continued runs go one after another).
    progress : callable, optional
        ``progress(done, total)`` after each run (``2 points`` runs).

    Returns
    -------
    ContactContinuation
        The points and the branches.
    """
    if param not in PARAMETERS:
        raise ValueError(f"param {param!r} is not one of {', '.join(PARAMETERS)}")
    lo, hi = float(value_range[0]), float(value_range[1])
    if not (0.0 < lo < hi and math.isfinite(hi)):
        raise ValueError(f"{param} range {lo!r}:{hi!r} {PARAMETERS[param]} must be positive and "
                         "increasing")
    if isinstance(points, bool) or int(points) != points or not 2 <= points <= MAX_POINTS:
        raise ValueError(f"points = {points!r} must be a whole number from 2 to {MAX_POINTS}")
    values = np.geomspace(lo, hi, int(points))
    values[0], values[-1] = lo, hi
    systems = [system.at(**{param: float(v)}) for v in values]
    total = 2 * len(systems)

    def startup_progress(done: int, _: int) -> None:
        if progress is not None:
            progress(done, total)

    starts = run_many([(s, None) for s in systems], t_max=t_max, max_events=max_events,
                      workers=workers, progress=startup_progress)
    continued: list[ContactOutcome] = []
    state = None
    for i, s in enumerate(systems):
        outcome = run_one(s, state, t_max, max_events)
        continued.append(outcome)
        state = outcome.final_state
        if progress is not None:
            progress(len(systems) + i + 1, total)
    found = tuple(ContactPoint(float(v), c, u)
                  for v, c, u in zip(values, continued, starts, strict=True))
    return ContactContinuation(system, param, (lo, hi), found, _branches(found))


__all__ = ["DEFAULT_POINTS", "FOLLOWED", "PARAMETERS", "ContactBranch", "ContactContinuation",
           "ContactPoint", "continue_contact"]
