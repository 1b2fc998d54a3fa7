"""Start-up time of the command line, next to the interpreter's and numba's own start in the same run.

Issue 21 asks for ``stickslip --help`` under 0.3 s and a warm ``stickslip simulate --json``
under 1 s. A warm run still pays numba's one-off cost of importing itself and registering its
typing and lowering (which imports ``scipy.linalg`` for BLAS), then loading each kernel the
command calls from the cache. The benchmark therefore also times, as floors any command
stands on: ``import numba``; a trivial cached numba function (``import numba`` + one cached
call: numba's floor for any numba-backed command); ``import scipy.linalg`` after numpy (numba's
first dispatch loads its target registries, and ``numba.np.arraymath`` imports
``scipy.linalg.cython_blas`` to check for BLAS: part of the floor, printed in the closing line;
``python -X importtime -c "import numpy, scipy.linalg"`` shows what it imports, ``numpy.f2py``
among it, which scipy's vendored ``array_api_compat`` pulls in by listing numpy's attributes);
typer parsing a command of five options.
Each command runs ``--repeat`` times after one warm-up; the median and the best wall time are
shown, and the best CPU time (user + system), which on a loaded machine says what the command
itself costs (on a quiet one it is close to the wall time: the start-up and numba's compiler
run in one thread).

    python benchmarks/bench_startup.py [--repeat 5] [--cold [simulate,map,basin]]

It times the ``stickslip`` next to the Python that runs it. The project's ``.venv`` holds the
test extra, whose ``twine`` brings ``cffi`` (through keyring, SecretStorage and cryptography);
numba imports ``cffi`` at its first dispatch when it is installed, about 0.08 s of its floor.
A user's plain install has no ``cffi``; to time that, run the benchmark with the Python of
one (``python -m venv /tmp/plain && /tmp/plain/bin/pip install . &&
/tmp/plain/bin/python benchmarks/bench_startup.py``). The first line says which it is.

With ``--cold`` it first times ``stickslip simulate --json`` against an empty numba cache (a
fresh ``NUMBA_CACHE_DIR``, so the package's own cache is left alone), as the first run after
an install (issue 21 asks for under 60 s), prints what the command said on stderr and counts
the kernels it compiled: compiled functions (numba's ``*.nbi`` index files), their
signatures (``*.nbc``), by kernel module. A ``simulate`` must compile none of the map's
(``batch``) or the basin's (``certificate``) kernels. ``--cold simulate,map,basin`` times a
one-cell ``map`` and a Stribeck ``basin`` the same way, each with its own empty cache.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

NUMBA_FLOOR = """
from numba import njit
import numpy as np

@njit(cache=True)
def total(a):
    return a.sum()

total(np.ones(3))
"""

#: typer parsing one command line of five options (typer >= 0.25 converts each through a
#: pydantic TypeAdapter, 0.1-0.2 s more; pyproject.toml holds typer below 0.25)
TYPER_FLOOR = """
import typer
from typer.main import get_command

app = typer.Typer()


@app.command()
def main(a: float = 0.0, b: float = 0.0, c: str = "", d: int = 0, e: bool = False) -> None:
    pass


get_command(app)(["--a", "1", "--b", "2", "--c", "x", "--d", "3", "--e"], standalone_mode=False)
"""

SIMULATE = ["simulate", "--lam", "3", "--zeta", "0.1", "--json"]


def child_cpu() -> float:
    """CPU seconds (user + system) used so far by the finished child processes."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def wall(cmd: list[str], repeat: int) -> tuple[float, float, float]:
    """Median and best wall-clock seconds and best CPU seconds of ``cmd`` over ``repeat`` runs.

    After one warm-up run. The CPU time (user + system) is nearly the wall time of a quiet
    machine: on a loaded one it says what the command itself costs.
    """
    subprocess.run(cmd, check=True, capture_output=True)
    times, cpus = [], []
    for _ in range(repeat):
        start, cpu = time.perf_counter(), child_cpu()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
        cpus.append(child_cpu() - cpu)
    return statistics.median(times), min(times), min(cpus)


#: The other commands ``--cold`` can time (``--cold simulate,map,basin``): a one-cell map, and a
#: basin under a Stribeck law (its early certificates compile the most kernels).
COLD_COMMANDS = {
    "simulate": SIMULATE,
    "map": ["map", "--lam", "3", "--zeta", "0.1", "--out", "{tmp}/m.nc", "--json"],
    "basin": ["basin", "--lam", "2", "--zeta", "0.1", "--friction", "stribeck:vs=0.2",
              "--samples", "1000", "--json"],
}


def cold_run(exe: str, argv: list[str]) -> tuple[float, float, str, Counter[str], int]:
    """One command with an empty numba cache (a fresh ``NUMBA_CACHE_DIR``).

    Returns wall and CPU seconds, its stderr, the compiled functions by kernel module and the
    number of compiled signatures.
    """
    with tempfile.TemporaryDirectory(prefix="stickslip-cold-cache-") as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        cmd = [exe, *(a.format(tmp=cache) for a in argv)]
        start, cpu = time.perf_counter(), child_cpu()
        done = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env)
        seconds, cpu = time.perf_counter() - start, child_cpu() - cpu
        # numba names its files <module>.<function>-<line>.py<version>[.<n>.nbc|.nbi]
        indexes = list(Path(cache).rglob("*.nbi"))
        functions = Counter(path.name.split(".")[0] for path in indexes)
        signatures = len(list(Path(cache).rglob("*.nbc")))
    return seconds, cpu, done.stderr.strip(), functions, signatures


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--cold", nargs="?", const="simulate", default="",
                        help="first time these commands (comma-separated, of "
                             f"{','.join(COLD_COMMANDS)}; default simulate) each with an empty "
                             "numba cache, count the kernels they compile")
    args = parser.parse_args()
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")
    python = sys.executable
    exe = shutil.which("stickslip", path=str(Path(python).parent)) or "stickslip"
    print(f"PYTHONDONTWRITEBYTECODE={os.environ.get('PYTHONDONTWRITEBYTECODE', '')!r} "
          "(when set, Python compiles every stickslip module from source at each start)")
    has_cffi = subprocess.run([python, "-c", "import importlib.util as u; "
                               "raise SystemExit(u.find_spec('cffi') is None)"]).returncode == 0
    print(f"{python}: cffi {'installed (numba imports it: part of its floor)' if has_cffi else 'absent'}")
    cold = [c for c in args.cold.split(",") if c]
    if set(cold) - set(COLD_COMMANDS):
        parser.error(f"--cold takes {', '.join(COLD_COMMANDS)}, not {args.cold!r}")
    for command in cold:
        seconds, cpu, notice, functions, signatures = cold_run(exe, COLD_COMMANDS[command])
        target = f"< 60 s {'ok' if seconds < 60 else 'MISSED'}" if command == "simulate" else ""
        print(f"{f'stickslip {command} (cold cache)':<42} {seconds:>9.3f} {'':>8} {cpu:>8.3f}"
              f"{'':>10}{target}")
        print(f"  kernels compiled: {sum(functions.values())} functions, {signatures} signatures; "
              + ", ".join(f"{module} {n}" for module, n in sorted(functions.items())))
        if command == "simulate":
            unneeded = sorted(set(functions) & {"batch", "certificate"})
            print(f"  map/basin kernels compiled: {', '.join(unneeded) if unneeded else 'none'}")
        for line in notice.splitlines() or ["(nothing)"]:
            print(f"  its stderr: {line}")
    with tempfile.TemporaryDirectory() as tmp:
        floor_script = Path(tmp) / "numba_floor.py"
        floor_script.write_text(NUMBA_FLOOR)
        typer_script = Path(tmp) / "typer_floor.py"
        typer_script.write_text(TYPER_FLOOR)
        rows = [
            ("python -c pass", [python, "-c", "pass"], None),
            ("python: import numba", [python, "-c", "import numba"], None),
            ("python: import numba, one cached call", [python, str(floor_script)], None),
            ("python: import numpy", [python, "-c", "import numpy"], None),
            ("python: import numpy, scipy.linalg", [python, "-c", "import numpy, scipy.linalg"],
             None),
            ("python: typer parses one command", [python, str(typer_script)], None),
            ("stickslip --help", [exe, "--help"], 0.3),
            ("stickslip --version", [exe, "--version"], 0.3),
            ("stickslip simulate --json (warm)", [exe, *SIMULATE], 1.0),
            ("stickslip map 1 cell --json (warm)",
             [exe, "map", "--lam", "3", "--zeta", "0.1", "--out", str(Path(tmp) / "m.nc"),
              "--overwrite", "--json"], None),
        ]
        base = None
        medians: dict[str, float] = {}
        cpus: dict[str, float] = {}
        print(f"{'command':<42} {'median s':>9} {'best s':>8} {'cpu s':>8} {'x python':>9}  target")
        for label, cmd, target in rows:
            median, best, cpu = wall(cmd, args.repeat)
            medians[label], cpus[label] = median, cpu
            base = base or median
            verdict = ""
            if target is not None:
                verdict = f"< {target:g} s " + ("ok" if median < target else "MISSED")
            print(f"{label:<42} {median:>9.3f} {best:>8.3f} {cpu:>8.3f} {median / base:>9.1f}  {verdict}")
        floor, sim = "python: import numba, one cached call", "stickslip simulate --json (warm)"
        typer_cpu = cpus["python: typer parses one command"] - cpus["python -c pass"]
        print(f"warm simulate above numba's floor: {medians[sim] - medians[floor]:.3f} s wall (median), "
              f"{cpus[sim] - cpus[floor]:.3f} s CPU (best), of which typer {typer_cpu:.3f} s CPU")
        bare = medians["python -c pass"]
        dispatch = medians[floor] - medians["python: import numba"]
        scipy_linalg = medians["python: import numpy, scipy.linalg"] - medians["python: import numpy"]
        print(f"numba's floor {medians[floor]:.3f} s: import numba "
              f"{medians['python: import numba'] - bare:.3f} s, first cached call {dispatch:.3f} s "
              f"(its target registries import scipy.linalg for BLAS: {scipy_linalg:.3f} s after numpy)"
              + ("; the floor alone is above the 1 s goal on this machine now"
                 if medians[floor] >= 1.0 else ""))


if __name__ == "__main__":
    main()
