"""A basin's stick-slip labels proven, not observed, on structures of two or more DOF.

The kernel certifies a stick-slip candidate when a breakaway state repeats to ``cycle_tol``
(:func:`stickslip.kernel.engine.record_state`). Beyond one degree of freedom that is an
observation (:mod:`stickslip.analysis.cycle_proof` says why), so a basin proves its labels as
:func:`stickslip.simulate` does, and uses the proofs to stop early:

1. *Pilot* (:func:`pilot_balls`): the first :data:`PILOT_STATES` states are run and their
   candidates proven (:func:`stickslip.analysis.simulation.prove_run`); each proof is a ball on
   the breakaway section that the cycle's return map contracts into itself
   (:mod:`stickslip.kernel.cycle_balls`). A candidate whose breakaway state lies in a ball
   proven before needs no proof of its own.
2. *Run*: every state runs with those balls; a run whose breakaway state enters one is
   certified there, with the ball's cycle (its minimal period and its numbers).
3. *Check* (:meth:`ProvenBalls.prove_candidates`): a run that still ends on a repeat (a cycle
   the pilot did not meet) is run again and its candidate proven (or found inside a ball
   proven since); unproven, its label is ``undetermined`` (status ``unproven-cycle``).

The kernel's balls are fixed before the first chunk, so a state's run does not depend on the
chunking, the backend or a resume; the labels are those of :func:`stickslip.simulate` from
each state, but for one bound: a basin does not carry a run's own rounding to the state it
finds in a ball (:mod:`stickslip.analysis.run_rounding`, about 0.1 ms per phase in Python,
more than the run itself), so on a chaotic transient ``simulate`` may answer
``undetermined`` where the basin says stick-slip. One degree of freedom needs none of
this (the breakaway state is unique).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.engine_run import EngineOptions, run_engine
from stickslip.analysis.return_map import ReturnMap
from stickslip.analysis.simulation import SimulationResult, prove_run
from stickslip.analysis.verdict import RunStatus
from stickslip.kernel import cycle_balls as cb
from stickslip.kernel import engine
from stickslip.kernel.system import SLIP_I
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]

#: States of the basin (its first ones) whose candidates are proven before the run.
PILOT_STATES = 16
#: Breakaways a candidate's run goes on for to enter a known ball before a proof of its own.
EXTRA_BREAKAWAYS = 32


@dataclass
class ProvenBalls:
    """The proven contraction balls of one system's stable stick-slip cycles (see module notes).

    Attributes
    ----------
    structure, slider : Structure, Slider
        The system (contact on DOF 0, dimensionless).
    options : EngineOptions
        The basin's engine options (horizon of the runs and proofs).
    data, norm : ndarray
        The kernel's rows (:mod:`stickslip.kernel.cycle_balls`): one per ball.
    """

    structure: Structure
    slider: Slider
    options: EngineOptions
    data: FloatArray = field(repr=False)
    norm: FloatArray = field(repr=False)
    section: ReturnMap = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.section = ReturnMap(self.structure, self.slider, self.options)

    @classmethod
    def empty(cls, structure: Structure, slider: Slider, options: EngineOptions) -> ProvenBalls:
        """No ball yet."""
        data, norm = cb.no_balls(structure.n_dof)
        return cls(structure, slider, options, data, norm)

    def __len__(self) -> int:
        return int(self.data.shape[0])

    def holding(self, state: FloatArray) -> tuple[int, float]:
        """The ball holding the breakaway state ``state`` (row, ``||C (b - b_hat)|| / rho``);
        ``(-1, inf)`` for none. Its section piece is the nearer stick-force level
        (:meth:`~stickslip.analysis.return_map.ReturnMap.direction_of`)."""
        n = self.structure.n_dof
        z = np.asarray(state, dtype=np.float64)
        onto = 0 if self.section.direction_of(z) == SLIP_I else 1
        p, distance = cb.ball_holding(np.append(z, 1.0), n, np.int64(onto), self.data, self.norm)
        return int(p), float(distance)

    def add(self, proven: SimulationResult) -> None:
        """Add the ball of a run whose cycle :func:`prove_run` proved."""
        proof = proven.cycle_proof
        if proof is None or proof.norm_matrix.size == 0 or self.holding(proof.fixed_point)[0] >= 0:
            return  # no ball, or one about the same fixed point (unique in a proven ball)
        n = self.structure.n_dof
        center = np.delete(proof.fixed_point, [0, n])
        row = np.empty(cb.B_CENTER + center.size)
        c_inv = float(np.linalg.norm(np.linalg.inv(proof.norm_matrix), 2))
        row[cb.B_RHO] = proof.radius / c_inv
        row[cb.B_ONTO] = 0.0 if proof.breakaway_onto == "slip-I" else 1.0
        row[cb.B_STICK_PHASES] = proof.stick_phases
        row[cb.B_PERIOD] = proven.period
        row[cb.B_AMPLITUDE] = proven.amplitude
        row[cb.B_XI_MIN], row[cb.B_XI_MAX] = proven.xi_range
        row[cb.B_STICK_RATIO] = proven.stick_ratio
        row[cb.B_CYCLE_MAX_VELOCITY] = proven.cycle_max_velocity
        row[cb.B_C_NORM] = float(np.linalg.norm(proof.norm_matrix, 2))
        row[cb.B_CENTER:] = center
        self.data = np.vstack([self.data, row[None, :]])
        self.norm = np.concatenate([self.norm, proof.norm_matrix[None, :, :]])

    def prove(self, state: FloatArray) -> tuple[int, SimulationResult | None]:
        """The run from ``state`` with its candidate proven (see :meth:`prove_candidates`).

        Returns ``(p, result)``: ``p >= 0`` when proven ball ``p`` holds the run's breakaway
        state at its candidate (no new proof), else ``-1`` with ``result`` the run after
        :func:`prove_run` (its ball added when proven); ``result`` is None when the run
        certifies no stick-slip candidate (steady sliding, a slip oscillation, a horizon).
        """
        n = self.structure.n_dof
        result = run_engine(self.structure, self.slider,
                            InitialState(state[:n], state[n:], "basin state"), self.options,
                            False, False)
        if result.status is not RunStatus.CERTIFIED_CYCLE:
            return -1, None
        p = self.holding(result.final_state)[0]
        if p >= 0:
            return p, result
        if len(self):  # a known cycle's ball may hold one of the next breakaways
            for state_later in self.section.next_breakaways(result.final_state, EXTRA_BREAKAWAYS):
                p = self.holding(state_later)[0]
                if p >= 0:
                    return p, result
        proven = prove_run(result, self.options, carry_rounding=False)
        self.add(proven)
        return -1, proven

    def prove_candidates(self, states: FloatArray, float_summary: FloatArray,
                         int_summary: NDArray[np.int64]) -> int:
        """Prove, in place, every repeat-certified candidate of a chunk's runs (step 3).

        A candidate's run is repeated in Python (:func:`run_engine`, the same engine) for its
        breakaway state; inside a proven ball it takes the ball's cycle, else
        :func:`prove_run` proves it (its minimal period, and the cycle's numbers when they
        change) or it becomes ``unproven-cycle`` (undetermined). Returns the number of
        candidates.
        """
        candidates = np.flatnonzero((int_summary[:, engine.I_STATUS] == engine.STATUS_CYCLE)
                                    & (float_summary[:, engine.F_CYCLE_MISMATCH] >= 0.0))
        for c in candidates.tolist():
            f_c, i_c = float_summary[c], int_summary[c]
            p, result = self.prove(states[c])
            if p >= 0:
                # its Python body: eight assignments, where a call through numba's dispatcher
                # compiled a signature of its own on a user's first run after `make`
                engine.record_ball_cycle.py_func(f_c, i_c, self.data, p, f_c[engine.F_T_CERTIFIED])
            elif result is None or result.status is not RunStatus.CERTIFIED_CYCLE:
                i_c[engine.I_STATUS] = RunStatus.UNPROVEN_CYCLE.code
            else:
                i_c[engine.I_CYCLE_K] = result.cycle_length
                f_c[engine.F_PERIOD] = result.period
                f_c[engine.F_AMPLITUDE] = result.amplitude
                f_c[engine.F_XI_MIN], f_c[engine.F_XI_MAX] = result.xi_range
                f_c[engine.F_STICK_RATIO] = result.stick_ratio
                f_c[engine.F_CYCLE_MAX_VELOCITY] = result.cycle_max_velocity
        return int(candidates.size)


def pilot_balls(structure: Structure, slider: Slider, states: FloatArray,
                options: EngineOptions) -> ProvenBalls:
    """The balls proven from the candidates of the first :data:`PILOT_STATES` states (step 1).

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (contact on DOF 0, ``n_dof >= 2``), dimensionless.
    states : ndarray, shape (n, 2 n_dof)
        The basin's states; the first :data:`PILOT_STATES` are run.
    options : EngineOptions
        The basin's engine options.

    Returns
    -------
    ProvenBalls
        One ball per distinct stable cycle proven (none for 1 DOF).
    """
    balls = ProvenBalls.empty(structure, slider, options)
    if structure.n_dof < 2:
        return balls
    for state in np.asarray(states, dtype=np.float64)[:PILOT_STATES]:
        balls.prove(state)
    return balls
