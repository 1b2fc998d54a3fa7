"""The published bistable case of docs/continuation.md: its full bifurcation diagram.

    .venv/bin/python docs/continuation_bistable.py [--out docs/figures] [--range 0.2:0.7]

Rigid base, ``zeta = 0.05``, ``gamma = 1``, exponential Stribeck law with ``v_s / V = 1/3``
(``n = 1``), continued in ``lambda``. Prints the branches and events the page quotes and the
slip oscillation at ``lambda = 1/3`` as ``stickslip cycles`` finds it, and writes
``continuation_bistable.png``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from stickslip.analysis.continuation import ContinuationSystem, continue_cycles
from stickslip.analysis.slip_oscillations import find_slip_oscillations
from stickslip.model.friction import StribeckFriction


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "figures")
    parser.add_argument("--range", default="0.2:0.7")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    lo, hi = (float(x) for x in args.range.split(":"))
    system = ContinuationSystem(1.0 / 3.0, 0.05, 1.0, None, StribeckFriction(0.3333))
    structure, slider = system.build()
    for osc in find_slip_oscillations(structure, slider):
        print(f"at lambda = 1/3: slip oscillation, {'stable' if osc.stable else 'unstable'}, "
              f"period {osc.period:.6g}, amplitude {osc.amplitude:.6g}, multiplier {osc.multiplier:.4g}, "
              f"found by {', '.join(osc.found_by)}")
    result = continue_cycles(system, "lam", (lo, hi))
    print(result.summary())
    path = result.plot().savefig(args.out / "continuation_bistable.png", dpi=130)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
