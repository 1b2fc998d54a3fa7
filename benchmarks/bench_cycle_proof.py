"""Benchmark: proving a large structure's stick-slip cycle, formed against factored propagators.

    .venv/bin/python benchmarks/bench_cycle_proof.py [--dof 60] [--repeats 3]

The machine (``tests/machines.py``): a grounded chain of ``--dof - 1`` nodes (5 kg, 2e7 N/m
to ground, 1e8 N/m between neighbours) with a 1 kg slider on a 1e6 N/m spring to its middle
node (40 N s/m dashpot), stiffness-proportional damping 2e-5 K, mu_s = 0.5, mu_k = 0.3,
1000 N at 0.2 m/s (a stick-slip cycle of period 6.61 ms at 60 DOF). ``simulate`` runs it from the start-up
state and proves the cycle (:func:`stickslip.analysis.cycle_proof.prove_cycle`); most of the
proof's time is sampling each phase's propagators (:func:`stickslip.analysis._phase_flow.sampled_flow`).
Three ways, interleaved in this run, best of ``--repeats``: every propagator formed by
doubling with its Frobenius norm (``DENSE_WORK`` infinite: the path of every structure below
about 20 DOF), factored (the default beyond ``DENSE_WORK``: ``2 sqrt(samples)`` products and
2-norm bounds), factored with every engine run preparing the structure afresh (no
``stickslip.kernel.prepared`` structure cache: the code before it), and factored with the tube
bounded in the engine's coordinates ``(q, v)`` instead of the structure's energy coordinates
(``stickslip.analysis._cycle_tube.Coordinates``: the code before them). Every proof must give
the same period; the ratios of the times, the balls' radii and the certificates are printed.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the machine lives in tests/

from tests.machines import grounded_chain_machine

from stickslip.analysis import _cycle_tube, _phase_flow
from stickslip.analysis.simulation import simulate
from stickslip.kernel import prepared


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dof", type=int, default=60)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    if not 2 <= args.dof <= 60:
        parser.error(f"--dof {args.dof} must be 2 to 60 (larger structures are reduced first)")
    if args.repeats < 1:
        parser.error(f"--repeats {args.repeats} must be at least 1")
    machine = grounded_chain_machine(args.dof)
    structure, slider = machine.structure(), machine.slider()
    default_dense, cache = _phase_flow.DENSE_WORK, prepared._structure_cache
    energy = _cycle_tube.Coordinates.__dict__["energy"]  # the classmethod itself

    def engine_coordinates(cls, mass, stiffness):
        return cls.identity(2 * mass.shape[0])

    ways = {"formed": (math.inf, cache, energy), "factored": (default_dense, cache, energy),
            "no cache": (default_dense, _NoStore(), energy),
            "(q, v)": (default_dense, cache, classmethod(engine_coordinates))}
    best = dict.fromkeys(ways, math.inf)
    runs = {}
    simulate(structure, slider)  # compile / load the cache
    for _ in range(args.repeats):
        for name, (dense, store, coords) in ways.items():
            _phase_flow.DENSE_WORK, prepared._structure_cache = dense, store
            _cycle_tube.Coordinates.energy = coords  # type: ignore[method-assign]
            start = time.perf_counter()
            runs[name] = simulate(structure, slider)
            best[name] = min(best[name], time.perf_counter() - start)
    _phase_flow.DENSE_WORK, prepared._structure_cache = default_dense, cache
    _cycle_tube.Coordinates.energy = energy  # type: ignore[method-assign]
    print(f"{args.dof}-DOF chain, simulate from start-up with the cycle's proof, best of {args.repeats}:")
    for name, run in runs.items():
        print(f"  {name:9s} {best[name]:7.2f} s  {run.verdict.value}, period {run.period:.10g}: "
              f"{run.certificate}")
    same = len({run.period for run in runs.values() if run.cycle_proof is not None}) == 1
    print(f"  factored/formed time {best['factored'] / best['formed']:.2f} "
          f"({best['formed'] / best['factored']:.1f}x faster); the structure's tables kept "
          f"between the proof's runs {best['no cache'] / best['factored']:.2f}x faster than "
          f"recomputed; same period (where proven): {same}")
    print("  the tube in the structure's energy coordinates against the engine's (q, v): "
          f"{best['(q, v)'] / best['factored']:.2f}x faster, ball radius "
          f"{_radius(runs['factored'])} against {_radius(runs['(q, v)'])}")


def _radius(run) -> str:
    return "none" if run.cycle_proof is None else f"{run.cycle_proof.radius:.3g}"


class _NoStore(dict):
    """A structure cache that keeps nothing (every engine run prepares its structure afresh)."""

    def __setitem__(self, key: object, value: object) -> None:
        pass


if __name__ == "__main__":
    main()
