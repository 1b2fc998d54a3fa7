"""Benchmark: the Dask backend against numba threads on the same cores, 1 and 2 workers, in one run.

Usage::

    .venv/bin/python benchmarks/bench_dask.py               # 100 x 100 cells
    .venv/bin/python benchmarks/bench_dask.py --n-lam 200 --n-zeta 200

The same map as ``bench_map.py`` (optimal foundation, lambda log in [0.1, 50], zeta in
[0.005, 0.4]). For each worker count a ``LocalCluster`` of single-threaded worker processes
is started on 127.0.0.1 and warmed up (each worker loads the compiled engine from numba's
cache) before the timed map. Printed: cluster start-up time, map time and cells per second
for 1 and 2 workers, the speedup, the ratio to the in-process serial backend and to the
in-process threads backend with as many threads as workers (Dask's overhead: scheduling,
pickling, worker processes), and whether every map is bit-identical to the serial one.
"""

from __future__ import annotations

import argparse
import time

from distributed import Client, LocalCluster

from stickslip.model.dva import DvaSpec
from stickslip.sweep import Axis, occurrence_map
from stickslip.sweep.execution import ExecutionOptions


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-lam", type=int, default=100)
    parser.add_argument("--n-zeta", type=int, default=100)
    parser.add_argument("--chunk-size", type=int, default=None)
    args = parser.parse_args(argv)

    lam = Axis.parse(f"log:0.1:50:{args.n_lam}", "lambda")
    zeta = Axis.parse(f"0.005:0.4:{args.n_zeta}", "zeta")
    dva = DvaSpec("optimal")
    n_cells = len(lam) * len(zeta)
    print(f"map: {len(lam)} x {len(zeta)} = {n_cells} cells, {dva.describe()}")

    occurrence_map([1.0], [0.1], dva,
                   execution=ExecutionOptions(backend="serial"))  # JIT compile or cache load
    t0 = time.perf_counter()
    serial = occurrence_map(lam, zeta, dva,
                            execution=ExecutionOptions(backend="serial", chunk_size=args.chunk_size))
    t_serial = time.perf_counter() - t0
    print(f"serial in-process (1 thread): {t_serial:6.2f} s  {n_cells / t_serial:8,.0f} cells/s")
    occurrence_map([1.0, 2.0], [0.1, 0.2], dva,
                   execution=ExecutionOptions(backend="threads", workers=2))  # start the thread pool
    t0 = time.perf_counter()
    threads = occurrence_map(lam, zeta, dva, execution=ExecutionOptions(
        backend="threads", workers=2, chunk_size=args.chunk_size))
    t_threads = time.perf_counter() - t0
    same = all(threads.dataset[n].values.tobytes() == serial.dataset[n].values.tobytes()
               for n in serial.dataset.variables)
    print(f"threads in-process (2 threads): {t_threads:6.2f} s  {n_cells / t_threads:8,.0f} cells/s  "
          f"bit-identical to serial: {same}")

    rates = {}
    for n_workers in (1, 2):
        t0 = time.perf_counter()
        with LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                          host="127.0.0.1", dashboard_address="127.0.0.1:0") as cluster:
            with Client(cluster) as client:
                client.wait_for_workers(n_workers)
            t_start = time.perf_counter() - t0
            address = cluster.scheduler_address
            t0 = time.perf_counter()
            occurrence_map([1.0, 2.0], [0.1, 0.2], dva,
                           execution=ExecutionOptions(backend="dask", scheduler=address,
                                                      chunk_size=1))  # every worker loads the engine
            t_warm = time.perf_counter() - t0
            t0 = time.perf_counter()
            result = occurrence_map(lam, zeta, dva,
                                    execution=ExecutionOptions(backend="dask", scheduler=address,
                                                               chunk_size=args.chunk_size))
            t_map = time.perf_counter() - t0
        rates[n_workers] = n_cells / t_map
        same = all(result.dataset[n].values.tobytes() == serial.dataset[n].values.tobytes()
                   for n in serial.dataset.variables)
        print(f"dask {n_workers} worker(s): cluster start {t_start:5.2f} s, warm-up {t_warm:5.2f} s, "
              f"map {t_map:6.2f} s  {rates[n_workers]:8,.0f} cells/s  "
              f"({result.chunks_total} tasks)  bit-identical to serial: {same}")
    print(f"speedup 2 workers / 1 worker: {rates[2] / rates[1]:.2f}x")
    print(f"dask 1 worker / serial in-process: {rates[1] * t_serial / n_cells:.2f}x   "
          f"dask 2 workers / serial in-process: {rates[2] * t_serial / n_cells:.2f}x")
    print(f"dask 2 workers / threads in-process (2 threads): {rates[2] * t_threads / n_cells:.2f}x "
          "(below 1: what Dask's scheduling, pickling and worker processes cost on the same cores)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
