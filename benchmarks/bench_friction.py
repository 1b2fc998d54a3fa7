"""Benchmark: friction laws in the engine against the solve_ivp oracle, and map throughput.

Usage::

    .venv/bin/python benchmarks/bench_friction.py

Measured on the 2-core development machine on 2026-11-29 at 11:42, a slow day on the shared
machine (the oracle 3.8x slower than on 2026-11-28 11:03, when the ratios were 56x, 4x and
0.22x); ``simulate`` proves its stick-slip cycle, which visits every friction band the cycle
crosses, and bounds the run's own rounding::

    linear, delta = 0.03            engine    54.63 ms  oracle 4.36 s  speed-up  80x
    stribeck, tolerance 1e-4        engine  1035.78 ms  oracle 4.13 s  speed-up   4x
    stribeck, tolerance 1e-6        engine 14572.11 ms  oracle 4.90 s  speed-up   0x
    rigid base map 1200 cells: linear  30179 cells/s, Coulomb  40266 cells/s, ratio 1.33
    foundation map 1200 cells: linear   7843 cells/s, Coulomb   9263 cells/s, ratio 1.18

* Per run: the elastic foundation (zeta = 0.1, M = 1.5, K = 1, zeta_a = 0.5), lambda = 3,
  gamma = 2, from startup, with a linear law (delta = 0.03) and a Stribeck law
  (v_s/V = 0.3, n = 1, d_v = 0.02) at tolerances 1e-4 and 1e-6. The engine (record=False,
  mean of 20 runs, band table included) and the oracle of tests/friction_oracle.py
  (DOP853, rtol = atol = 1e-12, max_step = 0.01, exact law) on the same horizon
  ``[0, engine t_end]``.
* Map throughput: ``run_cells`` over a 60 x 20 (lambda, delta) grid with the linear law
  against the same cells with the Coulomb table (cells/s, all numba threads).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the oracle lives in tests/

from tests.friction_oracle import friction_oracle_simulate

from stickslip import Slider, elastic_foundation, rigid_base, simulate
from stickslip.kernel.batch import coulomb_tables, run_cells
from stickslip.model.friction import LinearFriction, StribeckFriction
from stickslip.model.parameters import Foundation
from stickslip.sweep.executors import band_tables


def per_run() -> None:
    st = elastic_foundation(0.1, Foundation(1.5, 1.0, 0.5))
    laws = [
        LinearFriction(0.03),
        StribeckFriction(0.3, viscous=0.02, tolerance=1e-4),
        StribeckFriction(0.3, viscous=0.02, tolerance=1e-6),
    ]
    for law in laws:
        slider = Slider(3.0, friction=law)
        r = simulate(st, slider, record=False)  # compile
        t0 = time.perf_counter()
        for _ in range(20):
            r = simulate(st, slider, record=False)
        engine_s = (time.perf_counter() - t0) / 20
        t0 = time.perf_counter()
        friction_oracle_simulate(st, slider, r.t_end)
        oracle_s = time.perf_counter() - t0
        print(f"{law.describe()[:60]:<60} verdict {r.verdict.value:<14} engine {engine_s * 1e3:7.2f} ms  "
              f"oracle {oracle_s:5.2f} s  speed-up {oracle_s / engine_s:6.0f}x")


def _tables(cells: list[tuple[float, float]]):  # type: ignore[no-untyped-def]
    """Per-cell band tables of the linear law at ``(lambda, delta)``, as the map executor builds them."""
    lams = np.array([lam for lam, _ in cells])
    return band_tables(lams, 2.0, [LinearFriction(d) for _, d in cells])


def map_throughput() -> None:
    for name, st in (("rigid base", rigid_base(0.1)),
                     ("foundation", elastic_foundation(0.1, Foundation(1.5, 1.0, 0.5)))):
        cells = [(lam, d) for lam in np.geomspace(0.1, 30.0, 60) for d in np.linspace(-0.1, 0.08, 20)]
        n = len(cells)
        lams = np.array([c[0] for c in cells])
        gammas = np.full(n, 2.0)
        index = np.zeros(n, dtype=np.int64)
        head = (st.mass[None], st.damping[None], st.stiffness[None], index, lams, gammas)
        tail = (5000.0, 100_000, 1e-9, 8)
        linear = _tables(cells)
        coulomb = coulomb_tables(lams, gammas)
        run_cells(*head, *linear, *tail)
        run_cells(*head, *coulomb, *tail)
        t0 = time.perf_counter()
        run_cells(*head, *linear, *tail)
        t_lin = time.perf_counter() - t0
        t0 = time.perf_counter()
        run_cells(*head, *coulomb, *tail)
        t_cou = time.perf_counter() - t0
        print(f"{name:<11} map {n} cells: linear {n / t_lin:8.0f} cells/s, Coulomb {n / t_cou:8.0f} cells/s, "
              f"ratio {t_lin / t_cou:.2f}")


if __name__ == "__main__":
    per_run()
    map_throughput()
