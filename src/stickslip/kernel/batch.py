"""Many independent runs at once, in parallel over numba threads (arrays only).

The compiled kernels here contain the engine's run loop (numba compiles callees into the
caller). numba's cache checks only this file's time stamp, not the engine's: after editing
:mod:`stickslip.kernel.engine`, :mod:`stickslip.kernel.events`,
:mod:`stickslip.kernel.certificate` or :mod:`stickslip.kernel.outer_certificate` alone,
``make clean-cache`` (or a change here), or these kernels keep running the code they were
cached with.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel.certificate import prepare_certified
from stickslip.kernel.engine import (
    F_AMPLITUDE,
    F_CYCLE_MAX_VELOCITY,
    F_CYCLE_MISMATCH,
    F_MAX_VELOCITY,
    F_PERIOD,
    F_STICK_RATIO,
    F_T_CERTIFIED,
    F_T_END,
    F_T_LAST_STICK,
    F_XI_MAX,
    F_XI_MIN,
    I_CYCLE_K,
    I_N_BREAKAWAY,
    I_N_SEGMENTS,
    I_N_STEPS,
    I_N_STICK,
    I_STATUS,
    N_FLOAT,
    N_INT,
    STATUS_CYCLE,
    STATUS_OSCILLATION,
    STATUS_STEADY,
    STATUS_STUCK,
    STATUS_T_MAX,
    mode_at_belt_speed,
    run_prepared,
)
from stickslip.kernel.linalg import copy_vector, gauss_solve
from stickslip.kernel.outer_certificate import (
    ESCAPE_F_LO,
    ESCAPE_TIME,
    ESCAPE_XI_LO,
    N_ESCAPE,
    escape_certifies,
    friction_floor,
    slip_escape_region,
    slip_ii_stick_time,
)
from stickslip.kernel.system import (
    STICK,
    prepare_bands,
    prepare_point,
    structure_data_at,
    structure_data_stack,
)


@njit(cache=True)
def startup_vector(stiffness, lam, gamma):
    """Startup state ``(q, v)``: ``q = -gamma lam K^-1 e_0``, ``v = e_0``.

    ``K^-1 e_0`` by :func:`~stickslip.kernel.linalg.gauss_solve` (no LAPACK in the engine): for
    the rigid base and one foundation stage its arithmetic is that of LAPACK's ``gesv``, so a
    map cell starts from bit for bit the state :func:`stickslip.model.startup_state` gives
    (``tests/test_kernel_linalg.py``).
    """
    n = stiffness.shape[0]
    e0 = np.zeros(n)
    e0[0] = 1.0
    offset, _ = gauss_solve(stiffness.copy(), e0)  # writable, as gauss_solve always gets
    z0 = np.zeros(2 * n)
    for i in range(n):
        z0[i] = -gamma * lam * offset[i]
    z0[n] = 1.0
    return z0


def run_cells(masses, dampings, stiffnesses, structure_index, lams, gammas, edges, intercepts,
              slopes, n_bands, t_max, max_events, cycle_tol, max_period):
    """Run every cell from the startup state; cell ``c`` uses structure ``structure_index[c]``.

    Cell ``c`` has the friction band table ``edges[c, :n_bands[c] + 1]``,
    ``intercepts[c, :n_bands[c]]``, ``slopes[c, :n_bands[c]]`` (padded arrays of shapes
    ``(n_cells, max_bands + 1)``, ``(n_cells, max_bands)``, ``(n_cells, max_bands)``); see
    :func:`coulomb_tables` for the Coulomb law.

    Returns the float and integer summaries, shapes ``(n_cells, N_FLOAT)`` and
    ``(n_cells, N_INT)``, with the layouts of :mod:`stickslip.kernel.engine`. The structures'
    own data (:func:`~stickslip.kernel.system.structure_data_stack`) is computed here on every
    call; a sweep that runs many batches of the same structures computes it once and calls
    :func:`run_prepared_cells`. The matrices are copied into writable arrays, as a sweep
    stacks them: a read-only array (a ``Structure``'s own) is another numba type, and its
    first call compiled the whole run loop again (about a minute).
    """
    masses, dampings, stiffnesses = (np.array(a, dtype=np.float64, order="C")
                                     for a in (masses, dampings, stiffnesses))
    shared = structure_data_stack(masses, dampings, stiffnesses)
    return run_prepared_cells(shared, masses, dampings, stiffnesses, structure_index, lams,
                              gammas, edges, intercepts, slopes, n_bands, t_max, max_events,
                              cycle_tol, max_period)


@njit(parallel=True, cache=True)
def run_prepared_cells(shared, masses, dampings, stiffnesses, structure_index, lams, gammas, edges,
                       intercepts, slopes, n_bands, t_max, max_events, cycle_tol, max_period):
    """:func:`run_cells` with ``shared = structure_data_stack(masses, dampings, stiffnesses)``.

    Each cell prepares only what depends on its parameter point
    (:func:`~stickslip.kernel.system.prepare_point`, bit for bit what
    :func:`~stickslip.kernel.system.prepare_bands` gives; the slip modes the run never
    enters are not prepared at all, ``lazy``) and runs from the startup state; the cells
    run in parallel over numba threads.
    """
    n_cells = lams.shape[0]
    float_summary = np.empty((n_cells, N_FLOAT))
    int_summary = np.empty((n_cells, N_INT), dtype=np.int64)
    for c in prange(n_cells):
        s = structure_index[c]
        z0 = startup_vector(stiffnesses[s], lams[c], gammas[c])
        nb = n_bands[c]
        # literal flags (unlike kernel.linalg's note): the map's cells keep their own compiled
        # run loop with the flags folded in, as before; an A/B with np.bool_ flags measured the
        # same cells/s within the machine's noise (bench_map.py, 2.9-3.0x the old kernel both)
        prepared = prepare_point(structure_data_at(shared, s), masses[s], dampings[s],
                                 stiffnesses[s], lams[c], gammas[c], edges[c, : nb + 1],
                                 intercepts[c, :nb], slopes[c, :nb], True)
        result = run_prepared(masses[s], lams[c], gammas[c], edges[c, : nb + 1], prepared, z0,
                              t_max, max_events, cycle_tol, max_period, False, False, False, False)
        copy_vector(float_summary[c], result[4])
        copy_vector(int_summary[c], result[5])
    return float_summary, int_summary


def coulomb_tables(lams, gammas):
    """Padded band tables ``(edges, intercepts, slopes, n_bands)`` of the Coulomb law per cell."""
    lams = np.asarray(lams, dtype=np.float64)
    gammas = np.asarray(gammas, dtype=np.float64)
    n_cells = lams.shape[0]
    edges = np.empty((n_cells, 2))
    edges[:, 0] = 0.0
    edges[:, 1] = np.inf
    intercepts = (gammas * lams).reshape(n_cells, 1)
    slopes = np.zeros((n_cells, 1))
    n_bands = np.ones(n_cells, dtype=np.int64)
    return edges, intercepts, slopes, n_bands


def prepare_states(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes,
                   early_certificate=True, escape_region=True):
    """Per-system data of :func:`run_prepared_states`: ``(prepared, r_in, r_hi, escape_data)``.

    A Python function: it calls the compiled :func:`prepare_states_kernel` with both flags
    given, so that every caller, with or without the defaults, loads the one cached
    compilation (numba compiles a call that leaves a default out as another signature).

    ``prepared``: :func:`stickslip.kernel.certificate.prepare_certified` (with the slip trap
    region) or, without ``early_certificate``, :func:`~stickslip.kernel.system.prepare_bands`;
    ``r_in, r_hi, escape_data``: the slip escape region
    (:func:`stickslip.kernel.outer_certificate.slip_escape_region`; empty without
    ``early_certificate``, or without ``escape_region``: it costs tens of runs of the system,
    worth it for thousands of states, not for a few hundred), and in
    ``escape_data[ESCAPE_F_LO]`` the law's floor for the test of states above the belt speed
    (NaN: no test; without ``early_certificate``, for more than one degree of freedom and for
    a one-band law, as the regions).
    """
    return prepare_states_kernel(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes,
                                 bool(early_certificate), bool(escape_region))


@njit(cache=True)
def prepare_states_kernel(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes,
                          early_certificate, escape_region):
    """:func:`prepare_states` compiled, every argument given."""
    if early_certificate:
        prepared = prepare_certified(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes)
        if escape_region:
            r_in, r_hi, escape_data = slip_escape_region(mass, damping, stiffness, lam, gamma,
                                                         edges, intercepts, slopes, prepared)
        else:
            r_in = np.zeros(0)
            r_hi = np.zeros(0)
            escape_data = np.zeros(N_ESCAPE)
        escape_data[ESCAPE_F_LO] = np.nan
        if mass.shape[0] == 1 and intercepts.shape[0] >= 2:  # as the regions: not Coulomb
            escape_data[ESCAPE_F_LO] = friction_floor(edges, intercepts, slopes)
    else:
        prepared = prepare_bands(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes)
        r_in = np.zeros(0)
        r_hi = np.zeros(0)
        escape_data = np.zeros(N_ESCAPE)
        escape_data[ESCAPE_F_LO] = np.nan
    return prepared, r_in, r_hi, escape_data


def run_states(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, z0s, t_max,
               max_events, cycle_tol, max_period, join_startup=True, early_certificate=True):
    """Run one system from many initial states ``z0s`` (shape ``(n_states, 2 n)``) in parallel.

    A Python function over two cached kernels (:func:`prepare_states` and
    :func:`run_prepared_states`, every argument given): a compiled wrapper recompiled their
    whole call tree, about a minute, for its own first call.

    The system is prepared once (:func:`prepare_states`: the per-system data and, for one
    degree of freedom and a velocity-dependent law, the early certificates: the slip trap
    region of steady sliding and the slip escape region of states that reach the belt speed
    and stick; ``early_certificate=False`` leaves them out, for A/B comparisons) and shared by
    the threads; :func:`run_prepared_states` is the loop, for data prepared once for many
    calls. Returns the float and integer summaries, shapes
    ``(n_states, N_FLOAT)`` and ``(n_states, N_INT)`` (layouts of :mod:`stickslip.kernel.engine`).

    With ``join_startup`` and a single degree of freedom, each state is run only until its
    first stick phase, whose continuation is then taken from the start-up run
    (:func:`join_startup_summary`); other systems, and ``join_startup=False``, run every state
    to its own verdict; for more than one degree of freedom without tracking extremes or the
    exhaustive event search (the ``lean`` runs of :func:`~stickslip.kernel.engine.run_prepared`:
    the same roots to rounding, no velocity maximum, no amplitude of a cycle certified in the
    run; the basin keeps labels and end times). The shortcut's summaries carry no velocity
    maximum (NaN), and a slip oscillation certified before any stick has no amplitude (NaN; see
    :func:`~stickslip.kernel.engine.run_prepared`); verdicts, periods, certificate times,
    and the cycles of stick-slip runs (the start-up run's) are complete.

    Why this is exact (one degree of freedom, any friction law): while stuck, the slider moves
    with the belt, ``v = 1`` and ``xi' = 1`` while the stick force of Eq. (20),
    ``S = K xi + C v = K xi + C`` (shifted coordinates), stays between the static limits
    ``-lambda (1 + 2 gamma)`` and ``lambda``. The stick state is fixed by ``xi`` alone, ``xi``
    grows at unit rate and ``S`` with it (``K > 0``), so every stick phase ends where
    ``S = lambda``: at the same breakaway state, onto slip-I. Two stick
    states at ``xi_1 <= xi_2`` are the same motion shifted in time by ``xi_2 - xi_1``. The
    start-up state (``startup_vector``: ``v = 1``, spring at the kinetic offset) is such a
    stick state, so a state that sticks at time ``t_s`` in ``xi_s`` continues exactly as the
    start-up run does from time ``xi_s - xi_startup``: same verdict, same cycle (period,
    amplitude, stick ratio), and every later time shifted by
    ``t_s + xi_startup - xi_s``.

    Slip escape region (:mod:`stickslip.kernel.outer_certificate`, with the shortcut): a state
    in it provably reaches the belt speed by ``T`` and sticks in ``xi_s >= xi_lo``, so its
    verdict is the start-up run's without running it; it is used only when the start-up run
    is certified and ``T + t_cert(start-up) + xi_startup - xi_lo <= t_max`` (the joined clock
    of a direct run then certifies within the horizon: the same label). Likewise a state above
    the belt speed that provably decelerates to it and sticks
    (:func:`~stickslip.kernel.outer_certificate.slip_ii_stick_time`, with its own time bound).
    Their summaries are those of :func:`escape_summary` (certified at time 0, like the trap
    region's states).
    """
    prepared, r_in, r_hi, escape_data = prepare_states(mass, damping, stiffness, lam, gamma, edges,
                                                       intercepts, slopes, early_certificate)
    return run_prepared_states(mass, stiffness, lam, gamma, edges, prepared, r_in, r_hi,
                               escape_data, z0s, float(t_max), int(max_events), float(cycle_tol),
                               int(max_period), bool(join_startup))


@njit(parallel=True, cache=True)
def run_prepared_states(mass, stiffness, lam, gamma, edges, prepared, r_in, r_hi, escape_data, z0s,
                        t_max, max_events, cycle_tol, max_period, join_startup=True):
    """:func:`run_states` with the data of :func:`prepare_states` computed once."""
    n_states = z0s.shape[0]
    float_summary = np.empty((n_states, N_FLOAT))
    int_summary = np.empty((n_states, N_INT), dtype=np.int64)
    nz = z0s.shape[1]
    shortcut = join_startup and nz == 2
    # N DOF: a state keeps its label and end time only (engine.run_prepared's lean runs)
    lean = nz > 2
    startup = startup_vector(stiffness, lam, gamma)
    stick_row = prepared[7]
    if shortcut:
        shortcut = stick_row[0] > 0.0 and mode_at_belt_speed(
            np.array([startup[0], startup[1], 1.0]), stick_row, lam, gamma) == STICK
    startup_f = np.empty(N_FLOAT)
    startup_i = np.empty(N_INT, dtype=np.int64)
    escape = False
    slip_ii = False
    damping00 = stick_row[nz // 2] if nz == 2 else 0.0  # C: the stick force is K xi + C v
    if shortcut:
        # a joined clock runs behind the start-up run's by at most one stick phase, whose
        # length is at most the static range over the stick force's rate, lambda (2 + 2 gamma)
        # / K: the start-up run gets that much more time, so the horizon is the joined one's
        t_longer = t_max + lam * (2.0 + 2.0 * gamma) / stick_row[0]
        canonical = run_prepared(mass, lam, gamma, edges, prepared, startup, t_longer, max_events,
                                 cycle_tol, max_period, np.bool_(False), np.bool_(False),
                                 np.bool_(False), np.bool_(False))  # the states' signature: one compile
        copy_vector(startup_f, canonical[4])
        copy_vector(startup_i, canonical[5])
        status = startup_i[I_STATUS]
        certified = (status == STATUS_STEADY or status == STATUS_CYCLE
                     or status == STATUS_OSCILLATION)
        # the slip escape region: only where a direct run's joined clock certifies in time
        escape = (certified and r_in.shape[0] > 0
                  and escape_data[ESCAPE_TIME] + startup_f[F_T_CERTIFIED] + startup[0]
                  - escape_data[ESCAPE_XI_LO] <= t_max)
        slip_ii = certified and not np.isnan(escape_data[ESCAPE_F_LO])
    z_eq = prepared[15]
    for c in prange(n_states):
        w0 = np.array([z0s[c, 0], z0s[c, 1], 1.0])
        if escape and escape_certifies(w0, z_eq, r_in, r_hi, escape_data):
            escape_summary(float_summary[c], int_summary[c], startup_f, startup_i)
            continue
        if slip_ii and z0s[c, 1] > 1.0 and slip_ii_stick_time(
                w0, mass[0, 0], damping00, stiffness[0, 0], lam, gamma, escape_data[ESCAPE_F_LO]
        ) + startup_f[F_T_CERTIFIED] + startup[0] - z0s[c, 0] <= t_max:
            escape_summary(float_summary[c], int_summary[c], startup_f, startup_i)
            continue
        result = run_prepared(mass, lam, gamma, edges, prepared, z0s[c], t_max, max_events,
                              cycle_tol, max_period, np.bool_(False), np.bool_(False), shortcut,
                              lean)
        copy_vector(float_summary[c], result[4])
        copy_vector(int_summary[c], result[5])
        if shortcut and result[5][I_STATUS] == STATUS_STUCK:
            join_startup_summary(float_summary[c], int_summary[c], result[6][0], startup[0],
                                 startup_f, startup_i, t_max)
    return float_summary, int_summary


@njit(cache=True)
def escape_summary(fsum, isum, startup_f, startup_i):
    """The summaries of a state certified by the slip escape region, in place.

    Its verdict and cycle (period, amplitude, ``xi`` range, stick ratio, largest velocity in
    the cycle, mismatch, ``I_CYCLE_K``) are the start-up run's, exactly; it was certified at
    once, without a run: ``F_T_END = F_T_CERTIFIED = 0`` as for the slip trap region, no
    phase or step counted (``I_N_SEGMENTS = 1``, the initial phase), and the time of its last
    stick phase and its largest velocity unknown (NaN).
    """
    copy_vector(fsum, startup_f)
    copy_vector(isum, startup_i)
    fsum[F_T_END] = 0.0
    fsum[F_T_CERTIFIED] = 0.0
    fsum[F_T_LAST_STICK] = np.nan
    fsum[F_MAX_VELOCITY] = np.nan
    isum[I_N_STICK] = 0
    isum[I_N_BREAKAWAY] = 0
    isum[I_N_SEGMENTS] = 1
    isum[I_N_STEPS] = 0


@njit(cache=True)
def join_startup_summary(fsum, isum, xi_stuck, xi_startup, startup_f, startup_i, t_max):
    """Complete, in place, the summaries of a run that stopped at its first stick phase.

    ``fsum``, ``isum``: the stopped run's summaries (``F_T_END`` the time ``t_s`` the stick
    phase began, in ``xi_stuck``); ``startup_f``, ``startup_i``: those of the start-up run
    (stick state at ``xi_startup``). The joined run is the stopped one, then the start-up
    run's motion from its time ``xi_stuck - xi_startup`` on (see :func:`run_states`): its
    verdict, cycle and certificate are the start-up run's, its times are shifted by
    ``t_s + xi_startup - xi_stuck``, and its counts add (the shared stick phase and segment
    counted once). The horizon ``t_max`` applies to the joined time: a certificate that comes
    later is not one, as in a direct run (the start-up run was given the extra time a joined
    clock can lag by); the event budget applies to each part.
    """
    shift = fsum[F_T_END] + xi_startup - xi_stuck
    n_stick = isum[I_N_STICK] + startup_i[I_N_STICK] - 1
    n_bk = isum[I_N_BREAKAWAY] + startup_i[I_N_BREAKAWAY]
    n_seg = isum[I_N_SEGMENTS] + startup_i[I_N_SEGMENTS] - 1
    n_steps = isum[I_N_STEPS] + startup_i[I_N_STEPS]
    copy_vector(fsum, startup_f)
    copy_vector(isum, startup_i)
    fsum[F_MAX_VELOCITY] = np.nan  # not tracked before the stick phase (run_prepared)
    fsum[F_T_END] = startup_f[F_T_END] + shift
    fsum[F_T_LAST_STICK] = startup_f[F_T_LAST_STICK] + shift
    fsum[F_T_CERTIFIED] = startup_f[F_T_CERTIFIED] + shift
    isum[I_N_STICK] = n_stick
    isum[I_N_BREAKAWAY] = n_bk
    isum[I_N_SEGMENTS] = n_seg
    isum[I_N_STEPS] = n_steps
    certified = (isum[I_STATUS] == STATUS_STEADY or isum[I_STATUS] == STATUS_CYCLE
                 or isum[I_STATUS] == STATUS_OSCILLATION)
    if (certified and fsum[F_T_CERTIFIED] > t_max) or fsum[F_T_END] > t_max:
        # the horizon comes first on the joined clock: no certificate, as in a direct run
        isum[I_STATUS] = STATUS_T_MAX
        isum[I_CYCLE_K] = 0
        for column in (F_PERIOD, F_AMPLITUDE, F_XI_MIN, F_XI_MAX, F_STICK_RATIO,
                       F_CYCLE_MAX_VELOCITY, F_CYCLE_MISMATCH, F_T_CERTIFIED):
            fsum[column] = np.nan
        fsum[F_T_END] = t_max
