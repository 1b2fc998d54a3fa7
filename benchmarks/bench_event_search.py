"""Benchmark: the cost of a step of the N-DOF basin kernel, where the event search dominates.

    .venv/bin/python benchmarks/bench_event_search.py [--states 4000] [--old-src PATH] [--rounds 2]

The "foundation weak" basin of ``bench_basin.py`` (2-DOF foundation, exponential Stribeck law
tabulated in 101 bands) has an event at nearly every step: each band edge the slider's speed
crosses ends a step. This runs its first ``--states`` states (seed 1) on one numba thread
without the proven balls (``run_state_batch`` on a system without them), and prints the time
per step and per state, the steps and events, and the same for the paper's Coulomb law on the
same structure (lambda = 1.484, no bands: hardly any events), so that the two costs can be
told apart. With ``--old-src`` (another checkout's ``src``) both trees run in their own
processes, interleaved over ``--rounds`` rounds (the machine is shared and noisy: compare
within a round), and their statuses and step counts are compared.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

RUNNER = '''
import json, sys, time
sys.path.insert(0, sys.argv[2])
import numpy as np
from bench_basin import foundation_weak_case
from stickslip import Slider
from stickslip.analysis.simulation import EngineOptions
from stickslip.kernel.engine import I_N_SEGMENTS, I_N_STEPS, I_STATUS
from stickslip.sweep.basin import BasinSystem, run_state_batch, sample_box

structure, slider, box = foundation_weak_case()
states = sample_box(structure, slider, int(sys.argv[1]), box, seed=1)
out = {}
for name, law in (("stribeck", slider), ("coulomb", Slider(slider.lam))):
    system = BasinSystem.prepare(structure, law, len(states))
    run_state_batch(system, states[:10], EngineOptions(), 1)  # compile / load the cache
    best = np.inf
    for _ in range(2):
        start = time.perf_counter()
        _, isum = run_state_batch(system, states, EngineOptions(), 1)
        best = min(best, time.perf_counter() - start)
    out[name] = {"seconds": best, "steps": int(isum[:, I_N_STEPS].sum()),
                 "events": int(isum[:, I_N_SEGMENTS].sum()),
                 "status": isum[:, I_STATUS].tolist(), "per_state_steps": isum[:, I_N_STEPS].tolist()}
print(json.dumps(out))
'''


def run(src: Path, states: int) -> dict:
    """One process of the runner with ``src`` first on the path."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    done = subprocess.run([sys.executable, "-c", RUNNER, str(states), str(ROOT / "benchmarks")],
                          env=env, capture_output=True, text=True, check=True, cwd=ROOT)
    return json.loads(done.stdout.strip().splitlines()[-1])


def line(label: str, res: dict, n: int) -> str:
    s, c = res["stribeck"], res["coulomb"]
    return (f"{label}: Stribeck {s['seconds'] / s['steps'] * 1e9:.0f} ns/step, "
            f"{s['seconds'] / n * 1e6:.0f} us/state ({s['steps']:,} steps, {s['events']:,} events); "
            f"Coulomb {c['seconds'] / c['steps'] * 1e9:.0f} ns/step ({c['steps']:,} steps, "
            f"{c['events']:,} events)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--states", type=int, default=4000)
    parser.add_argument("--old-src", type=Path, default=None)
    parser.add_argument("--rounds", type=int, default=2)
    args = parser.parse_args()
    if args.states < 10 or args.rounds < 1:
        parser.error("--states must be at least 10 and --rounds at least 1")
    if args.old_src is not None and not (args.old_src / "stickslip").is_dir():
        parser.error(f"--old-src {args.old_src} holds no stickslip package")
    sides = [("this tree", ROOT / "src")] + ([("old", args.old_src)] if args.old_src else [])
    for r in range(args.rounds):
        results = {}
        for label, src in (sides if r % 2 == 0 else sides[::-1]):
            results[label] = run(src, args.states)
            print(f"round {r + 1}, " + line(label, results[label], args.states), flush=True)
        if "old" in results:
            new, old = results["this tree"]["stribeck"], results["old"]["stribeck"]
            same = new["status"] == old["status"] and new["per_state_steps"] == old["per_state_steps"]
            print(f"round {r + 1}: this/old {old['seconds'] / new['seconds']:.2f}x on the Stribeck "
                  f"states; statuses and steps equal: {same}", flush=True)


if __name__ == "__main__":
    main()
