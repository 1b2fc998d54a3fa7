"""One simulation with a certified verdict: does this system stick-slip?

The engine (:mod:`stickslip.kernel.engine`) propagates each friction mode exactly (matrix
exponential of the augmented affine system) and locates every mode switch, grazes
included. A verdict is certified, never guessed from the tail of a time series:

* ``steady-sliding``: in slip-I the structure is linear and stable; a quadratic Lyapunov
  function bounds every future slider velocity. Once the bound is below the belt speed no
  stick can ever happen again.
* ``stick-slip``: the state at a breakaway (end of a stick phase) repeats, to
  ``cycle_tol``, that of 1 to ``max_period`` breakaways before; the cycle's period and
  amplitude are then those of the repeating stretch.
* ``slip-oscillation`` (velocity-dependent friction only): a periodic motion that never
  sticks; the state at a Poincare section (a friction-band edge next to steady sliding,
  crossed outwards) repeats with no stick phase in between.
* ``undetermined``: none of these before ``t_max`` or ``max_events``.

The friction law is ``slider.friction`` (:mod:`stickslip.model.friction`); the result states
how it was computed (``friction_description``) and the linear stability of steady sliding
(:mod:`stickslip.analysis.stability`).
"""

from __future__ import annotations

import warnings
from dataclasses import replace

from stickslip.analysis.cycle_proof import CycleProof, prove_cycle
from stickslip.analysis.engine_run import (  # noqa: F401 (their home until now: re-exported)
    DEFAULT_CYCLE_TOL,
    DEFAULT_MAX_EVENTS,
    DEFAULT_MAX_PERIOD,
    DEFAULT_T_MAX,
    EngineOptions,
    SimulationResult,
    TimeHistory,
    run_engine,
)
from stickslip.analysis.run_rounding import rounding_to_entry
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.model._validate import friction_range
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure, state_permutation, to_user_order


def simulate(
    structure: Structure,
    slider: Slider,
    *,
    initial: InitialState | None = None,
    options: EngineOptions | None = None,
    t_max: float | None = None,
    record: bool = True,
    run_to_t_max: bool = False,
) -> SimulationResult:
    """Simulate the sliding system exactly and certify whether it stick-slips.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on
        ``structure.contact_dof`` (``rigid_base``, ``elastic_foundation``, any chain or any
        machine's structure); a contact elsewhere than DOF 0 runs through
        :meth:`Structure.contact_first`, with inputs and outputs in the user's order. The
        primary damping ratio
        ``zeta`` is part of it (:attr:`Structure.zeta`).
    slider : Slider
        The frictional contact: ``lambda`` and ``gamma``.
    initial : InitialState, optional
        Defaults to the startup state (belt starts, springs relaxed, slider stuck,
        foundation at rest); see :func:`stickslip.model.startup_state`.
    options : EngineOptions, optional
        Horizon ``t_max`` (dimensionless time ``tau``), event budget and cycle tolerance
        (defaults of :class:`EngineOptions`): the one way to set the horizon.
    t_max : float, optional
        Deprecated (one release, ``DeprecationWarning``): pass
        ``options=EngineOptions(t_max=...)``. Overrides ``options.t_max`` meanwhile.
    record : bool
        Keep the phase list (needed for dense output and plots).
    run_to_t_max : bool
        Go on after the verdict is certified, up to ``t_max`` (for time-history figures).
        The verdict, period and amplitude are those of the first certificate.

    Returns
    -------
    SimulationResult
        Verdict, certificate, cycle data and (with ``record``) the trajectory.
    """
    if t_max is not None:
        warnings.warn("simulate(..., t_max=T) is deprecated: pass options=EngineOptions(t_max=T)",
                      DeprecationWarning, stacklevel=2)
    opts = (options or EngineOptions()).with_t_max(t_max)
    friction_range(slider.lam, slider.gamma)  # 2 gamma lambda must not overflow (issue 12)
    if structure.contact_dof != 0:
        return _simulate_contact_first(structure, slider, initial, opts, record, run_to_t_max)
    return prove_run(run_engine(structure, slider, initial, opts, record, run_to_t_max), opts)


#: Proofs tried again, each asking the run to go on until its state is deeper in the ball,
#: when the run's rounding (:mod:`stickslip.analysis.run_rounding`) exceeds the margin.
MARGIN_RETRIES = 2
#: A run whose rounding grows more than this (a chaotic transient) is not tried again: going
#: on cannot undo what its transient amplified.
MARGIN_GAIN = 1e6


def prove_run(result: SimulationResult, opts: EngineOptions, *,
              carry_rounding: bool = True) -> SimulationResult:
    """The run with its stick-slip candidate proven, corrected to the minimal period, or undetermined.

    One degree of freedom: the breakaway state is unique (``xi' = 1``, ``S = lambda``), so the
    first repeat is exact and the cycle has one stick phase; nothing to prove. More degrees
    of freedom: :func:`stickslip.analysis.cycle_proof.prove_cycle` (Newton on the exact return
    map, a tube bound over a ball, contraction in the adapted norm, every shorter divisor
    excluded). When the proven period is the run's own, every number of the run stands (bit
    for bit); when it is shorter, the cycle's period, amplitude and stick ratio are those of
    an engine run started on the proven fixed point. Unproven: ``undetermined``.

    Parameters
    ----------
    result : SimulationResult
        A run of :func:`~stickslip.analysis.engine_run.run_engine` (contact on DOF 0).
    opts : EngineOptions
        Its engine options (the horizon of the proof's runs).
    carry_rounding : bool
        Also bound the run's own rounding carried to the state found in the ball
        (:mod:`stickslip.analysis.run_rounding`; a basin does not, see
        :mod:`stickslip.sweep.basin_cycles`).

    Returns
    -------
    SimulationResult
        The run with its proof (``cycle_proof``), its cycle corrected to the minimal period, or
        ``unproven-cycle`` (undetermined).
    """
    if result.status is not RunStatus.CERTIFIED_CYCLE or result.structure.n_dof < 2:
        return result
    structure, slider = result.structure, result.slider
    if result.t_end == result.t_certified:
        state = result.final_state
    else:  # run on past the certificate: the breakaway state at the certificate
        state = run_engine(structure, slider, result.initial, opts, False, False).final_state
    k = result.cycle_length
    why: list[str] = []
    proof = prove_cycle(structure, slider, state, k, opts, why=why)
    if proof is None:
        return replace(result, verdict=Verdict.UNDETERMINED, status=RunStatus.UNPROVEN_CYCLE,
                       certificate=f"undetermined (period-{k} candidate, not proven; "
                                   f"{'; '.join(why) or 'no period gave a proof'}): "
                                   f"{result.certificate}")
    if not carry_rounding:
        return _proven(result, proof, opts)
    rounding = rounding_to_entry(structure, slider, result.initial, opts, proof.extra_stick_phases)
    for _ in range(MARGIN_RETRIES):  # bounded: a run that entered the ball at its edge goes on
        if rounding is None or rounding.bound <= proof.margin or rounding.gain > MARGIN_GAIN:
            break
        deeper = prove_cycle(structure, slider, state, k, opts, min_margin=2.0 * rounding.bound)
        if deeper is None:
            break
        proof = deeper
        rounding = rounding_to_entry(structure, slider, result.initial, opts,
                                     proof.extra_stick_phases)
    if rounding is None or not rounding.bound <= proof.margin:
        carried = ("cannot be carried through its phases (an event grazes)" if rounding is None
                   else f"carried to it, up to {rounding.bound:.1e} (an error grows up to "
                        f"{rounding.gain:.1e}-fold along the run)")
        return replace(result, verdict=Verdict.UNDETERMINED, status=RunStatus.UNPROVEN_CYCLE,
                       certificate=f"undetermined (period-{proof.stick_phases} cycle proven, "
                                   f"ball of radius {proof.radius:.2e}, but the run's rounding "
                                   f"{carried} may exceed the margin {proof.margin:.1e} of its "
                                   "state in the ball: the computed run need not be the motion "
                                   f"from its start): {result.certificate}")
    return _proven(result, replace(proof, run_error=rounding.bound, run_gain=rounding.gain), opts)


def _proven(result: SimulationResult, proof: CycleProof, opts: EngineOptions) -> SimulationResult:
    """The run with its proof: its own cycle, or the proof's shorter one (see :func:`prove_run`)."""
    structure, slider, k = result.structure, result.slider, result.cycle_length
    certificate = f"{result.certificate}; {proof.describe()}"
    if proof.stick_phases == k:
        return replace(result, certificate=certificate, cycle_proof=proof)
    n = structure.n_dof
    cycle = run_engine(structure, slider,
                       InitialState(proof.fixed_point[:n], proof.fixed_point[n:], "proven cycle"),
                       replace(opts, max_period=proof.stick_phases), False, False)
    if cycle.status is not RunStatus.CERTIFIED_CYCLE or cycle.cycle_length != proof.stick_phases:
        return replace(result, verdict=Verdict.UNDETERMINED, status=RunStatus.UNPROVEN_CYCLE,
                       certificate=f"undetermined (period-{proof.stick_phases} cycle proven but "
                                   f"its run did not repeat): {result.certificate}")
    return replace(
        result,
        certificate=(f"breakaway state repeats after {k} stick phase(s) to "
                     f"{result.cycle_mismatch:.1e} (relative), a multiple of the proven period; "
                     f"{proof.describe()}"),
        cycle_length=proof.stick_phases, period=cycle.period, amplitude=cycle.amplitude,
        xi_range=cycle.xi_range, stick_ratio=cycle.stick_ratio,
        cycle_max_velocity=cycle.cycle_max_velocity, cycle_mismatch=cycle.cycle_mismatch,
        cycle_proof=proof,
    )


def _simulate_contact_first(structure: Structure, slider: Slider, initial: InitialState | None,
                            options: EngineOptions, record: bool,
                            run_to_t_max: bool) -> SimulationResult:
    """:func:`simulate` of a structure whose contact is not DOF 0, via its contact-first twin.

    The engine runs :meth:`Structure.contact_first` (an exact permutation, so verdict, period,
    amplitude and event times are those of the twin); the initial state goes in and every
    per-DOF output (phase states, final state) comes back in the user's order.
    """
    inner, perm = structure.contact_first()
    sp = state_permutation(perm)
    inner_initial = None
    if initial is not None:
        z = initial.as_vector(structure.n_dof)[sp]
        inner_initial = InitialState(z[: inner.n_dof], z[inner.n_dof:], initial.description)
    res = simulate(inner, slider, initial=inner_initial, options=options, record=record,
                   run_to_t_max=run_to_t_max)
    z0 = to_user_order(res.initial.as_vector(inner.n_dof), perm)
    user_initial = initial or InitialState(z0[: inner.n_dof], z0[inner.n_dof:],
                                           res.initial.description)
    return replace(
        res,
        structure=structure,
        initial=user_initial,
        segment_states=to_user_order(res.segment_states, perm, axis=1),
        final_state=to_user_order(res.final_state, perm),
    )
