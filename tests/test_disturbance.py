"""The certified safe disturbance margin of steady sliding (issue 13, point 3).

Sources: the undamped rigid base is a harmonic oscillator about steady sliding, so a velocity
kick ``dv`` gives a velocity amplitude ``dv`` exactly: below the belt speed it never sticks,
above it reaches the belt speed (closed form); for every other case, Lyapunov's argument in
:mod:`stickslip.analysis.disturbance` (``V`` non-increasing, ``|xi'| <= sqrt(kappa V)``), which the
engine must confirm state by state.
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import (
    Foundation,
    InitialState,
    PhysicalSystem,
    Slider,
    Verdict,
    elastic_foundation,
    optimal_foundation_fit,
    rigid_base,
    simulate,
)
from stickslip.analysis.disturbance import safe_disturbance
from stickslip.model.friction import LinearFriction, TableFriction


def _kick(structure, dv: float) -> InitialState:  # type: ignore[no-untyped-def]
    n = structure.n_dof
    v = np.zeros(n)
    v[0] = dv
    return InitialState(np.zeros(n), v, f"steady sliding + kick {dv}")


def test_undamped_rigid_base_margin_is_exactly_the_belt_speed() -> None:
    margin = safe_disturbance(rigid_base(0.0), Slider(3.0))
    assert margin.velocity_kick == pytest.approx(1.0, rel=1e-14)
    assert margin.energy == pytest.approx(0.5, rel=1e-14)
    below = simulate(rigid_base(0.0), Slider(3.0), initial=_kick(rigid_base(0.0), 0.999), record=False)
    above = simulate(rigid_base(0.0), Slider(3.0), initial=_kick(rigid_base(0.0), 1.001), record=False)
    assert below.verdict is Verdict.STEADY_SLIDING
    assert above.verdict is Verdict.STICK_SLIP


CASES = [
    ("rigid, coulomb", rigid_base(0.1), Slider(15.0)),
    ("foundation, coulomb", elastic_foundation(0.1, optimal_foundation_fit(0.1)), Slider(15.0)),
    ("foundation, K/2", elastic_foundation(0.05, optimal_foundation_fit(0.05).scaled(0.5)), Slider(8.0)),
    ("rigid, linear", rigid_base(0.2), Slider(4.0, friction=LinearFriction(0.1))),
    ("foundation, linear", elastic_foundation(0.1, Foundation(1.5, 1.0, 0.5)),
     Slider(6.0, friction=LinearFriction(0.15))),
    ("rigid, table", rigid_base(0.3), Slider(2.0, friction=TableFriction((0.0, 0.5, 1.5), (0.8, 0.2, 0.1)))),
]


@pytest.mark.parametrize(("name", "structure", "slider"), CASES, ids=[c[0] for c in CASES])
def test_sampled_states_inside_the_margin_end_in_steady_sliding(name, structure, slider) -> None:  # type: ignore[no-untyped-def]
    margin = safe_disturbance(structure, slider)
    assert margin.energy > 0.0, name
    n = structure.n_dof
    p_energy = np.zeros((2 * n, 2 * n))
    p_energy[:n, :n] = 0.5 * structure.stiffness
    p_energy[n:, n:] = 0.5 * structure.mass
    # equilibrium of the band around the belt speed: K q_eq = (F(1) - gamma lambda) e0
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    b = int(np.searchsorted(edges, 1.0, side="right") - 1)
    force = intercepts[b] + slopes[b] - slider.gamma * slider.lam
    q_eq = np.linalg.solve(structure.stiffness, force * np.eye(n)[0])
    rng = np.random.default_rng(11)
    for _ in range(25):
        z = rng.normal(size=2 * n)
        z *= np.sqrt(0.99 * margin.energy / (z @ p_energy @ z))
        start = InitialState(q_eq + z[:n], z[n:], "inside the certified margin")
        result = simulate(structure, slider, initial=start, record=False)
        assert result.verdict is Verdict.STEADY_SLIDING, (name, z)
        assert result.n_stick == 0


def test_kicks_just_inside_the_velocity_margin_are_harmless() -> None:
    structure = elastic_foundation(0.1, optimal_foundation_fit(0.1))
    slider = Slider(15.0)
    margin = safe_disturbance(structure, slider)
    result = simulate(structure, slider, initial=_kick(structure, 0.999 * margin.velocity_kick), record=False)
    assert result.verdict is Verdict.STEADY_SLIDING and result.n_stick == 0


def test_unstable_steady_sliding_has_no_margin() -> None:
    margin = safe_disturbance(rigid_base(0.05), Slider(3.0, friction=LinearFriction(0.1)))
    assert margin.energy == 0.0 and "not stable" in margin.certificate


def test_margin_in_physical_units() -> None:
    # energy in m V^2, kick in V, displacement in V / omega_n (Eqs. 15-18)
    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=150.0, speed=0.05)
    margin = safe_disturbance(system.structure(), system.slider())
    phys = margin.physical(system)
    assert phys["velocity_kick_m_s"] == pytest.approx(margin.velocity_kick * 0.05)
    assert phys["energy_J"] == pytest.approx(margin.energy * 2.0 * 0.05**2)
    assert phys["displacement_m"] == pytest.approx(margin.displacement * 0.05 / np.sqrt(5e4 / 2.0))
    sentence = margin.sentence(system)
    assert sentence.startswith("a velocity kick below 50 mm/s") and "cannot start stick-slip" in sentence
