"""Benchmark (issue 18 point 5): a 20-DOF structure's simulate against the solve_ivp oracle,
and the reduction of a 20,000-DOF sparse model, in one run.

Usage::

    .venv/bin/python benchmarks/bench_structure.py             # ~6-10 minutes
    .venv/bin/python benchmarks/bench_structure.py --quick     # fewer repeats, ~3-5 minutes

Case 1: a grounded 20-DOF chain (masses 0.8-1.6, springs 1-6.7 and a cross spring, Rayleigh
damping 0.05 M + 0.05 K, dimensionless) with the contact on DOF 10, lambda = 10 (stick-slip,
certified at tau = 1156) and 0.3 (steady sliding), gamma = 2, start-up state. The engine runs
``simulate`` to its certified verdict (``t_end``); the oracle (``tests/oracle.py``, DOP853 with
terminal events, contact DOF native) is timed on exactly ``[0, t_end]``, like for like. The
engine's compile is paid before timing (one warm-up run). The ratio is oracle time / engine
time, best of ``--repeats``. Under each case a line gives the stages of one ``simulate``
(structure checks, per-mode matrices, their step exponentials, the slip-I Lyapunov solve, the
whole preparation, the event loop, the rest), best of ``--repeats`` each.

Measured (2 cores shared with four other jobs, --quick, three runs: times vary 2x between
runs), after the O(n^3) Lyapunov solve, the balanced step norm and slip-II's step from
slip-I's block of :mod:`stickslip.kernel.linalg` for structures beyond 3 DOF: 116-232x on the
stick-slip case (61-108 ms; before: 29x, ~0.33 s, of which the O(n^6) Kronecker Lyapunov
solve took 0.1-0.18 s and the event loop 0.22 s for 39103 steps, now 10323), and 2-19x on the
steady case, whose horizon is only tau = 1.97: the oracle needs 8-57 ms there, the engine's
fixed cost (the preparation, ~1.3 ms: step exponentials and a Lyapunov solve) is most of its
2-8 ms. 100x on that case would need a whole run below 0.1-0.5 ms: not met.

Case 2: ``map --config``'s sweep over a 12 x 12 (--quick; 30 x 30 otherwise) speed/load grid of
the 3-DOF slideway of ``tests/test_operating_map.py``, serially and on every numba thread,
against the former implementation (one ``simulate`` per cell in a Python loop) in the same run;
it also checks serial == threads bit for bit and the verdicts against the loop's. Measured
(--quick, 2 cores shared with four other jobs): loop 0.78 s, serial 0.35 s (2.2x), threads
0.41 s (1.9x): on this loaded machine the second thread brought nothing; building each cell's
dimensionless law (a ``Machine`` per cell, ~0.35 ms) is serial Python.

Case 3: a 20,000-DOF sparse chain frame (5 kg nodes, 1e8 N/m links, 2e7 N/m to the floor at
both ends) with a 1 kg slider on 1e6 N/m at its middle:
:func:`stickslip.analysis.reduction.reduce_structure` at the default cut-off (sparse LU and
``eigsh`` in shift-invert), time and size of the reduced model. The baseline measured in the
same run is one sparse LU factorisation of the same stiffness (the least any reduction must do).

Case 4: the reduction's error (issue 18 point 5): the Coulomb critical belt speed of the
301-DOF frame of ``tests/test_structure_reduction.py`` (damping 2e-5 K), reduced at the default
cut-off (:class:`stickslip.analysis.machine_absorber.CriticalPoint` of the reduced machine)
against the full model's, bisected between 0.98 and 1.02 of it to 5e-3 (--quick) or 1e-3.
Measured at 1e-3: reduced 0.303267 m/s (50 DOF) vs full 0.303422 m/s, relative error -5.1e-4
(the full model's bisection took 206 s: each 301-DOF run is 15-30 s).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.oracle import oracle_simulate

from stickslip.analysis.reduction import default_cutoff_hz, reduce_structure
from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.kernel import engine
from stickslip.kernel.linalg import expm
from stickslip.kernel.system import lyapunov_solve, mode_matrices, prepare_bands
from stickslip.model import Slider
from stickslip.model.initial import startup_state
from stickslip.model.structure import Structure
from stickslip.sweep.executors import max_threads

GAMMA = 2.0
#: Stiffness-proportional damping of the 301-DOF frame in the reduction-error case, s (frame
#: modes at 2-9 % of critical; the 1e-6 s of the receptance tests leaves them so light that a
#: full run from start-up rarely certifies within the horizon).
FRAME_DAMPING = 2e-5


def chain_structure_20(n: int = 20, contact: int = 10) -> Structure:
    """The 20-DOF test chain of the module docstring (dimensionless)."""
    mass = np.diag(np.linspace(0.8, 1.6, n))
    mass[contact, contact] = 1.0
    k = np.zeros((n, n))

    def stamp(a: int, b: int | None, value: float) -> None:
        k[a, a] += value
        if b is not None:
            k[b, b] += value
            k[a, b] -= value
            k[b, a] -= value

    for i in range(n - 1):
        stamp(i, i + 1, 1.0 + 0.3 * i)
    stamp(0, None, 1.5)
    stamp(n - 1, None, 2.0)
    stamp(0, n - 1, 0.4)
    return Structure(mass, 0.05 * mass + 0.05 * k, k, name="20-DOF chain", contact_dof=contact)


def best_time(fn, repeats: int) -> float:  # type: ignore[no-untyped-def]
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def stage_breakdown(st: Structure, slider: Slider, repeats: int) -> str:
    """Where a ``simulate`` of ``st`` spends its time, best of ``repeats`` per stage (ms).

    Stages: the contact-first twin and the start-up state (structure checks), the per-mode
    matrices, their step exponentials, the Lyapunov solve of slip-I, the whole preparation
    (``prepare_bands``, which holds the three before and the event tables), the event loop
    (``run_prepared``) and the rest of ``simulate`` (stability of steady sliding, the result).
    """
    inner, _ = st.contact_first()
    lam, gamma = float(slider.lam), float(slider.gamma)
    bands = slider.friction.bands(lam, gamma)
    z0 = startup_state(inner, slider).as_vector(inner.n_dof)
    ahat, _ = mode_matrices(inner.mass, inner.damping, inner.stiffness, lam, gamma, *bands[1:])
    m = ahat.shape[1]
    slip_i = np.ascontiguousarray(ahat[0, : m - 1, : m - 1])
    prepared = prepare_bands(inner.mass, inner.damping, inner.stiffness, lam, gamma, *bands)
    hstep = prepared[2]
    opts = EngineOptions()

    def loop() -> None:
        engine.run_prepared(inner.mass, lam, gamma, bands[0], prepared, z0, opts.t_max,
                            opts.max_events, opts.cycle_tol, opts.max_period, False, False, False, False)

    stages = {
        "structure": best_time(lambda: (st.contact_first(), startup_state(inner, slider)), repeats),
        "mode matrices": best_time(lambda: mode_matrices(inner.mass, inner.damping, inner.stiffness,
                                                         lam, gamma, *bands[1:]), repeats),
        "expm x3": best_time(lambda: [expm(ahat[k] * hstep[k]) for k in range(ahat.shape[0])],
                             repeats),
        "Lyapunov": best_time(lambda: lyapunov_solve(slip_i, np.eye(m - 1)), repeats),
        "prepare (all)": best_time(lambda: prepare_bands(inner.mass, inner.damping, inner.stiffness,
                                                         lam, gamma, *bands), repeats),
        "event loop": best_time(loop, repeats),
    }
    total = best_time(lambda: simulate(st, slider, record=False), repeats)
    stages["rest of simulate"] = max(0.0, total - stages["structure"] - stages["prepare (all)"]
                                     - stages["event loop"])
    return "  stages (ms): " + ", ".join(f"{k} {v * 1e3:.2f}" for k, v in stages.items())


def bench_simulate(repeats: int) -> None:
    st = chain_structure_20()
    for lam in (10.0, 0.3):
        slider = Slider(lam, gamma=GAMMA)
        run = simulate(st, slider)  # warm-up (numba compile) and the horizon
        e_c = np.eye(st.n_dof)[st.contact_dof]
        q0 = -GAMMA * lam * np.linalg.solve(st.stiffness, e_c)
        t_engine = best_time(lambda: simulate(st, slider, record=False), repeats)  # noqa: B023
        holder = {}

        def oracle() -> None:
            holder["r"] = oracle_simulate(st.mass, st.damping, st.stiffness, lam, GAMMA, q0, e_c,  # noqa: B023
                                          run.t_end, contact_dof=st.contact_dof, max_step=0.05)  # noqa: B023

        t_oracle = best_time(oracle, max(1, repeats // 3))
        o = holder["r"]
        m = min(o.event_times.size, run.event_times.size)
        diff = float(np.abs(o.event_times[:m] - run.event_times[:m]).max()) if m else 0.0
        print(f"20-DOF, contact on DOF 10, lambda={lam:g}: {run.verdict.value} at t_end={run.t_end:.4g} "
              f"({run.event_times.size} events, {run.n_steps} steps); engine {t_engine * 1e3:.2f} ms, "
              f"oracle {t_oracle * 1e3:.1f} ms -> ratio {t_oracle / t_engine:.0f}x; max event-time "
              f"difference over {m} events {diff:.1e}")
        print(stage_breakdown(st, slider, repeats))


def bench_reduction(n_frame: int) -> None:
    from scipy.sparse.linalg import splu

    n = n_frame + 1
    attach, slider = n_frame // 2, n_frame
    rows, cols, vals = [], [], []

    def stamp(a: int, b: int | None, value: float) -> None:
        rows.append(a), cols.append(a), vals.append(value)
        if b is not None:
            rows.extend([b, a, b]), cols.extend([b, b, a]), vals.extend([value, -value, -value])

    for i in range(n_frame - 1):
        stamp(i, i + 1, 1e8)
    for i in (0, n_frame - 1):  # the frame rests on the floor at both ends
        stamp(i, None, 2e7)
    stamp(slider, attach, 1e6)
    k = sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsc()
    mass = sp.diags(np.r_[np.full(n_frame, 5.0), 1.0]).tocsc()
    t0 = time.perf_counter()
    splu(k)
    t_lu = time.perf_counter() - t0
    t0 = time.perf_counter()
    cutoff = default_cutoff_hz(mass, k, slider, speed=0.01, load=1000.0, mu_s=0.5, mu_k=0.3)
    red = reduce_structure(mass, k, [slider], cutoff_hz=cutoff)
    t_red = time.perf_counter() - t0
    print(f"reduction of a {n}-DOF sparse model ({k.nnz} stiffness entries): {t_red:.2f} s "
          f"(baseline: one sparse LU {t_lu:.3f} s, ratio {t_red / t_lu:.0f}x); {red.summary()}")


def bench_reduction_error(rtol: float) -> None:
    """Coulomb critical belt speed of the 301-DOF frame of tests/test_structure_reduction.py,
    reduced (Craig-Bampton at the default cut-off) against full, in one run."""
    from tests.test_structure_reduction import LOAD, MU_K, MU_S, frame_with_slider

    from stickslip.analysis.critical import bisect_crossings
    from stickslip.analysis.machine_absorber import CriticalPoint
    from stickslip.analysis.verdict import Verdict
    from stickslip.model.machine import Machine

    mass, damping, stiffness, contact = frame_with_slider(FRAME_DAMPING)
    t0 = time.perf_counter()
    cutoff = default_cutoff_hz(mass, stiffness, contact, speed=0.01, load=LOAD, mu_s=MU_S, mu_k=MU_K)
    red = reduce_structure(mass, stiffness, [contact], cutoff_hz=cutoff)
    reduced = Machine(red.mass, red.project(damping), red.stiffness, 0, MU_S, MU_K, LOAD, 0.01)
    v_red = CriticalPoint.of(reduced).speed
    t_red = time.perf_counter() - t0
    full = Machine(mass.toarray(), damping.toarray(), stiffness.toarray(), contact, MU_S, MU_K, LOAD, 0.01)
    structure = full.structure()
    gamma = full.slider().gamma
    lam_red = full.with_operating_point(speed=v_red, load=LOAD).slider().lam  # full scaling

    def classify(_group: np.ndarray, lams: np.ndarray) -> np.ndarray:
        return np.array([simulate(structure, Slider(float(lam), gamma=gamma), record=False).verdict.code
                         for lam in lams], dtype=np.int8)

    t0 = time.perf_counter()
    lo, hi = 0.98 * lam_red, 1.02 * lam_red  # speeds 2 % above and below the reduced onset
    ends = classify(np.zeros(2), np.array([lo, hi]))
    if (ends[0], ends[1]) != (Verdict.STEADY_SLIDING.code, Verdict.STICK_SLIP.code):
        print(f"reduction error: full model's verdicts at lambda {lo:.6g}, {hi:.6g} are "
              f"{ends.tolist()}, no onset within 2 % of the reduced model's")
        return
    [(_, crossing)], _ = bisect_crossings(classify, [(0, lo, hi, Verdict.STEADY_SLIDING.code)], rtol)
    v_full = full.speed_for_lambda(crossing.lam)
    t_full = time.perf_counter() - t0
    print(f"reduction error (Coulomb, 301-DOF frame, frame damping {FRAME_DAMPING:g} K): critical speed "
          f"reduced {v_red:.6g} m/s ({reduced.n_dof} DOF, {t_red:.1f} s) vs full {v_full:.6g} m/s "
          f"(bisected to {rtol:g}, {t_full:.0f} s) -> relative error {v_red / v_full - 1.0:+.2e}")


def bench_operating_map(n_side: int) -> None:
    """``map --config``'s sweep (:func:`stickslip.sweep.operating_map.operating_map`) over an
    ``n_side x n_side`` speed/load grid of the 3-DOF slideway of tests/test_operating_map.py:
    serial and on every numba thread, against the former implementation measured in the same
    run (one ``simulate`` per cell in a Python loop)."""
    from tests.test_operating_map import three_dof_machine

    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.grid import Axis
    from stickslip.sweep.operating_map import operating_map

    machine = three_dof_machine()
    speeds = Axis.parse(f"log:0.005:0.5:{n_side}", "speed")
    loads = Axis.parse(f"log:20:200:{n_side}", "load")
    operating_map(machine, speeds, loads, execution=ExecutionOptions(backend="serial"))  # compile
    t0 = time.perf_counter()
    before = [simulate(p.structure(), p.slider(), record=False).verdict.value
              for v in speeds.values for w in loads.values
              for p in [machine.with_operating_point(speed=v, load=w)]]
    t_before = time.perf_counter() - t0
    times = {}
    maps = {}
    for backend in ("serial", "threads"):
        t0 = time.perf_counter()
        maps[backend] = operating_map(machine, speeds, loads,
                                      execution=ExecutionOptions(backend=backend))  # type: ignore[arg-type]
        times[backend] = time.perf_counter() - t0
    same = all(np.array_equal(getattr(maps["serial"], k), getattr(maps["threads"], k), equal_nan=True)
               for k in ("period_s", "amplitude_m", "stick_ratio")) and np.array_equal(
        maps["serial"].verdict, maps["threads"].verdict)
    agree = list(maps["serial"].verdict.reshape(-1)) == before
    print(f"map --config, 3-DOF slideway, {n_side}x{n_side} speed/load cells: per-cell simulate loop "
          f"(before) {t_before:.2f} s; serial {times['serial']:.2f} s ({t_before / times['serial']:.1f}x); "
          f"threads ({max_threads()} numba threads) {times['threads']:.2f} s "
          f"({t_before / times['threads']:.1f}x); serial == threads bit for bit: {same}; verdicts "
          f"= simulate's: {agree}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats")
    parser.add_argument("--repeats", type=int, default=None, help="repeats of each timing (>= 1)")
    args = parser.parse_args()
    repeats = args.repeats if args.repeats is not None else (2 if args.quick else 6)
    if repeats < 1:
        parser.error(f"--repeats {repeats} must be at least 1")
    bench_simulate(repeats)
    bench_operating_map(12 if args.quick else 30)
    bench_reduction(20_000)
    bench_reduction_error(5e-3 if args.quick else 1e-3)


if __name__ == "__main__":
    main()
