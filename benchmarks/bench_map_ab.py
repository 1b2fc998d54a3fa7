"""Benchmark: the paper's map (or a basin), this tree against another commit's, in one run (A/B).

    .venv/bin/python benchmarks/bench_map_ab.py --commit fb2436e [--n 200] [--repeats 3]
    .venv/bin/python benchmarks/bench_map_ab.py --commit f1d5108 --case basin [--n 20000]

The other commit's ``src`` is extracted with ``git archive`` into a cache folder (its numba
cache kept there) and imported in a subprocess; both build the paper's Fig. 8b map (lambda
log 0.1-50 x zeta 0.005-0.4, ``--n`` x ``--n`` cells, the optimal foundation of Eqs. (28)-(30),
gamma = 2) with ``stickslip.occurrence_map`` on two numba threads, best of ``--repeats`` after
an untimed warm-up map in each of ``--rounds`` processes per side (interleaved: old, new, new,
old, ...), and the verdict, stick count, period, amplitude and stick ratio
arrays are compared bit for bit. ``bench_map.py`` holds the A/B against the kernel from before
the friction laws (its runner calls that commit's internal kernel); this one uses the public
API, so any commit since then is a baseline.

``--case basin``: bench_basin.py's "foundation weak" basin (``--n`` states, default 20,000,
seed 1) with ``stickslip.basin_stability`` on all numba threads, in the same interleaved
rounds; the labels are compared (samples/s and this/old printed).

``--case cea``: the critical friction coefficient with and without damping
(``critical_friction``) of a random damped ``--n``-DOF machine with a normal DOF (default 4,
seed 3), analyses/s and this/old; the values are printed for both sides (the exact search may
differ from a scan's bisection in the last digits).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

MAP_RUNNER = r"""
import sys, time, numpy as np
from stickslip import occurrence_map
from stickslip.sweep.execution import ExecutionOptions
n, repeats = int(sys.argv[1]), int(sys.argv[2])
lams, zetas = np.geomspace(0.1, 50.0, n), np.linspace(0.005, 0.4, n)
def run(l, z):
    return occurrence_map(l, z, "optimal", 2.0,
                          execution=ExecutionOptions(backend="threads", workers=2))
run(lams[:2], zetas[:2])
best = np.inf
for _ in range(repeats):
    t0 = time.perf_counter(); m = run(lams, zetas); best = min(best, time.perf_counter() - t0)
ds = m.dataset
names = ("verdict", "n_stick", "period", "amplitude", "stick_ratio")
np.savez(sys.argv[3], seconds=best, **{k: ds[k].values for k in names})
"""

BASIN_RUNNER = r"""
import sys, time, numpy as np
sys.path.insert(0, sys.argv[4])  # this tree's benchmarks folder: the case
from bench_basin import foundation_weak_case
from stickslip.sweep.basin import basin_stability, sample_box
n, repeats = int(sys.argv[1]), int(sys.argv[2])
structure, slider, box = foundation_weak_case()
states = sample_box(structure, slider, n, box, seed=1)
basin_stability(structure, slider, states[:64])
best = np.inf
for _ in range(repeats):
    result = basin_stability(structure, slider, states)
    best = min(best, result.elapsed)
np.savez(sys.argv[3], seconds=best, verdict=result.verdict)
"""

CEA_RUNNER = r"""
import sys, time, numpy as np
from stickslip.analysis.contact import FrictionCoupledSystem, critical_friction
n_dof, repeats = int(sys.argv[1]), int(sys.argv[2])
rng = np.random.default_rng(3)
a, b = rng.normal(size=(n_dof, n_dof)), rng.normal(size=(n_dof, n_dof))
system = FrictionCoupledSystem(np.eye(n_dof), 0.05 * b @ b.T, a @ a.T + n_dof * np.eye(n_dof), 0, 1,
                               normal_stiffness=2.0, normal_damping=0.01)
critical_friction(system)
best = np.inf
for _ in range(repeats):
    t0 = time.perf_counter()
    found = [critical_friction(system).mu, critical_friction(system.undamped()).mu]
    best = min(best, time.perf_counter() - t0)
np.savez(sys.argv[3], seconds=best, mu=np.array([np.nan if m is None else m for m in found]))
"""

#: per case: the runner, the arrays compared, the unit counted
CASES = {"map": (MAP_RUNNER, ("verdict", "n_stick", "period", "amplitude", "stick_ratio"), "cells"),
         "basin": (BASIN_RUNNER, ("verdict",), "samples"),
         "cea": (CEA_RUNNER, (), "analyses")}


def sources(commit: str) -> Path:
    """The ``src`` folder of ``commit``, extracted once into a cache folder."""
    folder = Path(tempfile.gettempdir()) / f"stickslip-ab-{commit}"
    if not (folder / "src" / "stickslip").is_dir():
        folder.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", commit, "src"], check=True,
                                 capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    return folder / "src"


def timed(case: str, src: Path, n: int, repeats: int, out: Path) -> dict[str, np.ndarray]:
    env = {**os.environ, "PYTHONPATH": str(src)}
    subprocess.run([sys.executable, "-c", CASES[case][0], str(n), str(repeats), str(out),
                    str(ROOT / "benchmarks")], check=True, env=env, cwd=out.parent)
    with np.load(out) as data:
        return {k: data[k] for k in data.files}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--commit", required=True, help="the baseline commit (any since 6c94c46)")
    parser.add_argument("--case", choices=sorted(CASES), default="map")
    parser.add_argument("--n", type=int, default=None,
                        help="map side (default 200) or basin states (default 20000)")
    parser.add_argument("--repeats", type=int, default=3, help="timed maps per process")
    parser.add_argument("--rounds", type=int, default=2, help="processes per side, interleaved")
    args = parser.parse_args()
    n = args.n if args.n is not None else {"map": 200, "basin": 20_000, "cea": 4}[args.case]
    if n < 2 or args.repeats < 1 or args.rounds < 1:
        parser.error("--n must be at least 2, --repeats and --rounds at least 1")
    with tempfile.TemporaryDirectory() as tmp:
        # interleaved rounds (old, new, new, old, ...): a machine that speeds up or slows down
        # during the run favours neither; each side keeps its best
        old = new = None
        for round_ in range(args.rounds):
            order = ("old", "new") if round_ % 2 == 0 else ("new", "old")
            for side in order:
                src = sources(args.commit) if side == "old" else ROOT / "src"
                got = timed(args.case, src, n, args.repeats, Path(tmp) / f"{side}{round_}.npz")
                best = old if side == "old" else new
                if best is None or float(got["seconds"]) < float(best["seconds"]):
                    if side == "old":
                        old = got
                    else:
                        new = got
        assert old is not None and new is not None
    _, keys, unit = CASES[args.case]
    count = {"map": n * n, "basin": n, "cea": 1}[args.case]
    same = all(np.array_equal(old[k], new[k], equal_nan=True) for k in keys)
    what = {"map": f"paper's map {n}x{n} (Fig. 8b, optimal foundation, 2 threads",
            "basin": f"foundation weak basin, {n} states (bench_basin.py, all threads",
            "cea": f"critical mu, damped and undamped, random {n}-DOF machine (one thread"}[args.case]
    print(f"{what}, best of {args.repeats} x {args.rounds} rounds): commit {args.commit} "
          f"{count / float(old['seconds']):,.0f} {unit}/s, "
          f"this tree {count / float(new['seconds']):,.0f} {unit}/s, this/old "
          f"{float(old['seconds']) / float(new['seconds']):.2f}x; "
          + (f"critical mu old {old['mu']}, new {new['mu']}" if args.case == "cea" else
             f"{'bit-identical' if args.case == 'map' else 'labels equal'}: {same}"))

if __name__ == "__main__":
    main()
