"""The worked example of docs/disturbances.md: a bistable slider, its basin and its safe region.

    .venv/bin/python docs/disturbances_example.py [--out docs/figures] [--samples 40000]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from stickslip import PhysicalSystem, simulate
from stickslip.analysis.disturbance import safe_disturbance
from stickslip.sweep.basin import basin_stability, sample_box
from stickslip.sweep.basin_maps import basin_map


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "figures")
    parser.add_argument("--samples", type=int, default=40_000)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    # the design worked example's machine at a lower speed: above the rigid-base boundary
    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=63.25,
                            mu_s=0.5, mu_k=0.3, load=150.0, speed=0.02)
    structure, slider = system.structure(), system.slider()
    print(f"lambda = {slider.lam:.4g}, zeta = {system.zeta:.4g}")
    print(f"from start-up: {simulate(structure, slider, record=False).verdict.value}")
    margin = safe_disturbance(structure, slider)
    print(f"safe margin: {margin.sentence(system)}")
    states = sample_box(structure, slider, args.samples, {"xi": (-6.0, 6.0), "v": (-4.0, 1.5)}, seed=1)
    result = basin_stability(structure, slider, states)
    fr, se = result.fractions, result.standard_errors
    print(f"basin: stick-slip {fr['stick-slip']:.4f} +- {se['stick-slip']:.4f}, steady sliding "
          f"{fr['steady-sliding']:.4f} +- {se['steady-sliding']:.4f} of {result.n} states "
          f"({result.samples_per_second:,.0f} samples/s)")
    result.plot(marker_size=2.0).savefig(args.out / "basin_rigid.png")
    print(f"figure written to {args.out / 'basin_rigid.png'}")

    # basin stability over the (lambda, zeta) plane: one fixed sample of knocks per cell
    n_lam, n_zeta, n_knocks = (8, 4, 100) if args.samples < 10_000 else (24, 12, 400)
    bmap = basin_map(np.geomspace(0.3, 20.0, n_lam), np.linspace(0.02, 0.3, n_zeta), "none",
                     samples=n_knocks, seed=1)
    column = bmap.dataset["stick_slip_fraction"].isel(**{"lambda": -1}).values
    print("stick-slip fraction at lambda = 20 by zeta: "
          + ", ".join(f"{z:.3g}: {f:.2f}" for z, f in zip(bmap.dataset["zeta"].values, column, strict=True)))
    bmap.plot().savefig(args.out / "basin_map_rigid.png")

    # over (lambda, delta) at zeta = 0.1: the linear law's slope delta > 0 weakens friction
    n_delta = 6 if args.samples < 10_000 else 12
    dmap = basin_map(np.geomspace(0.3, 10.0, n_lam), [0.1], "none", samples=n_knocks, seed=1,
                     deltas=np.linspace(-0.1, 0.2, n_delta))
    column = dmap.dataset["stick_slip_fraction"].isel(**{"lambda": -1}).values
    print("stick-slip fraction at lambda = 10 by delta: "
          + ", ".join(f"{d:.3g}: {f:.2f}" for d, f in zip(dmap.dataset["delta"].values, column, strict=True)))
    dmap.plot().savefig(args.out / "basin_map_delta.png")
    print(f"figure written to {args.out / 'basin_map_delta.png'}")


if __name__ == "__main__":
    main()
