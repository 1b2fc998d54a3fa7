"""The worked example of docs/continuation.md: bifurcation diagrams of the paper's slider.

    .venv/bin/python docs/continuation_example.py [--out docs/figures] [--quick]

Three diagrams against ``lambda`` at ``zeta = 0.1`` (gamma = 2): the rigid base and the
paper's fitted foundation (Eqs. 28-30) with the paper's Coulomb law, and the rigid base with a
Stribeck law (``v_s / V = 0.5``), where steady sliding loses stability at a Hopf point.
``--quick`` leaves the Stribeck diagram out (it is the slow one).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from matplotlib.figure import Figure

from stickslip.analysis.continuation import ContinuationResult, ContinuationSystem, continue_cycles
from stickslip.analysis.critical import lowest_onset
from stickslip.analysis.theory import critical_lambda_exact, optimal_foundation_fit
from stickslip.model.friction import StribeckFriction

ZETA = 0.1


def describe(name: str, result: ContinuationResult) -> None:
    """Print the branches and events of one diagram (the numbers the page quotes)."""
    for b in result.branches:
        lams = [p.param for p in b.points]
        stable = "stable" if all(p.stable for p in b.points if p.amplitude > 0.05) else "unstable"
        print(f"{name}: {b.kind} branch, {stable}, lambda in [{min(lams):.6g}, {max(lams):.6g}]")
    for e in result.events:
        print(f"{name}: {e.type} at lambda = {e.param:.8g} (amplitude {e.amplitude:.4g})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "figures")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    rigid = continue_cycles(ContinuationSystem(1.0, ZETA), "lam", (0.5, 25.0))
    describe("rigid", rigid)
    print(f"rigid: Eq. (36) gives lambda_crit = {critical_lambda_exact(ZETA):.8g}")
    foundation = optimal_foundation_fit(ZETA)
    with_foundation = continue_cycles(ContinuationSystem(1.0, ZETA, foundation=foundation), "lam",
                                      (0.5, 25.0), seeds=8)
    describe("foundation", with_foundation)
    from stickslip.model.structure import elastic_foundation

    onset = lowest_onset(elastic_foundation(ZETA, foundation))
    print(f"foundation: stick-slip from start-up from lambda = {onset:.6g}")
    panels: list[tuple[str, ContinuationResult]] = [("rigid base, Coulomb", rigid),
                                                    ("fitted foundation, Coulomb", with_foundation)]
    if not args.quick:
        law = StribeckFriction(0.5, tolerance=1e-5)
        stribeck = continue_cycles(ContinuationSystem(1.0, ZETA, friction=law), "lam", (0.3, 1.5),
                                   n_points=13, max_steps=80)
        describe("stribeck", stribeck)
        print(f"stribeck: Hopf closed form lambda_H = 2 zeta u_s e^(1/u_s) = "
              f"{2 * ZETA * 0.5 * math.exp(2.0):.8g}")
        panels.append(("rigid base, Stribeck v_s/V = 0.5", stribeck))
    fig = Figure(figsize=(5.0 * len(panels), 4.2), layout="constrained")
    for i, (title, result) in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), i + 1)
        result.plot(ax=ax)
        ax.set_title(title, fontsize="medium")
        ax.set_xlabel("lambda")
    path = args.out / "continuation_lambda.png"
    fig.savefig(path, dpi=110)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
