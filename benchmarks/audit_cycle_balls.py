"""Audit: proven cycle balls under band-edged friction laws against direct runs of the exact map.

    .venv/bin/python benchmarks/audit_cycle_balls.py [--seed 11] [--machines 24] [--points 20]

The grounded chains of ``tests/test_cycle_proof.py``'s ``random_machine`` (3-10 DOF, contact
anywhere, proportional or not damped), in turn under an exponential Stribeck law (v_s/V
0.05-0.5, tolerance 1e-5 to 1e-3), the linear law floored at zero (delta 0.2-1) and a
decreasing six-point table. For every cycle ``simulate`` proves (either tube of
:mod:`stickslip.analysis.cycle_proof`: band by band, or at equal times across the band
edges), ``--points`` states on the proven ball's boundary are mapped three times by the exact
return map (:class:`stickslip.analysis.return_map.ReturnMap`), and each distance from the
fixed point is compared with the proof's promise ``theta^k rho`` plus its residual terms:
the ratio printed must stay at or below 1 (``BAD`` otherwise). A wider net than the test
suite's two boundary points per machine.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the machines live in tests/

from tests.test_cycle_proof import random_machine

from stickslip import Slider, simulate
from stickslip.analysis.engine_run import EngineOptions
from stickslip.analysis.return_map import ReturnMap
from stickslip.analysis.verdict import Verdict
from stickslip.model.friction import LinearFriction, StribeckFriction, TableFriction


def law_for(k: int, rng: np.random.Generator):  # type: ignore[no-untyped-def]
    """The ``k``-th machine's law: Stribeck, linear, table in turn."""
    if k % 3 == 0:
        return StribeckFriction(float(rng.uniform(0.05, 0.5)), tolerance=float(10 ** rng.uniform(-5, -3)))
    if k % 3 == 1:
        return LinearFriction(float(rng.uniform(0.2, 1.0)))
    u = np.sort(rng.uniform(0.0, 2.0, 6))
    u[0] = 0.0
    return TableFriction(tuple(u), tuple(np.sort(rng.uniform(-0.4, 1.0, 6))[::-1]))


def worst_ratio(structure, slider, run, rng: np.random.Generator, points: int) -> float:  # type: ignore[no-untyped-def]
    """The largest distance over promise of ``points`` boundary states, three returns each."""
    proof = run.cycle_proof
    inner, _ = structure.contact_first()
    pmap = ReturnMap(inner, slider, EngineOptions(), 0 if proof.breakaway_onto == "slip-I" else 1)
    b_hat = pmap.reduce(proof.fixed_point)
    chol = proof.norm_matrix
    c_norm = float(np.linalg.norm(chol, 2))
    rho = proof.radius / np.linalg.norm(np.linalg.inv(chol), 2)
    worst = 0.0
    for _ in range(points):
        u = rng.normal(size=b_hat.size)
        b = b_hat + np.linalg.solve(chol, u / np.linalg.norm(u)) * rho
        bound = rho
        for _ in range(3):
            b = pmap(b, proof.stick_phases)
            if b is None:
                return np.inf
            bound = proof.contraction * bound + proof.residual * c_norm
            distance = float(np.linalg.norm(chol @ (b - b_hat)))
            worst = max(worst, distance / (bound + 1e-12 * c_norm))
    return worst


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--machines", type=int, default=24)
    parser.add_argument("--points", type=int, default=20)
    args = parser.parse_args()
    for name in ("machines", "points"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} {getattr(args, name)} must be at least 1")
    rng = np.random.default_rng(args.seed)
    checked = bad = 0
    for k in range(args.machines):
        structure, slider = random_machine(rng)
        slider = Slider(slider.lam, gamma=slider.gamma, friction=law_for(k, rng))
        run = simulate(structure, slider, record=False)
        if run.verdict is not Verdict.STICK_SLIP:
            continue
        proof = run.cycle_proof
        worst = worst_ratio(structure, slider, run, rng, args.points)
        checked += 1
        bad += worst > 1.0
        print(f"{k:3d} {structure.n_dof:2d} DOF {slider.friction.describe()[:34]:34s} q {proof.stick_phases} "
              f"radius {proof.radius:.2e} theta {proof.contraction:.3f} worst {worst:.3f} "
              f"{'BAD' if worst > 1.0 else 'ok'}", flush=True)
    print(f"{checked} proven cycles checked, {bad} beyond their promise")


if __name__ == "__main__":
    main()
