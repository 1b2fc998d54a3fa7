"""Stability of steady sliding with friction with memory: verdict, critical stiffness and speeds, maps.

Steady sliding at the drive speed ``V`` is the equilibrium ``y_ss`` of
``y' = f(y)`` (:func:`~stickslip.analysis.memory.friction.steady_state`): the contact at rest
relative to the ground, the springs holding the steady friction force, the state variable at
its steady value. Its linearisation ``delta' = J delta`` with the exact Jacobian ``J = df/dy``
(:func:`stickslip.kernel.stiff.jacobian`; structure *and* state variable) decides
local stability: every eigenvalue of ``J`` left of the imaginary axis, stable; one right of it,
unstable (Lyapunov's indirect method). An eigenvalue within its round-off bound of the axis
decides nothing: *neutral*, never rounded to either side.

Round-off bound. ``J`` mixes positions (m), velocities (m/s) and the state (``psi`` or the
bristle deflection), so it is balanced first: ``D^-1 J D`` with ``D`` the natural scales of
the components (:func:`~stickslip.analysis.memory.friction.state_scales`), the same eigenvalues;
each eigenvalue then carries the first-order bound of
:func:`~stickslip.analysis.contact.friction_coupling.bounded_eigenvalues`.

Critical values. The Hopf boundary in stiffness is
:func:`~stickslip.analysis.memory.friction.hopf_stiffness` (for the 1-DOF rate-and-state slider it
equals Rice and Ruina's ``k_c = N (b - a)/d_c (1 + m V^2/(N a d_c))``). In speed, the growth rate
``g(V) = max Re eig J(V)`` is scanned on a logarithmic grid (:data:`SPEED_DECADES` either side of
``V``, :data:`SPEED_POINTS` points) and every sign change is bisected to :data:`SPEED_RTOL`:
the critical speeds, with the ranges where steady sliding is unstable. For rate-and-state the
law depends on ``V`` only through ``ln V`` and the inertia term ``m V^2``, so for 1 DOF
``k < k_c(V)`` reads ``V^2 > (N a d_c / m)(k d_c / (N (b - a)) - 1)``: inertia destabilises, and
there is one critical speed, above which steady sliding is unstable, in closed form
(:func:`rice_ruina_critical_speed`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.contact.friction_coupling import bounded_eigenvalues
from stickslip.analysis.memory.friction import (
    hopf_stiffness,
    kernel_system,
    rice_ruina_critical_stiffness,
    state_scales,
    steady_sliding,
    steady_states,
)
from stickslip.kernel import stiff
from stickslip.model.state_friction import MemorySystem, RateStateFriction

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

#: Decades of drive speed scanned either side of the operating speed for critical speeds.
SPEED_DECADES = 2.0
#: Points of that scan (logarithmic).
SPEED_POINTS = 161
#: Relative width a critical speed is bisected to.
SPEED_RTOL = 1e-10


def linear_spectrum(system: MemorySystem, speed: float) -> tuple[ComplexArray, FloatArray]:
    """Eigenvalues (1/s) of steady sliding at ``speed`` (m/s) and their round-off bounds (1/s).

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).
    speed : float
        Drive speed, m/s.

    Returns
    -------
    values : ndarray of complex
        Eigenvalues of the balanced Jacobian (the structure and the state variable).
    bounds : ndarray
        Their first-order round-off bounds.
    """
    values, bounds = linear_spectra(system, np.array([float(speed)]))
    return values[0], bounds[0]


def linear_spectra(system: MemorySystem, speeds: FloatArray) -> tuple[ComplexArray, FloatArray]:
    """:func:`linear_spectrum` at every speed of ``speeds``, the eigenproblems as one stack.

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).
    speeds : ndarray, shape (n,)
        Drive speeds, m/s.

    Returns
    -------
    values, bounds : ndarray, shape (n, m)
        Eigenvalues (1/s) and their round-off bounds, one row per speed.
    """
    ks = kernel_system(system)
    v_all = np.asarray(speeds, dtype=np.float64).ravel()
    balanced = np.empty((v_all.size, ks.n, ks.n))
    law_work = np.empty(stiff.N_LAW)
    steady = steady_states(system, v_all)
    for i, v in enumerate(v_all.tolist()):
        y = np.ascontiguousarray(steady[i])
        stiff.jacobian(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_, ks.kq, y, v,
                       law_work, balanced[i])
        scale = state_scales(system, v, y)
        balanced[i] *= scale[None, :] / scale[:, None]
    return bounded_eigenvalues(balanced)


def spectrum_sign(values: ComplexArray, bounds: FloatArray) -> int:
    """The sign of the spectrum, read only beyond every eigenvalue's round-off bound.

    Parameters
    ----------
    values : ndarray of complex
        Eigenvalues, 1/s.
    bounds : ndarray
        Their round-off bounds, 1/s (:func:`linear_spectrum`).

    Returns
    -------
    int
        +1 unstable (a real part beyond its bound right of the axis), -1 stable (every one
        beyond its bound left of it), 0 neutral.
    """
    if np.any(values.real - bounds > 0.0):
        return 1
    if np.all(values.real + bounds < 0.0):
        return -1
    return 0


VERDICTS = {1: "unstable", -1: "stable", 0: "neutral"}


def growth_rate(system: MemorySystem, speed: float) -> float:
    """Largest real part of the eigenvalues of steady sliding.

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).
    speed : float
        Drive speed, m/s.

    Returns
    -------
    float
        The growth rate, 1/s (> 0: unstable).
    """
    return float(np.max(linear_spectrum(system, speed)[0].real))


def rice_ruina_critical_speed(system: MemorySystem) -> float | None:
    """The 1-DOF rate-and-state slider's critical speed from ``k = k_c(V)`` (module notes).

    Steady sliding is unstable above it.

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).

    Returns
    -------
    float or None
        ``V_c``, m/s; None where there is none: not a 1-DOF rate-and-state slider, ``b <= a``
        (stable at every speed), ``k <= N (b - a)/d_c`` (unstable at every speed, inertia or
        not), or the quasi-static slider (no inertia: ``k_c`` does not depend on ``V``).
    """
    law = system.friction
    if system.n_dof != 1 or not isinstance(law, RateStateFriction) or system.quasi_static:
        return None
    k, m, load = float(system.stiffness[0, 0]), float(system.mass[0, 0]), system.load
    if law.b <= law.a:
        return None
    ratio = k * law.d_c / (load * (law.b - law.a)) - 1.0
    if ratio <= 0.0:
        return None
    return math.sqrt(load * law.a * law.d_c / m * ratio)


def critical_speeds(system: MemorySystem, low: float, high: float, points: int = SPEED_POINTS
                    ) -> tuple[list[float], list[tuple[float, float]]]:
    """Speeds in ``[low, high]`` where steady sliding changes stability, and the unstable ranges.

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).
    low, high : float
        The drive speeds scanned, m/s (``0 < low < high``).
    points : int
        Points of the logarithmic scan.

    Returns
    -------
    critical : list of float
        Every sign change of the growth rate, bisected to :data:`SPEED_RTOL`, m/s.
    unstable : list of (float, float)
        The ranges where the growth rate is positive (ends at the critical speeds or the scan).
    """
    return sign_changes(lambda v: growth_rate(system, v), low, high, points)


def critical_loads(system: MemorySystem, speed: float, low: float, high: float,
                   points: int = SPEED_POINTS) -> tuple[list[float], list[tuple[float, float]]]:
    """Normal loads in ``[low, high]`` where steady sliding at ``speed`` changes stability.

    The load scales the friction force (``N mu``), so it moves the friction's negative
    stiffness and damping against the structure's: the same scan and bisection as
    :func:`critical_speeds`, along ``N``.

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).
    speed : float
        Drive speed, m/s.
    low, high : float
        The normal loads scanned, N (``0 < low < high``).
    points : int
        Points of the logarithmic scan.

    Returns
    -------
    critical : list of float
        Every sign change of the growth rate, bisected to :data:`SPEED_RTOL` (relative), N.
    unstable : list of (float, float)
        The load ranges where the growth rate is positive, N.
    """
    return sign_changes(lambda w: growth_rate(replace(system, load=w), speed), low, high, points)


def sign_changes(rate: Callable[[float], float], low: float, high: float, points: int
                 ) -> tuple[list[float], list[tuple[float, float]]]:
    """Sign changes of ``rate`` on a logarithmic scan of ``[low, high]``, each bisected.

    Parameters
    ----------
    rate : callable
        The growth rate (1/s) at a parameter value.
    low, high : float
        The scanned range (``0 < low < high``), in the parameter's unit.
    points : int
        Points of the logarithmic scan.

    Returns
    -------
    critical : list of float
        The sign changes, bisected in log scale to :data:`SPEED_RTOL` (relative).
    unstable : list of (float, float)
        The ranges where ``rate`` is positive (ends at the sign changes or the scan's ends).
    """
    grid = np.geomspace(low, high, int(points))
    rates = np.array([rate(float(x)) for x in grid])
    critical: list[float] = []
    for i in np.flatnonzero(np.sign(rates[:-1]) != np.sign(rates[1:])).tolist():
        lo, hi, r_lo = float(grid[i]), float(grid[i + 1]), rates[i]
        for _ in range(200):  # bounded: each halves the bracket in log scale
            if hi - lo <= SPEED_RTOL * hi:
                break
            mid = math.sqrt(lo * hi)
            r_mid = rate(mid)
            if np.sign(r_mid) == np.sign(r_lo):
                lo, r_lo = mid, r_mid
            else:
                hi = mid
        critical.append(0.5 * (lo + hi))
    unstable: list[tuple[float, float]] = []
    edges = [float(grid[0]), *critical, float(grid[-1])]
    for a, b in itertools.pairwise(edges):
        if rate(math.sqrt(a * b)) > 0.0:
            unstable.append((a, b))
    return critical, unstable


@dataclass(frozen=True)
class MemoryStability:
    """Linear stability of steady sliding with a friction law with memory (see module notes).

    Attributes
    ----------
    speed : float
        The operating drive speed, m/s.
    eigenvalues, bounds : ndarray
        Eigenvalues (1/s) and their round-off bounds.
    verdict : str
        ``stable``, ``unstable`` or ``neutral``.
    critical_stiffness_factor : float
        Every stiffness times this factor puts steady sliding on the Hopf boundary (NaN: none
        in ``[1e-6, 1e6]``).
    critical_speeds, unstable_speeds : list
        Sign changes of the growth rate in speed (m/s) and the unstable ranges, over
        :data:`SPEED_DECADES` decades either side of ``speed``.
    """

    system: MemorySystem = field(repr=False)
    speed: float
    eigenvalues: ComplexArray = field(repr=False)
    bounds: FloatArray = field(repr=False)
    verdict: str
    critical_stiffness_factor: float
    critical_speeds: list[float]
    unstable_speeds: list[tuple[float, float]]

    @property
    def growth_rate(self) -> float:
        """Largest real part of the eigenvalues, 1/s."""
        return float(np.max(self.eigenvalues.real))

    @property
    def critical_stiffness(self) -> float | None:
        """The 1-DOF slider's critical stiffness ``k_c``, N/m (None for N DOF or none found)."""
        if self.system.n_dof != 1 or not math.isfinite(self.critical_stiffness_factor):
            return None
        return self.critical_stiffness_factor * float(self.system.stiffness[0, 0])

    @property
    def hopf_frequency(self) -> float | None:
        """Frequency of the oscillation born on the Hopf boundary in stiffness, Hz.

        At every stiffness times :attr:`critical_stiffness_factor` the eigenvalue of largest
        real part is (to the bisection's 1e-14) on the imaginary axis; its imaginary part over
        ``2 pi`` is the frequency (for the 1-DOF rate-and-state slider Rice and Ruina's
        ``(V / d_c) sqrt((b - a) / a) / (2 pi)`` when ``m = 0``). None when no boundary was
        found.
        """
        factor = self.critical_stiffness_factor
        if not math.isfinite(factor):
            return None
        at = steady_sliding(self.system.with_stiffness_scale(factor), self.speed)
        z = at.eigenvalues[int(np.argmax(at.eigenvalues.real))]
        return abs(float(z.imag)) / (2.0 * math.pi)

    @property
    def unstable_side(self) -> str | None:
        """``"below"`` or ``"above"``: on which side of the Hopf boundary in stiffness steady
        sliding is unstable (None when no boundary was found).

        Rate-and-state on one DOF loses stability below ``k_c`` (Rice and Ruina); a LuGre
        slider with ``sigma_1 beta + sigma_2 < 0`` (``beta = V g'(V) / g(V)``) loses it above:
        its characteristic polynomial ``m s^3 + (m alpha + sigma_1 beta + sigma_2) s^2 + (k +
        sigma_0 beta + sigma_2 alpha) s + k alpha`` (``alpha = sigma_0 V / g``) has the
        Routh-Hurwitz condition ``k (sigma_1 beta + sigma_2) + A B > 0``, which a larger ``k``
        breaks when the bracket is negative. So the side is read from the eigenvalues at a
        stiffness 1e-4 below the boundary, not assumed.
        """
        factor = self.critical_stiffness_factor
        if not math.isfinite(factor):
            return None
        below = steady_sliding(self.system.with_stiffness_scale(factor * (1.0 - 1e-4)), self.speed)
        return "below" if below.growth_rate > 0.0 else "above"

    @property
    def rice_ruina(self) -> dict[str, float | None] | None:
        """Rice and Ruina's closed forms for the 1-DOF rate-and-state slider (None otherwise)."""
        law = self.system.friction
        if self.system.n_dof != 1 or not isinstance(law, RateStateFriction):
            return None
        k_c = rice_ruina_critical_stiffness(self.system.load, law.a, law.b, law.d_c,
                                            float(self.system.mass[0, 0]), self.speed)
        return {"critical_stiffness_N_per_m": k_c if k_c > 0.0 else None,
                "critical_speed_m_per_s": rice_ruina_critical_speed(self.system)}

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI; eigenvalues as ``[real_per_s, imag_per_s]`` pairs)."""
        lo, hi = self.speed * 10.0 ** -SPEED_DECADES, self.speed * 10.0 ** SPEED_DECADES
        factor = self.critical_stiffness_factor
        return {
            "speed_m_per_s": self.speed,
            "verdict": self.verdict,
            "stable": self.verdict == "stable",
            "growth_rate_per_s": self.growth_rate,
            "eigenvalues": [[float(z.real), float(z.imag)] for z in self.eigenvalues],
            "eigenvalue_bounds_per_s": [float(b) for b in self.bounds],
            "critical_stiffness_factor": factor if math.isfinite(factor) else None,
            "critical_stiffness_N_per_m": self.critical_stiffness,
            "hopf_frequency_Hz": self.hopf_frequency,
            "unstable_side_of_critical_stiffness": self.unstable_side,
            "critical_speeds_m_per_s": self.critical_speeds,
            "unstable_speeds_m_per_s": [list(r) for r in self.unstable_speeds],
            "speed_grid_m_per_s": [lo, hi, SPEED_POINTS],
            "rice_ruina": self.rice_ruina,
            "friction": self.system.friction.to_dict(),
            "load_N": self.system.load,
        }

    def summary(self) -> str:
        """A few lines for the terminal."""
        p = self.to_dict()
        verdict = self.verdict.upper() if self.verdict == "unstable" else self.verdict
        lines = [f"steady sliding at {self.speed:.6g} m/s: {verdict} (growth rate "
                 f"{self.growth_rate:.6g} 1/s; linearisation with the state variable)"]
        if self.verdict == "neutral":
            lines.append("            an eigenvalue lies within its round-off bound of the "
                         "imaginary axis: the linearisation decides nothing")
        elif self.verdict == "stable":
            how = ("a speed schedule that steps the drive speed disturbs the quasi-static "
                   "slider" if self.system.quasi_static
                   else "simulate --initial-kick -1 starts stuck to the drive")
            lines.append("            a local verdict: a large disturbance may still end in "
                         f"stick-slip ({how})")
        values = self.eigenvalues
        lines.append("eigenvalues " + ", ".join(f"{z.real:.6g}{z.imag:+.6g}j" for z in values[:8])
                     + (f" (+{values.size - 8}, listed by --json)" if values.size > 8 else "")
                     + " [1/s]")
        factor = p["critical_stiffness_factor"]
        hopf = p["hopf_frequency_Hz"]
        at = f" at {hopf:.6g} Hz" if hopf is not None else ""
        side = p["unstable_side_of_critical_stiffness"]
        if self.critical_stiffness is not None:
            lines.append(f"critical k  {self.critical_stiffness:.10g} N/m (Hopf boundary{at}; "
                         f"steady sliding is unstable {side} it)")
        elif factor is not None:
            lines.append(f"critical k  every stiffness x {factor:.10g} (Hopf boundary{at}; "
                         f"unstable {side} it)")
        else:
            lines.append("critical k  none between 1e-6 and 1e6 times the stiffness")
        rr = p["rice_ruina"]
        if rr is not None:
            speed = rr["critical_speed_m_per_s"]
            undamped = ("" if not np.any(self.system.damping) else
                        " (the closed form of an undamped slider; with the damping the Hopf "
                        "boundary is the critical k above)")
            k_c = rr["critical_stiffness_N_per_m"]
            lines.append("Rice-Ruina  k_c = " + (f"{k_c:.10g} N/m" if k_c is not None else
                                                 "none (b <= a: stable at every stiffness)")
                         + "; critical speed " + (f"{speed:.10g} m/s" if speed is not None else "none")
                         + undamped)
        lo, hi, _ = p["speed_grid_m_per_s"]
        speeds = ", ".join(f"{v:.8g}" for v in self.critical_speeds) or "none"
        ranges = ", ".join(f"{a:.4g} to {b:.4g}" for a, b in self.unstable_speeds) or "none"
        lines.append(f"critical V  {speeds}{' m/s' if self.critical_speeds else ''} "
                     f"(scan {lo:.3g} to {hi:.3g} m/s)")
        lines.append(f"unstable V  {ranges}{' m/s' if self.unstable_speeds else ''}")
        return "\n".join(lines)


def memory_stability(system: MemorySystem, speed: float | None = None) -> MemoryStability:
    """The linear stability of steady sliding at ``speed`` (default the schedule's last).

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).
    speed : float, optional
        Drive speed, m/s.

    Returns
    -------
    MemoryStability
        Verdict, eigenvalues with bounds, critical stiffness and speeds.
    """
    v = system.schedule.last if speed is None else float(speed)
    values, bounds = linear_spectrum(system, v)
    factor = hopf_stiffness(system, speed=v)
    spread = 10.0 ** SPEED_DECADES
    critical, unstable = critical_speeds(system, v / spread, v * spread)
    return MemoryStability(system, v, values, bounds, VERDICTS[spectrum_sign(values, bounds)],
                           factor, critical, unstable)
