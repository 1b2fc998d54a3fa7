"""Critical lambda of one structure by simulation: every verdict change along lambda.

For the rigid base the stick-slip region is ``lambda > lambda_c`` (Eq. 36), but with a
detuned foundation it need not be an interval (paper Fig. 11a). So the lambda axis is
scanned on a log grid, every change of verdict is bracketed, and each bracket is bisected
on the certified verdict to a relative tolerance.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from stickslip.analysis.simulation import DEFAULT_T_MAX, Verdict, simulate
from stickslip.model._validate import positive
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure


@dataclass(frozen=True)
class Crossing:
    """A verdict change at ``lam``: ``onset`` True when stick-slip starts above it."""

    lam: float
    onset: bool


@dataclass(frozen=True)
class CriticalLambdas:
    """All verdict changes found along lambda for one structure.

    Attributes
    ----------
    crossings : tuple of Crossing
        Sorted by ``lam``; each located to ``rtol`` relative.
    lam_min, lam_max : float
        The scanned range.
    undetermined : tuple of float
        Scan points whose verdict could not be certified (they are skipped).
    """

    crossings: tuple[Crossing, ...]
    lam_min: float
    lam_max: float
    rtol: float
    undetermined: tuple[float, ...] = field(default=())

    @property
    def lowest(self) -> float:
        """Smallest lambda at which stick-slip starts (``inf`` if never in the range).

        This is the design value: below it the system slides steadily (from the startup
        state). Equals the root of Eq. (36) for the rigid base.
        """
        for c in self.crossings:
            if c.onset:
                return c.lam
        return math.inf


def _is_stick_slip(structure: Structure, lam: float, zeta: float, gamma: float,
                   t_max: float) -> bool | None:
    verdict = simulate(structure, Slider(lam, zeta, gamma), t_max=t_max, record=False).verdict
    if verdict is Verdict.UNDETERMINED:
        return None
    return verdict is Verdict.STICK_SLIP


def critical_lambdas(
    structure: Structure,
    zeta: float,
    gamma: float = 2.0,
    *,
    lam_min: float = 0.01,
    lam_max: float = 100.0,
    n_scan: int = 48,
    rtol: float = 1e-6,
    t_max: float = DEFAULT_T_MAX,
) -> CriticalLambdas:
    """Every lambda in ``[lam_min, lam_max]`` where the certified verdict changes.

    Parameters
    ----------
    structure : Structure
        The structure (its damping already holds ``zeta``).
    zeta : float
        Primary damping ratio (recorded in the ``Slider`` of each run).
    gamma : float
        ``mu_k / (mu_s - mu_k)``.
    lam_min, lam_max : float
        Scan range, dimensionless, ``0 < lam_min < lam_max``.
    n_scan : int
        Log-spaced scan points (brackets narrower than the scan spacing can be missed).
    rtol : float
        Relative tolerance of each crossing.
    t_max : float
        Time horizon of each simulation.
    """
    lam_min = positive("lam_min", lam_min)
    lam_max = positive("lam_max", lam_max)
    rtol = positive("rtol", rtol)
    if lam_max <= lam_min:
        raise ValueError(f"lam_max={lam_max!r} must exceed lam_min={lam_min!r}")
    if n_scan < 2:
        raise ValueError(f"n_scan={n_scan!r} must be at least 2")
    grid = np.geomspace(lam_min, lam_max, n_scan)
    known: list[tuple[float, bool]] = []
    undetermined = []
    for lam in grid:
        state = _is_stick_slip(structure, float(lam), zeta, gamma, t_max)
        if state is None:
            undetermined.append(float(lam))
        else:
            known.append((float(lam), state))
    crossings = []
    for (lo, s_lo), (hi, s_hi) in itertools.pairwise(known):
        if s_lo == s_hi:
            continue
        while hi - lo > rtol * hi:
            mid = math.sqrt(lo * hi)
            state = _is_stick_slip(structure, mid, zeta, gamma, t_max)
            if state is None:
                break
            if state == s_lo:
                lo = mid
            else:
                hi = mid
        crossings.append(Crossing(0.5 * (lo + hi), onset=s_hi))
    return CriticalLambdas(tuple(crossings), lam_min, lam_max, rtol, tuple(undetermined))


def lowest_onset(
    structure: Structure,
    zeta: float,
    gamma: float = 2.0,
    *,
    lam_min: float = 0.05,
    lam_max: float = 200.0,
    growth: float = 1.25,
    rtol: float = 1e-6,
    t_max: float = DEFAULT_T_MAX,
) -> float:
    """Smallest lambda with a stick-slip verdict, scanning upwards from ``lam_min``.

    Faster than :func:`critical_lambdas` when only the onset matters (tuning): the scan
    multiplies lambda by ``growth`` until the first stick-slip verdict, then bisects the last
    step to ``rtol``. Returns ``lam_min`` if it already stick-slips and ``inf`` if nothing
    up to ``lam_max`` does. Undetermined points count as steady sliding. A stick-slip
    island narrower than one scan step can be stepped over.
    """
    lam_min = positive("lam_min", lam_min)
    if growth <= 1.0:
        raise ValueError(f"growth={growth!r} must exceed 1")
    lo = lam_min
    if _is_stick_slip(structure, lo, zeta, gamma, t_max):
        return lo
    hi = lo * growth
    while not _is_stick_slip(structure, hi, zeta, gamma, t_max):
        if hi >= lam_max:
            return math.inf
        lo, hi = hi, min(hi * growth, lam_max)
    while hi - lo > rtol * hi:
        mid = math.sqrt(lo * hi)
        if _is_stick_slip(structure, mid, zeta, gamma, t_max):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)
