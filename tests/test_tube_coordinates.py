"""The coordinates a cycle proof's tube is bounded in (stickslip.analysis._cycle_tube.Coordinates)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from stickslip.analysis._cycle_tube import Coordinates


def _random_structure(rng: np.random.Generator, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    def spd(scale: float) -> np.ndarray:
        x = rng.normal(size=(n, n))
        return x @ x.T + scale * np.eye(n)

    mass, stiffness = spd(0.1), spd(0.01) * 100.0
    x = rng.normal(size=(n, n))
    return mass, 0.1 * (x @ x.T), stiffness  # damping positive semi-definite


@pytest.mark.parametrize("n", [1, 2, 5])
def test_energy_coordinates_measure_the_mechanical_energy(n: int) -> None:
    # definition: y = T^-1 z with |y|^2 = q' K q + v' M v (twice the mechanical energy), and
    # T T^-1 = I (source: the quadratic forms evaluated directly)
    rng = np.random.default_rng(n)
    mass, _, stiffness = _random_structure(rng, n)
    coords = Coordinates.energy(mass, stiffness)
    assert np.allclose(coords.to_state @ coords.from_state, np.eye(2 * n), atol=1e-12)
    for _ in range(5):
        q, v = rng.normal(size=n), rng.normal(size=n)
        y = coords.from_state @ np.concatenate([q, v])
        assert y @ y == pytest.approx(q @ stiffness @ q + v @ mass @ v, rel=1e-12)
    assert coords.to_state_norm == pytest.approx(np.linalg.norm(coords.to_state, 2))
    assert coords.from_state_norm == pytest.approx(np.linalg.norm(coords.from_state, 2))


@pytest.mark.parametrize("seed", range(4))
def test_a_passive_flow_does_not_grow_in_energy_coordinates(seed: int) -> None:
    # M q'' + C q' + K q = 0 with C positive semi-definite: dE/dt = -v' C v <= 0, so
    # ||expm(A_y t)||_2 <= 1 in the energy coordinates for every t >= 0, while in (q, v) the
    # same flow can grow (by up to sqrt of the condition numbers); source: scipy's expm
    rng = np.random.default_rng(seed)
    n = 4
    mass, damping, stiffness = _random_structure(rng, n)
    minv = np.linalg.inv(mass)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ stiffness, -minv @ damping]])
    coords = Coordinates.energy(mass, stiffness)
    a_y = coords.from_state @ a @ coords.to_state
    grows = 0.0
    for t in np.linspace(0.0, 20.0, 81):
        assert np.linalg.norm(scipy.linalg.expm(a_y * t), 2) <= 1.0 + 1e-9
        grows = max(grows, float(np.linalg.norm(scipy.linalg.expm(a * t), 2)))
    assert grows > 1.0  # the engine's coordinates do not have that property


def test_without_an_energy_norm_the_coordinates_are_the_engines() -> None:
    # a stiffness matrix with a rigid-body mode (a free chain) has no energy norm of q
    mass = np.eye(2)
    stiffness = np.array([[1.0, -1.0], [-1.0, 1.0]])
    coords = Coordinates.energy(mass, stiffness)
    assert np.array_equal(coords.to_state, np.eye(4)) and np.array_equal(coords.from_state, np.eye(4))
