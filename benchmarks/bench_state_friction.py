"""Benchmark: the smooth stiff engine against scipy's solve_ivp with a Python right-hand side.

Usage::

    .venv/bin/python benchmarks/bench_state_friction.py

Measured on the 2-core development machine, shared with other jobs (times vary by tens of
per cent run to run; last run 2026-11-27 09:27, load average 1.7)::

    rate-and-state stability map 100x100: engine 0.25 s (goal 60 s), baseline (Python right-hand
      side, finite-difference Jacobian) 0.58 s, ratio 2.29x; same sign of the growth rate in
      10000/10000 cells
    velocity step (quasi-static rate-and-state): engine rtol 1e-8, error 3.37e-07, 0.36 ms
      scipy LSODA rtol 1e-09: error 9.89e-08, 3.3 ms, ratio 9.1x
      scipy Radau rtol 1e-08: error 1.43e-07, 20.5 ms, ratio 57.3x
    LuGre stick-slip (Canudas de Wit et al. 1995): engine rtol 1e-8, error 8.92e-07, 9.01 ms
      scipy LSODA rtol 1e-11: error 1.52e-07, 109.2 ms, ratio 12.1x
      scipy Radau rtol 1e-08: error 2.88e-07, 690.0 ms, ratio 76.6x

First a 100 x 100 stability map of a 1-DOF rate-and-state slider (m = 1 kg, k = 8000 N/m,
a = 0.01, b = 0.015, d_c = 10 um; speeds 1e-5 to 0.1 m/s, loads 1 to 100 N): the tool's map
(exact Jacobians, eigenvalues with round-off bounds, any structure and law) against what a user
writes by hand for this one law (a Python right-hand side, a central-difference Jacobian,
``numpy.linalg.eigvals``); the signs of the growth rates must agree. Then
two runs (docs/friction_memory.md): a velocity step of the quasi-static rate-and-state slider
(1 -> 10 um/s at 10 s, 20 s) and the LuGre stick-slip example of Canudas de Wit et al. (1995),
30 s from stick. The baseline is what ``rsfmodel`` does: scipy integrating a Python right-hand
side (LSODA, the method of ``odeint``, and Radau with the analytic Jacobian in Python). Equal
accuracy: the engine runs at ``rtol = 1e-8``; its largest error at 200 (resp. 300) output times,
in units of each component's scale, against a reference (the engine at ``rtol = 1e-12``,
which agrees with scipy's DOP853 at 1e-13 to 3e-9, tests/test_stiff_engine.py) sets the target;
each baseline runs at the loosest of ``rtol = 1e-6, 1e-7, ..., 1e-12`` that meets it. Times are
the best of 3 (engine compiled beforehand). The ratio is baseline time over engine time.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
import scipy.integrate

from stickslip.analysis.memory.friction import integrate_run, state_scales, steady_state
from stickslip.analysis.memory.simulation import initial_state
from stickslip.model.state_friction import (
    LuGreFriction,
    MemorySystem,
    RateStateFriction,
    SpeedSchedule,
)

RS = RateStateFriction(a=0.01, b=0.008, d_c=10e-6, mu_ref=0.6, v_ref=1e-6)
STEP = MemorySystem(np.zeros((1, 1)), np.zeros((1, 1)), np.array([[1e7]]), 0, 1e3, RS,
                    SpeedSchedule((0.0, 10.0), (1e-6, 1e-5)))
LUGRE = LuGreFriction(sigma0=1e5, sigma1=math.sqrt(1e5), sigma2=0.4, mu_c=1.0, mu_s=1.5,
                      stribeck_velocity=1e-3)
CANUDAS = MemorySystem(np.array([[1.0]]), np.array([[0.0]]), np.array([[2.0]]), 0, 1.0, LUGRE,
                       SpeedSchedule.constant(0.1))

Rhs = Callable[[float, np.ndarray], np.ndarray]


def step_rhs(speed: float) -> tuple[Rhs, Rhs]:
    """Quasi-static slider, aging law in psi: ``x' = V - v(x, psi)``; and its Jacobian."""
    a, b, dc, mu0, vref, load, k = RS.a, RS.b, RS.d_c, RS.mu_ref, RS.v_ref, 1e3, 1e7

    def f(_t: float, y: np.ndarray) -> np.ndarray:
        x, psi = y
        v = 2.0 * vref * math.exp(-psi / a) * math.sinh(k * x / (load * a))
        return np.array([speed - v, (b / dc) * (vref * math.exp((mu0 - psi) / b) - abs(v))])

    def jac(_t: float, y: np.ndarray) -> np.ndarray:
        x, psi = y
        c = 2.0 * vref * math.exp(-psi / a)
        v = c * math.sinh(k * x / (load * a))
        vx = c * math.cosh(k * x / (load * a)) * k / (load * a)
        vp = -v / a
        s = math.copysign(1.0, v)
        gp = -(vref / dc) * math.exp((mu0 - psi) / b)
        return np.array([[-vx, -vp], [-(b / dc) * s * vx, -(b / dc) * s * vp + gp]])

    return f, jac


def lugre_rhs(speed: float) -> tuple[Rhs, Rhs]:
    """LuGre slider ``m x'' + k x = F``, ``v = V - x'``; and a Jacobian by differences."""
    s0, s1, s2, mc, ms, vs = 1e5, math.sqrt(1e5), 0.4, 1.0, 1.5, 1e-3

    def f(_t: float, y: np.ndarray) -> np.ndarray:
        x, xd, z = y
        v = speed - xd
        g = mc + (ms - mc) * math.exp(-((v / vs) ** 2))
        dz = v - s0 * abs(v) * z / g
        force = s0 * z + s1 * dz + s2 * v
        return np.array([xd, -2.0 * x + force, dz])

    def jac(t: float, y: np.ndarray) -> np.ndarray:
        out = np.empty((3, 3))
        for j in range(3):
            h = 1e-8 * max(abs(y[j]), 1e-6)
            e = np.zeros(3)
            e[j] = h
            out[:, j] = (f(t, y + e) - f(t, y - e)) / (2 * h)
        return out

    return f, jac


def scipy_run(system: MemorySystem, make: Callable[[float], tuple[Rhs, Rhs]], y0: np.ndarray,
              times: np.ndarray, method: str, rtol: float) -> np.ndarray:
    """The baseline through the schedule, states at ``times``."""
    sched = system.schedule
    rows = [y0] if times[0] == 0.0 else []
    y = y0
    for i, speed in enumerate(sched.speeds):
        t0 = sched.times[i]
        t1 = sched.times[i + 1] if i + 1 < len(sched.times) else float(times[-1])
        f, jac = make(speed)
        inside = times[(times > t0) & (times <= t1)]
        options = {"jac": jac} if method == "Radau" else {}
        sol = scipy.integrate.solve_ivp(f, (t0, t1), y, method=method, rtol=rtol,
                                        atol=rtol * state_scales(system, speed), t_eval=inside,
                                        **options)
        if not sol.success:
            raise RuntimeError(sol.message)
        rows += list(sol.y.T)
        y = sol.y[:, -1] if sol.t.size and sol.t[-1] == t1 else scipy.integrate.solve_ivp(
            f, (t0, t1), y, method=method, rtol=rtol,
            atol=rtol * state_scales(system, speed), **options).y[:, -1]
    return np.array(rows)


def best_of(fn: Callable[[], object], repeat: int = 3) -> float:
    """Fastest wall time of ``repeat`` calls, s."""
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def case(name: str, system: MemorySystem, make: Callable[[float], tuple[Rhs, Rhs]],
         y0: np.ndarray, t_end: float, n_out: int) -> None:
    times = np.linspace(0.0, t_end, n_out)
    scale = state_scales(system, system.schedule.last)

    def engine(rtol: float) -> np.ndarray:
        run = integrate_run(system, y0, t_end, rtol=rtol, history_times=times)
        assert run.history is not None
        return run.history

    reference = engine(1e-12)
    target = float(np.max(np.abs(engine(1e-8) - reference) / scale))
    t_engine = best_of(lambda: engine(1e-8))
    print(f"{name}: engine rtol 1e-8, error {target:.2e}, {t_engine * 1e3:.2f} ms")
    for method in ("LSODA", "Radau"):
        for exponent in range(6, 13):
            rtol = 10.0 ** -exponent
            try:
                err = float(np.max(np.abs(scipy_run(system, make, y0, times, method, rtol)
                                          - reference) / scale))
            except RuntimeError:
                continue
            if err <= target:
                t_base = best_of(lambda m=method, r=rtol: scipy_run(system, make, y0, times, m, r))
                print(f"  scipy {method:5s} rtol {rtol:.0e}: error {err:.2e}, {t_base * 1e3:.1f} ms, "
                      f"ratio {t_base / t_engine:.1f}x")
                break
        else:
            print(f"  scipy {method:5s}: no rtol down to 1e-12 reached the engine's accuracy")


#: The stability map's slider (docs/friction_memory.md): m = 1 kg, k = 8000 N/m, N = 10 N,
#: a = 0.01, b = 0.015, d_c = 10 um (Rice and Ruina's k_c = 1e4 N/m at 1 mm/s).
MAP_LAW = RateStateFriction(a=0.01, b=0.015, d_c=10e-6, mu_ref=0.6, v_ref=1e-6)
MAP_SYSTEM = MemorySystem(np.array([[1.0]]), np.array([[0.0]]), np.array([[8000.0]]), 0, 10.0,
                          MAP_LAW, SpeedSchedule.constant(1e-3))


def baseline_growth(speed: float, load: float) -> float:
    """What a user without the tool writes: the aging-law slider's right-hand side in Python
    (classic form, y = (x, x', theta)), a central-difference Jacobian at steady sliding, eigvals."""
    law, m, k = MAP_LAW, 1.0, 8000.0

    def rhs(y: np.ndarray) -> np.ndarray:
        x, v, theta = y
        slip = speed - v
        mu = law.mu_ref + law.a * math.log(slip / law.v_ref) + law.b * math.log(law.v_ref * theta / law.d_c)
        return np.array([v, (load * mu - k * x) / m, 1.0 - slip * theta / law.d_c])

    theta = law.d_c / speed
    mu_ss = law.mu_ref + (law.a - law.b) * math.log(speed / law.v_ref)
    y0 = np.array([load * mu_ss / k, 0.0, theta])
    scale = np.array([abs(y0[0]), speed, theta])
    jac = np.empty((3, 3))
    for j in range(3):
        h = 1e-6 * scale[j]
        e = np.zeros(3)
        e[j] = h
        jac[:, j] = (rhs(y0 + e) - rhs(y0 - e)) / (2.0 * h)
    return float(np.max(np.linalg.eigvals(jac).real))


def stability_map_case(n_speed: int = 100, n_load: int = 100) -> None:
    """A 10^4-cell rate-and-state stability map: the tool's against the baseline's, one run."""
    from stickslip.sweep.memory.maps import memory_stability_map

    speeds, loads = np.geomspace(1e-5, 1e-1, n_speed), np.geomspace(1.0, 100.0, n_load)
    memory_stability_map(MAP_SYSTEM, speeds[:2], loads[:2])  # compile / load the cache
    start = time.perf_counter()
    data = memory_stability_map(MAP_SYSTEM, speeds, loads)
    engine = time.perf_counter() - start
    start = time.perf_counter()
    base = np.array([[baseline_growth(float(v), float(w)) for w in loads] for v in speeds])
    baseline = time.perf_counter() - start
    agree = int(np.sum((data.growth_rate > 0) == (base > 0)))
    print(f"rate-and-state stability map {n_speed}x{n_load}: engine {engine:.2f} s "
          f"(goal 60 s), baseline (Python right-hand side, finite-difference Jacobian) "
          f"{baseline:.2f} s, ratio {baseline / engine:.2f}x; same sign of the growth rate in "
          f"{agree}/{data.growth_rate.size} cells")


def main() -> None:
    stability_map_case()
    integrate_run(STEP, steady_state(STEP, 1e-6), 1.0)  # compile
    case("velocity step (quasi-static rate-and-state)", STEP, step_rhs,
         steady_state(STEP, 1e-6), 20.0, 201)
    case("LuGre stick-slip (Canudas de Wit et al. 1995)", CANUDAS, lugre_rhs,
         initial_state(CANUDAS, -1.0)[0], 30.0, 301)


if __name__ == "__main__":
    main()
