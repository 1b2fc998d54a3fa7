"""The kernel's paths for structures of more than 2 DOF (issue 18 point 5, speed).

Beyond :data:`stickslip.kernel.system.ORIGINAL_ARITHMETIC_DOF` DOFs the engine solves the
slip-I Lyapunov equation by the matrix sign function (``O(n^3)``, not the ``O(n^6)`` Kronecker
form) and sets its step from a balanced norm (the plain infinity norm grows like the square of
the fastest frequency). References: ``scipy.linalg.solve_continuous_lyapunov`` and
``scipy.linalg.expm`` (independent implementations), ``numpy.linalg.eigvals`` for the fastest
frequency, and the 2-DOF preset for the unchanged arithmetic.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm as scipy_expm
from scipy.linalg import solve_continuous_lyapunov

from stickslip.kernel.linalg import inf_norm, inverse_lu, solve_lyapunov_sign, step_norm
from stickslip.kernel.polynomial import TAYLOR_DEGREE, taylor_state, taylor_vectors
from stickslip.kernel.system import STEP_THETA, mode_matrices, prepare, prepare_bands
from stickslip.model import Foundation, elastic_foundation


def chain(n: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A grounded chain of ``n`` masses with non-proportional damping (dimensionless)."""
    rng = np.random.default_rng(seed)
    mass = np.diag(rng.uniform(0.5, 2.0, n))
    mass[0, 0] = 1.0
    k = np.zeros((n, n))
    for i in range(n - 1):
        s = rng.uniform(1.0, 8.0)
        k[i, i] += s
        k[i + 1, i + 1] += s
        k[i, i + 1] -= s
        k[i + 1, i] -= s
    k[0, 0] += 1.0
    k[n - 1, n - 1] += 2.0
    b = rng.normal(size=(n, n))
    damping = 0.02 * (b @ b.T) + 0.05 * k
    return mass, damping, k


@pytest.mark.parametrize("n", [4, 6, 20])
@pytest.mark.slow  # 9 s: out of the default run (kept under ten minutes)
def test_sign_function_lyapunov_matches_scipy(n: int) -> None:
    mass, damping, k = chain(n, seed=n)
    ahat, _ = mode_matrices(mass, damping, k, 5.0, 2.0, np.array([10.0]), np.array([0.0]))
    a = np.ascontiguousarray(ahat[0, : 2 * n, : 2 * n])
    ours, ok = solve_lyapunov_sign(a, np.eye(2 * n))
    assert ok
    ref = solve_continuous_lyapunov(a.T, -np.eye(2 * n))
    assert np.abs(ours - ref).max() <= 1e-11 * np.abs(ref).max()
    assert np.abs(a.T @ ours + ours @ a + np.eye(2 * n)).max() <= 1e-10 * np.abs(ref).max()


def test_sign_function_lyapunov_refuses_a_matrix_that_is_not_stable() -> None:
    mass, damping, k = chain(6)
    ahat, _ = mode_matrices(mass, damping, k, 5.0, 2.0, np.array([10.0]), np.array([0.0]))
    a = np.ascontiguousarray(ahat[0, :12, :12])
    assert not solve_lyapunov_sign(-a, np.eye(12))[1]  # unstable: sign(-a) = +I
    undamped, _ = mode_matrices(mass, 0.0 * damping, k, 5.0, 2.0, np.array([10.0]), np.array([0.0]))
    assert not solve_lyapunov_sign(np.ascontiguousarray(undamped[0, :12, :12]), np.eye(12))[1]


def test_inverse_lu_matches_numpy() -> None:
    a = np.random.default_rng(5).normal(size=(30, 30))
    inv, ok = inverse_lu(a)
    assert ok
    assert np.abs(inv - np.linalg.inv(a)).max() <= 1e-12 * np.abs(np.linalg.inv(a)).max()
    assert not inverse_lu(np.ones((4, 4)))[1]


@pytest.mark.parametrize("n", [4, 6, 20])
@pytest.mark.slow  # 17 s: out of the default run (kept under ten minutes)
def test_balanced_step_is_short_against_the_fastest_period_and_longer_than_the_plain_one(n: int) -> None:
    # the event search assumes h * omega_max <= 1/2 (> 12 steps per fastest period)
    mass, damping, k = chain(n, seed=n)
    ahat, _, hstep = prepare(mass, damping, k, 5.0, 2.0)[:3]
    m = 2 * n
    for mode in range(3):
        a = ahat[mode, :m, :m]
        omega = np.abs(np.linalg.eigvals(a)).max()
        assert hstep[mode] * omega <= STEP_THETA * (1 + 1e-12)
        assert hstep[mode] >= STEP_THETA / inf_norm(np.ascontiguousarray(a))
    if n == 20:  # the stiff chain: the balanced norm is what makes the steps long
        assert hstep[0] > 2.0 * STEP_THETA / inf_norm(np.ascontiguousarray(ahat[0, :m, :m]))


@pytest.mark.parametrize("mode", [0, 1, 2])
def test_taylor_polynomial_over_a_balanced_step_is_the_exponential(mode: int) -> None:
    # the event search evaluates the degree-16 Taylor polynomial anywhere on a step
    mass, damping, k = chain(20, seed=20)
    ahat, phi, hstep = prepare(mass, damping, k, 5.0, 2.0)[:3]
    w0 = np.r_[np.random.default_rng(mode).normal(size=40), 1.0]
    u = np.empty((TAYLOR_DEGREE + 1, 41))
    taylor_vectors(ahat[mode], w0, u)
    for s in (0.37 * hstep[mode], hstep[mode]):
        out = np.empty(41)
        taylor_state(u, s, out)
        ref = scipy_expm(ahat[mode] * s) @ w0
        assert np.abs(out - ref).max() <= 1e-13 * np.abs(ref).max()
    assert np.abs(phi[mode] - scipy_expm(ahat[mode] * hstep[mode])).max() <= 1e-13


def test_two_dof_structures_keep_the_plain_norm_step() -> None:
    # ORIGINAL_ARITHMETIC_DOF: the paper's presets (and 3-DOF chains) keep their step grid
    st = elastic_foundation(0.07, Foundation(1.7, 1.2, 0.8))
    ahat, _, hstep = prepare(st.mass, st.damping, st.stiffness, 2.5, 2.0)[:3]
    for mode in range(3):
        a = np.ascontiguousarray(ahat[mode, :4, :4])
        assert step_norm(a, 2) == inf_norm(a)
        assert hstep[mode] == STEP_THETA / inf_norm(a)


@pytest.mark.parametrize("law", ["coulomb", "bands"])
def test_slip_ii_step_from_the_shared_block_is_the_exponential(law: str) -> None:
    # beyond 3 DOF slip-II's step reuses slip-I's block (forced_step); reference: scipy expm
    mass, damping, k = chain(6, seed=3)
    if law == "coulomb":
        prepared = prepare(mass, damping, k, 5.0, 2.0)
    else:  # two affine bands (a velocity-weakening kink at u = 0.5): slip-I is forced too
        prepared = prepare_bands(mass, damping, k, 5.0, 2.0, np.array([0.0, 0.5, np.inf]),
                                 np.array([11.0, 10.6]), np.array([-1.0, -0.2]))
    ahat, phi, hstep = prepared[:3]
    for mode in range(ahat.shape[0]):
        ref = scipy_expm(ahat[mode] * hstep[mode])
        assert np.abs(phi[mode] - ref).max() <= 1e-13 * np.abs(ref).max(), mode


def test_phase_record_grows_past_its_first_size() -> None:
    # the record starts at RECORD_START phases and doubles; a long run keeps every phase.
    # Reference: the certified cycle (stick then slip-I, period T), so after the cycle is
    # reached phase k + 2 starts T after phase k; and the run without record has the same ends.
    from stickslip import EngineOptions, Slider, rigid_base, simulate
    from stickslip.kernel.engine import RECORD_START

    st, slider = rigid_base(0.05), Slider(2.0)
    opts = EngineOptions(t_max=4000.0)
    res = simulate(st, slider, options=opts, run_to_t_max=True)
    bare = simulate(st, slider, options=opts, run_to_t_max=True, record=False)
    seg = res.segment_times
    assert seg.size > 2 * RECORD_START
    assert np.all(np.diff(seg) > 0.0)
    tail = seg[-2 * RECORD_START:]
    assert np.allclose(tail[2:] - tail[:-2], res.period, rtol=1e-9)
    assert res.breakaway_times.size == res.n_breakaway > RECORD_START
    assert np.array_equal(res.final_state, bare.final_state) and res.t_end == bare.t_end
