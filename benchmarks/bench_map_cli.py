"""Benchmark: the ``stickslip map`` command end to end, against the command of commit 6c94c46.

Usage::

    .venv/bin/python benchmarks/bench_map_cli.py                 # 1000 x 1000 cells (issue 21)
    .venv/bin/python benchmarks/bench_map_cli.py --quick         # 200 x 200, for a quick look
    .venv/bin/python benchmarks/bench_map_cli.py --repeats 3 --baseline none

What is timed (issue 21, point 1): the whole command, as a user runs it, in a fresh process,
``stickslip map --lam log:0.1:50:N --zeta 0.005:0.4:N --dva optimal --out FILE.nc`` (the
paper's Fig. 8b axes, the optimal foundation, gamma = 2, default horizon, the default
``threads`` backend on ``--workers`` threads): start-up, the numba cache load, the cells,
the resume store, the netCDF file. Target: a 10^6-cell map in under 30 s on 2 cores.

Printed, all measured in this one run, best of ``--repeats`` (warm numba caches: one small
untimed map first):

* wall seconds of the process, cells per second, and the seconds the command itself reports
  for the cells (its ``computed ... in`` line);
* CPU seconds of the process (user + system, all threads), and that over the number of
  threads: the wall time the run would take on that many otherwise idle cores. On a shared
  machine (other jobs on the same cores) wall time is inflated, CPU time much less; the load
  average before and after is printed with every row;
* the same command from the sources of ``--baseline`` (default 6c94c46, the code before the
  friction-law generalisation; extracted with ``git archive`` into a cache folder, its numba
  cache kept there), on the same grid, the same threads, and whether both netCDF files hold
  the same verdicts, periods and amplitudes bit for bit.
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BASELINE_COMMIT = "6c94c46"
#: the console script's entry point, run in a fresh interpreter
sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_map import baseline_sources  # one home for the git-archive baseline  # noqa: E402

RUN_CLI = "import sys; from stickslip.cli.main import run; sys.argv[0] = 'stickslip'; run()"
#: variables compared between the current and the baseline map (bit for bit)
COMPARED = ("verdict", "n_stick", "period", "amplitude", "stick_ratio", "t_end")


def map_arguments(n_lam: int, n_zeta: int, lam: str, zeta: str, workers: int, out: Path) -> list[str]:
    """The command line of the timed map (without the program name)."""
    return ["map", "--lam", f"{lam}:{n_lam}", "--zeta", f"{zeta}:{n_zeta}", "--dva", "optimal",
            "--workers", str(workers), "--out", str(out)]


def run_cli(arguments: list[str], src: Path) -> tuple[float, float, str]:
    """Run the command in a fresh interpreter with ``src`` first on the path.

    Returns wall seconds, CPU seconds (user + system of the process and its threads) and stdout.
    """
    env = {**os.environ, "PYTHONPATH": str(src)}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", RUN_CLI, *arguments], env=env, capture_output=True,
                          text=True, check=False)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"stickslip {' '.join(arguments)} failed ({done.returncode}):\n{done.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, done.stdout


def reported_seconds(stdout: str) -> float:
    """The seconds of the command's own ``computed ... in X s`` line (NaN if absent)."""
    found = re.search(r"computed .* in ([0-9.]+) s", stdout)
    return float(found.group(1)) if found else float("nan")


def same_maps(a: Path, b: Path) -> bool:
    """Both netCDF files hold the same values of :data:`COMPARED`, bit for bit."""
    import xarray as xr

    with xr.open_dataset(a, engine="h5netcdf") as da, xr.open_dataset(b, engine="h5netcdf") as db:
        return all(da[n].values.tobytes() == db[n].values.tobytes() for n in COMPARED)


def timed(label: str, arguments: list[str], src: Path, out: Path, n_cells: int, workers: int,
          repeats: int) -> None:
    """Best of ``repeats`` runs of the command (each to a fresh output file); one printed row."""
    best: tuple[float, float, float] | None = None
    load = os.getloadavg()[0]
    for _ in range(repeats):
        out.unlink(missing_ok=True)
        wall, cpu, stdout = run_cli(arguments, src)
        if best is None or wall < best[0]:
            best = (wall, cpu, reported_seconds(stdout))
    assert best is not None
    wall, cpu, cells_s = best
    print(f"{label:<22} wall {wall:7.2f} s {n_cells / wall:9,.0f} cells/s   cells {cells_s:7.2f} s   "
          f"cpu {cpu:7.2f} s (cpu/{workers} {cpu / workers:6.2f} s)   "
          f"load {load:4.1f} -> {os.getloadavg()[0]:4.1f}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-lam", type=int, default=1000)
    parser.add_argument("--n-zeta", type=int, default=1000)
    parser.add_argument("--quick", action="store_true", help="200 x 200 cells")
    parser.add_argument("--lam", default="log:0.1:50", help="lambda range, without the count")
    parser.add_argument("--zeta", default="0.005:0.4", help="zeta range, without the count")
    parser.add_argument("--workers", type=int, default=2, help="numba threads of the command")
    parser.add_argument("--repeats", type=int, default=1, help="best of this many timed runs")
    parser.add_argument("--baseline", default=BASELINE_COMMIT,
                        help="commit of the old command for the A/B, or 'none'")
    args = parser.parse_args(argv)
    if args.quick:
        args.n_lam = args.n_zeta = 200
    if min(args.n_lam, args.n_zeta, args.workers, args.repeats) < 1:
        parser.error("--n-lam, --n-zeta, --workers and --repeats must be at least 1")

    n_cells = args.n_lam * args.n_zeta
    current = ROOT / "src"
    sources = [("current", current)]
    if args.baseline != "none":
        sources.append((f"old {args.baseline}", baseline_sources(args.baseline)))
    with tempfile.TemporaryDirectory() as tmp:
        outputs: dict[str, Path] = {}
        for label, src in sources:  # warm-up: compile or load the numba caches, untimed
            warm = Path(tmp) / f"warm-{len(outputs)}.nc"
            run_cli(map_arguments(4, 4, args.lam, args.zeta, args.workers, warm), src)
            outputs[label] = Path(tmp) / f"map-{len(outputs)}.nc"
        print(f"stickslip map --lam {args.lam}:{args.n_lam} --zeta {args.zeta}:{args.n_zeta} "
              f"--dva optimal --workers {args.workers}: {n_cells:,} cells, end to end, "
              f"best of {args.repeats} ({os.cpu_count()} cores on this machine)")
        for label, src in sources:
            out = outputs[label]
            timed(label, map_arguments(args.n_lam, args.n_zeta, args.lam, args.zeta, args.workers,
                                       out), src, out, n_cells, args.workers, args.repeats)
        if len(outputs) == 2:
            a, b = outputs.values()
            print(f"bit-identical ({', '.join(COMPARED)}): {same_maps(a, b)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
