"""The critical belt speed or load of a machine with its contact, from start-up runs.

A machine with a contact (a normal DOF, separation, a Jenkins element) has no closed-form
boundary, and neither has a structure of many DOF: the start-up verdict of the contact engine
(:func:`stickslip.analysis.contact.engine.simulate_contact`), or of the exact engine for a
:class:`~stickslip.model.machine.Machine` of a structure alone
(:func:`~stickslip.analysis.contact.pool.run_machine_point`), is computed along one operating
parameter, the belt speed ``V`` (m/s) or the preload ``W`` (N), the other held at the
machine's own value. Unlike the onset search of ``design``
(:func:`stickslip.analysis.critical.find_onset`, the first stick-slip of a scan from steady
sliding), it reports every change it brackets: an island of stick-slip above the onset (the
gallery's slideway has one) is two crossings. The search:

1. a scan of ``n_scan`` log-spaced values over ``[lo, hi]``, one run each;
2. every neighbouring pair of scan values with two different *determined* verdicts
   (steady sliding, stick-slip, slip-oscillation) is bisected at the geometric midpoint until
   the bracket's ratio is within ``1 + rtol``. A midpoint with a third determined verdict
   splits the bracket in two (both bisected on); every bisection is bounded
   (:data:`MAX_HALVINGS` rounds, :data:`MAX_RUNS` runs in all);
3. a pair with an undetermined verdict on one side (the horizon or the event budget ended the
   run before a verdict), at the scan or at a midpoint, is reported as an *undetermined*
   crossing with its bracket: never as a boundary.

Each crossing is the bracket ``[a, b]`` with the verdict at ``a`` (``below``) and at ``b``
(``above``); a boundary's value is the bracket's geometric midpoint. The midpoints of all open
brackets of a round run together, in the process pool of
:func:`stickslip.analysis.contact.pool.run_points`. A verdict change narrower than a scan
step (two changes between neighbouring scan values) is not seen.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from stickslip.analysis.contact._modes import ContactSystem
from stickslip.analysis.contact.pool import DEFAULT_WORKERS, ContactPoint, ContactPool
from stickslip.analysis.verdict import Verdict
from stickslip.model.machine import Machine

#: The operating parameters and their SI units.
PARAMS = {"speed": "m/s", "load": "N"}
#: Most scan points.
MAX_SCAN = 400
#: Most bisection rounds (halvings of a log-bracket) per crossing.
MAX_HALVINGS = 60
#: Most runs of one search, scan included.
MAX_RUNS = 5_000


@dataclass(frozen=True)
class ContactCrossing:
    """One verdict change along the parameter (SI).

    Attributes
    ----------
    param : str
        ``speed`` (m/s) or ``load`` (N).
    bracket : tuple of float
        The values ``(a, b)``, ``a < b``, either side of the change.
    below, above : Verdict
        The start-up verdicts at ``a`` and ``b``.
    converged : bool
        The bracket is within ``1 + rtol`` (False: a budget ended the bisection, or an
        undetermined verdict stopped it).
    """

    param: str
    bracket: tuple[float, float]
    below: Verdict
    above: Verdict
    converged: bool

    @property
    def is_boundary(self) -> bool:
        """True when both sides are determined verdicts (not ``undetermined``)."""
        return Verdict.UNDETERMINED not in (self.below, self.above)

    @property
    def value(self) -> float | None:
        """The critical value (geometric midpoint of the bracket) of a boundary, else None."""
        return math.sqrt(self.bracket[0] * self.bracket[1]) if self.is_boundary else None

    def to_dict(self) -> dict[str, Any]:
        """``param``, ``value_SI`` (None unless a boundary), ``bracket``, ``below``, ``above``,
        ``kind`` (``boundary`` or ``undetermined``), ``converged``."""
        return {"param": self.param, "value_SI": self.value, "bracket": list(self.bracket),
                "below": self.below.value, "above": self.above.value,
                "kind": "boundary" if self.is_boundary else "undetermined",
                "converged": self.converged}


@dataclass(frozen=True)
class ContactBoundary:
    """The verdict changes of a contact machine along speed or load (:func:`contact_boundary`).

    Attributes
    ----------
    param : str
        ``speed`` or ``load``.
    fixed : float
        The other operating value, held (N for a speed search, m/s for a load search).
    range : tuple of float
        The scanned interval, SI.
    rtol : float
        Relative tolerance of each bisection.
    scan : tuple of ContactPoint
        The scan's runs.
    crossings : tuple of ContactCrossing
        Every verdict change found, ascending.
    n_runs : int
        Runs in all (scan and bisection).
    elapsed_s : float
        Wall time, s.
    """

    param: str
    fixed: float
    range: tuple[float, float]
    rtol: float
    scan: tuple[ContactPoint, ...]
    crossings: tuple[ContactCrossing, ...]
    n_runs: int
    elapsed_s: float
    #: what each run's verdict is (the contact engine's, or the exact engine's)
    criterion: str = ("start-up verdict of the contact engine (observed periodic motion or the "
                      "steady-sliding bound)")

    @property
    def boundaries(self) -> tuple[ContactCrossing, ...]:
        """The crossings between two determined verdicts."""
        return tuple(c for c in self.crossings if c.is_boundary)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the search, the scan's verdicts and every crossing."""
        other = "load" if self.param == "speed" else "speed"
        return {"param": self.param, "unit": PARAMS[self.param],
                f"{other}_SI": self.fixed, "range_SI": list(self.range), "rtol": self.rtol,
                "n_scan": len(self.scan),
                "scan": [{"value_SI": p.speed if self.param == "speed" else p.load,
                          "verdict": p.verdict.value} for p in self.scan],
                "crossings": [c.to_dict() for c in self.crossings],
                "n_runs": self.n_runs, "elapsed_s": self.elapsed_s,
                "seconds_per_run": self.elapsed_s / self.n_runs if self.n_runs else None,
                "criterion": self.criterion}


def _check(param: str, lo: float, hi: float, n_scan: int, rtol: float) -> None:
    if param not in PARAMS:
        raise ValueError(f"param {param!r} must be one of {', '.join(PARAMS)}")
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise ValueError(f"range {lo!r}:{hi!r} must be positive and finite with lo < hi "
                         f"[{PARAMS[param]}]")
    if isinstance(n_scan, bool) or int(n_scan) != n_scan or not 2 <= n_scan <= MAX_SCAN:
        raise ValueError(f"n_scan = {n_scan!r} must be a whole number from 2 to {MAX_SCAN}")
    if not (math.isfinite(rtol) and 0.0 < rtol < 1.0):
        raise ValueError(f"rtol = {rtol!r} must be between 0 and 1")


#: :attr:`ContactBoundary.criterion` of a machine of a structure alone
EXACT_CRITERION = ("start-up verdict of the exact engine (a proven cycle or the steady-sliding "
                   "bound)")


def contact_boundary(system: ContactSystem | Machine, param: str, lo: float, hi: float, *,
                     n_scan: int = 12, rtol: float = 1e-3, workers: int = DEFAULT_WORKERS,
                     t_max: float | None = None, max_events: int = 100_000,
                     progress: Callable[[int, int], None] | None = None) -> ContactBoundary:
    """Every change of the start-up verdict along the belt speed or the load (module notes).

    Parameters
    ----------
    system : ContactSystem or Machine
        The machine (SI): with its contact, or a structure alone (the exact engine); the
        parameter not searched keeps its value.
    param : str
        ``speed`` (belt speed, m/s) or ``load`` (preload, N).
    lo, hi : float
        The interval scanned, SI, ``0 < lo < hi``.
    n_scan : int
        Log-spaced scan values (2 to :data:`MAX_SCAN`).
    rtol : float
        Each boundary's bracket ends within ``hi / lo <= 1 + rtol``.
    workers : int
        Worker processes (:func:`~stickslip.analysis.contact.pool.run_points`).
    t_max : float, optional
        Horizon of each run in natural times of the contact DOF (default 5000).
    max_events : int
        Bound on mode switches of each run.
    progress : callable, optional
        ``progress(done, total)`` after each run; ``total`` grows as brackets open.

    Returns
    -------
    ContactBoundary
        The scan and every crossing, with brackets and the verdicts either side.

    Raises
    ------
    ValueError
        A bad parameter name, range, scan size or tolerance.
    """
    _check(param, lo, hi, n_scan, rtol)
    began = time.perf_counter()
    fixed = system.load if param == "speed" else system.speed
    counted = [0, int(n_scan)]

    def point(x: float) -> tuple[float, float]:
        return (x, fixed) if param == "speed" else (fixed, x)

    def run(values: list[float]) -> list[Verdict]:
        offset = counted[0]

        def step(done: int, _total: int) -> None:
            if progress is not None:
                progress(offset + done, counted[1])

        found = pool.run([point(x) for x in values], progress=step)
        counted[0] += len(values)
        runs.extend(found)
        return [p.verdict for p in found]

    runs: list[ContactPoint] = []
    with ContactPool(system, workers=workers, t_max=t_max, max_events=max_events) as pool:
        values = np.geomspace(lo, hi, int(n_scan)).tolist()
        verdicts = run(values)
        scan = tuple(runs)
        done: list[ContactCrossing] = []
        open_: list[tuple[float, float, Verdict, Verdict, int]] = []
        for a, b, va, vb in zip(values[:-1], values[1:], verdicts[:-1], verdicts[1:], strict=True):
            if va is vb:
                continue
            if Verdict.UNDETERMINED in (va, vb):
                done.append(ContactCrossing(param, (a, b), va, vb, False))
            else:
                open_.append((a, b, va, vb, 0))
        while open_:
            still: list[tuple[float, float, Verdict, Verdict, int]] = []
            for a, b, va, vb, k in open_:
                if b / a - 1.0 <= rtol or k >= MAX_HALVINGS or counted[0] >= MAX_RUNS:
                    done.append(ContactCrossing(param, (a, b), va, vb, b / a - 1.0 <= rtol))
                else:
                    still.append((a, b, va, vb, k))
            if not still:
                break
            mids = [math.sqrt(a * b) for a, b, *_ in still]
            counted[1] = counted[0] + len(mids)
            open_ = []
            for (a, b, va, vb, k), m, vm in zip(still, mids, run(mids), strict=True):
                if vm is va:
                    open_.append((m, b, va, vb, k + 1))
                elif vm is vb:
                    open_.append((a, m, va, vb, k + 1))
                elif vm is Verdict.UNDETERMINED:
                    done += [ContactCrossing(param, (a, m), va, vm, False),
                             ContactCrossing(param, (m, b), vm, vb, False)]
                else:  # a third determined verdict between: two changes, both bisected on
                    open_ += [(a, m, va, vm, k + 1), (m, b, vm, vb, k + 1)]
    done.sort(key=lambda c: c.bracket[0])
    criterion = {"criterion": EXACT_CRITERION} if isinstance(system, Machine) else {}
    return ContactBoundary(param, float(fixed), (float(lo), float(hi)), float(rtol), scan,
                           tuple(done), len(runs), time.perf_counter() - began, **criterion)


__all__ = ["MAX_HALVINGS", "MAX_RUNS", "MAX_SCAN", "PARAMS", "ContactBoundary",
           "ContactCrossing", "contact_boundary"]
