"""The proven cycle's period against an independent integration (slow).

Reference: ``tests/oracle.py`` (Coulomb, contact on any DOF) and ``tests/friction_oracle.py``
(a velocity-dependent law, contact first), scipy's DOP853 at rtol = atol = 1e-11 with event
location, which share no code with the engine. From the start-up state each runs past the
point where ``simulate`` proved its cycle and on for ten more periods; the spacing of every
``q``-th breakaway after that point is the proven period (relative 1e-7, the oracle's event
times being good to about 1e-9 here), and no shorter spacing repeats (the period is minimal).
The machines are those of :func:`tests.test_cycle_proof.random_machine`: seed 900 gives, at
these positions, grounded chains of 7 and 3 DOF with the contact on the first mass and one of
10 DOF with the contact on its ninth, whose cycle has three stick phases; seed 700 gives a
4-DOF chain under a linear law and a 5-DOF chain under a six-point table (each reordered with
its contact first, as the friction oracle takes it).
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip import SimulationResult, simulate
from stickslip.analysis.verdict import Verdict
from stickslip.model.friction import FrictionLaw, LinearFriction, TableFriction
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure
from tests.friction_oracle import friction_oracle_simulate
from tests.oracle import oracle_simulate_structure
from tests.test_cycle_proof import random_machine

STICK = 2
#: relative agreement of the oracle's breakaway spacing with the proven period
PERIOD_TOL = 1e-7
#: periods the oracle runs beyond the engine's end (the spacings compared)
EXTRA_PERIODS = 10


def _coulomb_machine(index: int) -> tuple[Structure, Slider]:
    rng = np.random.default_rng(900)
    for _ in range(index):
        random_machine(rng)
    return random_machine(rng)


def _weakening_machine(index: int) -> tuple[Structure, Slider]:
    """The ``index``-th machine of seed 700: even positions a linear law, odd ones a table."""
    rng = np.random.default_rng(700)
    law: FrictionLaw
    for k in range(index + 1):
        structure, slider = random_machine(rng)
        if k % 2:
            u = np.sort(rng.uniform(0.0, 2.0, 6))
            u[0] = 0.0
            law = TableFriction(tuple(u), tuple(np.sort(rng.uniform(-0.4, 1.0, 6))[::-1]))
        else:
            law = LinearFriction(float(rng.uniform(0.2, 0.8)))
    return structure.contact_first()[0], Slider(slider.lam, gamma=slider.gamma, friction=law)


def _breakaways(event_times: np.ndarray, event_modes: np.ndarray) -> np.ndarray:
    leaves = (event_modes[:-1] == STICK) & (event_modes[1:] != STICK)
    return np.asarray(event_times)[1:][leaves]


def _check_against(breakaways: np.ndarray, run: SimulationResult) -> None:
    q, period = run.cycle_length, run.period
    tail = breakaways[breakaways > run.t_end]
    assert tail.size >= EXTRA_PERIODS * q - 1, tail.size
    spacing = tail[q:] - tail[:-q]
    assert np.max(np.abs(spacing - period)) <= PERIOD_TOL * period
    for d in range(1, q):
        if q % d == 0:  # a period of d stick phases would space them d / q periods apart
            shorter = tail[d:] - tail[:-d]
            assert np.max(np.abs(shorter - period * d / q)) > 1e-3 * period


@pytest.mark.slow
@pytest.mark.parametrize(("index", "stick_phases"), [(0, 1), (1, 1), (19, 3)])
def test_coulomb_chain_period_is_the_independent_one(index: int, stick_phases: int) -> None:
    structure, slider = _coulomb_machine(index)
    run = simulate(structure, slider, record=False)
    assert run.verdict is Verdict.STICK_SLIP and run.cycle_proof is not None
    assert run.cycle_length == stick_phases
    horizon = run.t_end + EXTRA_PERIODS * run.period
    oracle = oracle_simulate_structure(structure, slider, horizon, rtol=1e-11, atol=1e-11)
    _check_against(_breakaways(oracle.event_times, np.asarray(oracle.event_modes)), run)


@pytest.mark.slow
@pytest.mark.parametrize("index", [0, 1])
def test_weakening_law_chain_period_is_the_independent_one(index: int) -> None:
    structure, slider = _weakening_machine(index)
    run = simulate(structure, slider, record=False)
    assert run.verdict is Verdict.STICK_SLIP and run.cycle_proof is not None
    horizon = run.t_end + EXTRA_PERIODS * run.period
    oracle = friction_oracle_simulate(structure, slider, horizon, max_step=0.05, rtol=1e-11,
                                      atol=1e-11, max_events=100_000)
    _check_against(_breakaways(oracle.event_times, np.asarray(oracle.event_modes)), run)
