"""The critical-lambda search: bracket a change of verdict along ``lambda``, then bisect it.

One search serves every caller: the boundary curves of :func:`stickslip.sweep.stick_slip_boundary`
(all brackets of all ``zeta`` bisected together, one parallel batch per round), the onset of
one structure (:func:`find_onset` and :func:`lowest_onset`, used by the design procedure, the
stick-slip tuning and the reproduction; :func:`speed_and_load_onsets` for a machine's own
friction law, whose dimensionless form moves with the belt speed or the load) and anything
built on them. The rules, stated once:

* a bracket ``(lo, hi)`` has certified verdicts of different kinds at its ends;
* the midpoint is geometric, ``sqrt(lo hi)`` (``lambda`` spans decades);
* a bracket is done when ``hi - lo <= rtol * lo`` (or no float lies strictly inside it), and
  the crossing is reported at ``sqrt(lo hi)``, within ``rtol / 2`` relative;
* a midpoint whose run is undetermined stops its bracket, which is then reported as not
  converged rather than guessed.
"""

from __future__ import annotations

import itertools
import math
import warnings
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions, SimulationResult, simulate
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.model._validate import positive
from stickslip.model.parameters import Slider
from stickslip.model.physical import PhysicalSystem
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
CodeArray = NDArray[np.int8]

#: ``classify(group, lams)``: verdict codes of the runs at ``lams[i]`` in group ``group[i]``
#: (a group is one curve, e.g. one ``zeta``); called once per bisection round.
Classifier = Callable[[IntArray, FloatArray], CodeArray]



@dataclass(frozen=True)
class Crossing:
    """A change of verdict along ``lambda`` at fixed ``zeta``.

    Attributes
    ----------
    lam : float
        Location, the geometric midpoint of the final bracket (dimensionless).
    lam_below, lam_above : float
        Final bracket, ``lam_below < lam < lam_above``: the verdict at ``lam_below`` differs
        from the one at ``lam_above``. ``lo`` and ``hi`` are their former names (deprecated,
        one release); the JSON keys stay ``lo`` and ``hi``.
    onset : bool
        True when stick-slip lies above (steady sliding below), False for the reverse.
    converged : bool
        True when ``hi - lo <= rtol * lo``; False when a bisection run was undetermined.
    """

    lam: float
    lam_below: float
    lam_above: float
    onset: bool
    converged: bool

    @property
    def lo(self) -> float:
        """Deprecated name of :attr:`lam_below`."""
        warnings.warn("Crossing.lo is deprecated: use lam_below", DeprecationWarning, stacklevel=2)
        return self.lam_below

    @property
    def hi(self) -> float:
        """Deprecated name of :attr:`lam_above`."""
        warnings.warn("Crossing.hi is deprecated: use lam_above", DeprecationWarning, stacklevel=2)
        return self.lam_above

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``lambda``, the bracket ``lo`` and ``hi``, ``kind`` and ``converged``."""
        return {"lambda": self.lam, "lo": self.lam_below, "hi": self.lam_above,
                "kind": "onset" if self.onset else "end", "converged": self.converged}


def _narrow(lo: float, hi: float, rtol: float) -> bool:
    """Bracket reached the tolerance, or no float lies strictly between its ends."""
    mid = math.sqrt(lo * hi)
    return hi - lo <= rtol * lo or not lo < mid < hi


def scan_brackets(lams: FloatArray, codes: CodeArray) -> list[tuple[float, float, int]]:
    """Brackets ``(lo, hi, verdict at lo)`` between consecutive certified scan points that differ.

    Undetermined scan points are skipped: their certified neighbours bracket across them.

    Parameters
    ----------
    lams : ndarray
        Increasing scan points of ``lambda``.
    codes : ndarray of int
        Verdict codes at ``lams`` (:attr:`Verdict.code`).

    Returns
    -------
    list of (float, float, int)
        Each bracket ``(lo, hi, verdict code at lo)``, undetermined points skipped.
    """
    known = [(float(lam), int(c)) for lam, c in zip(lams, codes, strict=True)
             if c != Verdict.UNDETERMINED.code]
    return [(lo, hi, v_lo) for (lo, v_lo), (hi, v_hi) in itertools.pairwise(known) if v_lo != v_hi]



#: Smallest relative tolerance of a bisection: below it the bracket's ends are neighbouring
#: floating-point numbers, and "converged" would be claimed of a bracket it cannot resolve.
MIN_RTOL = 1e-14


def checked_rtol(rtol: float) -> float:
    """``rtol`` of a bisection, checked: positive, at least :data:`MIN_RTOL`, below 1.

    Parameters
    ----------
    rtol : float
        Relative tolerance of a crossing.

    Returns
    -------
    float
        ``rtol``.
    """
    rtol = positive("rtol", rtol)
    if not MIN_RTOL <= rtol < 1.0:
        raise ValueError(f"rtol={rtol!r} must lie in [{MIN_RTOL:g}, 1): below {MIN_RTOL:g} "
                         "double precision cannot resolve the crossing")
    return rtol


def bisect_crossings(
    classify: Classifier,
    brackets: Sequence[tuple[int, float, float, int]],
    rtol: float,
) -> tuple[list[tuple[int, Crossing]], int]:
    """Bisect every bracket ``(group, lo, hi, verdict at lo)`` to ``rtol``, all at once.

    Each round classifies the midpoints of every open bracket with one call, so a parallel
    classifier runs them as one batch. Returns the ``(group, Crossing)`` pairs in the order
    of ``brackets`` and the number of runs made.

    Parameters
    ----------
    classify : callable
        ``classify(group, lams)``: verdict codes of the runs at ``lams[i]`` in group ``group[i]``.
    brackets : sequence of (int, float, float, int)
        ``(group, lo, hi, verdict code at lo)``.
    rtol : float
        Relative width at which a bracket is narrow enough.

    Returns
    -------
    list of (int, Crossing), int
        The ``(group, Crossing)`` pairs in the order of ``brackets`` and the number of runs.
    """
    rtol = checked_rtol(rtol)
    state = [[j, lo, hi, v_lo, True] for j, lo, hi, v_lo in brackets]
    active = [b for b in state if not _narrow(b[1], b[2], rtol)]
    n_runs = 0
    while active:
        mids = np.array([math.sqrt(b[1] * b[2]) for b in active])
        codes = classify(np.array([b[0] for b in active], dtype=np.int64), mids)
        n_runs += mids.size
        for b, mid, code in zip(active, mids, codes, strict=True):
            if code == Verdict.UNDETERMINED.code:
                b[4] = False
            elif code == b[3]:
                b[1] = float(mid)
            else:
                b[2] = float(mid)
        active = [b for b in active if b[4] and not _narrow(b[1], b[2], rtol)]
    crossings = [
        (int(j), Crossing(math.sqrt(lo * hi), lo, hi, onset=v_lo == Verdict.STEADY_SLIDING.code,
                          converged=bool(ok)))
        for j, lo, hi, v_lo, ok in state
    ]
    return crossings, n_runs


#: ``slider_at(lam)``: the contact at ``lambda = lam`` (its friction law may change with it).
SliderAt = Callable[[float], Slider]
#: ``on_run(lam, result)``: called after every run of a search (progress, undetermined runs).
RunHook = Callable[[float, SimulationResult], None]


def run_code(structure: Structure, slider: Slider, options: EngineOptions,
             on_run: RunHook | None = None) -> int:
    """Certified verdict code of one run of ``slider`` from the startup state.

    Raises ``ValueError`` on a spent step budget (a structure the engine cannot step through).

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices.
    slider : Slider
        ``lambda``, ``gamma`` and the dimensionless friction law.
    options : EngineOptions
        Horizon, event budget and cycle tolerance.
    on_run : callable, optional
        ``on_run(slider.lam, result)`` after the run.

    Returns
    -------
    int
        :attr:`Verdict.code` of the run.
    """
    result = simulate(structure, slider, options=options, record=False)
    if on_run is not None:
        on_run(slider.lam, result)
    if result.status is RunStatus.MAX_STEPS:
        raise ValueError(f"lambda={slider.lam:g}: {result.status.message}")
    return result.verdict.code


def verdict_code(structure: Structure, lam: float, gamma: float, options: EngineOptions) -> int:
    """Certified verdict code of one Coulomb run from the startup state (raises on a spent step budget).

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.
    lam : float
        ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``, dimensionless, > 0.
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless.
    options : EngineOptions
        Horizon, event budget and cycle tolerance.

    Returns
    -------
    int
        :attr:`Verdict.code` of the run.
    """
    return run_code(structure, Slider(lam, gamma=gamma), options)


@dataclass(frozen=True)
class Onset:
    """Result of :func:`find_onset`: the smallest ``lambda`` where steady sliding is not proven.

    Attributes
    ----------
    lam : float
        The onset (dimensionless): ``lam_min`` when the first scan point already stick-slips
        (the true onset is at most that), ``inf`` when nothing up to ``lam_max`` does.
    lam_min, lam_max : float
        The range searched.
    converged : bool
        True when the final bracket is ``rtol`` narrow (kept for callers of the bracket searches:
        an undetermined run no longer stops this one, see :func:`find_onset`).
    n_runs : int
        Simulations made.
    n_undetermined : int
        Runs that ended undetermined (horizon, event budget, unproven cycle), all counted on the
        stick-slip side: steady sliding is not proven there.
    bracket : tuple of float
        ``(lam_below, lam_above)``: the last scan step or the final bisection bracket, between
        a run certified not to stick-slip and one that is not (``(lam_min, lam_min)`` or
        ``(lam_max, inf)`` at the ends of the range).
    undetermined_by : tuple of (str, int)
        The undetermined runs by run status (:attr:`RunStatus.label`, count): why they are.
    undetermined_above : bool
        The run at ``bracket[1]`` (at ``lam_min`` when the search starts there) ended
        undetermined: steady sliding ends at the onset, but stick-slip is not proven just above it.
    """

    lam: float
    lam_min: float
    lam_max: float
    converged: bool
    n_runs: int
    n_undetermined: int = 0
    bracket: tuple[float, float] = (math.nan, math.nan)
    undetermined_by: tuple[tuple[str, int], ...] = ()
    undetermined_above: bool = False

    @property
    def at_lower_bound(self) -> bool:
        """Steady sliding not proven already at ``lam_min``: the onset is ``<= lam_min``."""
        return self.lam <= self.lam_min

    @property
    def above_range(self) -> bool:
        """No stick-slip anywhere up to ``lam_max``: the onset is above it (or does not exist)."""
        return math.isinf(self.lam)


#: Ratio of consecutive ``lambda`` of the onset scan (:func:`find_onset`): 25 % steps.
ONSET_GROWTH = 1.25


def find_onset(
    structure: Structure,
    *,
    gamma: float = 2.0,
    slider_at: SliderAt | None = None,
    lam_min: float = 0.05,
    lam_max: float = 200.0,
    growth: float = ONSET_GROWTH,
    rtol: float = 1e-6,
    options: EngineOptions | None = None,
    on_run: RunHook | None = None,
) -> Onset:
    """Onset of stick-slip from the startup state: where steady sliding stops being proven.

    The scan multiplies ``lambda`` by ``growth`` from ``lam_min`` until the first run that is
    not certified to slide (a stick-slip verdict or an undetermined one: a run whose cycle is
    not proven, or which reaches its horizon, sticks or may; steady sliding and a slip
    oscillation are certified not to), then :func:`bisect_crossings` bisects the last step on
    that distinction. Below the onset every run of the search is certified not to stick-slip;
    :attr:`Onset.undetermined_above` says when the run just above it is undetermined rather
    than proven stick-slip (a machine whose stick-slip near the onset has no proven cycle).
    Counting undetermined runs as "not stick-slip" instead would report an onset deep in a
    region where the runs stick: on the tuned slideway example, 0.418 mm/s, below runs that
    stick-slip at 0.5 and 0.6 mm/s. A stick-slip island narrower than one scan step can be
    stepped over; for every verdict change, use :func:`stickslip.sweep.stick_slip_boundary`.

    Parameters
    ----------
    structure : Structure
        The slider on its structure (rigid base, foundation or chain).
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless (the Coulomb contact, without ``slider_at``).
    slider_at : callable, optional
        ``slider_at(lam)``: the contact at ``lambda = lam``, for a friction law whose
        dimensionless form moves with ``lambda`` (a Stribeck law's ``v_s / V`` when the belt
        speed ``V`` sets ``lambda``). Default: the paper's Coulomb law, ``Slider(lam, gamma)``.
    lam_min, lam_max : float
        Scan range, dimensionless.
    growth : float
        Ratio of consecutive scan points, > 1.
    rtol : float
        Relative width of the final bracket.
    options : EngineOptions, optional
        Engine limits of every run.
    on_run : callable, optional
        ``on_run(lam, result)`` after every run (progress; the status of undetermined runs).

    Returns
    -------
    Onset
        The onset, the range searched, whether the bisection converged and the number of runs.
    """
    lam_min = positive("lam_min", lam_min)
    if growth <= 1.0:
        raise ValueError(f"growth={growth!r} must exceed 1")
    opts = options or EngineOptions()
    contact = slider_at or (lambda lam: Slider(lam, gamma=gamma))
    n_runs = n_undetermined = 0
    why: Counter[str] = Counter()

    def watch(lam: float, result: SimulationResult) -> None:
        if result.verdict is Verdict.UNDETERMINED:
            why[result.status.label] += 1
        if on_run is not None:
            on_run(lam, result)

    undetermined_at: set[float] = set()

    def stick_slips(lam: float) -> int:
        """STICK_SLIP unless the run is certified not to stick-slip (then STEADY_SLIDING)."""
        nonlocal n_runs, n_undetermined
        n_runs += 1
        code = run_code(structure, contact(lam), opts, watch)
        if code == Verdict.UNDETERMINED.code:
            n_undetermined += 1
            undetermined_at.add(lam)
            return Verdict.STICK_SLIP.code  # steady sliding not proven: the stick-slip side
        if code == Verdict.STICK_SLIP.code:
            return code
        return Verdict.STEADY_SLIDING.code  # "not stick-slip": a slip oscillation counts as steady here

    def done(lam: float, converged: bool, bracket: tuple[float, float]) -> Onset:
        return Onset(lam, lam_min, lam_max, converged, n_runs, n_undetermined, bracket,
                     tuple(sorted(why.items())), bracket[1] in undetermined_at)

    def classify(_group: IntArray, lams: FloatArray) -> CodeArray:
        return np.array([stick_slips(float(lam)) for lam in lams], dtype=np.int8)

    lo = lam_min
    if stick_slips(lo) == Verdict.STICK_SLIP.code:
        return done(lo, True, (lo, lo))
    hi = lo * growth
    while stick_slips(hi) != Verdict.STICK_SLIP.code:
        if hi >= lam_max:
            return done(math.inf, True, (hi, math.inf))
        lo, hi = hi, min(hi * growth, lam_max)
    [(_, crossing)], _ = bisect_crossings(classify, [(0, lo, hi, Verdict.STEADY_SLIDING.code)], rtol)
    return done(crossing.lam, crossing.converged, (crossing.lam_below, crossing.lam_above))


@dataclass(frozen=True)
class SpeedLoadOnsets:
    """The onset of stick-slip of one structure along the belt speed and along the normal load.

    ``lambda = (mu_s - mu_k) W / (V sqrt(m k))`` moves with ``V`` and with ``W``; a friction
    law's dimensionless form moves with one of them too (a Stribeck law's ``v_s / V`` and
    ``sigma_v W / (2 sqrt(m k))``, a linear law's ``sigma W / (2 sqrt(m k))``, a table's
    ``v_i / V``), so the two onsets differ except under the paper's Coulomb law.

    Attributes
    ----------
    speed : Onset
        ``lambda`` moved by the belt speed at the operating load: stick-slip below
        ``V_c = (mu_s - mu_k) W / (lambda_c sqrt(m k))``.
    load : Onset
        ``lambda`` moved by the normal load at the operating speed: stick-slip above
        ``W_c = lambda_c V sqrt(m k) / (mu_s - mu_k)``.
    own_law : bool
        True when the searches ran with a law other than the paper's Coulomb law.
    """

    speed: Onset
    load: Onset
    own_law: bool


def speed_and_load_onsets(
    structure: Structure,
    system: PhysicalSystem,
    *,
    lam_min: float = 0.05,
    lam_max: float = 200.0,
    rtol: float = 1e-6,
    options: EngineOptions | None = None,
    on_run: Callable[[str, float, SimulationResult], None] | None = None,
) -> SpeedLoadOnsets:
    """Onsets of stick-slip along ``V`` and along ``W`` with the machine's own friction law.

    Each is :func:`find_onset` with the contact rebuilt at every ``lambda`` from the SI law
    (:meth:`~stickslip.model.physical.PhysicalFriction.dimensionless`) at the belt speed
    ``V(lambda)`` (operating load) or the load ``W(lambda)`` (operating speed). Under the
    paper's Coulomb law both are one search, the Coulomb :func:`find_onset`.

    Parameters
    ----------
    structure : Structure
        Dimensionless structure of the machine (scaled by ``system``'s ``m`` and ``k``).
    system : PhysicalSystem
        The contact in SI: ``m``, ``k`` of the scaling, ``mu_s``, ``mu_k``, operating ``W``
        and ``V``, friction law (a machine's :meth:`~stickslip.model.machine.Machine.reference_system`).
    lam_min, lam_max, rtol : float
        Scan range and relative bracket width of each search, dimensionless.
    options : EngineOptions, optional
        Engine limits of every run.
    on_run : callable, optional
        ``on_run(axis, lam, result)`` after every run, ``axis`` ``"speed"`` or ``"load"``
        (``"speed"`` for the single Coulomb search).

    Returns
    -------
    SpeedLoadOnsets
    """
    gamma = system.mu_k / (system.mu_s - system.mu_k)

    def search(axis: str, slider_at: SliderAt | None) -> Onset:
        hook = None if on_run is None else (lambda lam, result: on_run(axis, lam, result))
        return find_onset(structure, gamma=gamma, slider_at=slider_at, lam_min=lam_min,
                          lam_max=lam_max, rtol=rtol, options=options, on_run=hook)

    if system.friction.law == "coulomb":
        onset = search("speed", None)
        return SpeedLoadOnsets(onset, onset, own_law=False)
    law, m, k = system.friction, system.mass, system.stiffness

    def at_speed(lam: float) -> Slider:
        speed = system.speed_for_lambda(lam)
        return Slider(lam, gamma=gamma,
                      friction=law.dimensionless(m, k, system.mu_s, system.mu_k, system.load, speed))

    def at_load(lam: float) -> Slider:
        load = system.load_for_lambda(lam)
        return Slider(lam, gamma=gamma,
                      friction=law.dimensionless(m, k, system.mu_s, system.mu_k, load, system.speed))

    return SpeedLoadOnsets(search("speed", at_speed), search("load", at_load), own_law=True)


def lowest_onset(
    structure: Structure,
    *,
    gamma: float = 2.0,
    lam_min: float = 0.05,
    lam_max: float = 200.0,
    growth: float = ONSET_GROWTH,
    rtol: float = 1e-6,
    options: EngineOptions | None = None,
) -> float:
    """Onset of stick-slip from the startup state (dimensionless): :func:`find_onset`'s ``lam``.

    The design value: below it the system is certified to slide steadily. :func:`find_onset`
    with the paper's Coulomb law; its ``lam`` alone. Returns ``lam_min`` if steady sliding is
    not proven there and ``inf`` if it is proven everywhere up to ``lam_max``.

    Parameters
    ----------
    structure : Structure
        The slider on its structure (rigid base, foundation or chain).
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless.
    lam_min, lam_max : float
        Scan range, dimensionless.
    growth : float
        Ratio of consecutive scan points, > 1.
    rtol : float
        Relative width of the final bracket.
    options : EngineOptions, optional
        Engine limits of every run.

    Returns
    -------
    float
        The onset, dimensionless: ``lam_min`` if that already stick-slips, ``inf`` if nothing up
        to ``lam_max`` does.
    """
    return find_onset(structure, gamma=gamma, lam_min=lam_min, lam_max=lam_max, growth=growth,
                      rtol=rtol, options=options).lam


def onset_note(onset: Onset, what: str, si_at: Callable[[float], float], unit: str,
               ends: tuple[str, str], count_runs: bool = True) -> str:
    """What an onset search left open, in the machine's units ("" when nothing).

    Parameters
    ----------
    onset : Onset
        The search's result.
    what : str
        The axis in words (``"belt speed"``, ``"normal load"``).
    si_at : callable
        ``si_at(lam)``: the SI value (m/s or N) at a dimensionless ``lambda``.
    unit : str
        Unit of ``si_at``'s values.
    ends : (str, str)
        The ends of the range along this axis, least and most prone to stick-slip
        (``("fastest", "slowest")`` for the speed, ``("lightest", "heaviest")`` for the load).
    count_runs : bool
        Also say how many runs were undetermined, and why.

    Returns
    -------
    str
        The notes joined by ``"; "``: an onset at a bound of the range, a bracket an
        undetermined run left, an undetermined run just past the onset, the undetermined runs.
    """
    parts = []
    if onset.at_lower_bound:
        first = "steady sliding not proven" if onset.undetermined_above else "stick-slip"
        parts.append(f"{first} already at the {ends[0]} {what} searched, {si_at(onset.lam_min):.4g} "
                     f"{unit} (lambda = {onset.lam_min:g}, the search's lower bound): the critical "
                     f"{what} lies beyond it, not found")
    elif onset.above_range:
        parts.append(f"no run certified stick-slip, as far as the {ends[1]} {what}, "
                     f"{si_at(onset.lam_max):.4g} {unit} (lambda = {onset.lam_max:g}, the search's "
                     "upper bound): no critical value inside it")
    elif not onset.converged:
        a, b = sorted(si_at(x) for x in onset.bracket)
        parts.append(f"an undetermined run stopped the bisection: the critical {what} lies between "
                     f"{a:.4g} and {b:.4g} {unit}")
    if onset.undetermined_above and not (onset.above_range or onset.at_lower_bound):
        parts.append(f"steady sliding is proven at the runs before the critical {what}, but the run "
                     "just past it is undetermined, not proven stick-slip")
    if onset.n_undetermined and count_runs:
        messages = {status.label: status.message.split(";")[0] for status in RunStatus}
        why = ", ".join(f"{n}: {messages[label]}" for label, n in onset.undetermined_by)
        parts.append(f"{onset.n_undetermined} of {onset.n_runs} runs undetermined ({why}), counted "
                     "on the stick-slip side (steady sliding is not proven there): a larger t_max "
                     "may decide them")
    return "; ".join(parts)
