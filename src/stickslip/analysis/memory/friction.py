"""Steady sliding and runs of structures whose friction has memory (rate-state, LuGre).

The smooth stiff engine (:mod:`stickslip.kernel.stiff`, RODAS4 with error control and dense
output) integrates a :class:`~stickslip.model.state_friction.MemorySystem`. Verdicts:

* **steady sliding** is judged by its linearisation ``J`` (structure and state variable
  together): stable when every eigenvalue has a negative real part. The Hopf boundary is where
  the largest real part crosses zero; :func:`hopf_stiffness` finds it by bracketing and
  bisection on the eigenvalues (no simulation). For the 1-DOF slider with rate-and-state
  friction it is Rice and Ruina's (1983) critical stiffness, :func:`rice_ruina_critical_stiffness`.
  A run is called ``steady-sliding`` when steady sliding is linearly stable and the run ends
  within :data:`~stickslip.analysis.memory.simulation.STEADY_TOLERANCE` (relative, every
  component) of it.
* **cycles**: a periodic orbit is a fixed point of the return map to the Poincare section
  ``q_c' = 0`` crossed upwards. It is found by Newton shooting from the run's last crossing,
  with the map's Jacobian from the variational equations integrated with the orbit; the
  Floquet multipliers are the eigenvalues of the monodromy matrix ``Phi(T)``
  (:mod:`stickslip.analysis.memory.cycles`). A stable cycle is the run's verdict
  (:mod:`stickslip.analysis.memory.simulation`): ``stick-slip`` with a quasi-stick phase, else
  ``slip-oscillation``.
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
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.kernel import stiff
from stickslip.model.state_friction import MemorySystem, RateStateFriction

FloatArray = NDArray[np.float64]

#: Relative tolerance of runs (``atol_i = rtol * scale_i``, scales of :func:`state_scales`).
DEFAULT_RTOL = 1e-8
#: Up to this many speeds, :func:`steady_forces` evaluates rate-and-state friction with the
#: engine's compiled law (the same formula) rather than numpy's array set-up.
FEW_SPEEDS = 8
#: Attempted steps per schedule segment (a bound on every run).
MAX_STEPS = 2_000_000
#: Section crossings kept per run: the last ones of the last speed (the compiled run keeps them
#: in a ring).
MAX_CROSSINGS = 4096
#: Fresh calls of the integrator after its steps fell below the round-off of its clock.
MAX_CLOCK_RESTARTS = 100


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
    """``y = (q, q', s)`` (dynamic) or ``(x, psi)`` (quasi-static) and the kernel's arrays.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).

    Returns
    -------
    KernelSystem
        The kernel's arrays.
    """
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
    """Friction force of steady sliding at ``speed`` (m/s), N.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    speed : float
        Drive speed, m/s.

    Returns
    -------
    float
        The friction force, N.
    """
    return float(steady_forces(system, np.array([float(speed)]))[0])


def steady_forces(system: MemorySystem, speeds: FloatArray) -> FloatArray:
    """:func:`steady_force` at every speed of ``speeds`` (m/s), N (the law evaluated at once).

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    speeds : ndarray, shape (n,)
        Drive speeds, m/s.

    Returns
    -------
    ndarray, shape (n,)
        The friction forces, N.
    """
    v = np.asarray(speeds, dtype=np.float64).ravel()
    law, load = system.friction, system.load
    if isinstance(law, RateStateFriction):
        psi = np.array([law.steady_state(float(x), load) for x in v.tolist()])
        if v.size <= FEW_SPEEDS:  # a run's schedule: the compiled law, without numpy's set-up
            lv = np.empty(stiff.N_LAW)
            p = law.parameters(load)
            forces = np.empty(v.size)
            for i in range(v.size):
                stiff.law_values(law.code, p, float(v[i]), float(psi[i]), lv)
                forces[i] = lv[stiff.L_F]
            return forces
        return load * np.asarray(law.mu(v, psi), dtype=np.float64)
    return np.array([law.steady_mu(float(x), load) * load for x in v.tolist()])


def steady_state(system: MemorySystem, speed: float) -> FloatArray:
    """``y`` of steady sliding at ``speed`` (m/s): the contact at rest, springs holding ``F``.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    speed : float
        Drive speed, m/s.

    Returns
    -------
    ndarray
        The state ``y``.
    """
    return steady_states(system, np.array([float(speed)]))[0]


def steady_states(system: MemorySystem, speeds: FloatArray) -> FloatArray:
    """:func:`steady_state` at every speed of ``speeds`` (m/s), one row each.

    The friction force is evaluated for all speeds at once and the springs' deflection is
    ``F K^-1 e_c`` (one solve): stability maps take thousands of speeds.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    speeds : ndarray, shape (n,)
        Drive speeds, m/s.

    Returns
    -------
    ndarray, shape (n, len(y))
        The states ``y``.
    """
    v = np.asarray(speeds, dtype=np.float64).ravel()
    law, load = system.friction, system.load
    s = np.array([law.steady_state(float(x), load) for x in v.tolist()])
    force = steady_forces(system, v)
    if system.quasi_static:
        return np.column_stack([force / system.stiffness[0, 0], s])
    nd = system.n_dof
    e = np.zeros(nd)
    e[system.contact_dof] = 1.0
    y = np.zeros((v.size, 2 * nd + 1))  # (q, q', s): kernel_system's layout
    y[:, :nd] = force[:, None] * np.linalg.solve(system.stiffness, e)[None, :]
    y[:, 2 * nd] = s
    return y


def state_scales(system: MemorySystem, speed: float, steady: FloatArray | None = None) -> FloatArray:
    """Natural size of each component of ``y``: positions, velocities (``V``), the state.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    speed : float
        Drive speed, m/s.
    steady : ndarray, optional
        :func:`steady_state` at ``speed`` when the caller has it already.

    Returns
    -------
    ndarray
        One positive scale per component of ``y`` (m, m/s, the state's unit).
    """
    y = steady_state(system, speed) if steady is None else steady
    law = system.friction
    s_scale = law.a if isinstance(law, RateStateFriction) else max(abs(y[-1]), 1e-300)
    if system.quasi_static:
        return np.array([max(abs(y[0]), 1e-300), s_scale])
    nd = system.n_dof
    x_scale = max(float(np.max(np.abs(y[:nd]))), 1e-300)
    return np.concatenate([np.full(nd, x_scale), np.full(nd, speed), [s_scale]])


def jacobian_at(system: MemorySystem, y: FloatArray, speed: float) -> FloatArray:
    """The exact Jacobian ``df/dy`` of the system at ``y`` (drive speed ``speed``).

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    y : ndarray
        The state.
    speed : float
        Drive speed, m/s.

    Returns
    -------
    ndarray
        ``n x n``, 1/s and mixed units.
    """
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
    """Eigenvalues of the linearisation about steady sliding at ``speed`` (default: the last).

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    speed : float, optional
        Drive speed, m/s (default the schedule's last).

    Returns
    -------
    SteadySliding
        Eigenvalues and growth rate.
    """
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

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    low, high : float
        The factors scanned.
    speed : float, optional
        Drive speed, m/s (default the schedule's last).

    Returns
    -------
    float
        The factor (dimensionless), or NaN.
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
    reversals: int
    reversal_times: FloatArray


def integrate_run(system: MemorySystem, y0: FloatArray, t_max: float, *,
                  rtol: float = DEFAULT_RTOL, history_times: FloatArray | None = None,
                  ) -> _Run:
    """Integrate from ``y0`` at 0 s to ``t_max`` (s) through the speed schedule.

    Returns the final state, the upward section crossings after the last speed step and the
    states at ``history_times`` (rows, NaN outside the run).

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    y0 : ndarray
        Initial state.
    t_max : float
        End time, s.
    rtol : float
        Relative tolerance.
    history_times : ndarray, optional
        Output times, s.

    Returns
    -------
    _Run
        Final time and state, status, section crossings, history rows and step counts.
    """
    ks = kernel_system(system)
    sched = system.schedule
    z = np.array(y0, dtype=np.float64)
    h_times = np.zeros(0) if history_times is None else np.asarray(history_times, dtype=np.float64)
    z_out = np.full((h_times.size, ks.n), np.nan)
    cross_t = np.empty(MAX_CROSSINGS)
    cross_z = np.empty((MAX_CROSSINGS, ks.n))
    kept_t, kept_z = np.empty(0), np.empty((0, ks.n))  # the last segment's last crossings
    reversal_t = np.empty(MAX_CROSSINGS)
    steps = rejected = reversals = 0
    status = stiff.STATUS_DONE
    t = 0.0
    # a hold (speed 0) keeps the scales of the slide before it: steady sliding at 0 has none
    scale_speeds: list[float] = []
    for v in sched.speeds:
        scale_speeds.append(v if v > 0.0 else scale_speeds[-1])  # the first speed is positive
    steady = steady_states(system, np.asarray(scale_speeds, dtype=np.float64))
    last = False
    for i, speed in enumerate(sched.speeds):
        t_end = min(sched.times[i + 1], t_max) if i + 1 < len(sched.times) else t_max
        if t_end <= t:
            break
        atol = rtol * state_scales(system, scale_speeds[i], steady[i])
        last = i + 1 == len(sched.speeds)
        segment_steps = 0
        kept_t, kept_z = np.empty(0), np.empty((0, ks.n))
        # a call whose steps fell below the round-off of its own clock (1e-14 of the time since
        # its start: a slip reversal thousands of seconds into a run) goes on in a fresh call
        # from where it stopped, whose clock starts at zero; the drive speed is constant within
        # the segment, so the motion does not depend on the clock. A run that never underflows
        # makes one call, as before; the restarts share the segment's step budget
        for _call in range(MAX_CLOCK_RESTARTS + 1):
            stats = np.array([0.0, 0.0, 0.0, 0.0, math.inf, -math.inf, 0.0])
            start = t
            status, t, _h = stiff.integrate(
                ks.kind, ks.law, ks.p, ks.amat, ks.bvec, ks.iv, ks.is_, ks.kq, z, ks.n, False, t,
                t_end, float(speed), rtol, atol, 0.0, 0.0, MAX_STEPS - segment_steps, h_times,
                z_out, False, 0.0, cross_t, cross_z,
                reversal_t[min(reversals, MAX_CROSSINGS):], stats)
            segment_steps += int(stats[0]) + int(stats[1])
            steps += int(stats[0])
            rejected += int(stats[1])
            reversals += int(stats[6])
            # the call's ring of crossings, oldest first, after those of the calls before it
            rows = stiff.ring_order(int(stats[3]), MAX_CROSSINGS)
            kept_t = np.concatenate([kept_t, cross_t[rows]])[-MAX_CROSSINGS:]
            kept_z = np.concatenate([kept_z, cross_z[rows]])[-MAX_CROSSINGS:]
            if (status != stiff.STATUS_STEP_UNDERFLOW or not t > start
                    or segment_steps >= MAX_STEPS):
                break
        if status != stiff.STATUS_DONE:
            break
    if not last:  # the run ended before its last segment: no crossings of the last speed
        kept_t, kept_z = np.empty(0), np.empty((0, ks.n))
    return _Run(t, z, status, kept_t, kept_z,
                z_out if history_times is not None else None, steps, rejected, reversals,
                reversal_t[:min(reversals, MAX_CROSSINGS)].copy())


def observables(system: MemorySystem, y: FloatArray, speeds: FloatArray) -> dict[str, FloatArray]:
    """Contact position and velocity, slip speed, ``mu`` and the law's state along rows ``y``.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    y : ndarray
        Rows of states.
    speeds : ndarray
        Drive speed of each row, m/s.

    Returns
    -------
    dict
        ``x`` (m), ``v`` (m/s), ``slip`` (m/s), ``mu`` and ``state`` (theta in s, or z in m).
    """
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
    """Drive speed (m/s) of the schedule at times ``t`` (s).

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and schedule (SI).
    t : ndarray
        Times, s.

    Returns
    -------
    ndarray
        Drive speeds, m/s.
    """
    sched = system.schedule
    idx = np.searchsorted(np.asarray(sched.times), np.asarray(t), side="right") - 1
    return np.asarray(sched.speeds)[np.clip(idx, 0, len(sched.speeds) - 1)]


__all__ = [
    "KernelSystem",
    "SteadySliding",
    "hopf_stiffness",
    "integrate_run",
    "jacobian_at",
    "kernel_system",
    "observables",
    "rice_ruina_critical_stiffness",
    "speed_at",
    "state_scales",
    "steady_force",
    "steady_sliding",
    "steady_state",
]
