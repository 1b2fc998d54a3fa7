"""Neutral is not unstable: a growth rate within round-off of zero is marginally stable.

Sources: an undamped linear structure has purely imaginary eigenvalues (closed form: the
rigid base at zeta = 0 has ``s = +-i``), so its exact growth rate is 0; the paper's damped
rigid base has growth rate ``-zeta`` (Eq. 22, ``s = -zeta +- i sqrt(1 - zeta^2)``).
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import Foundation, elastic_foundation, rigid_base, simulate
from stickslip.analysis.disturbance import safe_disturbance
from stickslip.analysis.stability import steady_sliding_stability
from stickslip.model.friction import LinearFriction
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure
from tests.cli_helpers import run_cli


def _undamped_chain(n: int) -> Structure:
    stiffness = 2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    stiffness /= stiffness[0, 0]
    return Structure(np.eye(n), np.zeros((n, n)), stiffness, name="undamped chain")


@pytest.mark.parametrize("structure", [rigid_base(0.0), _undamped_chain(3), _undamped_chain(8)],
                         ids=["rigid-base", "chain3", "chain8"])
def test_undamped_is_neutral(structure: Structure) -> None:
    stability = steady_sliding_stability(structure, Slider(2.0))
    assert stability.neutral and not stability.stable
    assert abs(stability.growth_rate) <= stability.round_off < 1e-10


def test_damped_is_stable_and_weakened_is_unstable() -> None:
    stable = steady_sliding_stability(rigid_base(0.1), Slider(2.0))
    assert stable.stable and not stable.neutral
    assert stable.growth_rate == pytest.approx(-0.1, rel=1e-12)  # Eq. (22): Re s = -zeta
    weakened = steady_sliding_stability(rigid_base(0.1), Slider(2.0, friction=LinearFriction(0.2)))
    assert not weakened.stable and not weakened.neutral  # zeta - delta = -0.1 < 0


def test_simulate_says_neutral(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["simulate", "--lam", "2", "--zeta", "0", "--dva", "none"], capsys)
    assert code == 0, err
    sliding = next(line for line in out.splitlines() if line.startswith("sliding"))
    assert "neutral (marginally stable" in sliding and "UNSTABLE" not in sliding
    disturbance = next(line for line in out.splitlines() if line.startswith("disturbance"))
    assert "neither grows nor decays" in disturbance
    result = simulate(rigid_base(0.0), Slider(2.0), record=False)
    assert result.steady_sliding_neutral and not result.steady_sliding_stable


def test_a_badly_scaled_structure_is_not_called_neutral() -> None:
    """A foundation far stiffer than the slider: ``||A||_F ~ 1e12`` made the round-off bound
    0.22 and a growth rate of -0.1 "neutral"; the balanced matrix's norm (~1e6) bounds it.

    Source: on a foundation that does not move, the slider's eigenvalues tend to the rigid
    base's, ``-zeta +- i sqrt(1 - zeta^2)`` (Eq. 22), growth rate ``-zeta``.
    """
    structure = elastic_foundation(0.1, Foundation(1.0, 1e6, 0.1))
    stability = steady_sliding_stability(structure, Slider(3.0))
    assert stability.growth_rate == pytest.approx(-0.1, rel=1e-6)
    assert stability.stable and not stability.neutral and stability.round_off < 1e-6


def test_the_safe_disturbance_rests_on_a_checked_lyapunov_function() -> None:
    """The same structure made SciPy's Lyapunov solver warn in its own words on stderr; its
    solution is now checked (``a' P + P a`` negative definite) and the warning not shown."""
    import warnings

    structure = elastic_foundation(0.1, Foundation(1.0, 1e6, 0.1))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        safe = safe_disturbance(structure, Slider(3.0))
    assert safe.energy > 0.0 and safe.certificate in ("energy", "lyapunov")
