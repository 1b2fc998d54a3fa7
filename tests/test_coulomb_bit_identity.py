"""The paper's Coulomb law gives bit-for-bit the answers of the engine before friction laws.

Reference: ``tests/data/coulomb_reference.json``, written by ``tests/make_coulomb_reference.py``
with the engine at commit 6c94c46 (before any generalisation). Every float is compared
exactly (``float.hex``), so any change in rounding fails this test.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from stickslip import Foundation, Slider, chain_structure, simulate

CASES = json.loads((Path(__file__).parent / "data" / "coulomb_reference.json").read_text())


def _hex(values: object) -> list[str]:
    return [float(x).hex() for x in np.asarray(values, dtype=np.float64).reshape(-1)]


def _case_id(c: dict) -> str:
    return f"lam{c['lam']}-zeta{c['zeta']}-n{len(c['foundations'])}"


@pytest.mark.parametrize("case", CASES, ids=_case_id)
def test_coulomb_results_are_bit_identical(case: dict) -> None:
    structure = chain_structure(case["zeta"], tuple(Foundation(*f) for f in case["foundations"]))
    result = simulate(structure, Slider(case["lam"], gamma=case["gamma"]))
    fsum = [float.fromhex(x) for x in case["fsum"]]
    isum = case["isum"]
    assert result.status.code == isum[0]
    assert (result.n_stick, result.cycle_length, result.n_breakaway, result.n_steps) == (
        isum[1], isum[2], isum[3], isum[5])
    found = [result.lyapunov_bound, result.period, result.amplitude, result.xi_range[0],
             result.xi_range[1], result.stick_ratio, result.cycle_max_velocity, result.max_velocity,
             result.cycle_mismatch, result.t_end]
    assert _hex(found) == _hex(fsum[:10])
    assert _hex(result.segment_times) == case["segment_times"]
    assert [int(m) for m in result.segment_modes] == case["segment_modes"]
    assert _hex(result.final_state) == case["final_state"]
