"""The per-mode matrices against the paper's Eqs. (19)-(27), and the propagators against expm."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm as scipy_expm

from stickslip.kernel.system import SLIP_I, SLIP_II, STICK, prepare
from stickslip.model import Foundation, elastic_foundation

M, K, ZA, Z, LAM, GAMMA = 1.7, 1.2, 0.8, 0.07, 2.5, 2.0


def _prepared():
    st = elastic_foundation(Z, Foundation(M, K, ZA))
    return prepare(st.mass, st.damping, st.stiffness, LAM, GAMMA)


def _paper_rhs(mode: int, xi: float, xia: float, v: float, va: float) -> tuple[float, float]:
    """Accelerations written term by term from Eqs. (21), (23)-(24) and (26)-(27)."""
    if mode == STICK:
        acc_a = (2 * Z - 2 * Z * va - 2 * ZA * va + xi - xia - K**2 * xia) / M  # Eq. (21)
        return 0.0, acc_a
    rhs = -2 * GAMMA * LAM if mode == SLIP_II else 0.0
    acc = rhs - 2 * Z * v + 2 * Z * va - xi + xia  # Eqs. (23), (26)
    acc_a = (2 * Z * v - 2 * Z * va - 2 * ZA * va + xi - xia - K**2 * xia) / M  # Eqs. (24), (27)
    return acc, acc_a


@pytest.mark.parametrize("mode", [SLIP_I, SLIP_II, STICK])
def test_mode_matrices_reproduce_the_paper_equations(mode: int) -> None:
    ahat = _prepared()[0]
    rng = np.random.default_rng(mode)
    for _ in range(5):
        xi, xia, v, va = rng.normal(size=4)
        if mode == STICK:
            v = 1.0
        w = np.array([xi, xia, v, va, 1.0])
        dw = ahat[mode] @ w
        acc, acc_a = _paper_rhs(mode, xi, xia, v, va)
        assert dw[0] == pytest.approx(v, abs=1e-15)
        assert dw[1] == pytest.approx(va, abs=1e-15)
        assert dw[2] == pytest.approx(acc, abs=1e-13)
        assert dw[3] == pytest.approx(acc_a, abs=1e-13)
        assert dw[4] == 0.0


def test_stick_force_row_is_eq_20() -> None:
    # S = 2 zeta (1 - xi_a') + xi - xi_a, the middle term of Eq. (20)
    stick_row = _prepared()[7]
    w = np.array([0.3, -0.4, 1.0, 0.25, 1.0])
    assert stick_row @ w == pytest.approx(2 * Z * (1 - 0.25) + 0.3 + 0.4, abs=1e-15)


@pytest.mark.parametrize("mode", [SLIP_I, SLIP_II, STICK])
def test_step_propagator_is_the_matrix_exponential(mode: int) -> None:
    # reference: scipy.linalg.expm of the augmented affine system over one step
    ahat, phi, hstep = _prepared()[:3]
    ref = scipy_expm(ahat[mode] * hstep[mode])
    assert np.allclose(phi[mode], ref, rtol=1e-13, atol=1e-14)


def test_step_is_short_against_the_fastest_period() -> None:
    # the graze-proof event search assumes h * ||A|| <= 1/2, i.e. > 12 steps per period
    ahat, _, hstep = _prepared()[:3]
    for mode in (SLIP_I, SLIP_II, STICK):
        omega = np.abs(np.linalg.eigvals(ahat[mode][:4, :4])).max()
        assert hstep[mode] * omega <= 0.5 + 1e-12
