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
  ``V SPEED_SPAN`` and refined by Brent's method to :data:`SPEED_RTOL`. Where steady sliding
  is still unstable at an end of that scan, the scan walks on, at the same spacing, for at
  most :data:`EXTENSION_DECADES` decades until it is stable: a Stribeck law with ``n > 1``
  has a slope that vanishes as ``v -> 0``, so steady sliding is stable again at low enough
  speeds (``c + W mu'(v) > 0`` on one DOF), often far below ``V / SPEED_SPAN``. A range still
  open there is reported with the speed where the scan stopped, not as reaching zero or
  infinity.

Some structures (foundations near the stability optimum) lose stability at ``delta_crit`` and
regain it at a larger weakening before losing it again: steady sliding is stable on the
intervals of :func:`stickslip.analysis.stability.stability_intervals`. The margin of a speed
is therefore the distance of ``delta_local`` from the nearest weakening where the verdict
changes, positive where stable: ``delta_crit - delta_local`` on a structure without such a
window, and every boundary, also the window's, a root. Along the load the boundaries are
``W c / delta_local`` for each such weakening ``c``.

Hopf frequency. At a boundary a pair of eigenvalues ``+-i omega`` of the linearisation (slip-I
with the slope ``-2 c``) crosses the imaginary axis; the onset frequency ``omega omega_n /
(2 pi)`` (Hz) depends on the structure and ``c`` alone, not on which speed or load brought the
law's slope there. One DOF: ``s^2 + 1 = 0`` at ``c = zeta``, so ``f_H = omega_n / (2 pi)``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy.optimize import brentq

from stickslip.analysis.stability import (
    critical_weakening,
    slip_matrix,
    stability_intervals,
    steady_sliding_stability,
)
from stickslip.model.machine import Machine
from stickslip.model.parameters import Slider
from stickslip.model.physical import PhysicalSystem
from stickslip.model.structure import Structure

#: The speed scan reaches this factor below and above the belt speed.
SPEED_SPAN = 1e3
#: Log-spaced speeds of the scan.
SPEED_POINTS = 601
#: Relative tolerance of a refined boundary speed.
SPEED_RTOL = 1e-10
#: Decades the scan walks on beyond an end where steady sliding is still unstable.
EXTENSION_DECADES = 12


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
        ``W_H`` (N, at the operating speed): the first load where steady sliding loses
        stability; ``None`` when the law does not weaken at the belt speed (no load makes
        steady sliding unstable).
    operating : (float, float)
        The operating load (N) and belt speed (m/s) the two searches hold.
    unstable_loads : tuple of (float, float)
        Ranges of loads (N, at the operating speed) where it is unstable (the last one open,
        ``inf``); more than one where the structure regains stability (see the module notes).
    hopf_frequencies : tuple of float
        The onset frequency (Hz) at each weakening where the verdict changes, ascending in
        the weakening (the module notes).
    """

    speeds: tuple[float, ...]
    unstable_speeds: tuple[tuple[float, float], ...]
    scan: tuple[float, float]
    load: float | None
    operating: tuple[float, float]
    unstable_loads: tuple[tuple[float, float], ...] = ()
    hopf_frequencies: tuple[float, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``critical_speeds_m_s``, ``unstable_speeds_m_s``, ``speed_scan_m_s``,
        ``critical_load_N``."""
        return {"critical_speeds_m_s": list(self.speeds),
                "unstable_speeds_m_s": [list(r) for r in self.unstable_speeds],
                "speed_scan_m_s": list(self.scan), "critical_load_N": self.load,
                "unstable_loads_N": [list(r) for r in self.unstable_loads],
                "hopf_frequencies_Hz": list(self.hopf_frequencies)}

    def sentence(self) -> str:
        """One line: the unstable speeds (at the load) and loads (at the speed)."""
        lo, hi = self.scan
        parts = []
        for a, b in self.unstable_speeds:
            if a <= lo and b >= hi:
                parts.append(f"every belt speed scanned ({lo:.3g} to {hi:.3g} m/s)")
            elif a <= lo:
                parts.append(f"belt speeds below {b:.4g} m/s and down to at least {lo:.3g} m/s")
            elif b >= hi:
                parts.append(f"belt speeds above {a:.4g} m/s and up to at least {hi:.3g} m/s")
            else:
                parts.append(f"belt speeds {a:.4g} to {b:.4g} m/s")
        speeds = ("unstable at " + ", ".join(parts) if parts
                  else f"stable at every belt speed scanned ({lo:.3g} to {hi:.3g} m/s)")
        if self.load is None:
            loads = "stable at every load"
        elif len(self.unstable_loads) > 1:
            loads = "unstable at loads " + ", ".join(
                f"above {a:.4g} N" if math.isinf(b) else f"{a:.4g} to {b:.4g} N"
                for a, b in self.unstable_loads)
        else:
            loads = f"unstable at loads above {self.load:.4g} N"
        w, v = self.operating
        onset = (f"; onset frequency {', '.join(f'{f:.4g}' for f in self.hopf_frequencies)} Hz"
                 if self.hopf_frequencies else "")
        return (f"linear stability boundary (Hopf): {speeds} (W = {w:.4g} N); {loads} "
                f"(V = {v:.4g} m/s){onset}")


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
    return boundaries_along(structure, lambda v: replace(system, speed=v).slider(),
                            speed=system.speed, load=system.load,
                            natural_frequency=system.natural_frequency)


def machine_stability_boundaries(machine: Machine) -> StabilityBoundaries:
    """:func:`stability_boundaries` of a structure from its matrices (any number of DOF).

    The dimensionless structure (contact first, scales ``m_ref = M[c, c]``, ``k_ref = K[c, c]``)
    does not depend on the operating point, and the law's weakening acts at the contact DOF
    alone, so the derivation of the module notes holds unchanged.

    Parameters
    ----------
    machine : Machine
        Structure (SI), friction law and operating point.

    Returns
    -------
    StabilityBoundaries
        The speeds (at the machine's load) and the load (at its speed).
    """
    structure = machine.to_dimensionless()[0].contact_first()[0]
    return boundaries_along(
        structure, lambda v: machine.with_operating_point(speed=v, load=machine.load).slider(),
        speed=machine.speed, load=machine.load,
        natural_frequency=machine.reference_system().natural_frequency)


def boundaries_along(structure: Structure, slider_at: Callable[[float], Slider], *, speed: float,
                     load: float, natural_frequency: float) -> StabilityBoundaries:
    """The Hopf boundaries of ``structure`` along the belt speed, and along the load.

    Parameters
    ----------
    structure : Structure
        Dimensionless, contact on DOF 0.
    slider_at : callable
        The dimensionless slider at a belt speed (m/s), the load held.
    speed, load : float
        The operating point, m/s and N.
    natural_frequency : float
        ``omega_n`` of the dimensionless time, rad/s.

    Returns
    -------
    StabilityBoundaries
        See the module notes for the derivation.
    """
    delta_crit = critical_weakening(structure)
    intervals = stability_intervals(structure) if math.isfinite(delta_crit) else []
    changes = _verdict_changes(intervals)

    def margin(v: float) -> float:
        d = steady_sliding_stability(structure, slider_at(float(v))).delta_local
        if not changes:
            return delta_crit - d
        c = min(changes, key=lambda x: abs(d - x))
        distance = c - d if c > d else d - c
        return distance if _stable_at(intervals, d) else -distance

    grid = np.geomspace(speed / SPEED_SPAN, speed * SPEED_SPAN, SPEED_POINTS)
    values = np.array([margin(v) for v in grid])
    grid, values = _walk_open_ends(margin, grid, values)
    lo, hi = float(grid[0]), float(grid[-1])
    speeds: list[float] = []
    for i in range(len(grid) - 1):
        a, b = values[i], values[i + 1]
        if a == 0.0 or (a < 0.0) != (b < 0.0):
            speeds.append(float(grid[i]) if a == 0.0 else float(
                brentq(margin, grid[i], grid[i + 1], rtol=SPEED_RTOL)))
    edges = [lo, *speeds, hi]
    unstable = []
    for a, b in itertools.pairwise(edges):
        if margin(math.sqrt(a * b)) < 0.0:
            unstable.append((a, b))
    local = steady_sliding_stability(structure, slider_at(speed)).delta_local
    critical_load = load * max(delta_crit, 0.0) / local if local > 0.0 else None
    unstable_loads: list[tuple[float, float]] = []
    if critical_load is not None:
        for a, b, stable in intervals:
            if stable:
                continue
            if unstable_loads and unstable_loads[-1][1] == load * a / local:
                # a Hopf weakening where a second pair crosses: unstable on both sides
                unstable_loads[-1] = (unstable_loads[-1][0], load * b / local)
            else:
                unstable_loads.append((load * a / local, load * b / local))
    frequencies = tuple(_onset_frequency(structure, c) * natural_frequency / (2.0 * math.pi)
                        for c in changes if c > 0.0)
    return StabilityBoundaries(tuple(speeds), tuple(unstable), (lo, hi), critical_load,
                               (load, speed), tuple(unstable_loads), frequencies)


def _verdict_changes(intervals: list[tuple[float, float, bool]]) -> list[float]:
    """The weakenings where steady sliding's verdict changes, ascending (0 first when it is
    unstable without weakening), from the intervals of
    :func:`~stickslip.analysis.stability.stability_intervals` (none: stable at every one)."""
    changes = [0.0] if intervals and not intervals[0][2] else []
    for (_, hi, before), (_, _, after) in itertools.pairwise(intervals):
        if before != after:
            changes.append(hi)
    return changes


def _stable_at(intervals: list[tuple[float, float, bool]], d: float) -> bool:
    """The verdict at a weakening ``d``: its interval's (the first one's for ``d < 0``)."""
    if d < 0.0:
        return intervals[0][2]
    return next((stable for _, hi, stable in intervals if d < hi), intervals[-1][2])


def _onset_frequency(structure: Structure, weakening: float) -> float:
    """``omega`` (per unit ``tau``) of the eigenvalue pair on the imaginary axis at a Hopf
    weakening: the one whose real part is nearest zero."""
    values = np.linalg.eigvals(slip_matrix(structure, -2.0 * weakening))
    return float(abs(values[int(np.argmin(np.abs(values.real)))].imag))


def _walk_open_ends(margin: Callable[[float], float], grid: np.ndarray,
                    values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``grid`` and ``values`` walked on past an end where the margin is negative (unstable).

    The walk keeps the grid's ratio between neighbours and stops at the first speed with a
    margin of at least zero, after :data:`EXTENSION_DECADES` decades, or where the friction
    law cannot be scaled to the speed (a Stribeck ``v_s / V`` beyond its supported range).
    """
    ratio = float(grid[1] / grid[0])
    steps = math.ceil(EXTENSION_DECADES / math.log10(ratio))
    below: list[tuple[float, float]] = []
    v = float(grid[0])
    while values[0] < 0.0 and len(below) < steps and (not below or below[-1][1] < 0.0):
        step = _margin_within_law(margin, v / ratio)
        if step is None:
            break
        v = step[0]
        below.append(step)
    above: list[tuple[float, float]] = []
    v = float(grid[-1])
    while values[-1] < 0.0 and len(above) < steps and (not above or above[-1][1] < 0.0):
        step = _margin_within_law(margin, v * ratio)
        if step is None:
            break
        v = step[0]
        above.append(step)
    points = [*reversed(below), *zip(grid.tolist(), values.tolist(), strict=True), *above]
    return np.array([p[0] for p in points]), np.array([p[1] for p in points])


def _margin_within_law(margin: Callable[[float], float],
                       v: float) -> tuple[float, float] | None:
    """``(v, margin(v))``, or ``None`` where the law is outside its range at ``v``."""
    try:
        return v, margin(v)
    except ValueError:
        return None


def steady_sliding_report(structure: Structure, slider: Slider, boundaries: StabilityBoundaries, *,
                          natural_frequency: float, per_slope: float) -> dict[str, Any]:
    """Linear stability of steady sliding at the operating point, in SI, with its boundaries.

    Parameters
    ----------
    structure : Structure
        Dimensionless, contact on DOF 0.
    slider : Slider
        The dimensionless slider at the operating point.
    boundaries : StabilityBoundaries
        Its Hopf boundaries (:func:`stability_boundaries`, :func:`machine_stability_boundaries`).
    natural_frequency : float
        ``omega_n`` of the contact's scales, rad/s (turns growth rates per unit ``tau`` into 1/s).
    per_slope : float
        ``2 sqrt(m k) / W`` in s/m: a weakening ``delta`` is the friction slope ``delta per_slope``.

    Returns
    -------
    dict
        ``stable``, ``neutral``, ``growth_rate`` (1/s), ``delta_local``, ``delta_crit``,
        ``margin`` (``delta_crit - delta_local``, positive: stable), ``sigma_local`` and
        ``sigma_crit`` (s/m: the slope ``d mu / d v_r`` may fall by at most ``sigma_crit``) and
        ``boundaries`` (with its ``sentence``).
    """
    stab = steady_sliding_stability(structure, slider)
    delta_crit = critical_weakening(structure)
    return {"stable": bool(stab.stable), "neutral": bool(stab.neutral),
            "growth_rate": stab.growth_rate * natural_frequency,
            "delta_local": stab.delta_local, "delta_crit": delta_crit,
            "margin": delta_crit - stab.delta_local,
            "sigma_local": stab.delta_local * per_slope, "sigma_crit": delta_crit * per_slope,
            "boundaries": {**boundaries.to_dict(), "sentence": boundaries.sentence()}}
