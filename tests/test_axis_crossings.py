"""The exact critical friction coefficient: every crossing of the imaginary axis, none skipped.

Oracle throughout: numpy's eigenvalues of the unscaled first-order matrix
``[[0, I], [-M^-1 K(mu), -M^-1 C(mu)]]`` built here from ``FrictionCoupledSystem.matrices``
(whose linearisation is checked against the equations of motion in
tests/test_complex_eigenvalues.py), read at many values of ``mu``.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment

from stickslip.analysis.contact.axis_crossings import (
    bialternate_sum,
    crossing_candidates,
    steady_normal_force_pole,
)
from stickslip.analysis.contact.critical_coefficient import critical_friction
from stickslip.analysis.contact.friction_coupling import FrictionCoupledSystem


def _growth(system: FrictionCoupledSystem, mu: float) -> float:
    """Largest real part of the eigenvalues at ``mu`` (1/s): the oracle."""
    m, c, k = system.matrices(mu)
    n = m.shape[0]
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(m, k), -np.linalg.solve(m, c)]])
    return float(np.linalg.eigvals(a).real.max())


def _random_system(rng: np.random.Generator, n: int, slope: float) -> FrictionCoupledSystem:
    a, b = rng.normal(size=(n, n)), rng.normal(size=(n, n))
    t, nd = rng.choice(n, 2, replace=False)
    return FrictionCoupledSystem(np.diag(rng.uniform(0.5, 2.0, n)),
                                 rng.uniform(0.001, 0.1) * (b @ b.T), a @ a.T + n * np.eye(n),
                                 int(t), int(nd), normal_stiffness=rng.uniform(0.5, 5.0),
                                 normal_damping=rng.uniform(0.0, 0.2), slope=slope)


@pytest.mark.parametrize("m", [2, 3, 4, 6, 9])
def test_bialternate_sum_has_the_pairwise_sums_as_eigenvalues(m: int) -> None:
    # Stephanos (1900): the eigenvalues of 2A (.) I are s_i + s_j, i < j
    a = np.random.default_rng(m).normal(size=(m, m))
    s = np.linalg.eigvals(a)
    sums = np.array([s[i] + s[j] for i in range(m) for j in range(i)])
    got = np.linalg.eigvals(bialternate_sum(a))
    assert got.shape == sums.shape
    cost = np.abs(sums[:, None] - got[None, :])
    rows, cols = linear_sum_assignment(cost)
    assert cost[rows, cols].max() < 1e-12 * max(1.0, float(np.abs(s).max()))


def test_steady_normal_force_is_the_sherman_morrison_closed_form() -> None:
    # N_0(mu) = W / (1 + a mu), a = k_n (K_0^-1)_nt, against the equilibrium solved directly
    rng = np.random.default_rng(11)
    for n in (2, 3, 5):
        system = dataclasses.replace(_random_system(rng, n, 0.0), load=7.5)
        a = steady_normal_force_pole(system)
        for mu in (0.1, 0.6, 1.7):
            assert system.normal_force(mu) == pytest.approx(7.5 / (1 + a * mu), rel=1e-12)


def _narrow_window_system() -> FrictionCoupledSystem:
    """3 DOF whose steady sliding is unstable only for mu in about [0.73786, 0.73980].

    Found by a random search and a damping scale (1.0631...) tuned until the window was
    narrower than the old scan's step (2 / 400 = 0.005) and fell between two of its points.
    """
    damping = np.array([[0.06746639973246328, -0.07665833315690349, -0.010076062587705163],
                        [-0.07665833315690349, 0.22973509955950605, 0.026274559059895237],
                        [-0.010076062587705163, 0.026274559059895237, 0.007459951204565108]])
    stiffness = np.array([[6.270995454224508, 1.0004302218838719, 1.5367425192221413],
                          [1.0004302218838719, 3.8516016132621598, 0.5278710866280099],
                          [1.5367425192221413, 0.5278710866280099, 4.615328532798338]])
    return FrictionCoupledSystem(np.diag([1.882663122702684, 1.389747360093557, 1.8034392162225448]),
                                 1.0631286621093747 * damping, stiffness, 2, 0,
                                 normal_stiffness=3.4446096410953113,
                                 normal_damping=0.032468564260466404)


def test_a_window_narrower_than_the_old_scan_step_is_found() -> None:
    system = _narrow_window_system()
    # the old search's 401 points all see stable sliding: it would have answered "none"
    assert all(_growth(system, float(mu)) < 0.0 for mu in np.linspace(0.0, 2.0, 401))
    found = critical_friction(system, mu_max=2.0)
    assert found.mu is not None and found.method.startswith("exact")
    assert found.kind == "flutter"
    # oracle: a fine scan over the window finds its first unstable point next to found.mu
    fine = np.linspace(0.735, 0.745, 10_001)
    unstable = fine[[_growth(system, float(mu)) > 0.0 for mu in fine]]
    print(f"exact {found.mu:.12f} | fine scan {unstable[0]:.7f} .. {unstable[-1]:.7f}")
    assert abs(found.mu - unstable[0]) <= 1.0e-6
    assert unstable[-1] - unstable[0] < 0.005  # narrower than the old scan step
    assert found.bracket is not None
    assert _growth(system, found.bracket[0]) < 0.0 < _growth(system, found.bracket[1])
    roots = crossing_candidates(system, 2.0)
    assert roots is not None and len(roots) == 2  # in and out of the window


@pytest.mark.parametrize("seed", range(4))
def test_exact_critical_mu_against_the_eigenvalues_of_random_machines(seed: int) -> None:
    # 2-6 DOF, non-proportional damping, half of them with a falling or rising friction law
    rng = np.random.default_rng(100 + seed)
    exact = 0
    for trial in range(10):
        n = int(rng.integers(2, 7))
        system = _random_system(rng, n, float(rng.uniform(-0.05, 0.05)) * (trial % 2))
        if _growth(system, 0.0) >= 0.0:
            continue  # unstable without friction: nothing to search
        found = critical_friction(system, mu_max=2.0)
        assert found.method.startswith("exact"), found.method
        exact += 1
        top = 2.0 if found.mu is None else found.mu
        grid = np.linspace(0.0, 2.0, 401)
        assert all(_growth(system, float(mu)) < 0.0 for mu in grid[grid < top * (1 - 1e-7)])
        if found.mu is not None:
            assert _growth(system, found.mu * (1 - 1e-6)) < 0.0 < _growth(system, found.mu * (1 + 1e-6))
    assert exact >= 5


def test_where_the_roots_cannot_prove_the_scan_answers_and_says_so() -> None:
    rng = np.random.default_rng(5)
    # 23 DOF: the bialternate pencil has 1035 rows, beyond the exact search's bound
    big = _random_system(rng, 23, 0.0)
    found = critical_friction(big, mu_max=0.5, n_scan=20)
    assert "scan" in found.method and not found.method.startswith("exact")
    # undamped: its spectrum is on the axis for every mu below the coalescence (a singular pencil)
    small = _random_system(rng, 3, 0.0)
    assert crossing_candidates(small, 2.0) is not None
    assert crossing_candidates(small.undamped(), 2.0) is None


def _undamped_marginal(system: FrictionCoupledSystem, mu: float) -> bool:
    """Oracle: every squared frequency of M^-1 K(mu) real and positive (numpy)."""
    m, _, k = system.matrices(mu)
    lam = np.linalg.eigvals(np.linalg.solve(m, k))
    return bool(np.all(np.abs(lam.imag) <= 1e-9 * np.abs(lam)) and np.all(lam.real > 0.0))


@pytest.mark.parametrize("seed", range(3))
def test_exact_undamped_critical_mu_against_the_squared_frequencies(seed: int) -> None:
    # the first mu where two squared frequencies merge (flutter) or one reaches 0 (divergence)
    rng = np.random.default_rng(200 + seed)
    for _ in range(10):
        system = _random_system(rng, int(rng.integers(2, 7)), 0.0).undamped()
        found = critical_friction(system, mu_max=3.0)
        assert found.method.startswith("exact"), found.method
        top = 3.0 if found.mu is None else found.mu
        grid = np.linspace(0.0, 3.0, 601)
        assert all(_undamped_marginal(system, float(mu)) for mu in grid[grid < top * (1 - 1e-7)])
        if found.mu is not None:
            assert _undamped_marginal(system, found.mu * (1 - 1e-6))
            assert not _undamped_marginal(system, found.mu * (1 + 1e-6))
