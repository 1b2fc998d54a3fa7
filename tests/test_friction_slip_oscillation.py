"""A certified slip oscillation: steady sliding unstable, the slider never reaches the belt speed.

Case: rigid base, zeta = 0.02, lambda = 1, gamma = 2, Stribeck law ``v_s/V = 1.05``, ``n = 6``,
``d_v = 0.5``: sharp velocity weakening around ``u = 1`` (local slope about -1.1, so
``2 zeta + F'(1) < 0``, growth rate +0.54) and strengthening away from it (viscous term), a
Van der Pol-like self-excited oscillation. Started next to steady sliding. Measured
(reference for the last row: the solve_ivp oracle of tests/friction_oracle.py on the exact
law, period from upward zero crossings of xi' over 100 time units after the transient)::

    tolerance  bands  verdict           period       amplitude    max xi'
    1e-3         35   slip-oscillation  6.47202785   0.59349016   0.57999932
    1e-4        108   slip-oscillation  6.47241740   0.59396041   0.58041542
    1e-5        341   slip-oscillation  6.47246563   0.59400643   0.58045686
    1e-6       1077   slip-oscillation  6.47246953   0.59401143   0.58046152
    oracle                              6.47247002   0.59401196   0.58046202
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import Slider, Verdict, rigid_base, simulate
from stickslip.analysis.simulation import RunStatus
from stickslip.model import InitialState
from stickslip.model.friction import StribeckFriction
from tests.friction_oracle import friction_oracle_simulate

ZETA, LAM = 0.02, 1.0


def _case(tol: float):
    structure = rigid_base(ZETA)
    slider = Slider(LAM, friction=StribeckFriction(1.05, exponent=6.0, viscous=0.5, tolerance=tol))
    force = float(slider.friction.value(1.0, LAM, 2.0)) - 2.0 * LAM
    initial = InitialState(np.array([force + 0.02]), np.array([0.0]))
    return structure, slider, initial


@pytest.mark.parametrize("tol", [1e-3, 1e-4, 1e-5, 1e-6])
def test_slip_oscillation_is_certified_and_never_sticks(tol: float) -> None:
    structure, slider, initial = _case(tol)
    r = simulate(structure, slider, initial=initial)
    assert r.verdict is Verdict.SLIP_OSCILLATION
    assert r.status is RunStatus.CERTIFIED_OSCILLATION
    assert r.n_stick == 0 and r.n_breakaway == 0
    assert r.growth_rate > 0.5 and not r.steady_sliding_stable
    assert r.max_velocity < 0.6  # never near the belt speed
    assert r.stick_ratio == 0.0
    assert r.period == pytest.approx(6.47247002, rel=5 * tol)
    assert r.to_dict()["verdict"] == "slip-oscillation"
    assert "Poincare" in r.certificate


@pytest.mark.slow  # a long solve_ivp oracle run (17 s); the certificate tests stay in the default run
def test_slip_oscillation_matches_the_oracle() -> None:
    structure, slider, initial = _case(1e-6)
    r = simulate(structure, slider, initial=initial)
    oracle = friction_oracle_simulate(structure, slider, r.t_end + 200.0, initial=initial)
    assert oracle.event_times.size == 0  # the oracle never reaches the belt speed either
    t = np.linspace(r.t_end + 100.0, r.t_end + 200.0, 100001)
    sol = oracle.pieces[0].sol
    y = sol(t)
    q, v = y[0], y[1]
    up = np.nonzero((v[:-1] < 0) & (v[1:] >= 0))[0]
    crossings = t[up] - v[up] * (t[up + 1] - t[up]) / (v[up + 1] - v[up])
    period = float(np.diff(crossings).mean())
    assert r.period == pytest.approx(period, rel=1e-6)
    assert r.amplitude == pytest.approx(0.5 * (q.max() - q.min()), rel=1e-5)
    assert r.max_velocity == pytest.approx(v.max(), rel=1e-5)


def test_from_startup_the_slider_breaks_away_into_the_same_oscillation() -> None:
    # measured: after the initial stick phase the motion settles on the same limit cycle
    structure, slider, _ = _case(1e-4)
    r = simulate(structure, slider)
    assert r.verdict is Verdict.SLIP_OSCILLATION
    assert r.n_stick == 1  # only the startup stick phase
    assert r.period == pytest.approx(6.4724174, rel=1e-7)
