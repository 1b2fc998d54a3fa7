"""Where steady sliding loses linear stability along the belt speed and the normal load (SI).

A friction law whose slope moves with the sliding speed (Stribeck, table) makes steady sliding
linearly unstable over a range of belt speeds. Its ends are the Hopf boundary, which is not the
start-up onset ``V_c`` that ``design`` searches by simulation: between the two the machine is
bistable (steady sliding is stable, yet a start from rest ends in stick-slip).

Derivation. The dimensionless friction force is ``F(u) = W mu(u V) / (V sqrt(m k))`` (time
unit ``sqrt(m/k)``, speeds in units of ``V``, after Eq. 27), so its slope at the belt speed is
``dF/du = W mu'(V) / sqrt(m k)`` and the law's local weakening ``delta_local = -dF/du / 2 =
W sigma(V) / (2 sqrt(m k))`` with ``sigma = -mu'(V)`` in s/m
(:func:`stickslip.analysis.stability.steady_sliding_stability`). Steady sliding is stable while
``delta_local < delta_crit``, the critical weakening of the structure
(:func:`stickslip.analysis.stability.critical_weakening`), which depends on the damping ratio
and the foundation's ratios only, not on ``V`` or ``W``. Hence:

* along the load (``V`` held) ``delta_local`` is proportional to ``W``: the boundary is
  ``W_H = W delta_crit / delta_local`` when the law weakens at ``V`` (``delta_local > 0``),
  unstable above it; a law that does not weaken there has none;
* along the speed (``W`` held) the boundaries are the roots of ``delta_crit - delta_local(V)``,
  found by a scan of :data:`SPEED_POINTS` log-spaced speeds from ``V / SPEED_SPAN`` to
  ``V SPEED_SPAN`` and refined by Brent's method to :data:`SPEED_RTOL`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy.optimize import brentq

from stickslip.analysis.stability import critical_weakening, steady_sliding_stability
from stickslip.model.physical import PhysicalSystem
from stickslip.model.structure import Structure

#: The speed scan reaches this factor below and above the belt speed.
SPEED_SPAN = 1e3
#: Log-spaced speeds of the scan.
SPEED_POINTS = 601
#: Relative tolerance of a refined boundary speed.
SPEED_RTOL = 1e-10


@dataclass(frozen=True)
class StabilityBoundaries:
    """Hopf boundaries of steady sliding of one structure, in SI units.

    Attributes
    ----------
    speeds : tuple of float
        Belt speeds (m/s, at the operating load) where steady sliding changes stability.
    unstable_speeds : tuple of (float, float)
        Ranges of belt speeds (m/s) where it is unstable; an end equal to the scan's is open.
    scan : (float, float)
        The speeds scanned, m/s.
    load : float or None
        ``W_H`` (N, at the operating speed): unstable above it; ``None`` when the law does not
        weaken at the belt speed (no load makes steady sliding unstable).
    operating : (float, float)
        The operating load (N) and belt speed (m/s) the two searches hold.
    """

    speeds: tuple[float, ...]
    unstable_speeds: tuple[tuple[float, float], ...]
    scan: tuple[float, float]
    load: float | None
    operating: tuple[float, float]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``critical_speeds_m_s``, ``unstable_speeds_m_s``, ``speed_scan_m_s``,
        ``critical_load_N``."""
        return {"critical_speeds_m_s": list(self.speeds),
                "unstable_speeds_m_s": [list(r) for r in self.unstable_speeds],
                "speed_scan_m_s": list(self.scan), "critical_load_N": self.load}

    def sentence(self) -> str:
        """One line: the unstable speeds (at the load) and loads (at the speed)."""
        lo, hi = self.scan
        parts = []
        for a, b in self.unstable_speeds:
            if a <= lo and b >= hi:
                parts.append(f"every belt speed scanned ({lo:.3g} to {hi:.3g} m/s)")
            elif a <= lo:
                parts.append(f"belt speeds below {b:.4g} m/s")
            elif b >= hi:
                parts.append(f"belt speeds above {a:.4g} m/s")
            else:
                parts.append(f"belt speeds {a:.4g} to {b:.4g} m/s")
        speeds = ("unstable at " + ", ".join(parts) if parts
                  else f"stable at every belt speed scanned ({lo:.3g} to {hi:.3g} m/s)")
        loads = ("stable at every load" if self.load is None
                 else f"unstable at loads above {self.load:.4g} N")
        w, v = self.operating
        return (f"linear stability boundary (Hopf): {speeds} (W = {w:.4g} N); {loads} "
                f"(V = {v:.4g} m/s)")


def stability_boundaries(system: PhysicalSystem, structure: Structure) -> StabilityBoundaries:
    """The speeds and the load where steady sliding of ``structure`` changes stability.

    Parameters
    ----------
    system : PhysicalSystem
        The machine in SI units (its friction law, load and belt speed).
    structure : Structure
        The dimensionless structure (rigid base or with a foundation) of ``system``.

    Returns
    -------
    StabilityBoundaries
        See the module notes for the derivation.
    """
    delta_crit = critical_weakening(structure)

    def margin(speed: float) -> float:
        at = replace(system, speed=float(speed))
        return delta_crit - steady_sliding_stability(structure, at.slider()).delta_local

    lo, hi = system.speed / SPEED_SPAN, system.speed * SPEED_SPAN
    grid = np.geomspace(lo, hi, SPEED_POINTS)
    values = np.array([margin(v) for v in grid])
    speeds: list[float] = []
    for i in range(SPEED_POINTS - 1):
        a, b = values[i], values[i + 1]
        if a == 0.0 or (a < 0.0) != (b < 0.0):
            speeds.append(float(grid[i]) if a == 0.0 else float(
                brentq(margin, grid[i], grid[i + 1], rtol=SPEED_RTOL)))
    edges = [lo, *speeds, hi]
    unstable = []
    for a, b in itertools.pairwise(edges):
        if margin(math.sqrt(a * b)) < 0.0:
            unstable.append((a, b))
    local = steady_sliding_stability(structure, system.slider()).delta_local
    load = system.load * max(delta_crit, 0.0) / local if local > 0.0 else None
    return StabilityBoundaries(tuple(speeds), tuple(unstable), (lo, hi), load,
                               (system.load, system.speed))
