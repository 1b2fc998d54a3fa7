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
from pathlib import Path
from typing import Annotated

import typer

#: A small machine file for the ``--config`` warm-up: three DOF in SI with the belt on the
#: middle one, so that its runs take the paths of a user's machine (the structure read from
#: the file, its contact-first twin, the operating map's cells).
WARM_UP_MACHINE = """\
mu_s = 0.5
mu_k = 0.3
load = "100 N"
speed = "1 cm/s"

[structure]
mass = [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 5.0]]
stiffness = [[3e4, -1e4, 0.0], [-1e4, 2e4, -1e4], [0.0, -1e4, 3e4]]
rayleigh = [5.0, 1e-3]
contact_dof = 1
"""

#: One small run per family of kernels: (the family's name, arguments of ``stickslip``);
#: ``{tmp}`` is a scratch folder holding ``machine.toml`` (:data:`WARM_UP_MACHINE`). Ordered
#: longest first, so that ``--jobs`` processes finish together. ``simulate`` runs a
#: stick-slip point on a foundation, so the cycle proof's kernels (N DOF) are warmed with
#: the engine's.
WARM_UP_RUNS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("friction with memory (stiff engine, shooting)",
     ("simulate", "--lam", "7.07", "--zeta", "0", "--friction",
      "lugre:sigma0=5e4,sigma1=223.6,sigma2=0.283,mu_c=1,mu_s=1.5,vs=0.01", "--initial-kick", "-1",
      "--t-max", "80", "--json")),
    ("basin (velocity-dependent friction)",
     ("basin", "--lam", "2", "--zeta", "0.1", "--friction", "stribeck:vs=0.2", "--samples", "1000",
      "--json")),
    ("simulation engine and cycle proof",
     ("simulate", "--lam", "10", "--zeta", "0.1", "--dva", "optimal", "--friction",
      "stribeck:vs=0.2", "--json")),
    ("occurrence map",
     ("map", "--lam", "1:5:3", "--zeta", "0.05:0.2:3", "--dva", "optimal", "--out", "{tmp}/map.nc",
      "--json")),
    ("machine file (--config, N DOF)",
     ("map", "--config", "{tmp}/machine.toml", "--speed", "0.005,0.05", "--load", "20,100",
      "--out", "{tmp}/vw.nc", "--json")),
    ("basin (Coulomb)", ("basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "1000", "--json")),
    # stick-slip states on a foundation: the proven balls' kernels, which ProvenBalls calls
    # from Python (simulate --config and map --config reach them too)
    ("basin (N DOF, proven cycle balls)",
     ("basin", "--lam", "10", "--zeta", "0.1", "--dva", "optimal", "--samples", "64", "--json")),
    ("continuation", ("continue", "--param", "lam", "--range", "0.5:3", "--zeta", "0.1", "--json")),
    ("cycles", ("cycles", "--lam", "2", "--zeta", "0.1", "--json")),
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
    print(f"stickslip compile: compiling {len(WARM_UP_RUNS)} families of numba kernels, {jobs} at "
          "a time (a few minutes on 2 cores, once; later runs load them from the cache)",
          file=sys.stderr, flush=True)
    with tempfile.TemporaryDirectory(prefix="stickslip-compile-") as tmp:
        Path(tmp, "machine.toml").write_text(WARM_UP_MACHINE, encoding="utf-8")
        pending = list(WARM_UP_RUNS)
        running: list[tuple[str, tuple[str, ...], subprocess.Popen[str], float]] = []
        try:
            while pending or running:  # bounded: each run ends or is killed after RUN_TIMEOUT
                while pending and len(running) < jobs:
                    family, template = pending.pop(0)
                    args = tuple(a.format(tmp=tmp) for a in template)
                    proc = subprocess.Popen([sys.executable, "-m", "stickslip.cli.main", *args],
                                            cwd=tmp, stdout=subprocess.DEVNULL,
                                            stderr=subprocess.PIPE, text=True)
                    running.append((family, args, proc, time.perf_counter()))
                time.sleep(0.2)
                for item in list(running):
                    family, args, proc, t0 = item
                    if proc.poll() is None and time.perf_counter() - t0 < RUN_TIMEOUT:
                        continue
                    if proc.poll() is None:
                        proc.kill()
                    running.remove(item)
                    err = proc.stderr.read() if proc.stderr else ""
                    if proc.wait() != 0:
                        failed += 1
                        print(f"stickslip compile: {family}: `stickslip {' '.join(args)}` failed: "
                              f"{err.strip()}", file=sys.stderr, flush=True)
                    else:
                        print(f"stickslip compile: {family} kernels ready "
                              f"({time.perf_counter() - t0:.0f} s)", file=sys.stderr, flush=True)
        finally:  # Ctrl-C or an error here: no warm-up process is left running
            end_processes([proc for _, _, proc, _ in running])
    print(f"stickslip compile: done in {time.perf_counter() - start:.0f} s"
          + (f", {failed} failed" if failed else ""), file=sys.stderr)
    return failed


#: Seconds a warm-up process gets to stop after SIGTERM before it is killed.
STOP_TIMEOUT = 5.0


def end_processes(processes: list[subprocess.Popen[str]]) -> None:
    """Stop ``processes`` (SIGTERM, then SIGKILL after :data:`STOP_TIMEOUT`) and reap them.

    A warm-up interrupted in the middle of a compile loses only that compile: numba writes a
    cache entry only once it is complete.
    """
    for proc in processes:
        if proc.poll() is None:
            proc.terminate()
    deadline = time.monotonic() + STOP_TIMEOUT
    for proc in processes:
        try:
            proc.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        if proc.stderr is not None:
            proc.stderr.close()


def compile_command(
    jobs: Annotated[int, typer.Option("--jobs", min=1, max=64,
                                      help="warm-up processes at once (default: the cores, at most 4)")]
    = min(4, os.cpu_count() or 1),
) -> None:
    """Compile every numba kernel now, in parallel, so no later run waits for it.

    Runs one small case of each family of kernels (engine and cycle proof, maps, a machine
    file's runs, basins, continuation, cycles) in its own process, --jobs at a time; `make`
    runs it after installing.

    Example: stickslip compile --jobs 2
    """
    raise typer.Exit(1 if compile_kernels(jobs) else 0)


def register(app: typer.Typer) -> None:
    """Add ``compile`` to the application."""
    app.command("compile")(compile_command)
