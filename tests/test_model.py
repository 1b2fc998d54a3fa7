"""Model layer: validation, structures of the paper, physical units both ways."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from stickslip.model import (
    Foundation,
    PhysicalFoundation,
    PhysicalSystem,
    Slider,
    Structure,
    chain_structure,
    elastic_foundation,
    rigid_base,
    startup_state,
)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"lam": 0.0}, "lambda=0.0 must be positive"),
        ({"lam": -1.0}, "must be positive"),
        ({"lam": float("nan")}, "must be finite"),
        ({"lam": 1.0, "gamma": -2.0}, "gamma"),
    ],
)
def test_slider_rejects_bad_values(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        Slider(**kwargs)


@pytest.mark.parametrize(("zeta", "message"), [(-0.1, "zeta=-0.1 must not be negative"),
                                              (float("inf"), "must be finite")])
def test_structure_rejects_bad_zeta(zeta: float, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        chain_structure(zeta)


def test_slider_gamma_is_keyword_only() -> None:
    # zeta lives in the structure; a positional second number must not silently become gamma
    with pytest.raises(TypeError):
        Slider(3.0, 0.1)  # type: ignore[misc]


STAGES = [(), (Foundation(1.5, 0.9, 1.1),), (Foundation(1, 1, 0.5), Foundation(2, 1.5, 0.3))]


@pytest.mark.parametrize("stages", STAGES)
def test_structure_zeta_is_the_primary_damping(stages: tuple) -> None:
    # Section 2.3: zeta = c / (2 sqrt(mk)) is the only damper on DOF 0 of the chain
    assert chain_structure(0.137, stages).zeta == pytest.approx(0.137, rel=1e-15)


@pytest.mark.parametrize(
    "args", [(0.0, 1.0, 0.1), (1.0, 0.0, 0.1), (1.0, 1.0, -0.1), (-1.0, 1.0, 0.1)]
)
def test_foundation_rejects_bad_values(args: tuple) -> None:
    with pytest.raises(ValueError):
        Foundation(*args)


def test_structure_rejects_singular_or_asymmetric_matrices() -> None:
    with pytest.raises(ValueError, match="mass matrix must be positive definite"):
        Structure(np.diag([1.0, 0.0]), np.zeros((2, 2)), np.eye(2))
    with pytest.raises(ValueError, match="symmetric"):
        Structure(np.eye(2), np.zeros((2, 2)), np.array([[2.0, -1.0], [0.0, 2.0]]))
    with pytest.raises(ValueError, match="stiffness"):
        Structure(np.eye(1), np.zeros((1, 1)), np.zeros((1, 1)))


def test_two_dof_matrices_are_those_of_eqs_23_24() -> None:
    # Eqs. (23)-(24): xi'' + 2z(xi' - xi_a') + xi - xi_a = 0,
    # M xi_a'' - 2z xi' + (2z + 2z_a) xi_a' - xi + (1 + K^2) xi_a = 0
    z, big_m, big_k, za = 0.1, 1.5, 0.9, 1.1
    s = elastic_foundation(z, Foundation(big_m, big_k, za))
    assert np.array_equal(s.mass, np.diag([1.0, big_m]))
    assert np.allclose(s.damping, [[2 * z, -2 * z], [-2 * z, 2 * z + 2 * za]])
    assert np.allclose(s.stiffness, [[1.0, -1.0], [-1.0, 1.0 + big_k**2]])


def test_chain_of_two_foundations() -> None:
    s = chain_structure(0.0, (Foundation(1.0, 1.0, 0.0), Foundation(2.0, 2.0, 0.0)))
    assert np.allclose(s.stiffness, [[1, -1, 0], [-1, 2, -1], [0, -1, 5]])
    assert s.n_dof == 3


def test_startup_state_matches_design_formula() -> None:
    # DESIGN.md section 1: xi = -gamma lam (1 + 1/K^2), xi_a = -gamma lam / K^2
    sl = Slider(3.0, gamma=2.0)
    big_k = 0.8
    init = startup_state(elastic_foundation(0.1, Foundation(1.2, big_k, 0.5)), sl)
    assert init.position == pytest.approx([-6.0 * (1 + 1 / big_k**2), -6.0 / big_k**2])
    assert init.velocity == pytest.approx([1.0, 0.0])
    assert startup_state(rigid_base(0.1), sl).position == pytest.approx([-6.0])


def test_physical_system_groups() -> None:
    # definitions after Eq. (27); a 2 kg slider on 50 kN/m, mu_s = 0.5, mu_k = 0.3
    p = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=100.0, speed=0.1,
                       foundation=PhysicalFoundation(m_a=3.0, k_a=40e3, c_a=300.0))
    s = p.slider()
    root_mk = math.sqrt(2.0 * 50e3)
    assert s.lam == pytest.approx(0.2 * 100.0 / (0.1 * root_mk))
    assert p.zeta == pytest.approx(20.0 / (2 * root_mk))
    assert p.structure().zeta == pytest.approx(20.0 / (2 * root_mk))
    assert s.gamma == pytest.approx(0.3 / 0.2)
    f = p.dimensionless_foundation()
    assert f is not None
    assert f.mass_ratio == pytest.approx(1.5)
    assert f.stiffness_ratio == pytest.approx(math.sqrt(0.8))
    assert f.damping_ratio == pytest.approx(300.0 / (2 * root_mk))


def test_physical_rejects_mu_k_not_below_mu_s() -> None:
    with pytest.raises(ValueError, match=r"mu_k=0\.5 must be smaller than mu_s=0\.5"):
        PhysicalSystem(mass=1, stiffness=1, damping=0, mu_s=0.5, mu_k=0.5, load=1, speed=1)


@given(
    lam=st.floats(1e-3, 1e3),
    zeta=st.floats(0.0, 2.0),
    gamma=st.floats(0.0, 20.0),
    m=st.floats(1e-3, 1e4),
    k=st.floats(1.0, 1e8),
    mu_s=st.floats(0.01, 2.0),
    speed=st.floats(1e-4, 1e2),
    big_m=st.floats(0.01, 100.0),
    big_k=st.floats(0.05, 20.0),
    za=st.floats(0.0, 5.0),
)
def test_physical_round_trip(lam, zeta, gamma, m, k, mu_s, speed, big_m, big_k, za) -> None:
    # scaling law: the dimensionless groups survive the trip to SI units and back
    sl = Slider(lam, gamma=gamma)
    fnd = Foundation(big_m, big_k, za)
    p = PhysicalSystem.from_dimensionless(sl, zeta=zeta, m=m, k=k, mu_s=mu_s, speed=speed, foundation=fnd)
    back = p.slider()
    assert back.lam == pytest.approx(lam, rel=1e-9)
    assert p.zeta == pytest.approx(zeta, rel=1e-9, abs=1e-15)
    assert back.gamma == pytest.approx(gamma, rel=1e-9, abs=1e-12)
    f = p.dimensionless_foundation()
    assert f is not None
    assert (f.mass_ratio, f.stiffness_ratio, f.damping_ratio) == pytest.approx(
        (big_m, big_k, za), rel=1e-9, abs=1e-15
    )
    # lambda is proportional to W / V: the critical speed and load invert it
    assert p.speed_for_lambda(lam) == pytest.approx(speed, rel=1e-9)
    assert p.load_for_lambda(lam) == pytest.approx(p.load, rel=1e-9)
