"""Audit: a basin's labels against ``simulate``'s, which carries the run's own rounding.

    .venv/bin/python benchmarks/audit_basin_rounding.py [--states 200]

A basin on two or more DOF certifies a state stick-slip when its computed run enters a proven
ball (:mod:`stickslip.sweep.basin_cycles`); ``simulate`` from the same state also carries the
run's rounding to that state (:mod:`stickslip.analysis.run_rounding`) and answers
``undetermined`` when a chaotic transient has amplified it beyond the ball's margin. This
script runs the first ``--states`` states of ``benchmarks/bench_basin.py``'s "foundation weak"
box (seed 1, as the benchmark draws them) both ways and prints how many labels agree, each
disagreement with ``simulate``'s reason, and the largest rounding gain ``simulate`` carried.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the benchmark's case

from bench_basin import foundation_weak_case

from stickslip import simulate
from stickslip.analysis.verdict import Verdict
from stickslip.model.initial import InitialState
from stickslip.sweep.basin import basin_stability, sample_box


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--states", type=int, default=200)
    args = parser.parse_args()
    if args.states < 1:
        parser.error(f"--states {args.states} must be at least 1")
    structure, slider, box = foundation_weak_case()
    states = sample_box(structure, slider, 20_000, box, seed=1)[: args.states]
    basin = basin_stability(structure, slider, states)
    n = structure.n_dof
    names = {v.code: v.value for v in Verdict}
    agree, gains, start = 0, [], time.perf_counter()
    for i, state in enumerate(states):
        run = simulate(structure, slider, initial=InitialState(state[:n], state[n:]), record=False)
        label = names[int(basin.verdict[i])]
        if run.cycle_proof is not None and np.isfinite(run.cycle_proof.run_gain):
            gains.append(float(run.cycle_proof.run_gain))
        if run.verdict.value == label:
            agree += 1
        else:
            print(f"state {i}: basin {label}, simulate {run.verdict.value}: {run.certificate}")
    print(f"labels equal on {agree} of {len(states)} states "
          f"({time.perf_counter() - start:.0f} s of simulate runs); largest carried gain "
          f"{max(gains) if gains else float('nan'):.3g} over {len(gains)} proofs")


if __name__ == "__main__":
    main()
