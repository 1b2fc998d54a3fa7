"""Write ``tests/data/coulomb_reference.json``: bit-exact engine outputs for the Coulomb law.

Generated once with the engine as it stood before friction laws were added (commit 6c94c46),
so that ``tests/test_coulomb_bit_identity.py`` proves a generalisation never changes old answers
(every float is stored with ``float.hex``). Run: ``python tests/make_coulomb_reference.py``.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from stickslip.kernel import engine
from stickslip.model.structure import chain_structure

#: (lambda, zeta, gamma, foundations as (M, K, zeta_a) tuples)
CASES = [
    (3.0, 0.1, 2.0, ()),
    (1.4701, 0.1, 2.0, ()),
    (0.5, 0.05, 2.0, ()),
    (8.0, 0.3, 1.0, ()),
    (2.0, 0.0, 2.0, ()),
    (3.0, 0.1, 2.0, ((3.112, 1.1061, 1.4638),)),
    (15.0, 0.1, 2.0, ((2.824, 1.09102, 1.4981),)),
    (6.0, 0.01, 2.0, ((1.4846, 0.9479, 1.1284),)),
    (40.0, 0.2, 0.5, ((2.8, 0.6, 1.2),)),
    (5.0, 0.05, 2.0, ((1.0, 1.0, 0.5), (2.0, 1.5, 0.3))),
]


def startup(stiffness: np.ndarray, lam: float, gamma: float) -> np.ndarray:
    n = stiffness.shape[0]
    e0 = np.zeros(n)
    e0[0] = 1.0
    z0 = np.zeros(2 * n)
    z0[:n] = -gamma * lam * np.linalg.solve(stiffness, e0)
    z0[n] = 1.0
    return z0


def main() -> None:
    from stickslip.model.parameters import Foundation

    out = []
    for lam, zeta, gamma, stages in CASES:
        st = chain_structure(zeta, tuple(Foundation(*s) for s in stages))
        z0 = startup(st.stiffness, lam, gamma)
        seg_t, seg_mode, _, _, fsum, isum, z_end = engine.run(
            st.mass, st.damping, st.stiffness, lam, gamma, z0, 5000.0, 100_000, 1e-9, 8, True, False
        )
        out.append({
            "lam": lam, "zeta": zeta, "gamma": gamma, "foundations": [list(s) for s in stages],
            "fsum": [float(x).hex() for x in fsum],
            "isum": [int(x) for x in isum],
            "segment_times": [float(x).hex() for x in seg_t],
            "segment_modes": [int(x) for x in seg_mode],
            "final_state": [float(x).hex() for x in z_end],
        })
    path = Path(__file__).parent / "data" / "coulomb_reference.json"
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {len(out)} cases to {path}")


if __name__ == "__main__":
    main()
