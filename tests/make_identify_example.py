"""Write ``examples/rig_record.csv``: the synthetic stick-slip record of the identification guide.

Made by the independent SI simulator of ``tests/record_oracle.py`` (solve_ivp, not the
engine): a 1 kg slider, k = 10 kN/m, c = 5 N s/m, mu_s = 0.6, Coulomb mu_k = 0.4, W = 100 N,
V = 5 cm/s; 1.2 s sampled at 2 kHz starting in the middle of a slip phase; 0.5 % noise (of the
peak-to-peak range) on F and x, and a load-cell zero that is off by 1.5 N and drifts by
2 N/s. Run: ``python tests/make_identify_example.py``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from tests.record_oracle import coulomb, noisy, simulate_rig

TRUTH = {"m": 1.0, "k": 1.0e4, "c": 5.0, "mu_s": 0.6, "mu_k": 0.4, "load": 100.0, "speed": 0.05}
OFFSET, DRIFT = 1.5, 2.0
PATH = Path(__file__).resolve().parents[1] / "examples" / "rig_record.csv"


def main() -> None:
    rng = np.random.default_rng(19)
    rig = simulate_rig(m=TRUTH["m"], k=TRUTH["k"], c=TRUTH["c"], mu_s=TRUTH["mu_s"],
                       mu=coulomb(TRUTH["mu_k"]), load=TRUTH["load"], speed=TRUTH["speed"], t_end=1.43,
                       fs=2000.0, t_start=0.23)
    force = noisy(rig.F, 0.005, rng) + OFFSET + DRIFT * rig.t
    x = noisy(rig.x, 0.005, rng)
    rows = "\n".join(f"{t:.6f},{1e3 * xi:.6f},{f:.5f}" for t, xi, f in zip(rig.t, x, force, strict=True))
    PATH.write_text(
        "# synthetic stick-slip rig record for docs/identification.md (tests/make_identify_example.py)\n"
        "# truth: m 1 kg, k 10 kN/m, c 5 N s/m, mu_s 0.6, mu_k 0.4 (Coulomb), W 100 N, V 5 cm/s;\n"
        "# load-cell offset 1.5 N drifting 2 N/s; 0.5 % noise\n"
        "t [s],x [mm],F [N]\n" + rows + "\n"
    )


if __name__ == "__main__":
    main()
