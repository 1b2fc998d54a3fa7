"""Slip escape region: an early certificate that a 1-DOF motion reaches the belt speed and sticks.

The complement of :mod:`stickslip.kernel.certificate` (the slip trap region INSIDE the unstable
slip cycle, from which every motion slides steadily): a region OUTSIDE the unstable slip cycle
from which every motion provably reaches the belt speed, within a bounded time, and sticks
there. In one degree of freedom every stick phase ends at the same breakaway state (the
"1DOF shortcut" of :func:`stickslip.kernel.batch.run_states`), so such a state's verdict is
the start-up run's, and :func:`escape_certifies` gives it without simulating the way to the
belt speed: for a weakly damped system that way is tens of turns and thousands of band
crossings when the state starts near the unstable cycle, and a hundred crossings otherwise.
States above the belt speed have their own, analytic test (:func:`slip_ii_stick_time`:
friction decelerates them to the belt speed, where they stick).

Derivation. Notation of :mod:`stickslip.kernel.certificate`: slip-I (``v = xi' < 1``),
``M v' = -K z - g(v)`` with ``z = xi - xi_eq``, ``g(v) = k(v) v``,
``k(v) = C + sigma(1 - v)`` (``sigma`` the law's secant slope about ``u = 1``), and
``x = sqrt(K) z``, ``y = sqrt(M) v``, ``rho = |(x, y)|``, ``phi`` the clockwise angle from the
section ray ``S = {y = 0, x > 0}``; the belt speed is the line ``y = y_1 = sqrt(M)``.

0. *Global rotation and growth.* ``k`` ranges over ``[C + sigma_min, C + sigma_max]``, the
   secant slopes over every ``u >= 0`` (:func:`global_secant_range`). If
   ``k_abs = max |k| < 2 sqrt(K M)``, then everywhere in slip-I
   ``phi' = (omega rho^2 + (k/M) x y) / rho^2 >= omega_min = omega - k_abs / (2 M) > 0``
   (``|x y| <= rho^2 / 2``): every motion turns clockwise, a turn takes at most
   ``2 pi / omega_min``, and two motions, written as ``rho(phi)``, never cross (uniqueness:
   ``F`` is continuous and piecewise affine). The energy ``E = rho^2 / 2`` obeys
   ``E' = -g(v) v = (F(1 - v) - F(1)) v - C v^2 <= P`` with ``P`` the largest value of that
   power over ``v <= 1`` (:func:`power_bound`; on each band a quadratic in ``v``), so
   ``rho^2`` grows at most by ``2 P`` per unit of time, whatever the radius.
1. *The bounding trajectory* starts on ``S`` at ``rho_0`` (just outside the unstable cycle)
   and is followed with the engine's exact propagation until it reaches the belt speed. Its
   returns to ``S``, ``rho_1 < rho_2 < ... < rho_J`` (``J >= 1``), must increase strictly from
   ``rho_0``, and after ``rho_J`` it reaches ``v = 1`` before returning, at angle ``phi_b``.
   Its first turn (the arc ``A_0`` from ``rho_0`` to ``rho_1``) and the segment
   ``[rho_0, rho_1]`` of ``S`` bound a region ``D_0``; motions cross the segment only
   downwards, that is out of ``D_0`` (just above ``S`` the arc is at ``rho_1``, just below at
   ``rho_0``), and cannot cross the arc, so the exterior ``E`` of ``D_0`` is positively
   invariant while the motion is in slip-I.
2. *Escape in bounded time.* ``P`` (the first return to ``S``) is increasing (point 0), so for
   ``rho`` in ``[rho_j, rho_{j+1})`` either the motion reaches ``v = 1`` first or
   ``P(rho) >= P(rho_j) = rho_{j+1} > rho``. A motion in ``E`` crosses ``S`` (if it does) at
   ``rho >= rho_1`` (it approaches ``S`` from above, where ``E`` lies beyond ``rho_1``), and then
   climbs at least one rung of the ladder per turn; beyond ``rho_J`` it is outside the last
   turn of the bounding trajectory, which reaches ``y_1`` at ``phi_b``, so it has
   ``y >= y_1`` by that angle. Every motion in ``E`` therefore reaches the belt speed within
   ``J + 2`` turns, at a time ``t_s <= T = 2 pi (J + 2) / omega_min``.
3. *It sticks there.* At ``v = 1^-`` in band 0, ``M v' = F(0) - gamma lambda - S`` with the
   stick force ``S = K xi + C`` (Eq. 20 in shifted coordinates): a motion reaching
   ``v = 1`` from below has ``v' >= 0``, so ``S <= F(0) - gamma lambda <= lambda`` (checked:
   ``F(0) <= lambda (1 + gamma)``, i.e. ``mu_0 <= mu_s``). The tangency ``S = lambda`` is the
   breakaway state itself, from which a stick phase of no length and slip-I are one motion.
   It remains to show ``S > -lambda (1 + 2 gamma)``, i.e. ``x_a > x_lo`` at the arrival
   ``(x_a, y_1)``. In the upper half-plane ``x' = omega y > 0``, so ``x_a`` is at least ``x``
   where the motion last entered it, ``-rho_pi`` on the negative ``x`` axis (or its start).
   Two cases, by the stored envelope ``r_env(phi)``, a lower bound of the outermost turn
   of the bounding trajectory at ``phi`` (its last complete turn, and its final partial turn
   where that exists):
   (a) ``rho < r_env(phi)``: the state lies between two turns ``j, j + 1`` of the bounding
   trajectory at its angle, and stays between consecutive turns (non-crossing) until it
   arrives, so ``rho_pi <= R``, the largest radius of the bounding trajectory;
   (b) otherwise it is outside that turn and arrives before the bounding trajectory's next
   pass at the same angle: it reaches the negative ``x`` axis after turning at most
   ``Delta(phi) = pi - phi`` (lower half) or ``3 pi - phi`` (upper half), so
   ``rho_pi^2 <= rho^2 + 2 P Delta(phi) / omega_min``.
   The region's check ``R < -x_lo`` makes every state of (a) stick; a state of (b) sticks
   when ``rho^2 < x_lo^2 - 2 P Delta(phi) / omega_min``; the stored outer radius is the
   larger of the two bounds per angle bin (a state below it is in (a) or satisfies (b)).

The region is ``{v < 1, r_in(phi) < rho < r_hi(phi)}``, ``r_in`` an upper bound of ``A_0``'s
radius over each of :data:`ESCAPE_BINS` angle bins, ``r_hi`` the outer radius of point 3.
A state in it reaches the belt speed in at most ``T`` and sticks, in ``xi >= xi_lo``
(``S >= -lambda (1 + 2 gamma)``); its verdict is the start-up run's, and the joined clock of
a direct run certifies it by ``T + t_cert(start-up) + xi_startup - xi_lo``
(:func:`stickslip.kernel.batch.run_states` uses the region only where that is within the
horizon, so the label is the direct run's; like the trap region, the region does not count
the events a direct run would spend on the way, see ``run_states``).

Numerical rigour, as for the trap region: the bounding trajectory is the engine's exact
piecewise-linear solution sampled at ``dt`` (:data:`SAMPLES_PER_PERIOD`;
:func:`stickslip.kernel.dense_output.evaluate_prepared`). Between samples ``|v'| <= A = (sqrt(K) rho_max +
k_abs max|v|) / M`` and ``|rho'| <= G = k_abs max|v| / sqrt(M)`` (``|rho'| = |k| y^2 / (M rho)
<= |k| |v| / sqrt(M)``), with bootstrap bounds 10 % beyond the sampled ranges, checked. So:
each envelope bound is the smallest adjacent sample radius minus ``G dt`` and ``R`` the
largest plus ``G dt``; ``r_in`` is the largest adjacent radius plus ``G_1 dt_1`` on a finer
grid of the first turn (:data:`FIRST_TURN_SAMPLES`, ``G_1`` from that turn's own ``|v|``
range), since it sets how close to the unstable cycle the region reaches; and each return to
``S`` is located on a grid :data:`CROSSING_REFINE` times finer between the two samples around
it, within ``A dt_c^2 / 2`` (in ``z``) of the last fine sample before it (``v`` vanishes at the
return and changes at most at rate ``A``). The ladder is checked with these margins and the
angle must advance (by less than ``pi``) at every sample step. A region that fails any check
is not built (empty tables: no state is certified, every state runs).

The start radius: the first-return test :func:`first_return_outwards` (one turn, the return
interpolated between samples) climbs a ladder of fractions of the belt-speed radius
``sqrt(M)`` until a start's first return lies further out (a start inside the unstable cycle
comes back inside), then bisects :data:`BISECTIONS` times between the last inward and the
first outward start, locating the cycle. The proof (:func:`_trial`) is then tried from the
outward end, backing off outwards by growing steps (:data:`BACK_OFF` tries) while a check
fails (a start too close to the cycle has returns that the margins cannot tell apart). The
ring left between the region and the cycle, where states are simulated, is then a few
thousandths of the radius thick. The search only chooses the start; every kept region passed
every check of the proof.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel.dense_output import evaluate_prepared
from stickslip.kernel.engine import F_T_END, I_STATUS, STATUS_STUCK, run_prepared
from stickslip.kernel.system import SLIP_I, mode_kind, secant_range

#: Angle bins of the stored region.
ESCAPE_BINS = 1024
#: Samples of the bounding trajectory per undamped period.
SAMPLES_PER_PERIOD = 1024
#: Steps of the fine grid that locates each return to S between two samples.
CROSSING_REFINE = 64
#: Samples per undamped period of its first turn (the region's inner boundary).
FIRST_TURN_SAMPLES = 16384
#: Start radii tried, as fractions of the belt-speed radius ``sqrt(M)``, ascending.
LADDER = (0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9)
#: Bisection steps of the first-return test between the ladder's last inward and first
#: outward start (locating the unstable cycle), and most proofs tried from there outwards.
BISECTIONS = 16
BACK_OFF = 8
#: Time allowed for the bounding trajectory to reach the belt speed, in undamped periods.
TRIAL_PERIODS = 400.0
#: Most events of a bounding trajectory (a budget the run loop allocates records for: a
#: trajectory that needs more is refused), and of one turn of the search per friction band.
TRIAL_EVENTS = 20_000
TURN_EVENTS_PER_BAND = 4
#: Most samples of one bounding trajectory.
MAX_SAMPLES = 4_000_000

# layout of the region's scalars
ESCAPE_SQRT_K = 0
ESCAPE_SQRT_M = 1
ESCAPE_TIME = 2  # T: every state of the region reaches the belt speed by then
ESCAPE_XI_LO = 3  # lowest xi (shifted) where a motion of the region can stick
ESCAPE_RHO0 = 4  # start radius of the bounding trajectory on S
ESCAPE_R_MIN = 5  # smallest r_in and largest r_hi (quick tests before the angle)
ESCAPE_R_MAX = 6
ESCAPE_TURNS = 7  # J, returns of the bounding trajectory before it reaches the belt speed
ESCAPE_F_LO = 8  # smallest friction magnitude of the law (slip-II test), NaN: no test
N_ESCAPE = 9


@njit(cache=True)
def global_secant_range(edges, intercepts, slopes):
    """Extremes of the secant slope ``sigma(u) = (F(u) - F(1)) / (u - 1)`` over every ``u >= 0``.

    :func:`~stickslip.kernel.system.secant_range` over ``[0, edges[-2]]`` (every finite band
    edge), and the last band beyond its lower edge, where ``sigma`` is monotone and tends to
    the band's slope: its extremes are at the edge (included) and that limit.
    """
    nb = intercepts.shape[0]
    u_top = max(edges[nb - 1], 2.0) if nb > 1 else 2.0
    lo, hi = secant_range(edges, intercepts, slopes, 0.0, u_top)
    lo = min(lo, slopes[nb - 1])
    hi = max(hi, slopes[nb - 1])
    return lo, hi


@njit(cache=True)
def power_bound(damping00, edges, intercepts, slopes):
    """``P = sup (F(1 - v) - F(1)) v - C v^2`` over ``v <= 1``: the fastest energy gain in slip-I.

    With ``w = v = 1 - u`` on band ``b`` (``F = a + s u``) the power is
    ``(a + s - F(1)) w - (s + C) w^2``, a quadratic on ``w`` in ``[1 - e_{b+1}, 1 - e_b]``: its
    supremum is at an end or at the vertex. ``inf`` when the last band (``w -> -inf``) lets it
    grow without bound. Never negative (``v = 0`` gives 0).
    """
    nb = intercepts.shape[0]
    b1 = 0
    for b in range(nb):
        if edges[b] <= 1.0:
            b1 = b
    f_one = intercepts[b1] + slopes[b1]
    best = 0.0
    for b in range(nb):
        alpha = intercepts[b] + slopes[b] - f_one
        beta = slopes[b] + damping00
        w_hi = 1.0 - edges[b]
        w_lo = 1.0 - edges[b + 1]  # -inf on the last band
        if not np.isfinite(w_lo):
            if beta < 0.0 or (beta == 0.0 and alpha < 0.0):
                return np.inf
        else:
            best = max(best, alpha * w_lo - beta * w_lo * w_lo)
        best = max(best, alpha * w_hi - beta * w_hi * w_hi)
        if beta > 0.0:
            w_star = alpha / (2.0 * beta)
            if w_lo <= w_star <= w_hi:
                best = max(best, alpha * w_star - beta * w_star * w_star)
    return best


@njit(cache=True)
def friction_floor(edges, intercepts, slopes):
    """``min F(u)`` over ``u >= 0`` of the band table: at a finite edge, or ``-inf`` when the
    last band falls without end."""
    nb = intercepts.shape[0]
    if slopes[nb - 1] < 0.0:
        return -np.inf
    lo = np.inf
    for k in range(nb):  # the lower edge of every band (the last band rises from its edge)
        lo = min(lo, intercepts[k] + slopes[k] * edges[k])
        if k + 1 < nb:
            lo = min(lo, intercepts[k] + slopes[k] * edges[k + 1])
    return lo


@njit(cache=True)
def slip_ii_stick_time(w, mass00, damping00, stiffness00, lam, gamma, f_lo):
    """A bound on the time a 1-DOF state above the belt speed takes to stick, or ``inf``.

    Slip-II (``v = xi' > 1``, ``u = v - 1``): ``M v' = -K xi - C v - F(u) - gamma lambda``
    (shifted coordinates, Eqs. 25-27 with the law). While it lasts, ``xi`` grows (``xi' > 1``),
    ``C v >= C`` and ``F >= f_lo`` (:func:`friction_floor`), so ``M v' <= -D`` with
    ``D = K xi_0 + C + f_lo + gamma lambda``. If ``D > 0`` the slider is decelerated to the
    belt speed by ``t_a = M (v_0 - 1) / D`` (a band edge only changes the band), having
    moved to ``xi_a`` in ``[xi_0, xi_0 + v_0 t_a]``; there the stick force of Eq. (20),
    ``S = K xi_a + C``, lies in ``[K xi_0 + C, K (xi_0 + v_0 t_a) + C]``. When that interval
    is inside the static range ``[-lambda (1 + 2 gamma), lambda]`` (with a relative margin of
    1e-9 for the engine's rounding) the motion sticks there, by ``t_a``, at ``xi_a >= xi_0``:
    ``t_a`` is returned. ``inf`` otherwise (and for ``v_0 <= 1``, ``f_lo`` NaN, ``C < 0`` or
    ``K <= 0``, where the bound does not hold).
    """
    v0 = w[1]
    if not (v0 > 1.0 and f_lo > -np.inf and damping00 >= 0.0 and stiffness00 > 0.0):
        return np.inf
    xi0 = w[0]
    d = stiffness00 * xi0 + damping00 + f_lo + gamma * lam
    if not d > 0.0:
        return np.inf
    t_a = mass00 * (v0 - 1.0) / d
    margin = 1e-9 * max(1.0, lam * (1.0 + 2.0 * gamma))
    s_lo = stiffness00 * xi0 + damping00
    s_hi = stiffness00 * (xi0 + v0 * t_a) + damping00
    if s_lo >= -lam * (1.0 + 2.0 * gamma) + margin and s_hi <= lam - margin:
        return t_a
    return np.inf


@njit(cache=True)
def slip_escape_region(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, prepared):
    """The slip escape region of a 1-DOF system: ``(r_in, r_hi, data)``.

    ``r_in``, ``r_hi`` (:data:`ESCAPE_BINS`,) and ``data`` (:data:`N_ESCAPE`,) as described in
    the module docstring; ``prepared`` is the system's
    :func:`~stickslip.kernel.system.prepare_bands` (or ``prepare_certified``) data. Empty
    tables (no region) for more than one degree of freedom, a one-band law, a discontinuous
    law, ``F(0) > lambda (1 + gamma)``, a law whose slopes stop the rotation or let the energy
    grow without bound, a static range the motions could overshoot, or when no start radius
    passes every check (for instance no unstable slip cycle: every start decays).
    """
    data = np.zeros(N_ESCAPE)
    empty = np.zeros(0)
    nb = intercepts.shape[0]
    if mass.shape[0] != 1 or nb < 2:
        return empty, empty, data
    for b in range(nb - 1):
        e = edges[b + 1]
        left = intercepts[b] + slopes[b] * e
        right = intercepts[b + 1] + slopes[b + 1] * e
        if abs(left - right) > 1e-9 * max(1.0, abs(left)):
            return empty, empty, data
    if intercepts[0] - gamma * lam > lam * (1.0 + 1e-12):
        return empty, empty, data  # F(0) above the static limit: point 3 needs S <= lambda
    m00 = mass[0, 0]
    k00 = stiffness[0, 0]
    c00 = damping[0, 0]
    sig_lo, sig_hi = global_secant_range(edges, intercepts, slopes)
    k_abs = max(abs(c00 + sig_lo), abs(c00 + sig_hi))
    if not k_abs < 2.0 * np.sqrt(k00 * m00):
        return empty, empty, data  # the motions may stop turning (point 0)
    omega_min = np.sqrt(k00 / m00) - k_abs / (2.0 * m00)
    p_max = power_bound(c00, edges, intercepts, slopes)
    if not np.isfinite(p_max):
        return empty, empty, data
    sqrt_k = np.sqrt(k00)
    sqrt_m = np.sqrt(m00)
    z_eq = prepared[15]
    xi_lo = (-lam * (1.0 + 2.0 * gamma) - c00) / k00  # S = K xi + C at the static limit
    x_lo_abs = sqrt_k * (z_eq[0] - xi_lo) * (1.0 - 1e-9)  # -x_lo, with a margin for rounding
    if not x_lo_abs > 0.0:
        return empty, empty, data
    data[ESCAPE_SQRT_K] = sqrt_k
    data[ESCAPE_SQRT_M] = sqrt_m
    data[ESCAPE_XI_LO] = xi_lo
    rho_top = sqrt_m
    # locate the unstable cycle on S: the first return moves outwards beyond it
    f_in = 0.0
    f_out = -1.0
    for f in LADDER:
        if first_return_outwards(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes,
                                 prepared, f * rho_top, omega_min):
            f_out = f
            break
        f_in = f
    if f_out < 0.0:
        return empty, empty, data  # every start comes back inwards: no escape to certify
    for _ in range(BISECTIONS):
        f_mid = 0.5 * (f_in + f_out)
        if first_return_outwards(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes,
                                 prepared, f_mid * rho_top, omega_min):
            f_out = f_mid
        else:
            f_in = f_mid
    # the proof from just outside it, backing off (a start too close cannot be told from the
    # cycle within the sampling margins); the last try is the ladder's outward start
    step = max(f_out - f_in, 1e-6)
    for k in range(BACK_OFF):
        f = min(f_out + step * (4.0**k - 1.0), 0.95)
        r_in, r_hi, turns = _trial(mass, damping, stiffness, lam, gamma, edges, intercepts,
                                   slopes, prepared, f * rho_top, k_abs, omega_min, p_max,
                                   x_lo_abs)
        if r_in.shape[0] > 0:
            data[ESCAPE_TIME] = 2.0 * np.pi * (turns + 2) / omega_min
            data[ESCAPE_RHO0] = f * rho_top
            data[ESCAPE_R_MIN] = r_in.min()
            data[ESCAPE_R_MAX] = r_hi.max()
            data[ESCAPE_TURNS] = turns
            return r_in, r_hi, data
    return empty, empty, data


@njit(cache=True)
def first_return_outwards(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, prepared,
                          rho0, omega_min):
    """True when the motion from ``rho0`` on ``S`` reaches the belt speed or returns to ``S``
    further out (the crossing interpolated linearly between samples of a
    :data:`SAMPLES_PER_PERIOD` grid). Only locates the unstable cycle for the search; the
    proof is :func:`_trial`'s."""
    m00 = mass[0, 0]
    k00 = stiffness[0, 0]
    sqrt_k = np.sqrt(k00)
    z_eq = prepared[15]
    dt = 2.0 * np.pi * np.sqrt(m00 / k00) / SAMPLES_PER_PERIOD
    z0 = np.array([z_eq[0] + rho0 / sqrt_k, 0.0])
    budget = TURN_EVENTS_PER_BAND * edges.shape[0] + 64  # a turn crosses each edge twice
    seg_t, seg_mode, seg_state, _, fsum, isum, _ = run_prepared(
        mass, lam, gamma, edges, prepared, z0, 1.05 * 2.0 * np.pi / omega_min, budget, 1e-12,
        np.int64(4), np.bool_(True), np.bool_(False), np.bool_(True), np.bool_(False))
    times = np.arange(int(fsum[F_T_END] / dt)) * dt
    states, _ = evaluate_prepared(prepared[0], prepared[1], prepared[2], seg_t,
                         seg_mode, seg_state, times)
    for i in range(times.shape[0] - 1):
        v_a = states[i, 1]
        v_b = states[i + 1, 1]
        if v_a > 0.0 and v_b <= 0.0 and states[i, 0] > z_eq[0]:
            z_c = states[i, 0] + (states[i + 1, 0] - states[i, 0]) * v_a / (v_a - v_b)
            return sqrt_k * (z_c - z_eq[0]) > rho0
    return isum[I_STATUS] == STATUS_STUCK


@njit(cache=True)
def _clockwise_angle(x, y):
    phi = np.arctan2(-y, x)
    if phi < 0.0:
        phi += 2.0 * np.pi
    return phi


@njit(cache=True)
def _arc_bounds(x, y, i0, i1, pad, upper, out):
    """Per angle bin, the extreme radius of sample pairs ``(i, i + 1)``, ``i0 <= i < i1``.

    ``upper``: the largest adjacent sample radius plus ``pad`` (an upper bound of the arc's
    radius over the bin), else the smallest minus ``pad``; combined into ``out`` by max or
    min. A pair that crosses ``S`` covers the bins up to ``2 pi`` and from 0.
    """
    nbin = out.shape[0]
    scale = nbin / (2.0 * np.pi)
    for i in range(i0, i1):
        phi_a = _clockwise_angle(x[i], y[i])
        phi_b = _clockwise_angle(x[i + 1], y[i + 1])
        r_a = np.sqrt(x[i] * x[i] + y[i] * y[i])
        r_b = np.sqrt(x[i + 1] * x[i + 1] + y[i + 1] * y[i + 1])
        val = max(r_a, r_b) + pad if upper else min(r_a, r_b) - pad
        b_a = min(int(phi_a * scale), nbin - 1)
        b_b = min(int(phi_b * scale), nbin - 1)
        if b_b < b_a:  # across S: [phi_a, 2 pi) and [0, phi_b]
            for b in range(b_a, nbin):
                out[b] = max(out[b], val) if upper else min(out[b], val)
            b_a = 0
        for b in range(b_a, b_b + 1):
            out[b] = max(out[b], val) if upper else min(out[b], val)


# Longer than the house's 120 lines: one trial is one proof, step by step (follow the motion
# to the belt speed, check the ladder, bound the arcs), each check beside the step it guards,
# as in kernel.certificate._trial.
@njit(cache=True)
def _trial(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, prepared, rho0, k_abs,
           omega_min, p_max, x_lo_abs):
    """``(r_in, r_hi, J)`` of the bounding trajectory from ``rho0`` on ``S``, empty if a check fails."""
    empty = np.zeros(0)
    m00 = mass[0, 0]
    k00 = stiffness[0, 0]
    sqrt_k = np.sqrt(k00)
    sqrt_m = np.sqrt(m00)
    z_eq = prepared[15]
    period = 2.0 * np.pi * np.sqrt(m00 / k00)
    dt = period / SAMPLES_PER_PERIOD
    z0 = np.array([z_eq[0] + rho0 / sqrt_k, 0.0])
    # the motion, recorded until it reaches the belt speed (stop_at_stick ends the run there)
    seg_t, seg_mode, seg_state, _, fsum, isum, _ = run_prepared(
        mass, lam, gamma, edges, prepared, z0, TRIAL_PERIODS * period, np.int64(TRIAL_EVENTS), 1e-12,
        np.int64(4), np.bool_(True), np.bool_(False), np.bool_(True), np.bool_(False))
    if isum[I_STATUS] != STATUS_STUCK:
        return empty, empty, 0  # decayed, oscillates, or too slow
    t_stick = fsum[F_T_END]
    n_samples = int(np.ceil(t_stick / dt))  # every sample before the arrival
    if n_samples > MAX_SAMPLES or n_samples < 4:
        return empty, empty, 0
    times = np.arange(n_samples) * dt
    states, modes = evaluate_prepared(prepared[0], prepared[1], prepared[2],
                             seg_t, seg_mode, seg_state, times)
    for i in range(n_samples):
        if mode_kind(modes[i]) != SLIP_I or not states[i, 1] < 1.0:
            return empty, empty, 0
    x = sqrt_k * (states[:, 0] - z_eq[0])
    y = sqrt_m * states[:, 1]
    # bootstrap bounds between samples (v <= 1 before the arrival)
    v_lo = 0.0
    rho_max = 0.0
    for i in range(n_samples):
        v_lo = min(v_lo, states[i, 1])
        rho_max = max(rho_max, np.sqrt(x[i] * x[i] + y[i] * y[i]))
    v_lo_b = v_lo - 0.1 * (1.0 - v_lo) - 1e-6
    rho_max_b = 1.1 * rho_max
    v_abs_b = max(1.0, abs(v_lo_b))
    g_max = k_abs * v_abs_b
    rate_v = (sqrt_k * rho_max_b + g_max) / m00
    rate_rho = g_max / sqrt_m
    if not (v_lo - rate_v * dt >= v_lo_b and rho_max + rate_rho * dt <= rho_max_b):
        return empty, empty, 0
    # the angle advances at every step (point 0), and the returns to S climb (points 1, 2)
    for i in range(n_samples - 1):
        d = _clockwise_angle(x[i + 1], y[i + 1]) - _clockwise_angle(x[i], y[i])
        if d < 0.0:
            d += 2.0 * np.pi
        if not 0.0 < d < np.pi:
            return empty, empty, 0
    # each return located on a fine grid of CROSSING_REFINE steps between the two samples
    # around it: within z_err of the last fine sample before it (v vanishes there, |v'| <= A)
    dt_c = dt / CROSSING_REFINE
    z_err = 0.5 * rate_v * dt_c * dt_c * sqrt_k
    crossings = np.empty(n_samples, dtype=np.int64)
    window = np.empty(CROSSING_REFINE + 1)
    n_cross = 0
    prev_hi = x[0]
    for i in range(n_samples - 1):
        if y[i] > 0.0 and y[i + 1] <= 0.0 and x[i] > 0.0:
            for k in range(CROSSING_REFINE):
                window[k] = times[i] + k * dt_c
            window[CROSSING_REFINE] = times[i + 1]
            fine, _ = evaluate_prepared(prepared[0], prepared[1], prepared[2],
                               seg_t, seg_mode, seg_state, window)
            x_c = np.nan
            for k in range(CROSSING_REFINE):
                if fine[k, 1] > 0.0 and fine[k + 1, 1] <= 0.0:
                    x_c = sqrt_k * (fine[k, 0] - z_eq[0])
                    break
            if not x_c - z_err > prev_hi:  # also refuses a crossing not found (NaN)
                return empty, empty, 0
            prev_hi = x_c + z_err
            crossings[n_cross] = i
            n_cross += 1
    if n_cross < 1:
        return empty, empty, 0
    # r_in: upper bound of the first turn A_0 (the exterior of D_0 is the region, point 1),
    # sampled finely up to the sample after its return; its own bootstrap bound of |v|
    pad = rate_rho * dt
    dt_f = period / FIRST_TURN_SAMPLES
    times_f = np.arange(int(times[crossings[0] + 1] / dt_f) + 2) * dt_f
    first, _ = evaluate_prepared(prepared[0], prepared[1], prepared[2], seg_t,
                        seg_mode, seg_state, times_f)
    x_f = sqrt_k * (first[:, 0] - z_eq[0])
    y_f = sqrt_m * first[:, 1]
    v_abs_f = 0.0
    for i in range(times_f.shape[0]):
        v_abs_f = max(v_abs_f, abs(first[i, 1]))
    v_abs_fb = 1.1 * v_abs_f + 1e-6
    if not (v_abs_f + rate_v * dt_f <= v_abs_fb and times_f[-1] < t_stick):
        return empty, empty, 0
    i_ret = -1
    for i in range(times_f.shape[0] - 1):
        d = _clockwise_angle(x_f[i + 1], y_f[i + 1]) - _clockwise_angle(x_f[i], y_f[i])
        if d < 0.0:
            d += 2.0 * np.pi
        if not 0.0 < d < np.pi:
            return empty, empty, 0
        if i_ret < 0 and y_f[i] > 0.0 and y_f[i + 1] <= 0.0 and x_f[i] > 0.0:
            i_ret = i
    if i_ret < 0:
        return empty, empty, 0
    r_in = np.full(ESCAPE_BINS, -np.inf)
    _arc_bounds(x_f, y_f, 0, i_ret + 1, k_abs * v_abs_fb / sqrt_m * dt_f, True, r_in)
    # the envelope (point 3 a): per bin a radius below which, at every angle of the bin, some
    # turn of the bounding trajectory passes further out. The chain from the return before
    # the last (or the start) to just past the last return spans more than a turn, so its
    # minimum covers every angle; the final partial turn counts only on the bins its chain
    # covers completely (not those of its first and last samples)
    start_last = 0 if n_cross == 1 else crossings[n_cross - 2]
    r_env = np.full(ESCAPE_BINS, np.inf)
    _arc_bounds(x, y, start_last, crossings[n_cross - 1] + 1, pad, False, r_env)
    r_final = np.full(ESCAPE_BINS, np.inf)
    _arc_bounds(x, y, crossings[n_cross - 1], n_samples - 1, pad, False, r_final)
    scale = ESCAPE_BINS / (2.0 * np.pi)
    for i in (crossings[n_cross - 1], n_samples - 1):
        r_final[min(int(_clockwise_angle(x[i], y[i]) * scale), ESCAPE_BINS - 1)] = np.inf
    for b in range(ESCAPE_BINS):
        if not (np.isfinite(r_in[b]) and np.isfinite(r_env[b]) and r_in[b] > 0.0):
            return empty, empty, 0
        if np.isfinite(r_final[b]):
            r_env[b] = max(r_env[b], r_final[b])
    # point 3 (a): every motion inside the envelope enters the upper half-plane within R
    if not rho_max + pad < x_lo_abs:
        return empty, empty, 0
    # point 3 (b) outside it: the energy bound over the angle still to turn
    r_hi = np.empty(ESCAPE_BINS)
    for b in range(ESCAPE_BINS):
        phi_lo = b / scale
        phi_hi = (b + 1) / scale
        delta = np.pi - phi_lo if phi_hi <= np.pi else 3.0 * np.pi - phi_lo
        r2 = x_lo_abs * x_lo_abs - 2.0 * p_max * delta / omega_min
        r_crude = np.sqrt(r2) if r2 > 0.0 else 0.0
        r_hi[b] = max(r_env[b], r_crude)
    return r_in, r_hi, n_cross


@njit(cache=True)
def escape_certifies(w, z_eq, r_in, r_hi, data):
    """True when the 1-DOF state ``w`` lies in the slip escape region (it reaches the belt speed
    within ``data[ESCAPE_TIME]`` and sticks there, with ``xi >= data[ESCAPE_XI_LO]``).

    Conservative: ``r_in`` is an upper bound of the inner boundary's radius per angle bin, and
    ``r_hi`` a radius below which point 3 of the module docstring holds. Empty tables: never.
    """
    nbin = r_in.shape[0]
    if nbin == 0 or not w[1] < 1.0:
        return False
    x = data[ESCAPE_SQRT_K] * (w[0] - z_eq[0])
    y = data[ESCAPE_SQRT_M] * w[1]
    rho2 = x * x + y * y
    r_min = data[ESCAPE_R_MIN]
    r_max = data[ESCAPE_R_MAX]
    if rho2 <= r_min * r_min or rho2 >= r_max * r_max:
        return False
    rho = np.sqrt(rho2)
    b = int(_clockwise_angle(x, y) * (nbin / (2.0 * np.pi)))
    b = min(max(b, 0), nbin - 1)
    return r_in[b] < rho < r_hi[b]
