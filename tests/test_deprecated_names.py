"""Renamed and moved public names keep working for one release, with a DeprecationWarning (issue 17).

Each old spelling must give the same object or value as the new one (compared here against the
new spelling computed in the same test), and must warn; the new spelling must not warn.
"""

from __future__ import annotations

import importlib
import warnings

import pytest

from stickslip import EngineOptions, PhysicalSystem, Slider, rigid_base, simulate
from stickslip.analysis.critical import Crossing
from stickslip.analysis.dva import resolve_dva
from stickslip.model.dva import DvaSpec

MACHINE = {"mu_s": 0.5, "mu_k": 0.3, "load": 150.0, "speed": 0.05}


def test_physical_system_new_names_do_not_warn_and_old_ones_do() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        new = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, **MACHINE)
        positional = PhysicalSystem(2.0, 5e4, 20.0, 0.5, 0.3, 150.0, 0.05)
        assert (new.mass, new.stiffness, new.damping) == (2.0, 5e4, 20.0)
    assert positional == new
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        old = PhysicalSystem(m=2.0, k=5e4, c=20.0, **MACHINE)  # type: ignore[arg-type]
    messages = sorted(str(w.message) for w in caught if w.category is DeprecationWarning)
    assert messages == [
        f"PhysicalSystem.{former} is deprecated: use PhysicalSystem.{name}"
        for former, name in (("c", "damping"), ("k", "stiffness"), ("m", "mass"))
    ]
    assert old == new
    with pytest.warns(DeprecationWarning, match="use PhysicalSystem.damping"):
        assert old.c == 20.0
    with pytest.warns(DeprecationWarning, match="PhysicalSystem.m is deprecated"), pytest.raises(
        TypeError, match="both mass= and its former name m="
    ):
        PhysicalSystem(mass=2.0, m=2.0, stiffness=5e4, damping=20.0, **MACHINE)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="missing damping"):
        PhysicalSystem(mass=2.0, stiffness=5e4, **MACHINE)
    with pytest.raises(ValueError, match="must be positive"):
        PhysicalSystem(mass=-1.0, stiffness=5e4, damping=20.0, **MACHINE)


def test_crossing_bracket_names() -> None:
    c = Crossing(2.0, 1.5, 2.5, onset=True, converged=True)
    with pytest.warns(DeprecationWarning, match="lam_below"):
        assert c.lo == c.lam_below == 1.5
    with pytest.warns(DeprecationWarning, match="lam_above"):
        assert c.hi == c.lam_above == 2.5
    assert c.to_dict()["lo"] == 1.5 and c.to_dict()["hi"] == 2.5  # the JSON contract stays


def test_cycle_length_and_the_horizon_given_once() -> None:
    structure, slider = rigid_base(0.05), Slider(3.0)
    new = simulate(structure, slider, options=EngineOptions(t_max=2000.0), record=False)
    assert new.cycle_length > 0
    with pytest.warns(DeprecationWarning, match="cycle_length"):
        assert new.cycle_k == new.cycle_length
    with pytest.warns(DeprecationWarning, match="options=EngineOptions"):
        old = simulate(structure, slider, t_max=2000.0, record=False)
    assert (old.verdict, old.period, old.t_end) == (new.verdict, new.period, new.t_end)


def test_moved_modules_still_answer() -> None:
    dva = importlib.import_module("stickslip.analysis.dva")
    with pytest.warns(DeprecationWarning, match="stickslip.model.dva.DvaSpec"):
        legacy = dva.DvaSpec
    spec = legacy.parse("optimal")
    assert isinstance(spec, DvaSpec)
    with pytest.warns(DeprecationWarning, match="resolve_dva"):
        assert spec.resolve(0.1) == resolve_dva(DvaSpec.parse("optimal"), 0.1)
    tuning = importlib.import_module("stickslip.analysis.tuning")
    from stickslip.analysis.absorber_tuning import tune_foundation
    from stickslip.analysis.stability_tuning import optimal_foundation_stability

    with pytest.warns(DeprecationWarning, match="stickslip.analysis.absorber_tuning"):
        assert tuning.tune_foundation is tune_foundation
    with pytest.warns(DeprecationWarning, match="stickslip.analysis.stability_tuning"):
        assert tuning.optimal_foundation_stability is optimal_foundation_stability
    with pytest.raises(AttributeError):
        _ = tuning.no_such_name
