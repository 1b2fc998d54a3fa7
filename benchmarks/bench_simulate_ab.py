"""A/B of ``simulate`` (the non-quick engine path) against another source tree, in one session.

    .venv/bin/python benchmarks/bench_simulate_ab.py --old-src /path/to/old/checkout/src [--repeats 5]

Runs four cases (rigid-base and foundation Stribeck stick-slip, the fitted foundation's slip
oscillation under the linear law delta = 0.4, the foundation's Coulomb stick-slip) with this
tree's package and with ``--old-src``'s, each in its own process, interleaved over two rounds
(the machine is shared and noisy: compare within a round), printing the best time of
``--repeats`` runs with each case's verdict, period and amplitude, so that a change to the
engine's bookkeeping can be checked to leave the answers (and the time) as they were.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

CASES = '''
import sys, time
from stickslip import simulate, Slider
from stickslip.model.structure import elastic_foundation, rigid_base
from stickslip.analysis.theory import optimal_foundation_fit
from stickslip.model.friction import StribeckFriction, LinearFriction
cases = {
 "stribeck rigid stick-slip": (rigid_base(0.05), Slider(1/3, gamma=1.0, friction=StribeckFriction(0.3333))),
 "stribeck foundation": (elastic_foundation(0.05, optimal_foundation_fit(0.05)),
                         Slider(3.0, friction=StribeckFriction(0.2))),
 "linear foundation slip-osc": (elastic_foundation(0.1, optimal_foundation_fit(0.1)),
                                Slider(0.5, friction=LinearFriction(0.4))),
 "coulomb foundation": (elastic_foundation(0.1, optimal_foundation_fit(0.1)), Slider(10.0)),
}
for name, (st, sl) in cases.items():
    r = simulate(st, sl, record=False)
    best = 1e9
    for _ in range(int(sys.argv[1])):
        t = time.perf_counter(); r = simulate(st, sl, record=False); best = min(best, time.perf_counter() - t)
    print(f"  {name}: {best*1e3:.3f} ms  {r.verdict.value} period {r.period:.10g} "
          f"amplitude {r.amplitude:.10g}")
'''


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old-src", type=Path, required=True, help="the other tree's src folder")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    new_src = Path(__file__).resolve().parents[1] / "src"
    for round_ in (1, 2):
        for label, src in (("old", args.old_src.resolve()), ("new", new_src)):
            print(f"== {label} round {round_}", flush=True)
            env = {**os.environ, "PYTHONPATH": str(src)}
            subprocess.run([sys.executable, "-c", CASES, str(args.repeats)], env=env, check=True,
                           timeout=1800)


if __name__ == "__main__":
    main()
