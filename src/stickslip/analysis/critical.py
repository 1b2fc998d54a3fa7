"""Stick-slip onset of one structure by simulation: the smallest lambda that stick-slips.

This is the design value (below it the system slides steadily from the startup state) and
the objective of the stick-slip tuning. For every verdict change along lambda, including
non-monotone boundaries (paper Fig. 11a), use :func:`stickslip.sweep.stick_slip_boundary`.
"""

from __future__ import annotations

import math

from stickslip.analysis.simulation import DEFAULT_T_MAX, RunStatus, Verdict, simulate
from stickslip.model._validate import positive
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure


def _is_stick_slip(structure: Structure, lam: float, zeta: float, gamma: float,
                   t_max: float) -> bool | None:
    result = simulate(structure, Slider(lam, zeta, gamma), t_max=t_max, record=False)
    if result.status is RunStatus.MAX_STEPS:
        raise ValueError(f"lambda={lam:g}: {result.status.message}")
    if result.verdict is Verdict.UNDETERMINED:
        return None
    return result.verdict is Verdict.STICK_SLIP


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
