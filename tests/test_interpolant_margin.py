"""Steady sliding certified for a smooth law's interpolant only is withheld (independent audit G).

A Stribeck law runs as its piecewise-linear interpolant (tolerance 1e-4), whose slope at the
belt speed is the secant of the band holding ``u = 1``; the law's own linearisation has the
tangent. For the exponential law (``n = 1``, ``v_s/V = 0.2``, ``lambda = 2``) on the rigid base
the net damping ``2 zeta + F'(1)`` vanishes at ``zeta_0 = lambda exp(-1/v_s) / (2 v_s) =
0.0336897`` (closed form of the law's slope, ``F'(1) = -lambda exp(-1/v_s) / v_s``). Just below
it, at ``0.99 zeta_0``, the law's steady sliding grows while the interpolant's decays: the
audit's independent integration of the exact law (DOP853, rtol 1e-11) reaches the belt speed at
tau = 3,233 from the state below, where the engine certified steady sliding and a disturbance
margin.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stickslip import InitialState, Slider, rigid_base, simulate
from stickslip.analysis.disturbance import safe_disturbance
from stickslip.analysis.engine_run import EngineOptions
from stickslip.analysis.interpolant_margin import interpolant_mismatch, interpolant_steady_mismatch
from stickslip.analysis.stability import steady_sliding_stability
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.kernel import engine
from stickslip.model.dva import DvaSpec
from stickslip.model.friction import CoulombFriction, StribeckFriction
from stickslip.sweep.basin import basin_stability
from stickslip.sweep.cycle_check import withhold_interpolant_steady
from stickslip.sweep.executors import CellBatch, StructureSet

LAM, VS = 2.0, 0.2
ZETA_0 = LAM * math.exp(-1.0 / VS) / (2.0 * VS)
#: the audit's start: steady sliding's position, the slider slowed by 0.02 V
START = InitialState(np.array([0.013475893998170934]), np.array([-0.02]))


def _slider() -> Slider:
    return Slider(LAM, friction=StribeckFriction(VS, tolerance=1e-4))


def test_the_law_and_its_interpolant_fall_on_either_side_of_the_limit() -> None:
    structure, slider = rigid_base(0.99 * ZETA_0), _slider()
    assert steady_sliding_stability(structure, slider).slope == pytest.approx(-2.0 * ZETA_0, rel=1e-12)
    assert not steady_sliding_stability(structure, slider).stable
    assert interpolant_steady_mismatch(structure, slider) is not None
    # beyond the limit both are stable, below the interpolation's reach both unstable
    assert interpolant_steady_mismatch(rigid_base(1.05 * ZETA_0), slider) is None
    assert interpolant_steady_mismatch(rigid_base(0.9 * ZETA_0), slider) is None
    # an exact law is the engine's own: never withheld
    assert interpolant_steady_mismatch(rigid_base(0.0), Slider(LAM)) is None


def test_simulate_and_the_margin_withhold_the_interpolants_certificate() -> None:
    structure, slider = rigid_base(0.99 * ZETA_0), _slider()
    run = simulate(structure, slider, initial=START, options=EngineOptions(t_max=20000.0))
    assert run.verdict is Verdict.UNDETERMINED
    assert run.status is RunStatus.INTERPOLANT_STEADY
    assert "not linearly stable" in run.certificate
    margin = safe_disturbance(structure, slider)
    assert margin.energy == 0.0 and margin.velocity_kick == 0.0
    # at tolerance 1e-6 the interpolant's own verdict is the law's (the audit's run sticks)
    fine = Slider(LAM, friction=StribeckFriction(VS, tolerance=1e-6))
    assert simulate(structure, fine, initial=START,
                    options=EngineOptions(t_max=20000.0)).verdict is Verdict.STICK_SLIP


def test_the_basin_withholds_them_too() -> None:
    structure, slider = rigid_base(0.99 * ZETA_0), _slider()
    result = basin_stability(structure, slider, np.array([[0.013475893998170934, -0.02],
                                                          [0.013475893998170934, -0.003]]))
    assert (result.verdict == Verdict.UNDETERMINED.code).all()


def test_map_cells_are_withheld_only_where_the_two_disagree() -> None:
    zetas = np.array([0.99, 1.05, 0.9]) * ZETA_0
    structures = StructureSet.resolve(DvaSpec("none"), zetas)
    batch = CellBatch(np.arange(3, dtype=np.int64), np.full(3, LAM), 2.0,
                      StribeckFriction(VS, tolerance=1e-4))
    isum = np.zeros((3, engine.I_N_STEPS + 1), dtype=np.int64)
    isum[:, engine.I_STATUS] = engine.STATUS_STEADY
    assert withhold_interpolant_steady(structures, batch, isum) == 1
    assert isum[:, engine.I_STATUS].tolist() == [RunStatus.INTERPOLANT_STEADY.code,
                                                 engine.STATUS_STEADY, engine.STATUS_STEADY]
    coulomb = CellBatch(np.arange(3, dtype=np.int64), np.full(3, LAM), 2.0, CoulombFriction())
    isum[:, engine.I_STATUS] = engine.STATUS_STEADY
    assert withhold_interpolant_steady(structures, coulomb, isum) == 0


def test_the_interpolants_own_slip_oscillation_is_withheld_where_the_law_settles() -> None:
    # the other side: stribeck:vs=0.3,n=1 has its band about u = 1 steeper than the tangent
    # (-0.121274 against -0.118913 at lambda = 1), so between the zeros of the two net dampings,
    # zeta = 0.05945 and 0.06065, the law's steady sliding is stable and the interpolant's not:
    # at zeta = 0.06 the tolerance-1e-4 run certified a slip oscillation of amplitude 0.0145,
    # the tolerance-1e-6 run (whose band agrees with the law) steady sliding
    structure = rigid_base(0.06)
    slider = Slider(1.0, friction=StribeckFriction(0.3, tolerance=1e-4))
    exact = steady_sliding_stability(structure, slider)
    assert exact.stable and -0.5 * exact.slope < 0.06
    found = interpolant_mismatch(structure, slider)
    assert found is not None and found[0] == "oscillation"
    assert interpolant_steady_mismatch(structure, slider) is None
    start = InitialState(np.array([0.0]), np.array([-0.01]))
    run = simulate(structure, slider, initial=start, options=EngineOptions(t_max=20000.0))
    assert run.status is RunStatus.INTERPOLANT_OSCILLATION
    assert run.verdict is Verdict.UNDETERMINED
    fine = Slider(1.0, friction=StribeckFriction(0.3, tolerance=1e-6))
    assert simulate(structure, fine, initial=start,
                    options=EngineOptions(t_max=20000.0)).verdict is Verdict.STEADY_SLIDING
    structures = StructureSet.resolve(DvaSpec("none"), np.array([0.06]))
    batch = CellBatch(np.zeros(1, dtype=np.int64), np.ones(1), 2.0,
                      StribeckFriction(0.3, tolerance=1e-4))
    isum = np.zeros((1, engine.I_N_STEPS + 1), dtype=np.int64)
    isum[0, engine.I_STATUS] = engine.STATUS_OSCILLATION
    assert withhold_interpolant_steady(structures, batch, isum) == 1
    assert isum[0, engine.I_STATUS] == RunStatus.INTERPOLANT_OSCILLATION.code

