"""The run loop: exact piecewise-linear propagation, graze-proof events, certified verdicts.

Arrays in, arrays out; no Python objects. See :mod:`stickslip.kernel.system` for the state
layout and :mod:`stickslip.kernel.polynomial` for the event location.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel.linalg import dot, matvec
from stickslip.kernel.polynomial import (
    DERIVATIVE_DEPTH,
    MAX_BREAKPOINTS,
    N_POLYNOMIALS,
    TAYLOR_DEGREE,
    functional_polynomials,
    monotone_breakpoints,
    monotone_root,
    poly_value,
    taylor_state,
    taylor_vectors,
)
from stickslip.kernel.system import (
    F_VEL,
    F_XI,
    N_ROWS,
    N_SIGNATURE,
    NEXT_BELT,
    SLIP_I,
    SLIP_II,
    STICK,
    TRAP_V_BOUND,
    find_band,
    mode_band,
    mode_code,
    mode_kind,
    prepare_bands,
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
def lyapunov_applies(band, lyap_lo, lyap_hi, n_lyap):
    """True when some Lyapunov function holds in slip-I of ``band``."""
    for p in range(n_lyap):
        if lyap_lo[p] <= band <= lyap_hi[p]:
            return True
    return False


@njit(cache=True)
def lyapunov_bound(w, z_eq, lyap, kappa, n_lyap, band, lyap_lo, lyap_hi, margin):
    """Smallest bound on ``sup |v_0|`` over the future, and whether one certifies steady sliding.

    Each Lyapunov function ``p`` valid in slip-I of ``band`` gives ``|v_0| <= bound_p`` for
    as long as the motion stays in its bands; ``bound_p < margin[p]`` proves that it does, for
    ever. The functions are centred at the steady-sliding equilibrium ``z_eq`` (the origin
    for the Coulomb law, where ``w - z_eq`` is ``w`` exactly).
    """
    nz = lyap.shape[1]
    best = np.inf
    certified = False
    for p in range(n_lyap):
        if band < lyap_lo[p] or band > lyap_hi[p]:
            continue
        acc = 0.0
        for i in range(nz):
            row = 0.0
            for j in range(nz):
                row += lyap[p, i, j] * (w[j] - z_eq[j])
            acc += (w[i] - z_eq[i]) * row
        bound = np.sqrt(max(acc, 0.0) * kappa[p])
        best = min(best, bound)
        if bound < margin[p]:
            certified = True
    return best, certified


@njit(cache=True)
def signature(sig_rows, w, out):
    """Project the state on the mode's signature rows (once per state)."""
    for b in range(N_SIGNATURE):
        out[b] = dot(sig_rows[b], w)


@njit(cache=True)
def _no_sign_change(sig0, sig1, start):
    """True when ``g'``, ``g''`` and ``g'''`` keep their sign between the two states."""
    for j in range(1, N_ROWS):
        if sig0[start + j] * sig1[start + j] < 0.0:
            return False
    return True


@njit(cache=True)
def _taylor_bounds(sig0, sig1, start, sign, offset, h):
    """Lower and upper bounds of ``g`` on ``[0, h]`` from its derivatives at the left end.

    Taylor's theorem with the third derivative between its end values (it is monotone on a step, the
    standing assumption of the event search): ``g(s) <= g + g' s + g'' s^2/2 + G3 s^3/6``.
    """
    g0 = sign * sig0[start] + offset
    d1 = sign * sig0[start + 1]
    d2 = sign * sig0[start + 2]
    d3a = sign * sig0[start + 3]
    d3b = sign * sig1[start + 3]
    h2 = 0.5 * h * h
    h3 = h * h2 / 3.0
    hi = g0 + max(0.0, d1) * h + max(0.0, d2) * h2 + max(0.0, max(d3a, d3b)) * h3
    lo = g0 + min(0.0, d1) * h + min(0.0, d2) * h2 + min(0.0, min(d3a, d3b)) * h3
    return lo, hi


@njit(cache=True)
def _polynomials(sig_rows, start, sign, offset, u, row, coef, depth=DERIVATIVE_DEPTH + 1):
    """Taylor coefficients of the functional and its first ``depth`` derivatives over the step."""
    m = row.shape[0]
    for i in range(m):
        row[i] = sign * sig_rows[start, i]
    row[m - 1] += offset
    functional_polynomials(u, row, coef, depth)


@njit(cache=True)
def first_reach(sig_rows, start, sign, offset, sig0, sig1, w0, h, ahat, u, have_u, row, coef,
                bp, departing, quick=False):
    """First ``s`` in ``[0, h]`` where the event function ``g`` reaches 0.

    ``departing``: the state has just left ``g = 0`` (a breakaway onto a slip mode whose
    belt-speed event this is); a rise of ``g`` from exactly 0 on the first monotone piece is
    then rounding noise of a departure with zero acceleration (``mu(0+) = mu_s``), not an
    event. A departure with nonzero acceleration never has such a piece.

    ``g = sign * sig[start] + offset``; ``g <= 0`` is the safe side. Returns ``inf`` when
    ``g`` stays negative on the step. The cheap test (endpoint signs of ``g`` to ``g'''``)
    proves most steps event-free; the others are split into monotone pieces so that a
    graze (``g`` touching 0 between two negative end values) is found at its extremum.

    ``quick`` (the runs of :func:`stickslip.kernel.batch.run_states` that stop at the first
    stick): when the end signs of ``g'``, ``g''`` and ``g'''`` agree, ``g`` is monotone on the
    step (the cheap test's argument), so the search for monotone pieces is skipped and
    Newton's iteration starts from the left end's tangent; the Taylor vectors use
    their quick form (:func:`~stickslip.kernel.polynomial.taylor_vectors`). The root is the same
    to rounding; the other runs keep the engine's historical arithmetic bit for bit.
    """
    g0 = sign * sig0[start] + offset
    g1 = sign * sig1[start] + offset
    if g1 < 0.0 and g0 <= 0.0 and _no_sign_change(sig0, sig1, start):
        return np.inf
    if g0 <= 0.0 and _taylor_bounds(sig0, sig1, start, sign, offset, h)[1] < 0.0:
        return np.inf
    if have_u[0] == 0:
        taylor_vectors(ahat, w0, u, quick)
        have_u[0] = 1
    if quick and _no_sign_change(sig0, sig1, start):
        _polynomials(sig_rows, start, sign, offset, u, row, coef, 1)  # g and g' (Newton)
        ga = coef[0, 0]
        gb = poly_value(coef, 0, h)
        if gb >= 0.0 and gb > ga:
            if ga >= 0.0:
                return np.inf if departing else 0.0
            slope = coef[1, 0]
            tangent = -ga / slope if slope != 0.0 else np.nan  # Newton's first point from s = 0
            return monotone_root(coef, 0, 0.0, h, ga, gb, tangent)
        return np.inf
    _polynomials(sig_rows, start, sign, offset, u, row, coef)
    npts = monotone_breakpoints(coef, 0.0, h, bp)
    ga = poly_value(coef, 0, bp[0])
    for i in range(npts - 1):
        gb = poly_value(coef, 0, bp[i + 1])
        if gb >= 0.0 and gb > ga:
            if ga >= 0.0:
                if not (departing and i == 0):
                    return bp[i]
            else:
                return monotone_root(coef, 0, bp[i], bp[i + 1], ga, gb)
        ga = gb
    return np.inf


@njit(cache=True)
def value_range(sig_rows, start, sig0, sig1, w0, s_end, ahat, u, have_u, row, coef, bp,
                known_lo, known_hi):
    """Exact minimum and maximum of the signature functional ``sig[start]`` on ``[0, s_end]``.

    Interior extrema are only located when they could extend ``[known_lo, known_hi]``.
    """
    lo = min(sig0[start], sig1[start])
    hi = max(sig0[start], sig1[start])
    if _no_sign_change(sig0, sig1, start):
        return lo, hi
    bound_lo, bound_hi = _taylor_bounds(sig0, sig1, start, 1.0, 0.0, s_end)
    if bound_lo >= known_lo and bound_hi <= known_hi:
        return lo, hi
    if have_u[0] == 0:
        taylor_vectors(ahat, w0, u)
        have_u[0] = 1
    _polynomials(sig_rows, start, 1.0, 0.0, u, row, coef)
    npts = monotone_breakpoints(coef, 0.0, s_end, bp)
    for i in range(1, npts - 1):
        g = poly_value(coef, 0, bp[i])
        lo = min(lo, g)
        hi = max(hi, g)
    return lo, hi


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
    """
    prepared = prepare_bands(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes)
    return run_prepared(mass, lam, gamma, edges, prepared, z0, t_max, max_events, cycle_tol,
                        max_period, record, run_to_t_max, False)


@njit(cache=True)
def run_prepared(mass, lam, gamma, edges, prepared, z0, t_max, max_events, cycle_tol, max_period,
                 record, run_to_t_max, stop_at_stick):
    """:func:`run` with the per-system data of :func:`prepare_bands` computed once.

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
    """
    n = mass.shape[0]
    nz = 2 * n
    m = nz + 1
    (ahat, phi, hstep, sig_rows, f_start, f_sign, f_offset, stick_row, lyap, kappa, n_lyap,
     ev_count, ev_next, ev_vel, _eq_mode, z_eq, lyap_lo, lyap_hi, margin, sec_mode,
     sec_event, trap_radius, trap_data) = prepared
    cap = max_events + 1 if record else 1
    seg_t = np.empty(cap)
    seg_mode = np.empty(cap, dtype=np.int64)
    seg_state = np.empty((cap, nz))
    # the last max_period + 1 breakaways live in a ring buffer (slot = index % ring)
    ring = max_period + 1
    bk_t = np.empty(ring)
    bk_z = np.empty((ring, nz))
    bk_dir = np.empty(ring, dtype=np.int64)
    interval = np.empty((ring, 4))  # xi min, xi max, v max, stick time per breakaway interval
    all_bk_t = np.empty(cap)
    # Poincare-section states of slip oscillations, ring buffer like the breakaways
    os_t = np.empty(ring)
    os_z = np.empty((ring, nz))
    os_stick = np.empty(ring, dtype=np.int64)
    os_interval = np.zeros((ring, 4))  # xi min, xi max, v max per section interval; no stick
    n_os = 0
    fsum = np.full(N_FLOAT, np.nan)
    isum = np.zeros(N_INT, dtype=np.int64)

    u = np.empty((TAYLOR_DEGREE + 1, m))
    have_u = np.zeros(1, dtype=np.int64)
    coef = np.empty((N_POLYNOMIALS, TAYLOR_DEGREE + 1))
    bp = np.empty(MAX_BREAKPOINTS)
    w = np.zeros(m)
    w1 = np.empty(m)
    w_end = np.empty(m)
    row = np.empty(m)
    sig0 = np.empty(N_SIGNATURE)
    sig1 = np.empty(N_SIGNATURE)
    w[:nz] = z0
    w[m - 1] = 1.0

    t = 0.0
    mode = initial_mode(w, n, stick_row, lam, gamma, edges)
    n_seg = 0
    if record:
        seg_t[0] = 0.0
        seg_mode[0] = mode
        seg_state[0] = w[:nz]
    n_seg = 1
    seg_t_last = 0.0
    n_stick = 1 if mode == STICK else 0
    stick_start = 0.0
    t_last_stick = 0.0 if mode == STICK else np.nan
    cur_xmin = w[0]
    cur_xmax = w[0]
    cur_vmax = w[n]
    cur_stick = 0.0
    max_v = w[n]
    os_xmin = w[0]
    os_xmax = w[0]
    os_vmax = w[n]
    n_bk = 0
    n_ev = 0
    n_steps = 0
    status = STATUS_RUNNING
    last_bound = np.nan

    fresh = True  # the signature of w must be recomputed (at the start and after events)
    just_broke_away = False  # the first step after a breakaway (see first_reach)
    departing = False
    if stop_at_stick and mode == STICK:
        status = STATUS_STUCK
    while status != STATUS_STUCK:
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
            signature(sig_rows[mode], w, sig0)
            fresh = False
        h = hstep[mode]
        have_u[0] = 0
        if t + h > t_max:
            h = t_max - t
            taylor_vectors(ahat[mode], w, u, stop_at_stick)
            have_u[0] = 1
            taylor_state(u, h, w1)
        else:
            matvec(phi[mode], w, w1)
        signature(sig_rows[mode], w1, sig1)
        n_steps += 1
        departing = just_broke_away
        just_broke_away = False

        s_ev = np.inf
        e_ev = -1
        for e in range(ev_count[mode]):
            s = first_reach(sig_rows[mode], f_start[mode, e], f_sign[mode, e], f_offset[mode, e],
                            sig0, sig1, w, h, ahat[mode], u, have_u, row, coef, bp,
                            departing and ev_next[mode, e] == NEXT_BELT, stop_at_stick)
            if s < s_ev:
                s_ev = s
                e_ev = e
        if e_ev >= 0:
            if have_u[0] == 0:
                taylor_vectors(ahat[mode], w, u, stop_at_stick)
                have_u[0] = 1
            taylor_state(u, s_ev, w_end)
            if not stop_at_stick:  # the value ranges are not tracked (sig1 is only theirs)
                signature(sig_rows[mode], w_end, sig1)
            s_end = s_ev
        else:
            w_end[:] = w1
            s_end = h

        if mode == STICK:
            # xi grows at the belt speed (xi' = 1): its extremes are the step's ends
            cur_xmin = min(cur_xmin, w[0])
            cur_xmax = max(cur_xmax, w_end[0])
            cur_vmax = max(cur_vmax, 1.0)
            max_v = max(max_v, 1.0)
            os_xmin = min(os_xmin, w[0])
            os_xmax = max(os_xmax, w_end[0])
            os_vmax = max(os_vmax, 1.0)
        elif not stop_at_stick:
            lo, hi = value_range(sig_rows[mode], f_start[mode, F_XI], sig0, sig1, w, s_end,
                                 ahat[mode], u, have_u, row, coef, bp, cur_xmin, cur_xmax)
            cur_xmin = min(cur_xmin, lo)
            cur_xmax = max(cur_xmax, hi)
            os_xmin = min(os_xmin, lo)
            os_xmax = max(os_xmax, hi)
            lo, hi = value_range(sig_rows[mode], f_start[mode, F_VEL], sig0, sig1, w, s_end,
                                 ahat[mode], u, have_u, row, coef, bp, -np.inf, cur_vmax)
            cur_vmax = max(cur_vmax, hi)
            max_v = max(max_v, hi)
            os_vmax = max(os_vmax, hi)

        t += s_end
        w[:] = w_end
        sig0[:] = sig1
        if e_ev < 0:
            continue
        fresh = True

        n_ev += 1
        if mode == STICK:
            new_mode = SLIP_I if e_ev == 0 else SLIP_II
            just_broke_away = True
            cur_stick += t - stick_start
            j = n_bk % ring
            bk_t[j] = t
            bk_z[j] = w[:nz]
            bk_dir[j] = e_ev
            interval[j, 0] = cur_xmin
            interval[j, 1] = cur_xmax
            interval[j, 2] = cur_vmax
            interval[j, 3] = cur_stick
            if record and n_bk < cap:
                all_bk_t[n_bk] = t
            n_bk += 1
            cur_xmin = w[0]
            cur_xmax = w[0]
            cur_vmax = w[n]
            cur_stick = 0.0
            scale = 1.0
            for c in range(nz):
                scale = max(scale, abs(w[c]))
            for k in range(1, max_period + 1):
                if n_bk - 1 - k < 0 or status != STATUS_RUNNING:
                    break
                i = (n_bk - 1 - k) % ring
                if bk_dir[i] != bk_dir[j]:
                    continue
                diff = _mismatch(bk_z, j, i)
                if diff <= cycle_tol * scale:
                    status = STATUS_CYCLE
                    _record_cycle(fsum, isum, bk_t, interval, n_bk - 1, ring, k, j, i, diff, scale, t)
                    break
        elif ev_next[mode, e_ev] != NEXT_BELT:
            # a friction band edge: the slider velocity is the edge's, the band changes
            w[n] = ev_vel[mode, e_ev]
            new_mode = ev_next[mode, e_ev]
            if mode == sec_mode and e_ev == sec_event:
                j = n_os % ring
                os_t[j] = t
                os_z[j] = w[:nz]
                os_stick[j] = n_stick
                os_interval[j, 0] = os_xmin
                os_interval[j, 1] = os_xmax
                os_interval[j, 2] = os_vmax
                n_os += 1
                os_xmin = w[0]
                os_xmax = w[0]
                os_vmax = w[n]
                scale = 1.0
                for c in range(nz):
                    scale = max(scale, abs(w[c]))
                for k in range(1, max_period + 1):
                    if n_os - 1 - k < 0 or status != STATUS_RUNNING:
                        break
                    i = (n_os - 1 - k) % ring
                    if os_stick[i] != os_stick[j]:
                        break  # a stick phase inside the stretch: not a slip oscillation
                    diff = _mismatch(os_z, j, i)
                    if diff <= cycle_tol * scale:
                        status = STATUS_OSCILLATION
                        _record_cycle(fsum, isum, os_t, os_interval, n_os - 1, ring, k, j, i, diff,
                                      scale, t)
                        break
        else:
            w[n] = 1.0
            new_mode = mode_at_belt_speed(w, stick_row, lam, gamma)
            if new_mode == STICK:
                n_stick += 1
                stick_start = t
                t_last_stick = t
                if stop_at_stick and status == STATUS_RUNNING:
                    status = STATUS_STUCK
        if new_mode != mode:
            if mode == STICK and t == stick_start:
                n_stick -= 1  # a stick phase of zero duration is a touch, not a phase
            mode = new_mode
            if n_seg > 0 and t == seg_t_last:
                # the phase just left lasted no time: overwrite it, keep times increasing
                n_seg -= 1
            if record and n_seg < cap:
                seg_t[n_seg] = t
                seg_mode[n_seg] = mode
                seg_state[n_seg] = w[:nz]
            seg_t_last = t
            n_seg += 1
        if (status == STATUS_CYCLE or status == STATUS_OSCILLATION) and not run_to_t_max:
            break
        if status == STATUS_STUCK:
            break
        if n_ev >= max_events:
            if status == STATUS_RUNNING:
                status = STATUS_MAX_EVENTS
            break

    fsum[F_LYAPUNOV_BOUND] = last_bound
    fsum[F_MAX_VELOCITY] = max_v
    if stop_at_stick:
        # extremes are not tracked: the velocity maximum, and a slip oscillation's xi range
        fsum[F_MAX_VELOCITY] = np.nan
        if status == STATUS_OSCILLATION:
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
    n_keep = min(n_seg, cap) if record else 0
    return (
        seg_t[:n_keep].copy(),
        seg_mode[:n_keep].copy(),
        seg_state[:n_keep].copy(),
        all_bk_t[: min(n_bk, cap) if record else 0].copy(),
        fsum,
        isum,
        w[:nz].copy(),
    )


@njit(cache=True)
def evaluate(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, seg_t, seg_mode,
             seg_state, times):
    """Exact states at sorted ``times`` from the recorded phases (dense output).

    Reproduces the run loop's own step grid: full steps with ``expm(A_hat h)`` from the
    start of each phase, then the Taylor polynomial for the remainder.
    """
    n = mass.shape[0]
    nz = 2 * n
    m = nz + 1
    ahat, phi, hstep = prepare_bands(mass, damping, stiffness, lam, gamma, edges, intercepts,
                               slopes)[:3]
    out = np.empty((times.shape[0], nz))
    modes = np.empty(times.shape[0], dtype=np.int64)
    u = np.empty((TAYLOR_DEGREE + 1, m))
    w = np.empty(m)
    tmp = np.empty(m)
    res = np.empty(m)
    n_seg = seg_t.shape[0]
    p = -1
    t_k = 0.0
    for idx in range(times.shape[0]):
        t = times[idx]
        while p + 1 < n_seg and seg_t[p + 1] <= t:
            p += 1
            w[:nz] = seg_state[p]
            w[m - 1] = 1.0
            t_k = seg_t[p]
        mode = seg_mode[p]
        h = hstep[mode]
        while t_k + h <= t:
            matvec(phi[mode], w, tmp)
            w[:] = tmp
            t_k += h
        taylor_vectors(ahat[mode], w, u)
        taylor_state(u, t - t_k, res)
        out[idx] = res[:nz]
        modes[idx] = mode
    return out, modes
