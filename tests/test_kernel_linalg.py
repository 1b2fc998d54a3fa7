"""Kernel linear algebra against SciPy: expm, Lyapunov equation, Taylor propagation."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm as scipy_expm
from scipy.linalg import solve_continuous_lyapunov

from stickslip.kernel.linalg import expm, expm_at, solve_lyapunov
from stickslip.kernel.polynomial import TAYLOR_DEGREE, taylor_state, taylor_vectors


@pytest.mark.parametrize("seed", range(6))
def test_expm_matches_scipy(seed: int) -> None:
    # reference: scipy.linalg.expm (Al-Mohy and Higham), an independent implementation
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(5, 5)) * (0.3 + 3 * seed)
    ours = expm(a)
    ref = scipy_expm(a)
    assert np.allclose(ours, ref, rtol=1e-12, atol=1e-12 * np.abs(ref).max())


def test_expm_at_is_the_exponentials_one_at_a_time_bit_for_bit() -> None:
    # expm_at (the cycle proof's refined sample times, in one call) promises the bits of
    # expm(a * t) taken one at a time, as the proof took them before (same product, same kernel)
    rng = np.random.default_rng(5)
    for _ in range(50):
        a = rng.normal(size=(5, 5)) * rng.uniform(0.01, 10.0)
        times = rng.uniform(0.0, 3.0, size=9) * 2.0 ** -rng.integers(0, 40, size=9)
        stack = expm_at(a, times)
        assert stack.shape == (9, 5, 5)
        for t, e in zip(times, stack, strict=True):
            assert np.array_equal(e, expm(a * t))


def test_expm_of_nilpotent_jordan_block_is_exact() -> None:
    # the stick mode has q0' = 1: a Jordan block, exp([[0, 1], [0, 0]] t) = [[1, t], [0, 1]]
    a = np.array([[0.0, 1.0], [0.0, 0.0]]) * 7.5
    assert np.array_equal(expm(a), np.array([[1.0, 7.5], [0.0, 1.0]]))


@pytest.mark.parametrize("seed", range(4))
def test_lyapunov_matches_scipy(seed: int) -> None:
    # reference: scipy.linalg.solve_continuous_lyapunov solves A X + X A^H = Q
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(4, 4)) - 4.0 * np.eye(4)
    q = np.eye(4)
    ours, ok = solve_lyapunov(a, q)
    assert ok
    ref = solve_continuous_lyapunov(a.T, -q)
    assert np.allclose(ours, ref, rtol=1e-11, atol=1e-13)
    assert np.allclose(a.T @ ours + ours @ a, -q, atol=1e-11)


@pytest.mark.parametrize("s", [0.0, 0.013, 0.2, 0.5])
def test_taylor_polynomial_equals_matrix_exponential(s: float) -> None:
    # w(s) = expm(A s) w0 within a sub-step (||A|| s <= 1/2): truncation error ~ 0.5^17/17!
    rng = np.random.default_rng(42)
    a = rng.normal(size=(5, 5))
    a /= np.abs(a).sum(axis=1).max()
    w0 = rng.normal(size=5)
    u = np.empty((TAYLOR_DEGREE + 1, 5))
    taylor_vectors(a, w0, u)
    out = np.empty(5)
    taylor_state(u, s, out)
    assert np.allclose(out, scipy_expm(a * s) @ w0, rtol=1e-14, atol=1e-14)


def test_lyapunov_reports_a_singular_equation() -> None:
    # an undamped oscillator has eigenvalues +-i, which sum to zero: no unique solution
    a = np.array([[0.0, 1.0], [-1.0, 0.0]])
    _, ok = solve_lyapunov(a, np.eye(2))
    assert not ok


def test_inverse_of_a_diagonal_mass_is_exact() -> None:
    # the engine inverts mass matrices without LAPACK; for the paper's diagonal masses the
    # result must be exactly 1/M (what LAPACK gives, so old results stay bit for bit)
    from stickslip.kernel.linalg import inverse

    rng = np.random.default_rng(7)
    for _ in range(200):
        d = 10 ** rng.uniform(-3, 3, size=rng.integers(1, 5))
        assert np.array_equal(inverse(np.diag(d)), np.diag(1.0 / d))
    full = rng.normal(size=(4, 4)) + 4 * np.eye(4)
    assert np.allclose(inverse(full) @ full, np.eye(4), atol=1e-13)


def test_batch_startup_state_is_bit_identical_to_the_model_startup() -> None:
    # source: stickslip.model.startup_state (numpy), which simulate() uses; a map cell must
    # start from the same state bit for bit (rigid base and one foundation stage)
    from stickslip import Foundation, Slider, chain_structure, startup_state
    from stickslip.kernel.batch import startup_vector

    rng = np.random.default_rng(3)
    for _ in range(500):
        stages = () if rng.random() < 0.2 else (Foundation(10 ** rng.uniform(-2, 2),
                                                          10 ** rng.uniform(-2, 2), 0.3),)
        st = chain_structure(0.1, stages)
        lam, gamma = 10 ** rng.uniform(-2, 2), rng.uniform(0, 5)
        ref = startup_state(st, Slider(lam, gamma=gamma))
        z0 = startup_vector(st.stiffness, lam, gamma)
        assert np.array_equal(z0, np.concatenate([ref.position, ref.velocity]))
