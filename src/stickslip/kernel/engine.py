"""The run loop: exact piecewise-linear propagation, graze-proof events, certified verdicts.

Arrays in, arrays out; no Python objects. See :mod:`stickslip.kernel.system` for the state
layout and :mod:`stickslip.kernel.events` (with :mod:`stickslip.kernel.polynomial`) for the
event location on a step.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel import cycle_balls as cb
from stickslip.kernel.events import (
    P_FLAG,
    end_range,
    event_free,
    first_reach,
    interior_range,
    mode_taylor_vectors,
    poly_scratch,
    propagate,
    signature,
)
from stickslip.kernel.linalg import copy_vector, dot, grown, grown_rows
from stickslip.kernel.lyapunov_check import lyapunov_applies, lyapunov_bound
from stickslip.kernel.polynomial import (
    TAYLOR_DEGREE,
    quick_state,
    taylor_state,
)
from stickslip.kernel.prepared import prepared_tables
from stickslip.kernel.system import (
    F_VEL,
    F_XI,
    N_SIGNATURE,
    NEXT_BELT,
    SLIP_I,
    SLIP_II,
    STICK,
    TRAP_V_BOUND,
    fill_mode,
    find_band,
    mode_band,
    mode_code,
    mode_kind,
    trap_certifies,
)

STATUS_RUNNING = 0
STATUS_STEADY = 1
STATUS_CYCLE = 2
STATUS_T_MAX = 3
STATUS_MAX_EVENTS = 4
STATUS_MAX_STEPS = 5
#: a slip oscillation (periodic, never sticking) certified by a repeating section state
STATUS_OSCILLATION = 6
#: kernel-internal: a ``stop_at_stick`` run reached its first stick phase (see
#: :func:`stickslip.kernel.batch.run_states`, which replaces it by the verdict of the stick
#: phase's continuation; it never leaves the kernel)
STATUS_STUCK = 7

#: Bound on sub-steps per run. A very stiff or heavily damped structure needs tiny steps
#: (h ||A|| <= 1/2); this keeps such a run to seconds, ending with a reported status.
MAX_STEPS = 1_000_000

#: Phases the record holds before it first grows (it doubles up to ``max_events + 1``).
RECORD_START = 256

# layout of the float summary
F_LYAPUNOV_BOUND = 0
F_PERIOD = 1
F_AMPLITUDE = 2
F_XI_MIN = 3
F_XI_MAX = 4
F_STICK_RATIO = 5
F_CYCLE_MAX_VELOCITY = 6
F_MAX_VELOCITY = 7
F_CYCLE_MISMATCH = 8
F_T_END = 9
F_T_LAST_STICK = 10
F_T_CERTIFIED = 11
N_FLOAT = 12
# layout of the integer summary
I_STATUS = 0
I_N_STICK = 1
I_CYCLE_K = 2
I_N_BREAKAWAY = 3
I_N_SEGMENTS = 4
I_N_STEPS = 5
N_INT = 6


@njit(cache=True)
def mode_at_belt_speed(w, stick_row, lam, gamma):
    """Mode entered by a state whose slider moves exactly at the belt speed (Eq. 20)."""
    s = dot(stick_row, w)
    if s > lam:
        return SLIP_I
    if s < -lam * (1.0 + 2.0 * gamma):
        return SLIP_II
    return STICK


@njit(cache=True)
def initial_mode(w, n, stick_row, lam, gamma, edges):
    """Mode of the initial state: by the slider velocity (and its friction band), or by
    Eq. (20) at belt speed."""
    if w[n] < 1.0:
        return mode_code(SLIP_I, find_band(edges, 1.0 - w[n]))
    if w[n] > 1.0:
        return mode_code(SLIP_II, find_band(edges, w[n] - 1.0))
    return mode_at_belt_speed(w, stick_row, lam, gamma)


@njit(cache=True)
def _mismatch(ring_z, j, i):
    """Largest difference between the states in slots ``j`` and ``i`` of a ring buffer."""
    diff = 0.0
    for c in range(ring_z.shape[1]):
        diff = max(diff, abs(ring_z[j, c] - ring_z[i, c]))
    return diff


@njit(cache=True)
def _record_cycle(fsum, isum, ring_t, interval, newest, ring, k, j, i, diff, scale, t):
    """Write the summary of a certified cycle: the last ``k`` recorded intervals.

    ``interval[p]`` holds the xi minimum and maximum, the largest velocity and the stick time
    of the stretch ending at record ``p`` (a stick-slip cycle between breakaways, or a slip
    oscillation between section crossings, whose stick time is 0).
    """
    period = ring_t[j] - ring_t[i]
    xmin = np.inf
    xmax = -np.inf
    vmax = -np.inf
    stick = 0.0
    for back in range(k):
        p = (newest - back) % ring
        xmin = min(xmin, interval[p, 0])
        xmax = max(xmax, interval[p, 1])
        vmax = max(vmax, interval[p, 2])
        stick += interval[p, 3]
    fsum[F_PERIOD] = period
    fsum[F_AMPLITUDE] = 0.5 * (xmax - xmin)
    fsum[F_XI_MIN] = xmin
    fsum[F_XI_MAX] = xmax
    fsum[F_STICK_RATIO] = stick / period
    fsum[F_CYCLE_MAX_VELOCITY] = vmax
    fsum[F_CYCLE_MISMATCH] = diff / scale
    isum[I_CYCLE_K] = k
    fsum[F_T_CERTIFIED] = t


@njit(cache=True)
def record_ball_cycle(fsum, isum, ball_data, p, t):
    """Write the summary of a cycle certified by proven ball ``p``: the cycle's own numbers.

    ``F_CYCLE_MISMATCH`` is NaN (no repeat was measured): a ball's certificate, told apart
    from a repeat's (a mismatch, never NaN).
    """
    fsum[F_PERIOD] = ball_data[p, cb.B_PERIOD]
    fsum[F_AMPLITUDE] = ball_data[p, cb.B_AMPLITUDE]
    fsum[F_XI_MIN] = ball_data[p, cb.B_XI_MIN]
    fsum[F_XI_MAX] = ball_data[p, cb.B_XI_MAX]
    fsum[F_STICK_RATIO] = ball_data[p, cb.B_STICK_RATIO]
    fsum[F_CYCLE_MAX_VELOCITY] = ball_data[p, cb.B_CYCLE_MAX_VELOCITY]
    fsum[F_CYCLE_MISMATCH] = np.nan
    isum[I_CYCLE_K] = np.int64(ball_data[p, cb.B_STICK_PHASES])
    fsum[F_T_CERTIFIED] = t


@njit(cache=True, inline="never")
def ball_status(w, n, e_ev, ball_data, ball_norm, fsum, isum, t):
    """At a breakaway: ``STATUS_CYCLE`` (summary written) when a proven ball holds the state
    (:mod:`stickslip.kernel.cycle_balls`), else running; out of the run loop, as maps have none."""
    p = cb.ball_holding(w, n, np.int64(0 if e_ev == 0 else 1), ball_data, ball_norm)[0]
    if p < 0:
        return STATUS_RUNNING
    record_ball_cycle(fsum, isum, ball_data, p, t)
    return STATUS_CYCLE


@njit(cache=True)
def record_state(kind, t, w, key, xmin, xmax, vmax, stick_time, rec_t, rec_z, rec_key, rec_span, n_rec,
                 max_period, cycle_tol, key_breaks, status, verdict, fsum, isum):
    """Record a state in its ring buffer and look back for a repeat: the one cycle search.

    Two kinds of records: breakaways (``kind`` 0, ``key`` the stick phase's exit, a repeat
    certifies a stick-slip cycle) and Poincare-section crossings (``kind`` 1, ``key`` the
    number of stick phases so far, a repeat certifies a slip oscillation). The ring keeps
    the last ``max_period + 1`` records of each kind (slot = index % ring) with the time, the
    state, the key and the extremes and stick time of the stretch the record closes (which
    the caller then restarts at ``w``). While the run is undecided (``status`` running) the
    ``max_period`` records before are compared with this one, newest first: a record with
    another key is skipped, or ends the search when ``key_breaks`` (a stick phase inside
    the stretch: no slip oscillation). A state within ``cycle_tol`` (relative, max norm) of
    this one writes the cycle's summary (:func:`_record_cycle`) and returns ``verdict``;
    otherwise ``status`` is returned unchanged.
    """
    nz = rec_z.shape[2]
    ring = rec_t.shape[1]
    newest = n_rec[kind]
    j = newest % ring
    rec_t[kind, j] = t
    for c in range(nz):
        rec_z[kind, j, c] = w[c]
    rec_key[kind, j] = key
    rec_span[kind, j, 0] = xmin
    rec_span[kind, j, 1] = xmax
    rec_span[kind, j, 2] = vmax
    rec_span[kind, j, 3] = stick_time
    n_rec[kind] = newest + 1
    scale = 1.0
    for c in range(nz):
        scale = max(scale, abs(w[c]))
    for k in range(1, max_period + 1):
        if newest - k < 0 or status != STATUS_RUNNING:
            break
        i = (newest - k) % ring
        if rec_key[kind, i] != key:
            if key_breaks:
                break
            continue
        diff = _mismatch(rec_z[kind], j, i)
        if diff <= cycle_tol * scale:
            _record_cycle(fsum, isum, rec_t[kind], rec_span[kind], newest, ring, k, j, i, diff,
                          scale, t)
            return verdict
    return status


def run(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, z0, t_max, max_events,
        cycle_tol, max_period, record, run_to_t_max):
    """Simulate from ``z0 = (q, v)`` until a verdict is certified, ``t_max`` or ``max_events``.

    ``edges``, ``intercepts``, ``slopes``: the friction law's band table (see
    :func:`stickslip.kernel.system.prepare_bands`); the Coulomb law is
    ``([0, inf], [gamma lam], [0])``.

    Verdicts: steady sliding (a Lyapunov bound keeps ``xi'`` inside the band of the
    equilibrium for ever, or, with the data of
    :func:`stickslip.kernel.certificate.prepare_certified`, the state is inside the slip trap
    region; ``F_LYAPUNOV_BOUND`` is then the region's bound on ``|xi'|``), a stick-slip cycle
    (repeating breakaway state) or a slip oscillation (the state at a Poincare section, the
    equilibrium band's nearer speed edge crossed outwards, repeats with no stick phase in
    between).

    With ``run_to_t_max`` the run goes on after the verdict until ``t_max`` (for figures);
    the verdict and its time ``F_T_CERTIFIED`` are those of the first certificate.

    Returns ``(seg_t, seg_mode, seg_state, bk_t, fsum, isum, z_end)``: the start time,
    mode and state of every phase (only when ``record``), the breakaway times, the float
    and integer summaries (layouts ``F_*`` and ``I_*``) and the final state.

    A Python function over three compiled entry points (:func:`structure_data`,
    :func:`prepare_point`, :func:`run_prepared`), the steps of :func:`prepare_bands` and the
    run: numba optimises and compiles the whole call tree of each entry point again, so one
    compiled ``run`` over both trees cost a cold first ``simulate`` about 17 s more (issue
    21.5); the arithmetic is the same, so the results are bit for bit those of
    ``prepare_bands`` followed by ``run_prepared``.
    """
    prepared = prepared_tables(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes)
    return run_prepared(mass, lam, gamma, edges, prepared, z0, t_max, max_events, cycle_tol,
                        max_period, record, run_to_t_max, False, False)


@njit(cache=True)
def _summaries(fsum, isum, status, t, last_bound, max_v, t_last_stick, n_stick, n_bk, n_seg,
               n_steps, quick):
    """Complete the float and integer summaries at the end of a run (layouts ``F_*``, ``I_*``)."""
    fsum[F_LYAPUNOV_BOUND] = last_bound
    fsum[F_MAX_VELOCITY] = max_v
    if quick:
        # extremes are not tracked: the velocity maximum, and the xi range of a cycle certified
        # in the run (a proven ball's numbers, F_CYCLE_MISMATCH NaN, are the ball's own)
        fsum[F_MAX_VELOCITY] = np.nan
        if status == STATUS_OSCILLATION or (status == STATUS_CYCLE
                                            and not np.isnan(fsum[F_CYCLE_MISMATCH])):
            fsum[F_AMPLITUDE] = np.nan
            fsum[F_XI_MIN] = np.nan
            fsum[F_XI_MAX] = np.nan
            fsum[F_CYCLE_MAX_VELOCITY] = np.nan
    fsum[F_T_END] = t
    fsum[F_T_LAST_STICK] = t_last_stick
    isum[I_STATUS] = status
    isum[I_N_STICK] = n_stick
    isum[I_N_BREAKAWAY] = n_bk
    isum[I_N_SEGMENTS] = n_seg
    isum[I_N_STEPS] = n_steps


@njit(cache=True)
def run_prepared(mass, lam, gamma, edges, prepared, z0, t_max, max_events, cycle_tol, max_period,
                 record, run_to_t_max, stop_at_stick, lean):
    """:func:`run` with the per-system data of :func:`~stickslip.kernel.system.prepare_bands` computed once.

    Many runs of one system (basin stability: one system, many initial states) share the
    matrix exponentials and certificates; ``prepared`` is only read, so threads may share it.

    With ``stop_at_stick`` the run ends with the kernel-internal status ``STATUS_STUCK`` as
    soon as a stick phase begins (or at once when ``z0`` is a stick state), unless a verdict
    was certified before; ``F_T_END`` is then the time the stick phase began and the final
    state is the stick state. For a single degree of freedom every stick phase ends at the
    same breakaway state, so the rest of the motion is known from one run
    (:func:`stickslip.kernel.batch.run_states`). Such a run is the basin's hot loop, so it
    does not track extremes (half the cost of a step in a narrow friction band):
    ``F_MAX_VELOCITY`` is NaN, and so are the amplitude, ``xi`` range and largest velocity
    of a slip oscillation it certifies (its period is exact); and its event search is the
    ``quick`` one of :func:`first_reach` (the same roots to rounding).

    ``lean`` runs the same way without stopping at a stick phase: the N-DOF basin, whose
    labels and end times are all it keeps (the cycle's amplitude, period and extremes of a
    proven ball come from its proof, :mod:`stickslip.kernel.cycle_balls`). Its extremes are
    NaN, those of a cycle certified by a repeating breakaway state too (whose candidates the
    basin proves again, :mod:`stickslip.sweep.basin_cycles`).

    Why this function is longer than the house's 120 lines: the step is written out here,
    its small helpers inlined, the mode's arrays bound once per phase, and only events
    (rare) and the exact searches (rare) go through calls. numba counts a reference for every
    array sliced per step or passed to a call, which cost more than the step's arithmetic.
    Measured A/B in one session, same bits, a 200 x 200 log map serially: the loop with
    per-step slices and calls took 513 us/cell, this one 144 us/cell; a split into a
    per-phase inner loop with an inlined helper of 17 array arguments took 216-230 us/cell
    (inlining copies each array argument, with its reference count). Most steps of a map are
    stick steps (a 200 x 200 log map: 641 of the 689 steps of a stick-slip cell), whose cost
    is the step's two small matrix products (:func:`~stickslip.kernel.events.propagate`,
    :func:`~stickslip.kernel.events.signature`, unrolled for the paper's systems).
    """
    n = mass.shape[0]
    nz = 2 * n
    m = nz + 1
    quick = stop_at_stick or lean  # no extremes, the quick event search
    (ahat, phi, hstep, sig_rows, f_start, f_sign, f_offset, stick_row, lyap, kappa, n_lyap,
     ev_count, ev_next, ev_vel, _eq_mode, z_eq, lyap_lo, lyap_hi, margin, sec_mode,
     sec_event, trap_radius, trap_data, ball_data, ball_norm) = prepared
    # the phase record grows by doubling up to its bound (one phase per event, plus the first):
    # sized for the bound at once it took max_events x 2n doubles, 0.5 GB for 300 DOF
    cap_max = max_events + 1 if record else 1
    cap = min(cap_max, RECORD_START)
    seg_t = np.empty(cap)
    seg_mode = np.empty(cap, dtype=np.int64)
    seg_state = np.empty((cap, nz))
    all_bk_t = np.empty(cap)
    # ring buffers of the last max_period + 1 breakaways (0) and section crossings (1)
    ring = max_period + 1
    rec_t = np.empty((2, ring))
    rec_z = np.empty((2, ring, nz))
    rec_key = np.empty((2, ring), dtype=np.int64)
    rec_span = np.zeros((2, ring, 4))
    n_rec = np.zeros(2, dtype=np.int64)
    fsum = np.full(N_FLOAT, np.nan)
    isum = np.zeros(N_INT, dtype=np.int64)
    u = np.empty((TAYLOR_DEGREE + 1, m))
    # the event search's scratch (events.P_*: coefficients, breakpoints, row, flag), packed:
    # each array passed to a call costs two atomic reference counts (kernel._leaf)
    poly = poly_scratch(m)
    w = np.zeros(m)
    w1 = np.empty(m)
    w_end = np.empty(m)
    sig0 = np.empty(N_SIGNATURE)
    sig1 = np.empty(N_SIGNATURE)
    copy_vector(w, z0)  # w[:nz] = z0 (see kernel.linalg on slice assignment)
    w[m - 1] = 1.0

    t = 0.0
    mode = initial_mode(w, n, stick_row, lam, gamma, edges)
    if record:
        seg_t[0] = 0.0
        seg_mode[0] = mode
        copy_vector(seg_state[0], w[:nz])
    n_seg = 1
    seg_t_last = 0.0
    n_stick = 1 if mode == STICK else 0
    stick_start = 0.0
    t_last_stick = 0.0 if mode == STICK else np.nan
    # xi min, xi max and largest velocity since the last breakaway (cur) and section (os)
    cur_xmin = cur_xmax = os_xmin = os_xmax = w[0]
    cur_vmax = os_vmax = w[n]
    cur_stick = 0.0
    max_v = w[n]
    n_ev = 0
    n_steps = 0
    status = STATUS_STUCK if stop_at_stick and mode == STICK else STATUS_RUNNING
    last_bound = np.nan
    # the first step after a breakaway (see first_reach); a start at the belt speed onto a
    # slip mode (a breakaway state) is one: its rounding-level rise must not end the phase
    just_broke_away = mode != STICK and w[n] == 1.0
    fresh = True  # the signature of w must be recomputed (at the start and after events)
    fill_mode(ahat, phi, hstep, sig_rows, mode)  # a mode prepared lazily (prepare_point)
    while status != STATUS_STUCK:  # one step per iteration, at most MAX_STEPS
        if mode_kind(mode) == SLIP_I and status == STATUS_RUNNING and lyapunov_applies(
                mode_band(mode), lyap_lo, lyap_hi, n_lyap):
            last_bound, certified = lyapunov_bound(w, z_eq, lyap, kappa, n_lyap, mode_band(mode),
                                                   lyap_lo, lyap_hi, margin)
            if certified:
                status = STATUS_STEADY
                fsum[F_T_CERTIFIED] = t
                if not run_to_t_max:
                    break
        if (fresh and status == STATUS_RUNNING and trap_radius.shape[0] > 0
                and mode_kind(mode) == SLIP_I and trap_certifies(w, z_eq, trap_radius, trap_data)):
            # inside the slip trap region (kernel.certificate; empty unless prepared there)
            status = STATUS_STEADY
            fsum[F_T_CERTIFIED] = t
            last_bound = trap_data[TRAP_V_BOUND]
            if not run_to_t_max:
                break
        if t >= t_max:
            if status == STATUS_RUNNING:
                status = STATUS_T_MAX
            break
        if n_steps >= MAX_STEPS:
            if status == STATUS_RUNNING:
                status = STATUS_MAX_STEPS
            break
        if fresh:
            signature(sig_rows, mode, w, sig0)
            fresh = False
        h = hstep[mode]
        poly[P_FLAG, 0] = 0.0
        if t + h > t_max:
            h = t_max - t
            mode_taylor_vectors(ahat, mode, w, u, quick)
            poly[P_FLAG, 0] = 1.0
            taylor_state(u, h, w1)
        else:
            propagate(phi, mode, w, w1)
        signature(sig_rows, mode, w1, sig1)
        n_steps += 1
        departing = just_broke_away
        just_broke_away = False
        s_ev = np.inf
        e_ev = -1
        for e in range(ev_count[mode]):
            start, sign, offset = f_start[mode, e], f_sign[mode, e], f_offset[mode, e]
            if event_free(sig0, sig1, start, sign, offset, h):
                continue
            s = first_reach(sig_rows, mode, start, sign, offset, sig0, sig1, w, h, ahat, u, poly,
                            departing and ev_next[mode, e] == NEXT_BELT, quick)
            if s < s_ev:
                s_ev = s
                e_ev = e
        s_end = h
        if e_ev >= 0:
            if poly[P_FLAG, 0] == 0.0:
                mode_taylor_vectors(ahat, mode, w, u, quick)
                poly[P_FLAG, 0] = 1.0
            if quick:
                quick_state(u, s_ev, w_end)
            else:
                taylor_state(u, s_ev, w_end)
            if not quick:  # the value ranges are not tracked (sig1 is only theirs)
                signature(sig_rows, mode, w_end, sig1)
            s_end = s_ev
        else:
            copy_vector(w_end, w1)
        if mode == STICK or not quick:
            if mode == STICK:  # xi' = 1: xi's extremes are the step's ends, the velocity the belt's
                lo, hi, vhi = w[0], w_end[0], 1.0
            else:
                f_xi, f_vel = f_start[mode, F_XI], f_start[mode, F_VEL]
                lo, hi, settled = end_range(sig0, sig1, f_xi)
                # the extremes are located when they could extend either range: the one since
                # the last breakaway (cur) or the one since the last section crossing (os, a
                # slip oscillation's); pruning by cur alone lost the cycle's own extremes
                # after a larger transient (an amplitude 0.23 % low, independent audit)
                if not settled:
                    lo, hi = interior_range(sig_rows, mode, f_xi, sig0, sig1, w, s_end, ahat, u,
                                            poly, max(cur_xmin, os_xmin), min(cur_xmax, os_xmax),
                                            lo, hi)
                vlo, vhi, settled = end_range(sig0, sig1, f_vel)
                if not settled:
                    vhi = interior_range(sig_rows, mode, f_vel, sig0, sig1, w, s_end, ahat, u,
                                         poly, -np.inf, min(cur_vmax, os_vmax), vlo, vhi)[1]
            cur_xmin = min(cur_xmin, lo)
            cur_xmax = max(cur_xmax, hi)
            cur_vmax = max(cur_vmax, vhi)
            max_v = max(max_v, vhi)
            os_xmin = min(os_xmin, lo)
            os_xmax = max(os_xmax, hi)
            os_vmax = max(os_vmax, vhi)
        t += s_end
        copy_vector(w, w_end)
        copy_vector(sig0, sig1)
        if e_ev < 0:
            continue
        fresh = True
        n_ev += 1
        if mode == STICK:
            new_mode = SLIP_I if e_ev == 0 else SLIP_II
            just_broke_away = True
            cur_stick += t - stick_start
            if record and n_rec[0] >= all_bk_t.shape[0] and all_bk_t.shape[0] < cap_max:
                all_bk_t = grown(all_bk_t, min(cap_max, 2 * all_bk_t.shape[0]))
            if record and n_rec[0] < all_bk_t.shape[0]:
                all_bk_t[n_rec[0]] = t
            # constants as np.int64 / np.bool_: one compiled record_state (kernel.linalg's note)
            status = record_state(np.int64(0), t, w, np.int64(e_ev), cur_xmin, cur_xmax, cur_vmax,
                                  cur_stick, rec_t, rec_z, rec_key, rec_span, n_rec, max_period,
                                  cycle_tol, np.bool_(False), status, np.int64(STATUS_CYCLE), fsum,
                                  isum)
            if ball_data.shape[0] > 0 and status == STATUS_RUNNING:
                status = ball_status(w, n, e_ev, ball_data, ball_norm, fsum, isum, t)
            cur_xmin = cur_xmax = w[0]
            cur_vmax = w[n]
            cur_stick = 0.0
        elif ev_next[mode, e_ev] != NEXT_BELT:
            # a friction band edge: the slider velocity is the edge's, the band changes
            w[n] = ev_vel[mode, e_ev]
            new_mode = ev_next[mode, e_ev]
            if mode == sec_mode and e_ev == sec_event:
                status = record_state(np.int64(1), t, w, np.int64(n_stick), os_xmin, os_xmax,
                                      os_vmax, 0.0, rec_t, rec_z, rec_key, rec_span, n_rec,
                                      max_period, cycle_tol, np.bool_(True), status,
                                      np.int64(STATUS_OSCILLATION), fsum, isum)
                os_xmin = os_xmax = w[0]
                os_vmax = w[n]
        else:
            w[n] = 1.0
            new_mode = mode_at_belt_speed(w, stick_row, lam, gamma)
            if new_mode == STICK:
                n_stick += 1
                stick_start = t
                t_last_stick = t
                if stop_at_stick and status == STATUS_RUNNING:
                    status = STATUS_STUCK
            else:
                just_broke_away = True  # leaves the belt speed in slip: a departure as well
        if new_mode != mode:
            if mode == STICK and t == stick_start:
                n_stick -= 1  # a stick phase of zero duration is a touch, not a phase
            mode = new_mode
            if hstep[mode] != hstep[mode]:  # first entry of a lazily prepared mode
                fill_mode(ahat, phi, hstep, sig_rows, mode)
            if t == seg_t_last:
                # the phase just left lasted no time: overwrite it, keep times increasing
                n_seg -= 1
            if record and n_seg >= cap and cap < cap_max:
                cap = min(cap_max, 2 * cap)
                seg_t = grown(seg_t, cap)
                seg_mode = grown(seg_mode, cap)
                seg_state = grown_rows(seg_state, cap)
            if record and n_seg < cap:
                seg_t[n_seg] = t
                seg_mode[n_seg] = mode
                copy_vector(seg_state[n_seg], w[:nz])
            seg_t_last = t
            n_seg += 1
        if (status == STATUS_CYCLE or status == STATUS_OSCILLATION) and not run_to_t_max:
            break
        if n_ev >= max_events:
            if status == STATUS_RUNNING:
                status = STATUS_MAX_EVENTS
            break

    if n == 1 and status == STATUS_CYCLE and fsum[F_STICK_RATIO] == 0.0:
        # every stick phase of the cycle lasted no time (touches of the belt speed, e.g. an
        # undamped slider without kinetic friction): a slip oscillation, not stick-slip. With
        # one DOF the state at the belt speed is fixed by xi, so the repeat is exact as a proof.
        status = STATUS_OSCILLATION
    _summaries(fsum, isum, status, t, last_bound, max_v, t_last_stick, n_stick, n_rec[0], n_seg,
               n_steps, quick)
    n_keep = min(n_seg, cap) if record else 0
    return (
        seg_t[:n_keep].copy(),
        seg_mode[:n_keep].copy(),
        seg_state[:n_keep].copy(),
        all_bk_t[: min(n_rec[0], all_bk_t.shape[0]) if record else 0].copy(),
        fsum,
        isum,
        w[:nz].copy(),
    )

