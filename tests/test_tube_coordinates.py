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


def test_the_rounding_allowance_counts_the_engines_steps_in_any_coordinates() -> None:
    # the engine steps with h ||A||_F <= 1/2 in its own coordinates (q, v); the allowance for
    # its rounding must not shrink because the tube is bounded in other coordinates (an audit:
    # counted with the energy coordinates' norm it fell 1.7-2.6x on 25-44 DOF machines, to
    # 1.04x the error measured in extended precision). Source: the allowance of the same
    # nominal run sampled in the engine's coordinates
    from stickslip import Slider, elastic_foundation, simulate
    from stickslip.analysis._cycle_tube import phases, rounding_allowance
    from stickslip.analysis.engine_run import EngineOptions
    from stickslip.analysis.return_map import ReturnMap
    from stickslip.model.friction import LinearFriction
    from stickslip.model.parameters import Foundation

    structure = elastic_foundation(0.1, Foundation(1.17013, 0.109102, 0.69939))
    slider = Slider(3.0, friction=LinearFriction(0.8))
    run = simulate(structure, slider, options=EngineOptions(t_max=20000))
    pmap = ReturnMap(structure, slider, EngineOptions())
    b_hat = pmap.reduce(run.cycle_proof.fixed_point)
    energy = Coordinates.energy(np.asarray(structure.mass), np.asarray(structure.stiffness))
    in_energy = phases(pmap, b_hat, 1, energy)
    in_engine = phases(pmap, b_hat, 1, Coordinates.identity(4))
    assert in_energy is not None and in_engine is not None
    tube_norms = [ph.norm_a for ph in in_energy[0]]
    engine_norms = [ph.norm_a for ph in in_engine[0]]
    assert tube_norms != pytest.approx(engine_norms, rel=1e-3)  # the coordinates differ
    assert rounding_allowance(in_energy[0], 1.0) == pytest.approx(
        rounding_allowance(in_engine[0], 1.0), rel=1e-12)
