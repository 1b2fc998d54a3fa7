"""Benchmark: ``stickslip identify`` on a long record, 1e6 rows by default (issue 32 item 3).

Usage::

    .venv/bin/python benchmarks/bench_identify_long.py              # 1e6 rows, ~2 minutes
    .venv/bin/python benchmarks/bench_identify_long.py --rows 100000

The record: the rig of ``tests/make_identify_example.py`` (1 kg, k = 10 kN/m, c = 5 N s/m,
mu_s = 0.6, Coulomb mu_k = 0.4, W = 100 N, V = 5 cm/s; period 0.112 s) simulated by the
independent solve_ivp rig simulator of ``tests/record_oracle.py``, sampled at 10 kHz for
``rows`` samples (1e6 rows: 100 s, about 890 periods; :func:`make_record`), force and
displacement with 0.5 % noise, written as CSV. The command runs as a subprocess, as a user
runs it; printed: its wall time and peak resident memory (``ru_maxrss`` of the child), the
window the fit used (:func:`stickslip.analysis.identification.record_fit.fit_window`: at most 30 periods
and 20,000 samples) and the fitted values beside the truth. Measured on 2 shared cores
(2026-11-25): 1e5 rows 14.5 s and 377 MiB; 1e6 rows 34.3 s and 880 MiB, k 9999.77 +/- 1.3
N/m, mu_s 0.600005, mu_k 0.399989 (truth 10000, 0.6, 0.4). Goal (issue 32): 1e6 rows in under 60 s and 2 GB.
Before the window, a 1e5-row record took 272 s and 4.9 GB, and 1e6 rows died allocating a
64 GiB Jacobian.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

TRUTH = {"k": 1.0e4, "c": 5.0, "mu_s": 0.6, "mu_k": 0.4}


def make_record(path: Path, rows: int, fs: float, seed: int) -> None:
    """The rig record (CSV: t [s], x [mm], F [N]) of ``rows`` samples at ``fs`` Hz.

    A Coulomb rig repeats itself exactly from its second breakaway on (each breakaway starts
    from the same state: ``k x + c V = mu_s W``, ``x' = V``), so the oracle is run once through
    two periods at 1 MHz and the record sampled from it periodically (linear interpolation
    between 1 us samples: an error below 1e-9 of the signal, far below the 0.5 % noise).
    """
    from tests.record_oracle import coulomb, noisy, simulate_rig

    rig = simulate_rig(m=1.0, k=TRUTH["k"], c=TRUTH["c"], mu_s=TRUTH["mu_s"], mu=coulomb(TRUTH["mu_k"]),
                       load=100.0, speed=0.05, t_end=0.5, fs=1e6, t_start=0.0)
    first, period = float(rig.breakaways[1]), float(rig.breakaways[2] - rig.breakaways[1])
    t = 0.23 + np.arange(rows) / fs
    phase = np.where(t < first, t, first + np.mod(t - first, period))
    rng = np.random.default_rng(seed)
    x = noisy(np.interp(phase, rig.t, rig.x), 0.005, rng)
    force = noisy(np.interp(phase, rig.t, rig.F), 0.005, rng)
    np.savetxt(path, np.column_stack([t - t[0], 1e3 * x, force]), delimiter=",",
               header="t [s],x [mm],F [N]", comments="", fmt="%.9g")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--fs", type=float, default=10_000.0, help="sampling rate, Hz")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        record = Path(folder) / "long.csv"
        tic = time.perf_counter()
        make_record(record, args.rows, args.fs, args.seed)
        print(f"record: {args.rows} rows at {args.fs:g} Hz, {record.stat().st_size / 1e6:.1f} MB "
              f"(made in {time.perf_counter() - tic:.0f} s)")
        command = [str(ROOT / ".venv" / "bin" / "stickslip"), "identify", str(record), "--mass", "1 kg",
                   "--load", "100 N", "--speed", "5 cm/s", "--json"]
        tic = time.perf_counter()
        done = subprocess.run(command, capture_output=True, text=True, check=False)
        wall = time.perf_counter() - tic
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024  # KiB -> MiB (Linux)
    print(f"identify: exit {done.returncode}, {wall:.1f} s wall, peak resident memory {peak:.0f} MiB "
          f"(goal: 60 s, 2048 MiB)")
    if done.returncode != 0:
        print(done.stderr.strip())
        return
    report = json.loads(done.stdout)
    print(f"window: {report['window']}")
    print(f"reduced chi-square {report['reduced_chi2']:.4g}, warnings {report['warnings']}")
    for name, truth in TRUTH.items():
        p = report["parameters"][name]
        print(f"  {name:<5} {p['value']:.6g} +/- {p['stderr']:.2g}   truth {truth:g}")


if __name__ == "__main__":
    main()
