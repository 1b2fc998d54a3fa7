"""Where a cycle proof under a fine friction table spends its time: its parts' shares.

    .venv/bin/python benchmarks/profile_fine_table_proof.py [--tolerance 1e-6]

The Stribeck case of ``bench_friction.py`` (elastic foundation zeta = 0.1, M = 1.5, K = 1,
zeta_a = 0.5; lambda = 3, gamma = 2; v_s/V = 0.3, n = 1, d_v = 0.02, tabulated to
``--tolerance``), one ``simulate`` from start-up under :mod:`cProfile` after a warm-up run.
It prints the run's time, the certificate and, for each part of the proof, its cumulative
time and its share of the run: the candidate's phases
(:func:`stickslip.analysis._cycle_tube.phases`, the sampled flows), the norms of the nominal
products (:meth:`stickslip.analysis._product_norms.ProductNorms.of`, about ``N^2 / 2`` for
``N`` phases, and their symmetric eigenvalue problems), the tube bounds of the ball's ladder
(:func:`stickslip.analysis._cycle_tube.tube_bound`) and the engine's runs (the run's own and
the proof's). The shares, not the absolute times, carry over between machines (this one is
shared and its speed varies from hour to hour).
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import time

from stickslip import Slider, elastic_foundation, simulate
from stickslip.model.friction import StribeckFriction
from stickslip.model.parameters import Foundation

#: (label, file suffix, function name) of the parts whose cumulative time is printed
PARTS = (
    ("proof of the cycle (all)", "analysis/cycle_proof.py", "prove_cycle"),
    ("  candidate: sampled phases", "analysis/_cycle_tube.py", "phases"),
    ("  norms of the products", "analysis/_product_norms.py", "of"),
    ("    of which 2-norm bounds", "analysis/_phase_flow.py", "two_norm_bounds"),
    ("  tube bounds (ladder)", "analysis/_cycle_tube.py", "tube_bound"),
    ("engine runs (the run and the proof)", "analysis/engine_run.py", "run_engine"),
)


def cumulative(stats: pstats.Stats, suffix: str, name: str) -> tuple[int, float]:
    """Calls and cumulative seconds of the function ``name`` in a file ending with ``suffix``."""
    calls, seconds = 0, 0.0
    for (path, _, func), (_, ncalls, _, cum, _) in stats.stats.items():  # type: ignore[attr-defined]
        if func == name and path.replace("\\", "/").endswith(suffix):
            calls, seconds = calls + ncalls, seconds + cum
    return calls, seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tolerance", type=float, default=1e-6, help="the law's table tolerance")
    args = parser.parse_args()
    structure = elastic_foundation(0.1, Foundation(1.5, 1.0, 0.5))
    try:
        law = StribeckFriction(0.3, viscous=0.02, tolerance=args.tolerance)
    except ValueError as err:
        parser.error(f"--tolerance {args.tolerance:g}: {err}")  # one line, exit status 2
    slider = Slider(3.0, friction=law)
    simulate(structure, slider, record=False)  # compile / load the cache
    start = time.perf_counter()
    result = simulate(structure, slider, record=False)
    plain = time.perf_counter() - start
    profile = cProfile.Profile()
    profile.enable()
    simulate(structure, slider, record=False)
    profile.disable()
    stats = pstats.Stats(profile)
    total = cumulative(stats, "analysis/simulation.py", "simulate")[1]
    print(f"tolerance {args.tolerance:g}: simulate {plain:.2f} s ({total:.2f} s under the profiler), "
          f"verdict {result.verdict.value}")
    print(f"certificate: {result.certificate}")
    for label, suffix, name in PARTS:
        calls, seconds = cumulative(stats, suffix, name)
        print(f"{label:<36} {calls:>7} calls {seconds:8.2f} s {100.0 * seconds / total:5.1f} %")


if __name__ == "__main__":
    main()
