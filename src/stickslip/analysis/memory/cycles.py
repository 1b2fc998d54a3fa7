"""Periodic orbits of structures with friction with memory: Newton shooting and Floquet multipliers.

A periodic orbit is a fixed point of the return map ``P`` to the Poincare section ``q_c' = 0``
crossed upwards (every periodic motion crosses it: the contact's mean velocity over a period is
zero). ``P`` and its Jacobian come from one run of the orbit with its variational equations
``Phi' = J(y) Phi`` (:mod:`stickslip.kernel.stiff`); the Jacobian of ``P`` is
``(I - f g^T / (g . f)) Phi(T)`` (``f`` the flow at the return, ``g`` the section's gradient)
and the Floquet multipliers are the eigenvalues of the monodromy matrix ``Phi(T)``, one of them
the trivial 1 of the flow direction (its distance from 1 measures the accuracy of ``Phi``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.memory.friction import (
    DEFAULT_RTOL,
    MAX_STEPS,
    FloatArray,
    kernel_system,
    state_scales,
    steady_state,
)
from stickslip.kernel import stiff
from stickslip.model.state_friction import MemorySystem

#: Largest scaled residual ``|P(y) - y|`` of an accepted periodic orbit.
SHOOTING_TOLERANCE = 1e-7
#: Smallest orbit told apart from steady sliding: ``max_i |y0 - y_ss|_i / scale_i``.
MIN_ORBIT_SIZE = 1e-6
#: Newton iterations of shooting.
MAX_NEWTON = 25
#: Largest scaled Newton step at an accepted orbit, as a fraction of the orbit's size (its
#: largest scaled distance from steady sliding on the section). A small residual alone is no
#: fixed point: next to a Hopf point on its stable side the return map is nearly the identity
#: (a multiplier pair at 0.99999 +- 0.0026i), so a slowly decaying spiral about steady sliding
#: returns within the tolerance while the fixed point that Newton's step points to, steady
#: sliding itself, lies as far away as the state is from it (an independent audit: "stable
#: orbits" of amplitude 1e-10 m at 1.00001 times the Rice-Ruina critical stiffness, where no
#: cycle exists; Newton's step was 1.0 and 0.33 of the orbit's size there, 2e-7 or less on
#: every genuine orbit it checked).
STEP_RESOLUTION = 1e-3
#: A nontrivial multiplier whose modulus is within this of 1 leaves the stability undecided:
#: the monodromy matrix integrated at the default tolerance is wrong by about as much (an
#: independent audit, shooting in deviation variables and the normal form of the supercritical
#: Hopf point of ``examples/friction_memory/rate_state.toml``, first Lyapunov coefficient
#: -915, found the three orbits nearest the Hopf point at |mu| = 1.0000044-1.0000055, where the
#: truth is 0.99997 (stable), and |mu| = 0.999943 against 0.999925 a little further out).
MULTIPLIER_RESOLUTION = 1e-4


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit found by Newton shooting, with its Floquet multipliers.

    Attributes
    ----------
    y0 : ndarray
        State on the section ``q_c' = 0`` (crossed upwards).
    period : float
        Period, s.
    residual : float
        Scaled residual ``max_i |P(y0) - y0|_i / scale_i`` of the last iterate.
    multipliers : ndarray
        Eigenvalues of the monodromy matrix ``Phi(T)``, sorted by decreasing modulus distance
        from 1 last: the trivial multiplier (closest to 1) is ``trivial_multiplier``.
    trivial_multiplier : complex
        The multiplier of the flow direction (1 in exact arithmetic).
    iterations : int
        Newton iterations.
    """

    y0: FloatArray
    period: float
    residual: float
    multipliers: NDArray[np.complex128]
    trivial_multiplier: complex
    iterations: int

    @property
    def stable(self) -> bool:
        """True when every nontrivial multiplier lies inside the unit circle (see
        :attr:`stability_resolved`)."""
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    @property
    def stability_resolved(self) -> bool:
        """The largest nontrivial multiplier's modulus is more than
        :data:`MULTIPLIER_RESOLUTION` from 1, so :attr:`stable` is not decided by the
        monodromy's own error."""
        moduli = np.abs(self.multipliers)
        return bool(moduli.size == 0 or abs(float(moduli.max()) - 1.0) > MULTIPLIER_RESOLUTION)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"period_s": self.period, "residual": self.residual,
                "floquet_multipliers": [[float(m.real), float(m.imag)] for m in self.multipliers],
                "trivial_multiplier": [float(self.trivial_multiplier.real),
                                       float(self.trivial_multiplier.imag)],
                "newton_iterations": self.iterations, "stable": self.stable,
                "stability_resolved": self.stability_resolved,
                "section": "contact velocity q_c' = 0, crossed upwards"}


def return_map(system: MemorySystem, y0: FloatArray, speed: float, *, min_time: float,
               t_limit: float, rtol: float = DEFAULT_RTOL,
               ) -> tuple[FloatArray, FloatArray, float] | None:
    """The first upward return to the section after ``min_time`` (s): ``(y(T), Phi(T), T)``.

    The variational equations are integrated with the orbit, ``Phi`` under the same error
    control as ``y``; where that cannot be met (the steps shrink to round-off at the kink of
    ``|v|`` in the laws, at a reversal of the slip speed) ``Phi`` rides on the steps chosen for
    ``y`` alone. None when no return comes before ``t_limit`` (s).

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    y0 : ndarray
        Start state (on the section).
    speed : float
        Drive speed, m/s.
    min_time : float
        Earliest return counted, s.
    t_limit : float
        Latest, s.
    rtol : float
        Relative tolerance.

    Returns
    -------
    tuple or None
        ``(y(T), Phi(T), T)``.
    """
    ks = kernel_system(system)
    n = ks.n
    atol = rtol * state_scales(system, speed)
    for phi_rtol in (rtol, 0.0):
        z = np.concatenate([np.asarray(y0, dtype=np.float64), np.eye(n).ravel()])
        stats = np.array([0.0, 0.0, 0.0, 0.0, math.inf, -math.inf, 0.0])
        cross_t = np.empty(1)
        cross_z = np.empty((1, n + n * n))
        status, t, _ = stiff.integrate(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_,
                                       ks.kq, z, n, True, 0.0, t_limit, float(speed), rtol, atol,
                                       phi_rtol, 0.0, MAX_STEPS, np.zeros(0),
                                       np.zeros((0, n + n * n)), True, min_time, cross_t, cross_z,
                                       np.empty(0), stats)
        if status == stiff.STATUS_SECTION:
            return z[:n].copy(), z[n:].reshape((n, n)).copy(), float(t)
        if status == stiff.STATUS_DONE:
            return None
    return None


def _section_gradient(system: MemorySystem, y: FloatArray, speed: float) -> FloatArray:
    """Gradient of the section function ``q_c'(y)``."""
    ks = kernel_system(system)
    g = np.zeros(ks.n)
    if system.quasi_static:
        _, vx, vp = stiff.quasi_static_speed(ks.p, ks.kq, float(y[0]), float(y[1]))
        g[0], g[1] = -vx, -vp
    else:
        g[ks.iv] = 1.0
    return g


def flow(system: MemorySystem, y: FloatArray, speed: float) -> FloatArray:
    """The vector field ``y' = f(y)`` at ``y`` for the drive speed ``speed`` (m/s).

    Parameters
    ----------
    system : MemorySystem
        Structure, load and law (SI).
    y : ndarray
        State.
    speed : float
        Drive speed, m/s.

    Returns
    -------
    ndarray
        ``f(y)``, in the state's units per second.
    """
    ks = kernel_system(system)
    f = np.empty(ks.n)
    stiff.rhs(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_, ks.kq,
              np.ascontiguousarray(y, dtype=np.float64), float(speed), np.empty(stiff.N_LAW), f)
    return f


def shoot_cycle(system: MemorySystem, y_start: FloatArray, period_guess: float, *,
                speed: float | None = None, rtol: float = DEFAULT_RTOL,
                tolerance: float = SHOOTING_TOLERANCE,
                min_fraction: float = 0.2) -> PeriodicOrbit | None:
    """Newton shooting for a fixed point of the return map to the section ``q_c' = 0``.

    Unknown: the state ``y0`` on the section. Equations: ``P(y0) - y0 = 0`` and the section
    condition, solved in the least-squares sense each step (``N + 1`` equations, ``N``
    unknowns, scaled by :func:`state_scales`) with the Jacobian ``Phi(T) - I`` corrected by the
    change of return time, ``(I - f g^T / (g . f)) Phi(T) - I`` (``g``: the section's
    gradient, ``f``: the flow at the return). An orbit is accepted when the residual is below
    ``tolerance`` and Newton's next step below :data:`STEP_RESOLUTION` of the orbit's size
    (a small residual alone also holds on a slowly decaying spiral next to a Hopf point, whose
    fixed point is steady sliding). Returns None when Newton does not converge within
    :data:`MAX_NEWTON` iterations, or converges onto steady sliding.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    y_start : ndarray
        First guess on the section.
    period_guess : float
        First guess of the period, s.
    speed : float, optional
        Drive speed, m/s (default the schedule's last).
    rtol : float
        Relative tolerance of the runs.
    tolerance : float
        Largest scaled residual accepted.
    min_fraction : float
        The return counted is the first after this fraction of the period: 0.2 takes the
        next upward crossing; an orbit that crosses the section upward ``p`` times per
        period needs a fraction beyond its ``(p-1)``-th crossing.

    Returns
    -------
    PeriodicOrbit or None
        The orbit and its Floquet multipliers.
    """
    v = system.schedule.last if speed is None else float(speed)
    scale = state_scales(system, v)
    y = np.asarray(y_start, dtype=np.float64).copy()
    period = period_guess
    size = math.inf
    for it in range(1, MAX_NEWTON + 1):
        ret = return_map(system, y, v, min_time=min_fraction * period, t_limit=5.0 * period,
                         rtol=rtol)
        if ret is None:
            return None
        y1, phi, period = ret
        r = y1 - y
        residual = float(np.max(np.abs(r) / scale))
        if residual < tolerance:
            size = float(np.max(np.abs(y - steady_state(system, v)) / scale))
            if size < MIN_ORBIT_SIZE:
                return None  # steady sliding itself (an equilibrium on the section), no cycle
        step = _newton_step(system, y, y1, phi, r, scale, v)
        if residual < tolerance and float(np.max(np.abs(step))) <= STEP_RESOLUTION * size:
            mult = np.linalg.eigvals(phi)
            k = int(np.argmin(np.abs(mult - 1.0)))
            trivial = complex(mult[k])
            others = np.delete(mult, k)
            others = others[np.argsort(-np.abs(others))]
            return PeriodicOrbit(y, period, residual, others, trivial, it)
        y = y + step * scale
        if system.quasi_static:
            continue
        y[kernel_system(system).iv] = 0.0
    return None


def _newton_step(system: MemorySystem, y: FloatArray, y1: FloatArray, phi: FloatArray,
                 r: FloatArray, scale: FloatArray, v: float) -> FloatArray:
    """Newton's scaled step from ``y`` (see :func:`shoot_cycle`): the least-squares solution
    of ``((I - f g^T / (g . f)) Phi(T) - I) dy = -r`` with the section condition."""
    f1 = flow(system, y1, v)
    g = _section_gradient(system, y1, v)
    proj = np.eye(y.size) - np.outer(f1, g) / float(g @ f1)
    dp = proj @ phi
    g0 = _section_gradient(system, y, v)
    jac = np.vstack([(dp - np.eye(y.size)) / scale[:, None] * scale[None, :],
                     (g0 * scale)[None, :] / max(float(np.max(np.abs(g0 * scale))), 1e-300)])
    rhs_vec = np.concatenate([-r / scale, [0.0]])
    step, *_ = np.linalg.lstsq(jac, rhs_vec, rcond=None)
    return np.asarray(step, dtype=np.float64)


__all__ = ["PeriodicOrbit", "flow", "return_map", "shoot_cycle"]
