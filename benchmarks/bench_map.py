"""Benchmark: throughput of an occurrence map, serial and threaded, against the scipy oracle.

Usage::

    .venv/bin/python benchmarks/bench_map.py                 # 200 x 200 cells, 10 oracle cells
    .venv/bin/python benchmarks/bench_map.py --n-lam 300 --n-zeta 300 --oracle-cells 20

The map is the paper's Fig. 8b setting: the 2DOF system on the fitted optimal foundation
(Eqs. 28-30 at each zeta), gamma = 2, startup state, lambda log-spaced in [0.1, 50] and zeta
linear in [0.005, 0.4], default engine settings (t_max = 5000). Every cell runs until its
verdict is certified (or t_max).

Printed, all measured in this one run:

* cells per second with one numba thread (``backend="serial"``) and with two threads
  (``backend="threads"``), the speedup, and a check that both maps are bit-identical;
* the scipy oracle (``tests/oracle.py``: solve_ivp DOP853, rtol = atol = 1e-12,
  max_step = 0.01) on a random sample of the same cells, each over ``[0, t_end]`` of the
  engine's run of that cell (like for like: the same simulated time), against the engine
  timed on the same cells one at a time (best of 5); the ratio is oracle seconds per cell
  over engine seconds per cell.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from oracle import oracle_simulate
from stickslip.analysis.dva import resolve_dva
from stickslip.model import startup_state
from stickslip.model.dva import DvaSpec
from stickslip.model.parameters import Slider
from stickslip.model.structure import chain_structure
from stickslip.sweep import Axis, occurrence_map
from stickslip.sweep.execution import ExecutionOptions
from stickslip.sweep.executors import CellBatch, EngineSettings, StructureSet, run_batch


def _same(a: object, b: object) -> bool:
    ds_a, ds_b = a.dataset, b.dataset  # type: ignore[attr-defined]
    return all(ds_a[n].values.tobytes() == ds_b[n].values.tobytes() for n in ds_a.variables)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-lam", type=int, default=200)
    parser.add_argument("--n-zeta", type=int, default=200)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--oracle-cells", type=int, default=10)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)

    lam = Axis.parse(f"log:0.1:50:{args.n_lam}", "lambda")
    zeta = Axis.parse(f"0.005:0.4:{args.n_zeta}", "zeta")
    dva = DvaSpec("optimal")
    n_cells = len(lam) * len(zeta)
    print(f"map: {len(lam)} lambda (log, 0.1-50) x {len(zeta)} zeta (0.005-0.4) = {n_cells} cells, "
          f"{dva.describe()}, gamma = 2, t_max = {EngineSettings().t_max:g}")

    t0 = time.perf_counter()
    occurrence_map([1.0], [0.1], dva,
                   execution=ExecutionOptions(backend="serial"))  # JIT compile or cache load
    print(f"warm-up (JIT compile or cache load): {time.perf_counter() - t0:.2f} s")

    t0 = time.perf_counter()
    serial = occurrence_map(lam, zeta, dva, execution=ExecutionOptions(backend="serial"))
    t_serial = time.perf_counter() - t0
    t0 = time.perf_counter()
    threads = occurrence_map(lam, zeta, dva,
                             execution=ExecutionOptions(backend="threads", workers=args.threads))
    t_threads = time.perf_counter() - t0
    rate_serial, rate_threads = n_cells / t_serial, n_cells / t_threads
    print(f"serial  (1 thread) : {t_serial:7.2f} s  {rate_serial:9,.0f} cells/s")
    print(f"threads ({args.threads} threads): {t_threads:7.2f} s  {rate_threads:9,.0f} cells/s")
    print(f"speedup threads/serial: {rate_threads / rate_serial:.2f}x   "
          f"bit-identical: {_same(serial, threads)}")
    print(f"verdicts: {serial.counts}")

    ds = serial.dataset
    rng = np.random.default_rng(args.seed)
    cells = [(int(i), int(j)) for i, j in zip(rng.integers(0, len(lam), args.oracle_cells),
                                              rng.integers(0, len(zeta), args.oracle_cells),
                                              strict=True)]
    structures = StructureSet.resolve(dva, zeta.values)
    settings = EngineSettings()
    engine_s, oracle_s = [], []
    print(f"\noracle sample ({len(cells)} random cells of the same map; horizon = engine t_end):")
    print(f"{'lambda':>9} {'zeta':>7} {'verdict':>15} {'t_end':>9} {'engine s':>10} {'oracle s':>10} "
          f"{'ratio':>9}")
    for i, j in cells:
        lam_i, zeta_j = float(lam.values[i]), float(zeta.values[j])
        batch = CellBatch(np.array([j], dtype=np.int64), np.array([lam_i]), 2.0)
        times = []
        for _ in range(5):
            t0 = time.perf_counter()
            run_batch(structures, batch, settings, 1)
            times.append(time.perf_counter() - t0)
        t_end = float(ds["t_end"][i, j])
        structure = chain_structure(zeta_j, (resolve_dva(dva, zeta_j),))  # type: ignore[arg-type]
        start = startup_state(structure, Slider(lam_i, gamma=2.0))
        t0 = time.perf_counter()
        oracle_simulate(structure.mass, structure.damping, structure.stiffness, lam_i, 2.0,
                        start.position, start.velocity, t_end, max_step=0.01)
        t_oracle = time.perf_counter() - t0
        engine_s.append(min(times))
        oracle_s.append(t_oracle)
        verdict = ("steady-sliding", "stick-slip", "undetermined")[int(ds["verdict"][i, j])]
        print(f"{lam_i:9.4g} {zeta_j:7.4g} {verdict:>15} {t_end:9.4g} {min(times):10.2e} "
              f"{t_oracle:10.3f} {t_oracle / min(times):9,.0f}")
    mean_engine, mean_oracle = float(np.mean(engine_s)), float(np.mean(oracle_s))
    print(f"\nmean per cell on the sample: engine {mean_engine:.2e} s, oracle {mean_oracle:.3f} s, "
          f"ratio oracle/engine {mean_oracle / mean_engine:,.0f}")
    print(f"oracle s/cell (sample) over engine s/cell in the serial map ({1 / rate_serial:.2e} s): "
          f"{mean_oracle * rate_serial:,.0f}")
    print(f"oracle s/cell (sample) over engine s/cell in the threaded map ({1 / rate_threads:.2e} s): "
          f"{mean_oracle * rate_threads:,.0f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
