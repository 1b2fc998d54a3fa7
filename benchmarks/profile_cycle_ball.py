"""Why a proven cycle ball has the radius it has: the proof's ladder, radius by radius.

    .venv/bin/python benchmarks/profile_cycle_ball.py [--radii 12]

The cycle of bench_basin.py's 2-DOF "foundation weak" case (exponential Stribeck law
v_s/V = 0.2 at tolerance 1e-4, lambda = 1.484, zeta = 0.05, foundation mass and stiffness
ratios 1, damping ratio 0.1), reached by ``simulate`` from one start and proven by
:func:`stickslip.analysis.cycle_proof.prove_cycle`. For each radius of the proof's ladder
(:data:`~stickslip.analysis.cycle_proof.RADIUS_START` down by
:data:`~stickslip.analysis.cycle_proof.RADIUS_FACTOR`, and twice the proven radius) it prints
whether the tube holds (:func:`stickslip.analysis._cycle_tube.tube_bound`), the bound ``E(r)``
of the Jacobian's variation over the ball and the contraction bound ``theta = ||J||_W + kappa
E(r)`` (a proof needs ``theta < 1``), or the phase where the tube fails: its mode, band, the
band's width in sliding speed, its duration and the deviation the tube carried into it.
"""

from __future__ import annotations

import argparse

import numpy as np

from stickslip import Foundation, InitialState, Slider, elastic_foundation, simulate
from stickslip.analysis import _cycle_tube as tube
from stickslip.analysis import cycle_proof
from stickslip.analysis.engine_run import EngineOptions
from stickslip.analysis.return_map import ReturnMap
from stickslip.kernel.system import mode_kind_band
from stickslip.model.friction import StribeckFriction

KINDS = {0: "slip-I", 1: "slip-II", 2: "stick"}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--radii", type=int, default=12, help="ladder radii to try, largest first")
    args = parser.parse_args()
    if args.radii < 1:
        parser.error(f"--radii {args.radii} must be at least 1")
    slider = Slider(0.05 * 0.2 * float(np.exp(5.0)), friction=StribeckFriction(0.2, tolerance=1e-4))
    structure = elastic_foundation(0.05, Foundation(1.0, 1.0, 0.1))
    run = simulate(structure, slider, initial=InitialState(np.array([0.6, 0.1]), np.array([-0.7, 0.1])))
    proof = run.cycle_proof
    if proof is None:
        raise SystemExit(f"the run from the chosen start ends {run.verdict.value}: no cycle to profile")
    print(run.verdict.value + ": " + proof.describe())
    pmap = ReturnMap(structure, slider, EngineOptions())
    cand = cycle_proof._candidate(pmap, pmap.reduce(proof.fixed_point), proof.stick_phases)
    if cand is None:
        raise SystemExit("Newton's method did not converge from the proven fixed point")
    n2 = 2 * pmap.n
    norms = tube.ProductNorms.of(cand.phases, pmap.lift, np.delete(np.eye(n2), [0, pmap.n], axis=0))
    scale = max(1.0, float(np.max(np.abs(pmap.state(cand.b_hat)))))
    adapted = cycle_proof._adapted_norm(cand.jac)
    if adapted is None:
        raise SystemExit("the cycle's multipliers are not inside the unit circle")
    _, norm_w, kappa = adapted
    edges = pmap.edges
    crossings = sum(1 for ph in cand.phases if not (ph.breakaway or ph.belt_decision))
    print(f"{len(cand.phases)} phases ({crossings} band-edge crossings, {edges.size - 1} bands); "
          f"||J||_W = {norm_w:.3f}, kappa = {kappa:.3f}")
    ladder = [scale * cycle_proof.RADIUS_START * cycle_proof.RADIUS_FACTOR ** -i for i in range(args.radii)]
    radii = sorted(set(ladder) | {2.0 * proof.radius}, reverse=True)
    for radius in radii:
        t = tube.tube_bound(cand.phases, norms, pmap.stick_normal, float(slider.lam),
                            float(slider.gamma), radius, scale)
        if t.ok:
            theta = norm_w + kappa * t.jacobian_bound
            print(f"r = {radius:9.3e}: tube holds, E(r) = {t.jacobian_bound:9.3e}, theta = {theta:7.3f}"
                  f" ({'contracts' if theta < 1.0 else 'no contraction'})")
            continue
        ph = cand.phases[t.failed_phase]
        kind, band = mode_kind_band(ph.mode)
        width = (f", band width {float(edges[band + 1] - edges[band]):.2e}" if kind != 2
                 and np.isfinite(edges[band + 1]) else "")
        print(f"r = {radius:9.3e}: tube fails in phase {t.failed_phase} ({KINDS[kind]}, band {band}"
              f"{width}, duration {ph.duration:.3g}), carried deviation {t.failed_deviation:.2e}")


if __name__ == "__main__":
    main()
