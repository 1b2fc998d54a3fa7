"""Why a proven cycle ball has the radius it has: the proof's ladder, radius by radius.

    .venv/bin/python benchmarks/profile_cycle_ball.py [--radii 12]

The cycle of bench_basin.py's 2-DOF "foundation weak" case (exponential Stribeck law
v_s/V = 0.2 at tolerance 1e-4, lambda = 1.484, zeta = 0.05, foundation mass and stiffness
ratios 1, damping ratio 0.1), reached by ``simulate`` from one start and proven by
:func:`stickslip.analysis.cycle_proof.prove_cycle`. For each radius of the proof's ladder
(:data:`~stickslip.analysis.cycle_proof.RADIUS_START` down by
:data:`~stickslip.analysis.cycle_proof.RADIUS_FACTOR`, the proven radius and twice it) it prints
whether the tube holds (:func:`stickslip.analysis._cycle_tube.tube_bound`; both variants: band
by band, each edge an event, and at equal times across the band edges), the bound ``E(r)``
of the Jacobian's variation over the ball and the contraction bound ``theta = ||J||_W + kappa
E(r)`` (a proof needs ``theta < 1``), or the phase where the tube fails: its mode, band, the
band's width in sliding speed, its duration and the deviation the tube carried into it; and,
at the proven radius, which phases make ``E(r)`` (its first-order terms by kind of phase), and
for the largest, how much of the event function's deviation a bound through its own row's
products would keep (an observation).

Then the return map itself, sampled about its fixed point out to radius 0.3: its curvature
and its local contraction factor in the proof's norm (observations: what a tighter tube could
at best prove). Then what a larger ball would buy (``--states``, 300 by default; 0 skips it): the first
``--states`` states of bench_basin.py's box (same seed) run with ``simulate``, and for each
stick-slip one the breakaway states' Euclidean distances to the proven fixed point in the
foundation coordinates ``b`` (the norm of the proven radius). For each radius it prints the
mean number of stick phases, and the mean time, until the first breakaway inside a ball of
that radius: where a basin run with such a ball would stop. The distances at the first
breakaway are printed too (their quantiles): they set how far any ball must reach. For the
steady-sliding states, when the Lyapunov bound certifies them against when the slider's
velocity last deviated by more than 0.3, 0.2 and 0.1 (what a larger steady-sliding region
would buy).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))  # bench_basin's case

from bench_basin import foundation_weak_case

from stickslip import InitialState, simulate
from stickslip.analysis import cycle_proof
from stickslip.analysis._product_norms import ProductNorms
from stickslip.analysis.engine_run import EngineOptions
from stickslip.analysis.return_map import ReturnMap
from stickslip.kernel.system import STICK, mode_kind_band
from stickslip.sweep.basin import sample_box

KINDS = {0: "slip-I", 1: "slip-II", 2: "stick"}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--radii", type=int, default=12, help="ladder radii to try, largest first")
    parser.add_argument("--states", type=int, default=300,
                        help="basin states for what a larger ball would buy (0: skip)")
    args = parser.parse_args()
    if args.radii < 1:
        parser.error(f"--radii {args.radii} must be at least 1")
    if args.states < 0:
        parser.error(f"--states {args.states} must be at least 0")
    structure, slider, box = foundation_weak_case()
    run = simulate(structure, slider, initial=InitialState(np.array([0.6, 0.1]), np.array([-0.7, 0.1])))
    proof = run.cycle_proof
    if proof is None:
        raise SystemExit(f"the run from the chosen start ends {run.verdict.value}: no cycle to profile")
    print(run.verdict.value + ": " + proof.describe())
    pmap = ReturnMap(structure, slider, EngineOptions())
    cand = cycle_proof._candidate(pmap, pmap.reduce(proof.fixed_point), proof.stick_phases)
    if isinstance(cand, str):
        raise SystemExit(f"no candidate at the proven fixed point: {cand}")
    tube_at, scale = cycle_proof.tubes(pmap, cand)
    adapted = cycle_proof._adapted_norm(cand.jac)
    if adapted is None:
        raise SystemExit("the cycle's multipliers are not inside the unit circle")
    _, norm_w, kappa = adapted
    edges = pmap.edges
    crossings = sum(1 for ph in cand.phases if not (ph.breakaway or ph.belt_decision))
    print(f"{len(cand.phases)} phases ({crossings} band-edge crossings, {edges.size - 1} bands); "
          f"||J||_W = {norm_w:.3f}, kappa = {kappa:.3f}")
    ladder = [scale * cycle_proof.RADIUS_START * cycle_proof.RADIUS_FACTOR ** -i for i in range(args.radii)]
    radii = sorted(set(ladder) | {proof.radius, 2.0 * proof.radius}, reverse=True)
    for equal_time in (False, True):
        print("band by band (each edge an event):" if not equal_time
              else "equal times across the band edges:")
        for radius in radii:
            ladder_line(cand, edges, tube_at(radius, equal_time), radius, norm_w, kappa)
    e_terms(pmap, cand, tube_at(proof.radius, True), proof.radius)
    true_map(pmap, cand, cycle_proof._adapted_norm(cand.jac)[0])
    if args.states > 0:
        center = pmap.reduce(proof.fixed_point)
        states = sample_box(structure, slider, args.states, box, seed=1)
        larger_balls(structure, slider, states, center, sorted({proof.radius, 1e-4, 1e-3, 1e-2, 1e-1, 1.0}))
        steady_entry(structure, slider, states, (0.3, 0.2, 0.1))


def ladder_line(cand, edges, t, radius, norm_w, kappa) -> None:  # type: ignore[no-untyped-def]
    """One radius of the ladder: the contraction bound, or where the tube fails."""
    if t.ok:
        theta = norm_w + kappa * t.jacobian_bound
        print(f"r = {radius:9.3e}: tube holds, E(r) = {t.jacobian_bound:9.3e}, theta = {theta:7.3f}"
              f" ({'contracts' if theta < 1.0 else 'no contraction'})")
        return
    ph = cand.phases[t.failed_phase]
    kind, band = mode_kind_band(ph.mode)
    width = (f", band width {float(edges[band + 1] - edges[band]):.2e}" if kind != 2
             and np.isfinite(edges[band + 1]) else "")
    print(f"r = {radius:9.3e}: tube fails in phase {t.failed_phase} ({KINDS[kind]}, band {band}"
          f"{width}, duration {ph.duration:.3g}), carried deviation {t.failed_deviation:.2e}")


def e_terms(pmap, cand, tube, radius) -> None:  # type: ignore[no-untyped-def]
    """Where ``E(r)`` comes from: the tube's first-order terms ``||R G(i + 1, N)|| w_i`` by phase.

    ``w_i`` bounds ``||(X_i - X_i*) G(0, i) L||`` (the equal-time variant's weights); the rest
    of ``E`` is the suffixes' own variation (second order). Grouped by the phase's kind: the
    departure after the breakaway (phase 0), the band-edge crossings, the arrival at the belt
    speed, the stick phase; the largest single terms are listed with their phase.
    """
    if not tube.ok:
        print(f"r = {radius:9.3e}: the equal-time tube fails; no terms")
        return
    reduce_rows = np.delete(np.eye(2 * pmap.n), [0, pmap.n], axis=0)
    norms = ProductNorms.of(cand.phases, cand.coords.from_state @ pmap.lift,
                            reduce_rows @ cand.coords.to_state)
    terms = np.array(norms.suffix) * np.array(tube.weights)
    last = len(cand.phases) - 1
    groups = {"departure (phase 0)": [0],
              "band-edge crossings": [i for i, ph in enumerate(cand.phases)
                                      if 0 < i and not (ph.belt_decision or ph.breakaway)],
              "arrival at the belt speed": [i for i, ph in enumerate(cand.phases) if ph.belt_decision],
              "stick phase": [i for i, ph in enumerate(cand.phases) if ph.breakaway and i == last]}
    parts = ", ".join(f"{name} {terms[idx].sum():.3g}" for name, idx in groups.items() if idx)
    print(f"r = {radius:9.3e}: E(r) = {tube.jacobian_bound:.3g} = {terms.sum():.3g} first order "
          f"({parts}) + {tube.jacobian_bound - terms.sum():.3g} from the suffixes' variation")
    ratios = event_row_ratios(pmap, cand)
    for i in np.argsort(-terms)[:5]:
        kind, band = mode_kind_band(cand.phases[i].mode)
        print(f"  phase {i:4d} ({KINDS[kind]}, band {band}, duration {cand.phases[i].duration:.3g}):"
              f" {terms[i]:.3g} ({terms[i] / tube.jacobian_bound:.0%} of E); its event row's "
              f"product over the products' norms {ratios[i]:.3g}")


def event_row_ratios(pmap, cand) -> np.ndarray:  # type: ignore[no-untyped-def]
    """Per phase, ``||n^T expm(A t*) G(0, i) L|| / (||n|| ||expm(A t*)|| ||G(0, i) L||)``.

    ``n`` is the row of the event that ends the phase. The tube bounds an event function's
    deviation at the event by ``||n|| M(t*) Z`` (norms multiplied); through the nominal
    products, the first-order part of it is the numerator times the radius. The ratio is what
    a bound through the event row's own products would keep of that part (an observation for
    a tighter tube, not a bound).
    """
    current = cand.coords.from_state @ pmap.lift
    ratios = np.empty(len(cand.phases))
    for i, ph in enumerate(cand.phases):
        row = ph.functions[ph.ending][0]
        tight = float(np.linalg.norm(row @ ph.e_nominal @ current))
        crude = float(np.linalg.norm(row)) * ph.e_norm * float(np.linalg.norm(current, 2))
        ratios[i] = tight / crude if crude > 0.0 else np.nan
        current = ph.salt @ ph.e_nominal @ current
    return ratios


def true_map(pmap, cand, chol) -> None:  # type: ignore[no-untyped-def]
    """How far the return map itself stays nearly linear and contracting (no bound: sampled).

    For radii ``r``, 12 random directions ``d`` of length ``r`` each: the largest
    ``||P(b_hat + d) - P(b_hat) - J d|| / r^2`` (the map's curvature; a tube's ``E(r)`` bounds
    the Jacobian's variation, about twice that times ``r`` for a smooth map) and the largest
    local contraction factor in the proof's norm ``||C x||`` (a difference quotient at
    ``b_hat + d`` over a step of 1e-6). Observations, not bounds: what a tighter tube could
    at best prove.
    """
    rng = np.random.default_rng(0)
    for radius in (1e-4, 1e-3, 1e-2, 1e-1, 3e-1):
        curvature, contraction = 0.0, 0.0
        for _ in range(12):
            d = rng.normal(size=cand.b_hat.size)
            d *= radius / np.linalg.norm(d)
            step = rng.normal(size=cand.b_hat.size)
            step *= 1e-6 / np.linalg.norm(step)
            image, nearby = pmap(cand.b_hat + d, cand.q), pmap(cand.b_hat + d + step, cand.q)
            if image is None or nearby is None:
                print(f"true map, r = {radius:g}: a state of the ball does not reach the section")
                break
            curvature = max(curvature, float(np.linalg.norm(image - cand.value - cand.jac @ d)) / radius**2)
            contraction = max(contraction, float(np.linalg.norm(chol @ (nearby - image))
                                                 / np.linalg.norm(chol @ step)))
        else:
            print(f"true map, r = {radius:g}: curvature {curvature:.3g}, local contraction in the "
                  f"proof's norm up to {contraction:.3f}")


def steady_entry(structure, slider, states, levels) -> None:  # type: ignore[no-untyped-def]
    """When the steady states are certified, against when their slider velocity last left a band.

    For each steady-sliding state: the certificate's time (the Lyapunov bound) and the last
    phase start at which the slider's velocity deviation from steady sliding exceeded each
    level (a certificate whose region reached that level could stop the run there at best).
    """
    n = structure.n_dof
    rows = []
    for state in states:
        run = simulate(structure, slider, initial=InitialState(state[:n], state[n:]), record=True)
        if run.verdict.value != "steady-sliding":
            continue
        t = np.asarray(run.segment_times)
        dv = np.abs(np.asarray(run.segment_states)[:, n])
        rows.append([run.t_certified] + [float(t[np.flatnonzero(dv > x)[-1]]) if np.any(dv > x)
                                         else 0.0 for x in levels])
    if not rows:
        print(f"none of the {len(states)} states is steady sliding")
        return
    mean = np.mean(rows, axis=0)
    lasts = ", ".join(f"> {x:g} at tau {m:.1f}" for x, m in zip(levels, mean[1:], strict=True))
    print(f"{len(rows)} of {len(states)} states slide steadily: certified at tau {mean[0]:.1f} on "
          f"average; the slider's velocity deviation was last {lasts}")


def larger_balls(structure, slider, states, center, radii) -> None:  # type: ignore[no-untyped-def]
    """Where basin runs would stop with a proven ball of each radius (see the module's text)."""
    n = structure.n_dof
    distances, times = [], []
    for state in states:
        run = simulate(structure, slider, initial=InitialState(state[:n], state[n:]), record=True)
        if run.verdict.value != "stick-slip":
            continue
        modes = np.asarray(run.segment_modes)
        rows = np.asarray(run.segment_states)
        bk = np.flatnonzero((modes[:-1] == STICK) & (modes[1:] != STICK)) + 1
        b = np.concatenate([rows[bk, 1:n], rows[bk, n + 1:]], axis=1)
        distances.append(np.linalg.norm(b - center, axis=1))
        times.append(np.asarray(run.segment_times)[bk])
    if not distances:
        print(f"none of the {len(states)} states is stick-slip")
        return
    first = np.quantile([d[0] for d in distances], [0.1, 0.5, 0.9])
    print(f"{len(distances)} of {len(states)} states stick-slip; distance of the first breakaway "
          f"from the fixed point: 10% {first[0]:.3g}, median {first[1]:.3g}, 90% {first[2]:.3g}")
    for radius in radii:
        # the first breakaway inside the ball (the last one when none is: the run's certificate)
        enter = [int(np.argmax(d <= radius)) if np.any(d <= radius) else d.size - 1 for d in distances]
        phases = np.mean(enter) + 1.0
        tau = np.mean([t[j] for t, j in zip(times, enter, strict=True)])
        print(f"ball radius {radius:9.3e}: stops after {phases:5.2f} stick phases, at tau {tau:7.2f}"
              " on average")


if __name__ == "__main__":
    main()
