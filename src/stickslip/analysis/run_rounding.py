"""The run's own rounding, carried to the state a cycle proof finds in its ball.

A proof of a stick-slip cycle (:mod:`stickslip.analysis.cycle_proof`) shows that the return
map contracts a ball about its fixed point and that the *computed* breakaway state lies in the
ball. The verdict is about the motion from the user's initial state, so the computed state
must also be close enough to the true one.

The proof already takes one evaluation of the map to be off by the engine's calibrated
allowance (:func:`stickslip.analysis._cycle_tube.rounding_allowance`: ``STEP_ROUNDING``
machine epsilons of the state's scale per step, at most ``2 t ||A||_F + 1`` steps in a phase of
duration ``t``; measured against an extended-precision integration, it covers the whole
error of a map evaluation). The run is a chain of such evaluations, breakaway to breakaway
(the first from the initial state), and each one's error is carried to the end by the later
ones: to first order, through the product of their Jacobians (the phases' propagators
``expm(A t)`` and the saltations of their events,
:meth:`stickslip.analysis.return_map.ReturnMap.phase_factors`). With ``a_j`` the allowance of
the ``j``-th evaluation (its steps, the scale ``max(1, max |z|)`` of its end states) and
``D_j`` the derivative of the rest of the run with respect to the ``j``-th breakaway state
(in the foundation coordinates ``b``, through the lift ``L``),

    ``e = sum_j ||D_j||_2 a_j``,   ``D_last = I``,

bounds the error of the computed state at the end. The last term is the proof's own
allowance for one evaluation. A motion that wanders among unstable cycles before it settles
(a chaotic transient) has ``||D_j||`` of order ``exp(growth x duration)``: its computed state
says nothing about the true one, and the bound says so. The state is proven in the ball when
the ball's margin about the computed state, in the norm of the proof, holds ``e``.

The bound is first order in the rounding (the errors are ``1e-13`` of the scale, the second
order terms below their square), the standard of the proof's own allowance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis import _cycle_tube
from stickslip.analysis.cycle_proof import EXTRA_CHUNK
from stickslip.analysis.engine_run import EngineOptions, SimulationResult, run_engine
from stickslip.analysis.return_map import ReturnMap
from stickslip.kernel.system import STICK
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class RunRounding:
    """The rounding of a computed run, carried to its last breakaway state.

    Attributes
    ----------
    bound : float
        ``e``: a first-order bound of ``||b_computed - b_true||_2`` in the foundation
        coordinates (``V/omega_n`` and ``V``).
    gain : float
        The largest ``||D_j||_2``: the growth by the end of an error at one breakaway (the
        run's sensitivity; in the millions and beyond a transient has amplified it).
    phases : int
        The phases carried.
    """

    bound: float
    gain: float
    phases: int


def run_rounding(pmap: ReturnMap, legs: list[tuple[SimulationResult, float]]) -> RunRounding | None:
    """Bound the error of the last breakaway state of a chain of recorded runs (module notes).

    Parameters
    ----------
    pmap : ReturnMap
        The system's return map (its mode matrices, reduction and lift).
    legs : list of (SimulationResult, float)
        Recorded runs in order, each with the time of the breakaway it ends at; each later
        leg starts at the previous leg's breakaway state.

    Returns
    -------
    RunRounding or None
        None when a leg's phases cannot be linearised (an event grazes its surface, or the
        leg does not end in a stick phase): the run's error is then unbounded here.
    """
    n2 = 2 * pmap.n
    later = np.delete(np.eye(n2), [0, pmap.n], axis=0)  # d(end b)/d(state), R at the end
    total, gain, count = 0.0, 1.0, 0
    steps, scale, end_gain = 0.0, 1.0, 1.0  # the evaluation being summed (the last: D = I)
    for result, t_hit in reversed(legs):
        factors = pmap.phase_factors(result, t_hit)
        if factors is None:
            return None
        z_hit, phase_list = factors
        ends = [*result.segment_states[1:len(phase_list)], z_hit]
        for i, step in reversed(list(enumerate(phase_list))):
            if step.mode == STICK and count > 0:
                # a stick phase ends at a breakaway: the evaluation that ends there is next
                total += end_gain * _cycle_tube.step_allowance(steps, scale)
                end_gain = float(np.linalg.norm(later @ pmap.lift, 2))
                gain = max(gain, end_gain)
                steps, scale = 0.0, 1.0
            steps += _cycle_tube.engine_steps(step.duration,
                                              float(np.linalg.norm(pmap.flow_matrix[step.mode])))
            scale = max(scale, float(np.max(np.abs(result.segment_states[i]))),
                        float(np.max(np.abs(ends[i]))))
            # later S expm(A t), with S = I + jump n^T / rate
            later = (later + np.outer(later @ step.jump, step.normal) / step.rate) @ step.propagator
            if not np.all(np.isfinite(later)):
                return None
            count += 1
    total += end_gain * _cycle_tube.step_allowance(steps, scale)  # from the initial state
    if not math.isfinite(total):
        return None
    return RunRounding(total, gain, count)


def rounding_to_entry(structure: Structure, slider: Slider, initial: InitialState,
                      options: EngineOptions, extra: int) -> RunRounding | None:
    """The run's rounding carried to the state a cycle proof found in its ball.

    The run from ``initial`` to its candidate breakaway (where the engine saw its state
    repeat), recorded, then ``extra`` more breakaways in the chunks of
    :func:`stickslip.analysis.cycle_proof.prove_cycle` (:data:`EXTRA_CHUNK` per run, each
    from the last one's breakaway state), and :func:`run_rounding` over them.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (contact on DOF 0), dimensionless.
    initial : InitialState
        The run's start.
    options : EngineOptions
        The run's engine options.
    extra : int
        Breakaways the proof went on past the candidate before its state entered the ball.

    Returns
    -------
    RunRounding or None
        None when a leg cannot be recorded or linearised.
    """
    pmap = ReturnMap(structure, slider, options)
    first = run_engine(structure, slider, initial, options, True, False)
    times = first.breakaway_times
    if times.size == 0:
        return None
    legs = [(first, float(times[-1]))]
    state = first.final_state
    remaining = int(extra)
    while remaining > 0:  # bounded: each pass takes at least one breakaway off
        count = min(EXTRA_CHUNK, remaining)
        run = pmap.recorded_run(state, count, on_section=False)
        if run is None:
            return None
        result, hits = run
        legs.append((result, float(hits[-1])))
        q, v, _ = result.state_at(hits[-1:])
        state = np.concatenate([q[0], v[0]])
        remaining -= count
    return run_rounding(pmap, legs)
