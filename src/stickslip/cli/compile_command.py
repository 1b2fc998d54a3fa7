"""``stickslip compile``: compile every numba kernel ahead of the first run, in parallel.

numba compiles a kernel on its first call and caches it (``cache=True``); the first run of
each command after an install waits for that, about a minute per family of kernels on this
project's 2-core machine (the simulation engine, the map kernels, the basin kernels with their
early certificates, continuation). This command runs one small case of each family in its own
process, ``--jobs`` at a time, so the families compile side by side; every later run loads
them from the cache. ``make`` runs it after installing, so neither the first command a user
types nor the test suite waits for compilation. Nothing is written but numba's cache (the
small cases run in a temporary folder that is removed).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from typing import Annotated

import typer

#: One small run per family of kernels (arguments of ``stickslip``); ``{tmp}`` is a scratch
#: folder. Ordered longest first, so that ``--jobs`` processes finish together.
WARM_UP_RUNS: tuple[tuple[str, ...], ...] = (
    ("basin", "--lam", "2", "--zeta", "0.1", "--friction", "stribeck:vs=0.2", "--samples", "1000",
     "--json"),
    ("simulate", "--lam", "2", "--zeta", "0.1", "--dva", "optimal", "--friction", "stribeck:vs=0.2",
     "--json"),
    ("map", "--lam", "1:5:3", "--zeta", "0.05:0.2:3", "--dva", "optimal", "--out", "{tmp}/map.nc",
     "--json"),
    ("basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "1000", "--json"),
    ("continue", "--param", "lam", "--range", "0.5:3", "--zeta", "0.1", "--json"),
    ("cycles", "--lam", "2", "--zeta", "0.1", "--json"),
    # the smooth stiff engine of friction with memory, its shooting (variational equations) too
    ("simulate", "--lam", "7.07", "--zeta", "0", "--friction",
     "lugre:sigma0=5e4,sigma1=223.6,sigma2=0.283,mu_c=1,mu_s=1.5,vs=0.01", "--initial-kick", "-1",
     "--t-max", "80", "--json"),
)
#: Longest a warm-up run may take, s (a cold compile takes one to three minutes).
RUN_TIMEOUT = 1800.0


def compile_kernels(jobs: int = 2) -> int:
    """Run :data:`WARM_UP_RUNS`, ``jobs`` processes at a time; return how many failed.

    Parameters
    ----------
    jobs : int
        Processes at once (one per core is the fastest: a compile is single-threaded).

    Returns
    -------
    int
        The number of runs that failed (their stderr is printed).
    """
    failed = 0
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="stickslip-compile-") as tmp:
        pending = list(WARM_UP_RUNS)
        running: list[tuple[tuple[str, ...], subprocess.Popen[str], float]] = []
        while pending or running:  # bounded: each run ends or is killed after RUN_TIMEOUT
            while pending and len(running) < jobs:
                args = tuple(a.format(tmp=tmp) for a in pending.pop(0))
                proc = subprocess.Popen([sys.executable, "-m", "stickslip.cli.main", *args], cwd=tmp,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                running.append((args, proc, time.perf_counter()))
            time.sleep(0.2)
            for item in list(running):
                args, proc, t0 = item
                if proc.poll() is None and time.perf_counter() - t0 < RUN_TIMEOUT:
                    continue
                if proc.poll() is None:
                    proc.kill()
                running.remove(item)
                err = proc.stderr.read() if proc.stderr else ""
                if proc.wait() != 0:
                    failed += 1
                    print(f"stickslip compile: `stickslip {' '.join(args)}` failed: {err.strip()}",
                          file=sys.stderr)
                else:
                    print(f"stickslip compile: {args[0]} kernels ready "
                          f"({time.perf_counter() - t0:.0f} s)", file=sys.stderr)
    print(f"stickslip compile: done in {time.perf_counter() - start:.0f} s"
          + (f", {failed} failed" if failed else ""), file=sys.stderr)
    return failed


def compile_command(
    jobs: Annotated[int, typer.Option("--jobs", min=1, max=64,
                                      help="warm-up processes at once (default: the cores, at most 4)")]
    = min(4, os.cpu_count() or 1),
) -> None:
    """Compile every numba kernel now, in parallel, so no later run waits for it.

    Runs one small case of each family of kernels (engine, maps, basins, continuation,
    cycles) in its own process, --jobs at a time; `make` runs it after installing.

    Example: stickslip compile --jobs 2
    """
    raise typer.Exit(1 if compile_kernels(jobs) else 0)


def register(app: typer.Typer) -> None:
    """Add ``compile`` to the application."""
    app.command("compile")(compile_command)
