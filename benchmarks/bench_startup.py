"""Start-up time of the command line, next to the interpreter's own start in the same run.

Issue 9 asks for ``stickslip --help`` under 0.3 s and a warm ``stickslip simulate --json``
under 1 s. A warm run still pays numba's one-off cost of loading its compiled cache and
registering its typing (about 0.5 s on this project's 2-core machine), so the benchmark also
times a trivial cached numba function: that is the floor any numba-backed command starts
from. Each command runs ``--repeat`` times after one warm-up; the median wall time is shown.

    python benchmarks/bench_startup.py [--repeat 5] [--cold]

With ``--cold`` the benchmark first deletes numba's cache files of the imported package (what
``make clean-cache`` does) and times the first ``stickslip simulate --json`` (issue 21 asks
for under 60 s), with the notice it prints on stderr; the warm rows follow.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

NUMBA_FLOOR = """
from numba import njit
import numpy as np

@njit(cache=True)
def total(a):
    return a.sum()

total(np.ones(3))
"""


def wall(cmd: list[str], repeat: int) -> float:
    """Median wall-clock seconds of ``cmd`` over ``repeat`` runs, after one warm-up run."""
    subprocess.run(cmd, check=True, capture_output=True)
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def cold_run(exe: str) -> tuple[float, str]:
    """Delete numba's cache of the package, then time one ``simulate --json``; (s, stderr)."""
    import stickslip

    package = Path(stickslip.__file__).parent
    for pattern in ("*.nbi", "*.nbc"):
        for path in package.rglob(pattern):
            path.unlink()
    start = time.perf_counter()
    done = subprocess.run([exe, "simulate", "--lam", "3", "--zeta", "0.1", "--json"], check=True,
                          capture_output=True, text=True)
    return time.perf_counter() - start, done.stderr.strip()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--cold", action="store_true", help="first time the run after clearing the cache")
    args = parser.parse_args()
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")
    python = sys.executable
    exe = shutil.which("stickslip", path=str(Path(python).parent)) or "stickslip"
    if args.cold:
        seconds, notice = cold_run(exe)
        print(f"{'stickslip simulate --json (cold cache)':<40} {seconds:>9.3f}            "
              f"< 60 s {'ok' if seconds < 60 else 'MISSED'}")
        print(f"  its stderr: {notice or '(nothing)'}")
    with tempfile.TemporaryDirectory() as tmp:
        floor_script = Path(tmp) / "numba_floor.py"
        floor_script.write_text(NUMBA_FLOOR)
        rows = [
            ("python -c pass", [python, "-c", "pass"], None),
            ("python: import numba, one cached call", [python, str(floor_script)], None),
            ("stickslip --help", [exe, "--help"], 0.3),
            ("stickslip --version", [exe, "--version"], 0.3),
            ("stickslip simulate --json (warm)",
             [exe, "simulate", "--lam", "3", "--zeta", "0.1", "--json"], 1.0),
            ("stickslip map 1 cell --json (warm)",
             [exe, "map", "--lam", "3", "--zeta", "0.1", "--out", str(Path(tmp) / "m.nc"),
              "--overwrite", "--json"], None),
        ]
        base = None
        print(f"{'command':<40} {'median s':>9} {'x python':>9}  target")
        for label, cmd, target in rows:
            seconds = wall(cmd, args.repeat)
            base = base or seconds
            verdict = ""
            if target is not None:
                verdict = f"< {target:g} s " + ("ok" if seconds < target else "MISSED")
            print(f"{label:<40} {seconds:>9.3f} {seconds / base:>9.1f}  {verdict}")


if __name__ == "__main__":
    main()
