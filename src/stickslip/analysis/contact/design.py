"""``design`` for a machine with its contact (normal DOF, separation, a Jenkins element).

The paper's closed forms (Eq. 36) and its foundation tuning (Eqs. 28-30) assume a rigid
contact under a constant normal load. With a contact the design answers by the contact
engine (:func:`~stickslip.analysis.contact.engine.simulate_contact`) for each variant of the
machine (the machine as given; for the paper's slider also the rigid base and the foundation,
given or recommended by Eqs. 28-30 for the rigid contact, then assessed with the contact):

- the **start-up verdict** at the operating point, with period, amplitude and whether the
  contact lifted off (observed, not proven, as the engine says);
- the **critical belt speed and load**: every change of the start-up verdict along the speed
  (the load held) and along the load (the speed held), over :data:`DECADES` decade either side
  of the operating point (:func:`~stickslip.analysis.contact.boundary.contact_boundary`: a scan
  and bisection to :data:`RTOL`; a change next to an undetermined run is never a boundary).

Steady sliding's complex-eigenvalue analysis (machines with a normal DOF) is the caller's:
it needs the machine's contact, not only its engine system.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from stickslip.analysis.contact._modes import ContactSystem
from stickslip.analysis.contact.boundary import ContactBoundary, contact_boundary
from stickslip.analysis.contact.engine import ContactRun, simulate_contact
from stickslip.analysis.contact.pool import DEFAULT_WORKERS

#: Decades of speed and load either side of the operating point searched for verdict changes.
DECADES = 1.0
#: Scan values of each search.
N_SCAN = 9
#: Relative width of each boundary's bracket.
RTOL = 1e-3


@dataclass(frozen=True)
class ContactDesignRow:
    """One variant of the machine: its start-up run and its critical speed and load searches."""

    name: str
    system: ContactSystem = field(repr=False)
    run: ContactRun = field(repr=False)
    speed_search: ContactBoundary = field(repr=False)
    load_search: ContactBoundary = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI)."""
        run = self.run
        return {"name": self.name, "verdict": run.verdict.value, "certificate": run.certificate,
                "period_s": run.period_s, "amplitude_m": run.amplitude_m,
                "separated": run.separated,
                "critical_speeds_m_per_s": [c.value for c in self.speed_search.boundaries],
                "critical_loads_N": [c.value for c in self.load_search.boundaries],
                "speed_search": self.speed_search.to_dict(),
                "load_search": self.load_search.to_dict()}


@dataclass(frozen=True)
class ContactDesign:
    """The design report of a machine with its contact (module notes)."""

    rows: tuple[ContactDesignRow, ...]
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI)."""
        return {"rows": [r.to_dict() for r in self.rows], "notes": list(self.notes),
                "engine": "exact piecewise-affine engine with the contact (start-up runs)",
                "search": {"decades": DECADES, "n_scan": N_SCAN, "rtol": RTOL}}

    def summary(self) -> str:
        """A few lines per variant for the terminal."""
        lines = []
        for row in self.rows:
            p = row.to_dict()
            cycle = ("" if p["period_s"] is None else
                     f", period {p['period_s']:.6g} s, amplitude {p['amplitude_m']:.6g} m")
            lift = ", the contact lifts off" if p["separated"] else ""
            lines.append(f"{row.name:24} {p['verdict']}{cycle}{lift}")
            for search, unit in ((row.speed_search, "m/s"), (row.load_search, "N")):
                lines.append(f"{'':24} {_crossings(search, unit)}")
        lines += [f"note: {n}" for n in self.notes]
        return "\n".join(lines)


def _crossings(search: ContactBoundary, unit: str) -> str:
    """One line: the verdict changes of a search, with the verdicts either side."""
    what = "speed" if search.param == "speed" else "load"
    lo, hi = search.range
    if not search.crossings:
        verdict = search.scan[0].verdict.value if search.scan else "-"
        return (f"critical {what}: none, {verdict} from {lo:.4g} to {hi:.4g} {unit}")
    parts = []
    for c in search.crossings:
        a, b = c.bracket
        if c.is_boundary:
            parts.append(f"{c.value:.5g} {unit} ({c.below.value} below, {c.above.value} above)")
        else:
            parts.append(f"between {a:.4g} and {b:.4g} {unit} ({c.below.value} / "
                         f"{c.above.value}: not a boundary)")
    return f"critical {what}: " + "; ".join(parts)


def design_contact(systems: Mapping[str, ContactSystem], *, workers: int = DEFAULT_WORKERS,
                   notes: tuple[str, ...] = (),
                   progress: Callable[[str, int], None] | None = None) -> ContactDesign:
    """Start-up verdicts and critical speeds and loads of each variant of a contact machine.

    Parameters
    ----------
    systems : mapping of str to ContactSystem
        The variants by name (SI), e.g. ``{"rigid base": ..., "recommended foundation": ...}``.
    workers : int
        Worker processes of the searches.
    notes : tuple of str
        Sentences the report carries (what was not assessed, and why).
    progress : callable, optional
        ``progress(stage, runs)`` as the searches go.

    Returns
    -------
    ContactDesign
        One row per variant.
    """
    rows = []
    runs = 0
    for name, system in systems.items():
        if progress is not None:
            progress(f"{name}: start-up run", runs)
        run = simulate_contact(system)
        runs += 1
        searches = []
        for param, value in (("speed", system.speed), ("load", system.load)):
            spread = 10.0 ** DECADES
            done = runs

            def step(count: int, _total: int, stage: str = f"{name}: critical {param}",
                     base: int = done) -> None:
                if progress is not None:
                    progress(stage, base + count)

            search = contact_boundary(system, param, value / spread, value * spread,
                                      n_scan=N_SCAN, rtol=RTOL, workers=workers, progress=step)
            runs += search.n_runs
            searches.append(search)
        rows.append(ContactDesignRow(name, system, run, searches[0], searches[1]))
    return ContactDesign(tuple(rows), notes)
