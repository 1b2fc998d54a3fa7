"""Benchmark: map throughput against the engine before friction laws, serial and threaded, and the oracle.

Usage::

    .venv/bin/python benchmarks/bench_map.py                 # 200 x 200 cells, 10 oracle cells
    .venv/bin/python benchmarks/bench_map.py --repeats 5 --oracle-cells 0
    .venv/bin/python benchmarks/bench_map.py --baseline none  # skip the old-kernel A/B

Printed, all measured in this one run:

* **A/B against the old kernel** (issue 21): the Coulomb map path of commit ``6c94c46``
  (before the friction-law generalisation) is extracted with ``git archive`` into a cache
  folder and imported in a subprocess (``PYTHONPATH``); on the same grids, the same
  structures (built once, by the current code) and the same number of numba threads, its
  ``run_cells`` and the current ``run_batch`` are timed (best of ``--repeats``), and the
  summaries are compared bit for bit. Grids: 200 x 200 linear (lambda 0.1-50) and 200 x 200
  log (lambda 0.1-100), zeta 0.005-0.4, optimal foundation, gamma = 2, default engine
  settings. The first run compiles the old kernel once (numba cache in the cache folder).
* the paper's Fig. 8b map (lambda log 0.1-50) through ``occurrence_map`` with one numba
  thread (``backend="serial"``) and with two threads, best of ``--repeats`` each after an
  untimed one-cell map on each backend (the threaded kernel is a compiled function of its
  own: its first load is not the map's cost), the speedup, and a check that both maps are
  bit-identical;
* the scipy oracle (``tests/oracle.py``: solve_ivp DOP853, rtol = atol = 1e-12,
  max_step = 0.01) on a random sample of the same cells, each over ``[0, t_end]`` of the
  engine's run of that cell (like for like: the same simulated time), against the engine
  timed on the same cells one at a time (best of 5); the ratio is oracle seconds per cell
  over engine seconds per cell.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from oracle import oracle_simulate
from stickslip.analysis.dva import resolve_dva
from stickslip.analysis.simulation import EngineOptions
from stickslip.model import startup_state
from stickslip.model.dva import DvaSpec
from stickslip.model.parameters import Slider
from stickslip.model.structure import chain_structure
from stickslip.sweep import Axis, OccurrenceMap, occurrence_map
from stickslip.sweep.execution import ExecutionOptions
from stickslip.sweep.executors import CellBatch, StructureSet, run_batch

ROOT = Path(__file__).resolve().parents[1]
BASELINE_COMMIT = "6c94c46"
#: the old kernel's map path, run in a subprocess with the old sources first on the path
OLD_RUNNER = """
import sys, time, numpy as np, numba
from stickslip.kernel.sweep import run_cells
d = np.load(sys.argv[1]); repeats = int(sys.argv[2]); numba.set_num_threads(int(sys.argv[3]))
args = lambda sel: (d["masses"], d["dampings"], d["stiffnesses"], d["index"][sel], d["lams"][sel],
                    np.full(d["lams"][sel].size, 2.0), float(d["t_max"]), int(d["max_events"]),
                    float(d["cycle_tol"]), int(d["max_period"]))
run_cells(*args(slice(0, 2)))
best = np.inf
for _ in range(repeats):
    t0 = time.perf_counter(); f, i = run_cells(*args(slice(None))); best = min(best, time.perf_counter() - t0)
np.savez(sys.argv[4], f=f, i=i, seconds=best)
"""


def _same(a: object, b: object) -> bool:
    ds_a, ds_b = a.dataset, b.dataset  # type: ignore[attr-defined]
    return all(ds_a[n].values.tobytes() == ds_b[n].values.tobytes() for n in ds_a.variables)


def baseline_sources(commit: str) -> Path:
    """The ``src`` folder of ``commit``, extracted once into a cache folder (kept for numba's cache)."""
    folder = Path(tempfile.gettempdir()) / f"stickslip-baseline-{commit}"
    if not (folder / "src" / "stickslip").is_dir():
        folder.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", commit, "src"], check=True,
                                 capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    return folder / "src"


def ab_old_kernel(label: str, lam: Axis, zeta: Axis, commit: str, threads: int, repeats: int) -> None:
    """Time the old kernel (subprocess) and the current one on the same grid; print both."""
    dva = DvaSpec("optimal")
    options = EngineOptions()
    structures = StructureSet.resolve(dva, zeta.values)
    lams = np.repeat(np.asarray(lam.values, dtype=np.float64), len(zeta))
    index = np.tile(np.arange(len(zeta), dtype=np.int64), len(lam))
    batch = CellBatch(index, lams, 2.0)
    run_batch(structures, CellBatch(index[:2], lams[:2], 2.0), options, threads)  # compile or load
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        f_new, i_new = run_batch(structures, batch, options, threads)
        best = min(best, time.perf_counter() - t0)
    with tempfile.TemporaryDirectory() as tmp:
        grid = Path(tmp) / "grid.npz"
        out = Path(tmp) / "old.npz"
        np.savez(grid, masses=structures.masses, dampings=structures.dampings,
                 stiffnesses=structures.stiffnesses, index=index, lams=lams, t_max=options.t_max,
                 max_events=options.max_events, cycle_tol=options.cycle_tol,
                 max_period=options.max_period)
        env = {**os.environ, "PYTHONPATH": str(baseline_sources(commit))}
        subprocess.run([sys.executable, "-c", OLD_RUNNER, str(grid), str(repeats), str(threads),
                        str(out)], check=True, env=env, cwd=tmp)
        old = np.load(out)
        same = bool(np.array_equal(old["f"], f_new, equal_nan=True) and np.array_equal(old["i"], i_new))
        old_rate = lams.size / float(old["seconds"])
    new_rate = lams.size / best
    print(f"{label:<34} old {commit}: {old_rate:9,.0f} cells/s   current: {new_rate:9,.0f} cells/s   "
          f"current/old {new_rate / old_rate:5.2f}x   bit-identical: {same}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-lam", type=int, default=200)
    parser.add_argument("--n-zeta", type=int, default=200)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3, help="best of this many timed runs")
    parser.add_argument("--baseline", default=BASELINE_COMMIT,
                        help="commit of the old kernel for the A/B, or 'none'")
    parser.add_argument("--oracle-cells", type=int, default=10)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    if min(args.n_lam, args.n_zeta, args.threads, args.repeats) < 1 or args.oracle_cells < 0:
        parser.error("--n-lam, --n-zeta, --threads and --repeats must be at least 1, "
                     "--oracle-cells at least 0")

    zeta_ab = Axis.parse(f"0.005:0.4:{args.n_zeta}", "zeta")
    if args.baseline != "none":
        print(f"A/B against the kernel of commit {args.baseline} (same grids, {args.threads} "
              f"thread(s), best of {args.repeats}, optimal foundation, gamma = 2):")
        for label, spec in ((f"{args.n_lam} x {args.n_zeta} linear lambda 0.1-50", "0.1:50"),
                            (f"{args.n_lam} x {args.n_zeta} log lambda 0.1-100", "log:0.1:100")):
            ab_old_kernel(label, Axis.parse(f"{spec}:{args.n_lam}", "lambda"), zeta_ab,
                          args.baseline, args.threads, args.repeats)
        print()

    lam = Axis.parse(f"log:0.1:50:{args.n_lam}", "lambda")
    zeta = Axis.parse(f"0.005:0.4:{args.n_zeta}", "zeta")
    dva = DvaSpec("optimal")
    n_cells = len(lam) * len(zeta)
    print(f"map: {len(lam)} lambda (log, 0.1-50) x {len(zeta)} zeta (0.005-0.4) = {n_cells} cells, "
          f"{dva.describe()}, gamma = 2, t_max = {EngineOptions().t_max:g}")

    serial_run = ExecutionOptions(backend="serial")
    threads_run = ExecutionOptions(backend="threads", workers=args.threads)
    t0 = time.perf_counter()
    # JIT compile or cache load of both backends' kernels (the threaded one is its own
    # compiled function: untimed, its load would count against the threads)
    for execution in (serial_run, threads_run):
        occurrence_map([1.0], [0.1], dva, execution=execution)
    print(f"warm-up (JIT compile or cache load, both backends): {time.perf_counter() - t0:.2f} s")

    def best_of(execution: ExecutionOptions) -> tuple[OccurrenceMap, float]:
        best, result = np.inf, None
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            result = occurrence_map(lam, zeta, dva, execution=execution)
            best = min(best, time.perf_counter() - t0)
        assert result is not None
        return result, best

    serial, t_serial = best_of(serial_run)
    threads, t_threads = best_of(threads_run)
    rate_serial, rate_threads = n_cells / t_serial, n_cells / t_threads
    print(f"serial  (1 thread) : {t_serial:7.2f} s  {rate_serial:9,.0f} cells/s")
    print(f"threads ({args.threads} threads): {t_threads:7.2f} s  {rate_threads:9,.0f} cells/s")
    print(f"speedup threads/serial: {rate_threads / rate_serial:.2f}x   "
          f"bit-identical: {_same(serial, threads)}")
    print(f"verdicts: {serial.counts}")

    if args.oracle_cells == 0:
        return 0
    ds = serial.dataset
    rng = np.random.default_rng(args.seed)
    cells = [(int(i), int(j)) for i, j in zip(rng.integers(0, len(lam), args.oracle_cells),
                                              rng.integers(0, len(zeta), args.oracle_cells),
                                              strict=True)]
    structures = StructureSet.resolve(dva, zeta.values)
    settings = EngineOptions()
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
