"""The generalised engine with the Coulomb band table returns the old engine's numbers bit for bit.

Reference: ``tests/data/coulomb_reference.json``, written by ``tests/make_coulomb_reference.py``
with the engine before friction laws (commit 6c94c46); every float is compared through
``float.hex``, so a single changed bit fails.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from stickslip.kernel import engine
from stickslip.model.parameters import Foundation
from stickslip.model.structure import chain_structure

REFERENCE = json.loads((Path(__file__).parent / "data" / "coulomb_reference.json").read_text())


def _startup(stiffness: np.ndarray, lam: float, gamma: float) -> np.ndarray:
    n = stiffness.shape[0]
    e0 = np.zeros(n)
    e0[0] = 1.0
    z0 = np.zeros(2 * n)
    z0[:n] = -gamma * lam * np.linalg.solve(stiffness, e0)
    z0[n] = 1.0
    return z0


@pytest.mark.parametrize("case", REFERENCE, ids=lambda c: f"lam{c['lam']}-n{len(c['foundations'])}")
def test_coulomb_band_table_is_bit_identical(case: dict) -> None:
    lam, zeta, gamma = case["lam"], case["zeta"], case["gamma"]
    st = chain_structure(zeta, tuple(Foundation(*s) for s in case["foundations"]))
    z0 = _startup(st.stiffness, lam, gamma)
    edges = np.array([0.0, np.inf])
    intercepts = np.array([gamma * lam])
    slopes = np.array([0.0])
    seg_t, seg_mode, _, _, fsum, isum, z_end = engine.run(
        st.mass, st.damping, st.stiffness, lam, gamma, edges, intercepts, slopes, z0,
        5000.0, 100_000, 1e-9, 8, True, False,
    )
    assert [float(x).hex() for x in fsum] == case["fsum"]
    assert [int(x) for x in isum] == case["isum"]
    assert [float(x).hex() for x in seg_t] == case["segment_times"]
    assert [int(x) for x in seg_mode] == case["segment_modes"]
    assert [float(x).hex() for x in z_end] == case["final_state"]
