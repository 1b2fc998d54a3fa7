"""The critical-lambda search: bracket a change of verdict along ``lambda``, then bisect it.

One search serves every caller: the boundary curves of :func:`stickslip.sweep.stick_slip_boundary`
(all brackets of all ``zeta`` bisected together, one parallel batch per round), the onset of
one structure (:func:`lowest_onset`, used by the design procedure, the stick-slip tuning and
the reproduction) and anything built on them. The rules, stated once:

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
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.model._validate import positive
from stickslip.model.parameters import Slider
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
    rtol = positive("rtol", rtol)
    if rtol >= 1.0:
        raise ValueError(f"rtol={rtol!r} must be below 1")
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


def verdict_code(structure: Structure, lam: float, gamma: float, options: EngineOptions) -> int:
    """Certified verdict code of one run from the startup state (raises on a spent step budget).

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
    result = simulate(structure, Slider(lam, gamma=gamma), options=options, record=False)
    if result.status is RunStatus.MAX_STEPS:
        raise ValueError(f"lambda={lam:g}: {result.status.message}")
    return result.verdict.code


def lowest_onset(
    structure: Structure,
    *,
    gamma: float = 2.0,
    lam_min: float = 0.05,
    lam_max: float = 200.0,
    growth: float = 1.25,
    rtol: float = 1e-6,
    options: EngineOptions | None = None,
) -> float:
    """Smallest ``lambda`` with a stick-slip verdict from the startup state (dimensionless).

    The design value: below it the system slides steadily. The scan multiplies ``lambda`` by
    ``growth`` from ``lam_min`` until the first stick-slip verdict (undetermined scan points
    count as not stick-slip), then :func:`bisect_crossings` bisects the last step. Returns
    ``lam_min`` if it already stick-slips and ``inf`` if nothing up to ``lam_max`` does. A
    stick-slip island narrower than one scan step can be stepped over; for every verdict
    change, use :func:`stickslip.sweep.stick_slip_boundary`.

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
    lam_min = positive("lam_min", lam_min)
    if growth <= 1.0:
        raise ValueError(f"growth={growth!r} must exceed 1")
    opts = options or EngineOptions()

    def classify(_group: IntArray, lams: FloatArray) -> CodeArray:
        return np.array([verdict_code(structure, float(lam), gamma, opts) for lam in lams],
                        dtype=np.int8)

    lo = lam_min
    if verdict_code(structure, lo, gamma, opts) == Verdict.STICK_SLIP.code:
        return lo
    hi = lo * growth
    while verdict_code(structure, hi, gamma, opts) != Verdict.STICK_SLIP.code:
        if hi >= lam_max:
            return math.inf
        lo, hi = hi, min(hi * growth, lam_max)
    [(_, crossing)], _ = bisect_crossings(classify, [(0, lo, hi, Verdict.STEADY_SLIDING.code)], rtol)
    return crossing.lam
