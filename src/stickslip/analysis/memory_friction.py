"""Runs, steady sliding and cycles of structures whose friction has memory (rate-state, LuGre).

The smooth stiff engine (:mod:`stickslip.kernel.stiff`, RODAS4 with error control and dense
output) integrates a :class:`~stickslip.model.state_friction.MemorySystem`. Verdicts:

* **steady sliding** is judged by its linearisation ``J`` (structure and state variable
  together): stable when every eigenvalue has a negative real part. The Hopf boundary is where
  the largest real part crosses zero; :func:`hopf_stiffness` finds it by bracketing and
  bisection on the eigenvalues (no simulation). For the 1-DOF slider with rate-and-state
  friction it is Rice and Ruina's (1983) critical stiffness, :func:`rice_ruina_critical_stiffness`.
  A run is called ``steady-sliding`` when steady sliding is linearly stable and the run ends
  within :data:`STEADY_TOLERANCE` (relative, every component) of it.
* **cycles**: a periodic orbit is a fixed point of the return map to the Poincare section
  ``q_c' = 0`` crossed upwards. It is found by Newton shooting from the run's last crossing,
  with the map's Jacobian from the variational equations integrated with the orbit; the
  Floquet multipliers are the eigenvalues of the monodromy matrix ``Phi(T)``. A cycle whose
  residual is below :data:`SHOOTING_TOLERANCE` and whose nontrivial multipliers lie inside the
  unit circle is the run's verdict: ``stick-slip`` when the slip speed drops below
  :data:`QUASI_STICK` times the drive speed (a quasi-stick phase), else ``slip-oscillation``.
* otherwise ``undetermined``, with the reason.

Derivation of the 1-DOF Hopf condition (Rice and Ruina 1983, J. Appl. Mech. 50, 343-349):
with ``m x'' + k x = N mu``, ``v = V - x'`` and the linearisation of either evolution law
about steady sliding (``dF/dv = N a / V``, ``dF/dpsi = N``, ``dG/dv = -b/d_c``,
``dG/dpsi = -V/d_c``), the characteristic polynomial is
``m s^3 + (m V/d_c + N a/V) s^2 + (k - N (b - a)/d_c) s + k V/d_c``. Routh-Hurwitz puts the
Hopf point at ``a2 a1 = a3 a0``, i.e. ``k_c = N (b - a)/d_c (1 + m V^2/(N a d_c))``, with
frequency ``omega_c = (V/d_c) sqrt((b - a)/a)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.verdict import Verdict
from stickslip.kernel import stiff
from stickslip.model.state_friction import LuGreFriction, MemorySystem, RateStateFriction

FloatArray = NDArray[np.float64]

#: Relative tolerance of runs (``atol_i = rtol * scale_i``, scales of :func:`state_scales`).
DEFAULT_RTOL = 1e-8
#: A run has reached steady sliding when every component is this close to it (in its scale).
STEADY_TOLERANCE = 1e-4
#: Largest scaled residual ``|P(y) - y|`` of an accepted periodic orbit.
SHOOTING_TOLERANCE = 1e-7
#: Smallest orbit told apart from steady sliding: ``max_i |y0 - y_ss|_i / scale_i``.
MIN_ORBIT_SIZE = 1e-6
#: Newton iterations of shooting.
MAX_NEWTON = 25
#: Quasi-stick: the slip speed below this fraction of the drive speed.
QUASI_STICK = 1e-2
#: Attempted steps per schedule segment (a bound on every run).
MAX_STEPS = 2_000_000
#: Section crossings kept per run.
MAX_CROSSINGS = 4096


def rice_ruina_critical_stiffness(load: float, a: float, b: float, d_c: float, mass: float,
                                  speed: float) -> float:
    """Rice & Ruina's critical stiffness of the 1-DOF rate-and-state slider, N/m.

    ``k_c = N (b - a) / d_c (1 + m V^2 / (N a d_c))``: steady sliding is linearly unstable for
    ``k < k_c`` (Rice and Ruina 1983; the derivation is in the module docstring).

    Parameters
    ----------
    load : float
        Normal load ``N``, N.
    a, b : float
        Rate-and-state parameters (dimensionless).
    d_c : float
        Slip distance, m.
    mass : float
        Slider mass, kg (0: the quasi-static slider).
    speed : float
        Drive speed ``V``, m/s.

    Returns
    -------
    float
        ``k_c``, N/m (negative when ``b < a``: stable for every stiffness).
    """
    return load * (b - a) / d_c * (1.0 + mass * speed**2 / (load * a * d_c))


@dataclass(frozen=True)
class KernelSystem:
    """The arrays :func:`stickslip.kernel.stiff.integrate` takes for one system."""

    kind: int
    law: int
    p: FloatArray
    amat: FloatArray
    bvec: FloatArray
    iv: int
    is_: int
    kq: float
    n: int


def kernel_system(system: MemorySystem) -> KernelSystem:
    """``y = (q, q', s)`` (dynamic) or ``(x, psi)`` (quasi-static) and the kernel's arrays."""
    p = system.friction.parameters(system.load)
    law = system.friction.code
    if system.quasi_static:
        return KernelSystem(stiff.KIND_QUASI_STATIC, law, p, np.zeros((2, 2)), np.zeros(2), 0, 1,
                            float(system.stiffness[0, 0]), 2)
    nd = system.n_dof
    n = 2 * nd + 1
    minv = np.linalg.inv(system.mass)
    amat = np.zeros((n, n))
    amat[:nd, nd:2 * nd] = np.eye(nd)
    amat[nd:2 * nd, :nd] = -minv @ system.stiffness
    amat[nd:2 * nd, nd:2 * nd] = -minv @ system.damping
    bvec = np.zeros(n)
    bvec[nd:2 * nd] = minv[:, system.contact_dof]
    return KernelSystem(stiff.KIND_DYNAMIC, law, p, amat, bvec, nd + system.contact_dof, 2 * nd,
                        0.0, n)


def steady_force(system: MemorySystem, speed: float) -> float:
    """Friction force of steady sliding at ``speed`` (m/s), N."""
    law = system.friction
    if isinstance(law, RateStateFriction):
        return system.load * law.steady_mu(speed)
    return law.steady_mu(speed, system.load) * system.load


def steady_state(system: MemorySystem, speed: float) -> FloatArray:
    """``y`` of steady sliding at ``speed`` (m/s): the contact at rest, springs holding ``F``."""
    ks = kernel_system(system)
    s = system.friction.steady_state(speed, system.load)
    force = steady_force(system, speed)
    if system.quasi_static:
        return np.array([force / system.stiffness[0, 0], s])
    nd = system.n_dof
    y = np.zeros(ks.n)
    e = np.zeros(nd)
    e[system.contact_dof] = 1.0
    y[:nd] = np.linalg.solve(system.stiffness, force * e)
    y[2 * nd] = s
    return y


def state_scales(system: MemorySystem, speed: float) -> FloatArray:
    """Natural size of each component of ``y``: positions, velocities (``V``), the state."""
    y = steady_state(system, speed)
    law = system.friction
    s_scale = law.a if isinstance(law, RateStateFriction) else max(abs(y[-1]), 1e-300)
    if system.quasi_static:
        return np.array([max(abs(y[0]), 1e-300), s_scale])
    nd = system.n_dof
    x_scale = max(float(np.max(np.abs(y[:nd]))), 1e-300)
    return np.concatenate([np.full(nd, x_scale), np.full(nd, speed), [s_scale]])


def jacobian_at(system: MemorySystem, y: FloatArray, speed: float) -> FloatArray:
    """The exact Jacobian ``df/dy`` of the system at ``y`` (drive speed ``speed``)."""
    ks = kernel_system(system)
    jac = np.empty((ks.n, ks.n))
    stiff.jacobian(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_, ks.kq,
                   np.ascontiguousarray(y, dtype=np.float64), float(speed),
                   np.empty(stiff.N_LAW), jac)
    return jac


@dataclass(frozen=True)
class SteadySliding:
    """The linearisation of steady sliding at one drive speed.

    Attributes
    ----------
    speed : float
        Drive speed, m/s.
    eigenvalues : ndarray
        Eigenvalues of the Jacobian (structure and state variable), 1/s.
    growth_rate : float
        Largest real part, 1/s.
    """

    speed: float
    eigenvalues: NDArray[np.complex128]
    growth_rate: float

    @property
    def stable(self) -> bool:
        """True when every eigenvalue has a negative real part."""
        return self.growth_rate < 0.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"speed_m_s": self.speed, "growth_rate_per_s": self.growth_rate,
                "stable": self.stable,
                "eigenvalues_per_s": [[float(z.real), float(z.imag)] for z in self.eigenvalues]}


def steady_sliding(system: MemorySystem, speed: float | None = None) -> SteadySliding:
    """Eigenvalues of the linearisation about steady sliding at ``speed`` (default: the last)."""
    v = system.schedule.last if speed is None else float(speed)
    eig = np.asarray(np.linalg.eigvals(jacobian_at(system, steady_state(system, v), v)),
                     dtype=np.complex128)
    return SteadySliding(v, eig, float(np.max(eig.real)))


def hopf_stiffness(system: MemorySystem, *, low: float = 1e-6, high: float = 1e6,
                   speed: float | None = None) -> float:
    """Stiffness factor of the Hopf boundary: every stiffness scaled by it, steady sliding is neutral.

    The largest real part of the eigenvalues is bracketed in ``[low, high]`` (factors of the
    system's stiffness, scanned on a logarithmic grid of 121 points) and the sign change
    nearest the system's own stiffness is refined by bisection to 1e-14 relative. For the 1-DOF
    slider the factor times ``k`` is the critical stiffness ``k_c``. NaN when no sign change
    is found.
    """
    def rate(f: float) -> float:
        return steady_sliding(system.with_stiffness_scale(f), speed).growth_rate

    grid = np.geomspace(low, high, 121)
    rates = np.array([rate(f) for f in grid])
    changes = np.nonzero(np.sign(rates[:-1]) != np.sign(rates[1:]))[0]
    if changes.size == 0:
        return math.nan
    i = int(changes[np.argmin(np.abs(np.log(grid[changes])))])
    lo, hi = float(grid[i]), float(grid[i + 1])
    r_lo = rates[i]
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        r_mid = rate(mid)
        if np.sign(r_mid) == np.sign(r_lo):
            lo, r_lo = mid, r_mid
        else:
            hi = mid
        if hi - lo <= 1e-14 * hi:
            break
    return 0.5 * (lo + hi)


@dataclass
class _Run:
    """What :func:`integrate_run` returns."""

    t: float
    y: FloatArray
    status: int
    cross_t: FloatArray
    cross_y: FloatArray
    history: FloatArray | None
    steps: int
    rejected: int


def integrate_run(system: MemorySystem, y0: FloatArray, t_max: float, *,
                  rtol: float = DEFAULT_RTOL, history_times: FloatArray | None = None,
                  ) -> _Run:
    """Integrate from ``y0`` at 0 s to ``t_max`` (s) through the speed schedule.

    Returns the final state, the upward section crossings after the last speed step and the
    states at ``history_times`` (rows, NaN outside the run).
    """
    ks = kernel_system(system)
    sched = system.schedule
    z = np.array(y0, dtype=np.float64)
    h_times = np.zeros(0) if history_times is None else np.asarray(history_times, dtype=np.float64)
    z_out = np.full((h_times.size, ks.n), np.nan)
    cross_t = np.empty(MAX_CROSSINGS)
    cross_z = np.empty((MAX_CROSSINGS, ks.n))
    n_cross = 0
    steps = rejected = 0
    status = stiff.STATUS_DONE
    t = 0.0
    for i, speed in enumerate(sched.speeds):
        t_end = min(sched.times[i + 1], t_max) if i + 1 < len(sched.times) else t_max
        if t_end <= t:
            break
        atol = rtol * state_scales(system, speed)
        stats = np.array([0.0, 0.0, 0.0, 0.0, math.inf, -math.inf])
        last = i + 1 == len(sched.speeds)
        status, t, _h = stiff.integrate(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_,
                                       ks.kq, z, ks.n, False, t, t_end, float(speed), rtol, atol,
                                       0.0, 0.0, MAX_STEPS, h_times, z_out, False, 0.0, cross_t,
                                       cross_z, stats)
        steps += int(stats[0])
        rejected += int(stats[1])
        if last:
            n_cross = min(int(stats[3]), MAX_CROSSINGS)
        if status != stiff.STATUS_DONE:
            break
    return _Run(t, z, status, cross_t[:n_cross].copy(), cross_z[:n_cross].copy(),
                z_out if history_times is not None else None, steps, rejected)


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
        """True when every nontrivial multiplier lies inside the unit circle."""
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"period_s": self.period, "residual": self.residual,
                "floquet_multipliers": [[float(m.real), float(m.imag)] for m in self.multipliers],
                "trivial_multiplier": [float(self.trivial_multiplier.real),
                                       float(self.trivial_multiplier.imag)],
                "newton_iterations": self.iterations, "stable": self.stable,
                "section": "contact velocity q_c' = 0, crossed upwards"}


def return_map(system: MemorySystem, y0: FloatArray, speed: float, *, min_time: float,
               t_limit: float, rtol: float = DEFAULT_RTOL,
               ) -> tuple[FloatArray, FloatArray, float] | None:
    """The first upward return to the section after ``min_time`` (s): ``(y(T), Phi(T), T)``.

    The variational equations are integrated with the orbit, ``Phi`` under the same error
    control as ``y``; where that cannot be met (the steps shrink to round-off at the kink of
    ``|v|`` in the laws, at a reversal of the slip speed) ``Phi`` rides on the steps chosen for
    ``y`` alone. None when no return comes before ``t_limit`` (s).
    """
    ks = kernel_system(system)
    n = ks.n
    atol = rtol * state_scales(system, speed)
    for phi_rtol in (rtol, 0.0):
        z = np.concatenate([np.asarray(y0, dtype=np.float64), np.eye(n).ravel()])
        stats = np.array([0.0, 0.0, 0.0, 0.0, math.inf, -math.inf])
        cross_t = np.empty(1)
        cross_z = np.empty((1, n + n * n))
        status, t, _ = stiff.integrate(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_,
                                       ks.kq, z, n, True, 0.0, t_limit, float(speed), rtol, atol,
                                       phi_rtol, 0.0, MAX_STEPS, np.zeros(0),
                                       np.zeros((0, n + n * n)), True, min_time, cross_t, cross_z,
                                       stats)
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


def _flow(system: MemorySystem, y: FloatArray, speed: float) -> FloatArray:
    ks = kernel_system(system)
    f = np.empty(ks.n)
    stiff.rhs(ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_, ks.kq,
              np.ascontiguousarray(y, dtype=np.float64), float(speed), np.empty(stiff.N_LAW), f)
    return f


def shoot_cycle(system: MemorySystem, y_start: FloatArray, period_guess: float, *,
                speed: float | None = None, rtol: float = DEFAULT_RTOL,
                tolerance: float = SHOOTING_TOLERANCE) -> PeriodicOrbit | None:
    """Newton shooting for a fixed point of the return map to the section ``q_c' = 0``.

    Unknown: the state ``y0`` on the section. Equations: ``P(y0) - y0 = 0`` and the section
    condition, solved in the least-squares sense each step (``N + 1`` equations, ``N``
    unknowns, scaled by :func:`state_scales`) with the Jacobian ``Phi(T) - I`` corrected by the
    change of return time, ``(I - f g^T / (g . f)) Phi(T) - I`` (``g``: the section's
    gradient, ``f``: the flow at the return). Returns None when Newton does not converge
    within :data:`MAX_NEWTON` iterations to ``tolerance``.
    """
    v = system.schedule.last if speed is None else float(speed)
    scale = state_scales(system, v)
    y = np.asarray(y_start, dtype=np.float64).copy()
    period = period_guess
    for it in range(1, MAX_NEWTON + 1):
        ret = return_map(system, y, v, min_time=0.2 * period, t_limit=5.0 * period, rtol=rtol)
        if ret is None:
            return None
        y1, phi, period = ret
        r = y1 - y
        residual = float(np.max(np.abs(r) / scale))
        if residual < tolerance:
            if float(np.max(np.abs(y - steady_state(system, v)) / scale)) < MIN_ORBIT_SIZE:
                return None  # steady sliding itself (an equilibrium on the section), no cycle
            mult = np.linalg.eigvals(phi)
            k = int(np.argmin(np.abs(mult - 1.0)))
            trivial = complex(mult[k])
            others = np.delete(mult, k)
            others = others[np.argsort(-np.abs(others))]
            return PeriodicOrbit(y, period, residual, others, trivial, it)
        f1 = _flow(system, y1, v)
        g = _section_gradient(system, y1, v)
        proj = np.eye(y.size) - np.outer(f1, g) / float(g @ f1)
        dp = proj @ phi
        g0 = _section_gradient(system, y, v)
        jac = np.vstack([(dp - np.eye(y.size)) / scale[:, None] * scale[None, :],
                         (g0 * scale)[None, :] / max(float(np.max(np.abs(g0 * scale))), 1e-300)])
        rhs_vec = np.concatenate([-r / scale, [0.0]])
        step, *_ = np.linalg.lstsq(jac, rhs_vec, rcond=None)
        y = y + step * scale
        if system.quasi_static:
            continue
        y[kernel_system(system).iv] = 0.0
    return None


@dataclass(frozen=True)
class MemoryResult:
    """One run of a structure with friction with memory, and its verdict.

    Attributes
    ----------
    system : MemorySystem
        What was run.
    verdict : Verdict
        ``steady-sliding``, ``stick-slip``, ``slip-oscillation`` or ``undetermined``.
    certificate : str
        What supports the verdict, in words ("" when undetermined).
    reason : str
        Why the verdict is what it is (for ``undetermined``: what to change).
    steady : SteadySliding
        Linearisation at the last drive speed.
    orbit : PeriodicOrbit or None
        The periodic orbit, when found.
    period : float
        Period, s (NaN without a cycle).
    amplitude : float
        Half the peak-to-peak displacement of the contact DOF over the cycle, m (NaN without).
    min_slip_speed : float
        Smallest slip speed over the cycle, m/s (NaN without).
    t_end : float
        Time reached, s.
    initial : ndarray
        Initial state ``y``.
    history : dict or None
        ``t_s``, ``x_m``, ``v_m_s``, ``slip_speed_m_s``, ``mu``, ``state`` at the asked times.
    steps, rejected : int
        Accepted and rejected steps of the run.
    """

    system: MemorySystem
    verdict: Verdict
    certificate: str
    reason: str
    steady: SteadySliding
    orbit: PeriodicOrbit | None
    period: float
    amplitude: float
    min_slip_speed: float
    t_end: float
    t_max: float
    initial: FloatArray
    initial_description: str
    rtol: float
    steps: int
    rejected: int
    history: dict[str, list[float]] | None = field(default=None)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI)."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        out: dict[str, Any] = {
            "verdict": self.verdict.value,
            "certificate": self.certificate,
            "status_message": self.reason,
            "engine": "smooth stiff engine (RODAS4, order 4, error control and dense output)",
            "rtol": self.rtol,
            "period_s": num(self.period),
            "amplitude_m": num(self.amplitude),
            "min_slip_speed_m_s": num(self.min_slip_speed),
            "t_end_s": float(self.t_end),
            "t_max_s": float(self.t_max),
            "steps": self.steps,
            "rejected_steps": self.rejected,
            "steady_sliding": self.steady.to_dict(),
            "steady_sliding_stable": self.steady.stable,
            "growth_rate_per_s": self.steady.growth_rate,
            "cycle": None if self.orbit is None else self.orbit.to_dict(),
            "initial_condition": self.initial_description,
            "initial_state": self.initial.tolist(),
            "friction": {**self.system.friction.to_dict(),
                         "description": self.system.friction.describe(),
                         "state": self.system.friction.state_name()},
            "machine": self.system.to_dict(),
        }
        if self.history is not None:
            out["history"] = self.history
        return out


def _observables(system: MemorySystem, y: FloatArray, speeds: FloatArray) -> dict[str, FloatArray]:
    """Contact position and velocity, slip speed, ``mu`` and the law's state along rows ``y``."""
    ks = kernel_system(system)
    lv = np.empty(stiff.N_LAW)
    rows = y.shape[0]
    x = np.empty(rows)
    xv = np.empty(rows)
    mu = np.empty(rows)
    for i in range(rows):
        yi = np.ascontiguousarray(y[i])
        if not np.all(np.isfinite(yi)):
            x[i] = xv[i] = mu[i] = math.nan
            continue
        xv[i] = stiff.contact_speed(ks.kind, ks.law, ks.p, ks.kq, ks.iv, yi, float(speeds[i]))
        x[i] = yi[0] if system.quasi_static else yi[system.contact_dof]
        stiff.law_values(ks.law, ks.p, float(speeds[i]) - xv[i], float(yi[ks.is_]), lv)
        mu[i] = lv[stiff.L_F] / system.load
    state = np.asarray(system.friction.state_output(y[:, ks.is_]), dtype=np.float64)
    return {"x": x, "v": xv, "slip": speeds - xv, "mu": mu, "state": state}


def speed_at(system: MemorySystem, t: FloatArray) -> FloatArray:
    """Drive speed (m/s) of the schedule at times ``t`` (s)."""
    sched = system.schedule
    idx = np.searchsorted(np.asarray(sched.times), np.asarray(t), side="right") - 1
    return np.asarray(sched.speeds)[np.clip(idx, 0, len(sched.speeds) - 1)]


def default_horizon(system: MemorySystem) -> float:
    """Default run length, s: the last speed step plus 100 of the slowest natural times.

    Natural times: the structure's period ``2 pi sqrt(m/k)`` (contact DOF), the state's
    relaxation ``d_c / V`` and the elastic loading time ``N a / (k V)`` (rate-state), the
    loading time ``mu_s N / (k V)`` (LuGre). When
    steady sliding is unstable with growth rate ``sigma``, at least ``40 / sigma`` (a
    disturbance grows by ``e^40``).
    """
    v = system.schedule.last
    c = system.contact_dof
    k = float(system.stiffness[c, c])
    times = []
    if not system.quasi_static:
        times.append(2.0 * math.pi * math.sqrt(float(system.mass[c, c]) / k))
    law = system.friction
    if isinstance(law, RateStateFriction):
        times += [law.d_c / v, system.load * law.a / (k * v)]
    else:
        times.append(law.mu_s * system.load / (k * v))
    growth = steady_sliding(system).growth_rate
    span = 100.0 * max(times)
    if growth > 0.0:
        span = max(span, 40.0 / growth)
    return system.schedule.times[-1] + span


def initial_state(system: MemorySystem, kick: float = 0.0) -> tuple[FloatArray, str]:
    """Steady sliding at the first speed; with ``kick = F`` the contact moves at ``-F V``.

    The slip speed is then ``(1 + F) V``; positions and the state are those of steady sliding.
    The quasi-static slider has no velocity of its own: a kick is refused for it.
    """
    v = system.schedule.first
    y = steady_state(system, v)
    text = f"steady sliding at {v:g} m/s"
    if kick != 0.0:
        if system.quasi_static:
            raise ValueError("--initial-kick needs the slider's mass: the quasi-static slider "
                             "(m = 0) has no velocity of its own")
        y[kernel_system(system).iv] = -kick * v
        text += f", the contact kicked to move at {-kick * v:g} m/s (slip speed {(1 + kick) * v:g} m/s)"
    return y, text


def simulate_memory(system: MemorySystem, *, t_max: float | None = None, kick: float = 0.0,
                    history_times: FloatArray | None = None, rtol: float = DEFAULT_RTOL,
                    initial: FloatArray | None = None) -> MemoryResult:
    """One run from steady sliding at the first speed (or ``initial``), its verdict and cycle.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and speed schedule (SI).
    t_max : float, optional
        Run length, s (default :func:`default_horizon`).
    kick : float
        Initial kick ``F``: the contact starts moving at ``-F V`` (see :func:`initial_state`).
    history_times : array_like, optional
        Times (s) of the ``history`` arrays.
    rtol : float
        Relative tolerance of the engine.
    initial : ndarray, optional
        Initial state ``y`` instead of steady sliding (``(q, q', s)`` or ``(x, psi)``).

    Returns
    -------
    MemoryResult
        The verdict (see the module docstring), period and amplitude, the linearisation and
        the orbit's certificate.
    """
    horizon = default_horizon(system) if t_max is None else float(t_max)
    if not (math.isfinite(horizon) and horizon > 0.0):
        raise ValueError(f"t_max={horizon!r} s must be positive and finite")
    if initial is None:
        y0, description = initial_state(system, kick)
    else:
        y0, description = np.asarray(initial, dtype=np.float64).copy(), "user-defined"
    h_times = None if history_times is None else np.asarray(history_times, dtype=np.float64)
    run = integrate_run(system, y0, horizon, rtol=rtol, history_times=h_times)
    steady = steady_sliding(system)
    v = system.schedule.last
    history = None
    if h_times is not None and run.history is not None:
        obs = _observables(system, run.history, speed_at(system, h_times))

        def clean(a: FloatArray) -> list[float]:
            return [float(x) if math.isfinite(x) else math.nan for x in a]

        history = {"t_s": clean(h_times), "x_m": clean(obs["x"]), "v_m_s": clean(obs["v"]),
                   "slip_speed_m_s": clean(obs["slip"]), "mu": clean(obs["mu"]),
                   "state": clean(obs["state"])}
    common: dict[str, Any] = dict(system=system, steady=steady, t_end=run.t, t_max=horizon, initial=y0,
                  initial_description=description, rtol=rtol, steps=run.steps,
                  rejected=run.rejected, history=history)
    nan = math.nan
    if run.status != stiff.STATUS_DONE:
        why = ("the step budget was used up" if run.status == stiff.STATUS_MAX_STEPS
               else "the step size fell to round-off")
        return MemoryResult(verdict=Verdict.UNDETERMINED, certificate="",
                            reason=f"the run stopped at {run.t:.6g} s: {why}", orbit=None,
                            period=nan, amplitude=nan, min_slip_speed=nan, **common)
    scale = state_scales(system, v)
    distance = float(np.max(np.abs(run.y - steady_state(system, v)) / scale))
    if steady.stable and distance < STEADY_TOLERANCE:
        return MemoryResult(
            verdict=Verdict.STEADY_SLIDING,
            certificate=(f"steady sliding at {v:g} m/s is linearly stable (largest real part of "
                         f"the eigenvalues {steady.growth_rate:.6g} 1/s, state variable included) "
                         f"and the run ends within {distance:.2g} of it (relative, every "
                         "component)"),
            reason="steady sliding: linearly stable and reached", orbit=None, period=nan,
            amplitude=nan, min_slip_speed=nan, **common)
    if run.cross_t.size >= 3:
        period_guess = float(run.cross_t[-1] - run.cross_t[-2])
        orbit = shoot_cycle(system, run.cross_y[-1], period_guess, rtol=rtol)
        if orbit is not None:
            return _cycle_result(system, orbit, common)
        reason = ("the run oscillates but Newton shooting on the section q_c' = 0 did not "
                  "converge; increase t_max")
    elif not steady.stable and distance < STEADY_TOLERANCE:
        reason = (f"steady sliding is linearly unstable (growth rate {steady.growth_rate:.6g} 1/s) "
                  "but the run stayed at it (an unstable equilibrium); start it off steady "
                  "sliding (--initial-kick) or run longer")
    else:
        reason = "the run neither reached steady sliding nor settled on a cycle; increase t_max"
    return MemoryResult(verdict=Verdict.UNDETERMINED, certificate="", reason=reason, orbit=None,
                        period=nan, amplitude=nan, min_slip_speed=nan, **common)


#: Samples of one period for the cycle's amplitude and smallest slip speed.
CYCLE_SAMPLES = 4001


def _cycle_result(system: MemorySystem, orbit: PeriodicOrbit, common: dict[str, Any]) -> MemoryResult:
    v = system.schedule.last
    times = np.linspace(0.0, orbit.period, CYCLE_SAMPLES)
    one = MemorySystem(system.mass, system.damping, system.stiffness, system.contact_dof,
                       system.load, system.friction, type(system.schedule).constant(v))
    run = integrate_run(one, orbit.y0, orbit.period, rtol=common["rtol"], history_times=times)
    assert run.history is not None
    obs = _observables(one, run.history, np.full(times.size, v))
    amplitude = 0.5 * float(np.nanmax(obs["x"]) - np.nanmin(obs["x"]))
    min_slip = float(np.nanmin(obs["slip"]))
    multipliers = ", ".join(f"{abs(m):.6g}" for m in orbit.multipliers)
    if not orbit.stable:
        return MemoryResult(
            verdict=Verdict.UNDETERMINED, certificate="",
            reason=(f"a periodic orbit of period {orbit.period:.6g} s was found but it is unstable "
                    f"(Floquet multiplier moduli {multipliers}); the run is still on its way "
                    "elsewhere: increase t_max"),
            orbit=orbit, period=math.nan, amplitude=math.nan, min_slip_speed=math.nan, **common)
    stick = min_slip < QUASI_STICK * v
    verdict = Verdict.STICK_SLIP if stick else Verdict.SLIP_OSCILLATION
    certificate = (f"periodic orbit by Newton shooting on the section q_c' = 0: period "
                   f"{orbit.period:.8g} s, scaled residual {orbit.residual:.2g}, nontrivial Floquet "
                   f"multipliers of modulus {multipliers} (< 1: stable), trivial multiplier "
                   f"{orbit.trivial_multiplier.real:.8f}; smallest slip speed {min_slip:.3g} m/s "
                   + (f"(< {QUASI_STICK:g} V: quasi-stick)" if stick else f"(>= {QUASI_STICK:g} V: "
                      "it never sticks)"))
    return MemoryResult(verdict=verdict, certificate=certificate,
                        reason="a stable periodic orbit attracts the run", orbit=orbit,
                        period=orbit.period, amplitude=amplitude, min_slip_speed=min_slip,
                        **common)


__all__ = [
    "LuGreFriction",
    "MemoryResult",
    "PeriodicOrbit",
    "RateStateFriction",
    "SteadySliding",
    "hopf_stiffness",
    "rice_ruina_critical_stiffness",
    "shoot_cycle",
    "simulate_memory",
    "steady_sliding",
]
