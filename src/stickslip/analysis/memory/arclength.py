"""Pseudo-arclength continuation of the periodic orbits of a machine with friction with memory.

Natural-parameter steps (shoot at the next speed from the last orbit) stop at a fold, where a
stable orbit meets an unstable one and both cease to exist. Pseudo-arclength continuation
(Keller 1977; Allgower and Georg, *Numerical Continuation Methods*, 1990, ch. 2) follows the
branch through it: the unknowns are the orbit's start on the section ``q_c' = 0`` *and*
``p = ln V``, and the step is taken along the branch's tangent.

Unknowns ``u = (w, p)``: ``w`` the state on the section without its contact velocity (0 there),
divided by the state's scales at the step's first speed (:func:`state_scales`), ``p = ln V``.
Equations ``r(u) = (P(y, V) - y) / scale`` over the same components (``P`` the return map;
its contact-velocity component is 0 on the section). Their Jacobian is ``[A | b]`` with
``A = (I - f g^T / (g . f)) Phi(T) - I`` (the return time's variation projected out, as in
:func:`~stickslip.analysis.memory.cycles.shoot_cycle`) restricted to those components, and
``b = dr/dp`` by a forward difference of the return map in ``p`` (step :data:`DP`). The tangent
``t`` is the null vector of ``[A | b]`` (the last right singular vector), oriented along the
previous one. A step predicts ``u + h t`` and corrects by Newton on ``r(u) = 0``,
``t . (u - u_pred) = 0``, to the shooting tolerance. (Single shooting: the return map of an
unstable orbit magnifies the run's own error by its largest Floquet multiplier, so a branch
whose multiplier grows to the thousands ends where that error exceeds the tolerance;
accepting a residual of the tolerance times the multiplier was tried on the LuGre slider's
unstable branch and gave erratic periods there.) A failed correction halves ``h``, a success
grows it by 1.5 up to the bound. A **fold** is where ``dp/ds`` (the tangent's last
component) changes sign between two points; its speed is the vertex of the parabola through
the three points around it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.memory.cycles import (
    MIN_ORBIT_SIZE,
    SHOOTING_TOLERANCE,
    PeriodicOrbit,
    flow,
    return_map,
    shoot_cycle,
)
from stickslip.analysis.memory.friction import kernel_system, state_scales, steady_state
from stickslip.kernel import stiff
from stickslip.model.state_friction import MemorySystem

FloatArray = NDArray[np.float64]

#: Forward-difference step in ``ln V`` of ``dr/dp``.
DP = 1e-6
#: Newton iterations of one corrector.
MAX_CORRECTOR = 12
#: An orbit shrinking this close to steady sliding (largest scaled component of its start on
#: the section) has shrunk into a Hopf point: nearer, its multipliers' distance from 1 is
#: round-off. (A growing one is kept: a branch leaving a Hopf point starts nearer.)
HOPF_SIZE = 1e-3
#: A sign change of ``dp/ds`` counts as a fold only where the orbit is at least this far from
#: steady sliding: nearer, the branch is tangent to ``V = V_H`` (``V - V_H`` grows as the
#: amplitude squared) and that sign is round-off.
FOLD_MIN_SIZE = 1e-2


@dataclass(frozen=True)
class SectionOrbit:
    """A periodic orbit on the section at a speed (SI), with its tangent to the branch."""

    speed: float
    y0: FloatArray
    period: float
    multipliers: NDArray[np.complex128]
    tangent: FloatArray
    size: float = math.inf


def _residual(system_at: Callable[[float], MemorySystem], y: FloatArray, speed: float,
              period: float) -> tuple[FloatArray, FloatArray, float] | None:
    system = system_at(speed)
    return return_map(system, y, speed, min_time=0.2 * period, t_limit=5.0 * period)


def _system_jacobian(system_at: Callable[[float], MemorySystem], y: FloatArray, speed: float,
                     period: float, scale: FloatArray
                     ) -> tuple[FloatArray, FloatArray, FloatArray, float] | None:
    """``r``, ``[A | b]`` (scaled, module notes), ``Phi(T)`` and ``T`` at ``(y, speed)``."""
    system = system_at(speed)
    iv = kernel_system(system).iv
    free = np.array([i for i in range(y.size) if i != iv])
    ret = _residual(system_at, y, speed, period)
    shifted = _residual(system_at, y, speed * math.exp(DP), period)
    if ret is None or shifted is None:
        return None
    y1, phi, t_ret = ret
    f1 = flow(system, y1, speed)
    g = np.zeros(y.size)
    g[iv] = 1.0
    proj = np.eye(y.size) - np.outer(f1, g) / float(g @ f1)
    a = (proj @ phi - np.eye(y.size))[np.ix_(free, free)] * scale[free][None, :] / scale[free][:, None]
    b = (shifted[0] - y1)[free] / scale[free] / DP
    r = (y1 - y)[free] / scale[free]
    return r, np.column_stack([a, b]), phi, t_ret


def _null_tangent(jac: FloatArray, previous: FloatArray | None, sign: int) -> FloatArray:
    t = np.linalg.svd(jac)[2][-1]
    if previous is not None:
        return t if float(t @ previous) >= 0.0 else -t
    return t if t[-1] * sign >= 0.0 else -t


def _multipliers(phi: FloatArray) -> NDArray[np.complex128]:
    mult = np.linalg.eigvals(phi)
    k = int(np.argmin(np.abs(mult - 1.0)))
    others = np.delete(mult, k)
    return others[np.argsort(-np.abs(others))]


def tangent_at(system_at: Callable[[float], MemorySystem], y0: FloatArray, speed: float,
               period: float, sign: int) -> FloatArray | None:
    """The unit tangent of the branch at an orbit, oriented so that ``V`` moves by ``sign``.

    Parameters
    ----------
    system_at : callable
        The machine at a drive speed (m/s).
    y0 : ndarray
        The orbit's start on the section.
    speed, period : float
        Its drive speed (m/s) and period (s).
    sign : int
        +1: towards higher speed; -1: lower.

    Returns
    -------
    ndarray or None
        The tangent in the scaled unknowns of the module notes (None: no return map there).
    """
    scale = state_scales(system_at(speed), speed)
    found = _system_jacobian(system_at, y0, speed, period, scale)
    return None if found is None else _null_tangent(found[1], None, sign)


def arclength_step(system_at: Callable[[float], MemorySystem], at: SectionOrbit, h: float
                   ) -> SectionOrbit | None:
    """One predictor-corrector step of length ``h`` (scaled unknowns) from ``at``.

    Parameters
    ----------
    system_at : callable
        The machine at a drive speed (m/s).
    at : SectionOrbit
        The last orbit, with its tangent.
    h : float
        Step length along the tangent.

    Returns
    -------
    SectionOrbit or None
        The next orbit (None when Newton does not converge or the orbit has collapsed).
    """
    system = system_at(at.speed)
    iv = kernel_system(system).iv
    free = np.array([i for i in range(at.y0.size) if i != iv])
    scale = state_scales(system, at.speed)
    u0 = np.concatenate([at.y0[free] / scale[free], [math.log(at.speed)]])
    predicted = u0 + h * at.tangent
    u = predicted.copy()
    period = at.period
    for _ in range(MAX_CORRECTOR):
        y = np.zeros(at.y0.size)
        y[free] = u[:-1] * scale[free]
        speed = math.exp(float(u[-1]))
        found = _system_jacobian(system_at, y, speed, period, scale)
        if found is None:
            return None
        r, jac, phi, period = found
        arc = float(at.tangent @ (u - predicted))
        if float(np.max(np.abs(r))) < SHOOTING_TOLERANCE and abs(arc) < SHOOTING_TOLERANCE:
            size = float(np.max(np.abs(y - steady_state(system_at(speed), speed))
                                / state_scales(system_at(speed), speed)))
            if size < MIN_ORBIT_SIZE or (size < HOPF_SIZE and size < at.size):
                return None
            tangent = _null_tangent(jac, at.tangent, 1)
            # in the next step's unknowns (scaled at the new speed): dw_new = dw_old s_old/s_new
            new_scale = state_scales(system_at(speed), speed)
            tangent[:-1] *= scale[free] / new_scale[free]
            return SectionOrbit(speed, y, period, _multipliers(phi),
                                tangent / float(np.linalg.norm(tangent)), size)
        du = np.linalg.solve(np.vstack([jac, at.tangent[None, :]]), -np.concatenate([r, [arc]]))
        if not np.all(np.isfinite(du)):
            return None
        u = u + du
    return None


def fold_speed(points: list[tuple[float, float]]) -> float:
    """The vertex of the parabola through three ``(s, ln V)`` points, as a speed (m/s).

    Parameters
    ----------
    points : list of (float, float)
        Three points ``(arclength, ln V)`` around a fold.

    Returns
    -------
    float
        ``V`` at the vertex, m/s (the middle point's where the parabola is degenerate).
    """
    (s0, p0), (s1, p1), (s2, p2) = points
    coeffs = np.polyfit([s0, s1, s2], [p0, p1, p2], 2)
    if coeffs[0] == 0.0:
        return math.exp(p1)
    s_star = -coeffs[1] / (2.0 * coeffs[0])
    if not min(s0, s2) <= s_star <= max(s0, s2):
        return math.exp(p1)
    return math.exp(float(np.polyval(coeffs, s_star)))




#: Distances of the first orbit from a Hopf point, in ``ln V``, tried in turn on each side.
HOPF_OFFSETS = (1e-3, 3e-3, 1e-2, 3e-2)
#: Sizes of the first guess: the contact velocity's amplitude as a share of the drive speed.
HOPF_AMPLITUDES = (0.05, 0.15, 0.4)


def hopf_seed(system_at: Callable[[float], MemorySystem], speed: float
              ) -> tuple[float, PeriodicOrbit] | None:
    """A small periodic orbit near a Hopf point, by shooting from the critical eigenvector.

    Near a Hopf point at ``V_H`` with critical eigenvalues ``+-i omega`` and eigenvector
    ``phi``, the orbit born there is ``y_ss + eps Re(phi e^{i omega t}) + O(eps^2)`` with
    period ``2 pi / omega + O(eps^2)``, on the side of ``V_H`` where it exists (the stable side
    of steady sliding for a subcritical Hopf point, where the orbit is unstable; the unstable
    side for a supercritical one). Its start on the section ``q_c' = 0`` (``y_ss`` lies on it:
    the contact is at rest in steady sliding) is the phase ``theta`` with
    ``Re(phi_c e^{i theta}) = 0`` crossing upwards, scaled so that the contact's velocity
    oscillates by a share of ``V`` (:data:`HOPF_AMPLITUDES`: the linear regime needs it below
    ``V``, or the slip speed reverses). Newton shooting
    (:func:`~stickslip.analysis.memory.cycles.shoot_cycle`) from that guess is tried at
    :data:`HOPF_OFFSETS` on both sides and :data:`HOPF_AMPLITUDES`, the first orbit that is
    not steady sliding kept.

    Parameters
    ----------
    system_at : callable
        The machine at a drive speed (m/s).
    speed : float
        The Hopf point ``V_H``, m/s.

    Returns
    -------
    (float, PeriodicOrbit) or None
        The speed of the orbit found and the orbit (None: no orbit converged).
    """
    system = system_at(speed)
    ks = kernel_system(system)
    y_ss = steady_state(system, speed)
    jac = np.empty((ks.n, ks.n))
    stiff.jacobian(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_, ks.kq,
                   np.ascontiguousarray(y_ss), float(speed), np.empty(stiff.N_LAW), jac)
    values, vectors = np.linalg.eig(jac)
    candidates = [i for i in range(values.size) if values[i].imag > 0.0]
    if not candidates:
        return None
    k = min(candidates, key=lambda i: abs(values[i].real) / abs(values[i]))
    omega, phi = float(values[k].imag), vectors[:, k]
    theta = 0.5 * math.pi - float(np.angle(phi[ks.iv]))
    if float((1j * omega * phi[ks.iv] * np.exp(1j * theta)).real) < 0.0:
        theta += math.pi  # cross the section upwards
    direction = (phi * np.exp(1j * theta)).real
    direction[ks.iv] = 0.0
    for offset in HOPF_OFFSETS:
        for side in (1.0, -1.0):
            v = speed * math.exp(side * offset)
            near = system_at(v)
            base = steady_state(near, v)
            size = float(abs(phi[ks.iv]))  # the mode's contact-velocity amplitude
            if not size > 0.0:
                return None
            for amplitude in HOPF_AMPLITUDES:
                guess = base + (amplitude * v / size) * direction
                guess[ks.iv] = 0.0
                orbit = shoot_cycle(near, guess, 2.0 * math.pi / omega, speed=v)
                if orbit is not None:
                    return v, orbit
    return None


__all__ = ["FOLD_MIN_SIZE", "SectionOrbit", "arclength_step", "fold_speed", "hopf_seed", "tangent_at"]
