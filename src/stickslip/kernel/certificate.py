"""Slip trap region: an early certificate of steady sliding for the whole friction law (1 DOF).

The Lyapunov certificates of :func:`stickslip.kernel.system.prepare_bands` hold only on the
friction bands around the belt speed where the net damping stays non-negative; with a
velocity-weakening law that eats most of the structural damping, a sliding motion needs tens
of periods (and thousands of band crossings) to decay into them. This module computes, once
per system, a positively invariant region of the slip-I plane from which every motion slides
steadily, for the law's full band table (every band the motion can still visit), and
:func:`stickslip.kernel.system.trap_certifies` tests a state against it.

Derivation (one degree of freedom, ``M q'' + C q' + K q = F(1 - q') - gamma lambda`` in
slip-I, Eqs. (22)-(24) with the slider's friction law; ``F`` continuous and piecewise
affine, hence Lipschitz, so solutions are unique). Relative to the equilibrium
``q_eq = (F(1) - gamma lambda) / K`` with ``z = q - q_eq``, ``v = q'``:

    M v' = -K z - g(v),    g(v) = C v + F(1) - F(1 - v) = k(v) v,
    k(v) = C + sigma(1 - v),  sigma(u) = (F(u) - F(1)) / (u - 1)  (the secant slope).

In ``x = sqrt(K) z``, ``y = sqrt(M) v`` (``rho^2 / 2 = x^2/2 + y^2/2`` is the energy of
:func:`~stickslip.kernel.system.lyapunov_data`) with ``omega = sqrt(K / M)``:

    x' = omega y,   y' = -omega x - k(v) y / M,
    rho' = -k(v) y^2 / (M rho),   theta' = -(omega rho^2 + (k / M) x y) / rho^2.

1. *Rotation.* Where ``|k(v)| < 2 sqrt(K M)`` the quadratic form ``omega rho^2 + (k/M) x y``
   is positive definite, so the polar angle decreases strictly (the motion turns clockwise)
   at a rate bounded away from 0: every motion crosses the section ray
   ``S = {y = 0, x > 0}`` once per turn, downwards, and the first-return map ``P`` on ``S``
   (``rho -> rho`` after one turn) is defined and continuous. Planar trajectories do not
   cross, so ``P`` is increasing.
2. *The bounding trajectory.* Start on ``S`` at ``rho_0`` and follow the motion (the engine's
   exact propagation) for one turn, back to ``S`` at ``rho_1 = P(rho_0)``. If ``rho_1 < rho_0``
   the arc and the segment ``[rho_1, rho_0]`` of ``S`` bound a region ``D`` (Bendixson's trap):
   motions cannot leave through the arc (uniqueness) and cross the segment only inwards (they
   turn clockwise), so ``D`` is positively invariant. ``v`` is linear, so its extremes on ``D``
   are on the boundary: if ``v < 1`` on the arc, no motion in ``D`` reaches the belt speed, it
   never sticks and stays in slip-I. The velocity range of ``D`` fixes the secant range
   ``[sigma_min, sigma_max]`` of the law over every band ``D`` reaches
   (:func:`~stickslip.kernel.system.secant_range`), hence the range of ``k`` used in point 1.
3. *Convergence.* Follow the same motion further, until the energy certificate holds at
   ``t_E``: ``rho(t_E) < r_E = sqrt(M) margin``, the radius of the energy certificate's disk
   (there the energy never grows and bounds ``|v|`` below the margin of the bands where it
   holds). Its returns to ``S`` before ``t_E``, ``rho_0 > rho_1 > ... > rho_J``, must
   decrease; the next one, after ``t_E``, has ``rho_{J+1} <= rho(t_E) < r_E`` (the energy does
   not grow). For ``rho`` in ``(rho_{j+1}, rho_j]``, ``P`` increasing gives
   ``P(rho) <= P(rho_j) = rho_{j+1} < rho``; so ``P(rho) < rho`` on ``[r_E, rho_0]``, and
   inside the disk too. A motion in ``D`` crosses ``S`` at decreasing radii; their limit
   would be a fixed point of ``P`` (continuity) unless they enter the disk; there is none,
   so the motion enters the energy disk after finitely many turns, where the energy
   certificate proves steady sliding. Hence every state of ``D`` slides steadily for ever,
   and ``sup |xi'|`` over its future is at most the bound of ``|v|`` on ``D``.

Numerical rigour: the bounding trajectory is the engine's own exact piecewise-linear
solution, sampled densely (step ``dt``) by :func:`stickslip.kernel.dense_output.evaluate_prepared`. Between
samples, ``|rho'| <= G = max |k| max |v| / sqrt(M)`` and ``|v'| <= A = (sqrt(K) rho_max + max
|g|) / M`` (bounds from the sampled ranges with a 10 % bootstrap margin, which is checked), so:
the arc's radius over an angle bin is at least the smallest adjacent sample radius minus
``G dt``; ``|v|`` on the arc is within ``A dt`` of the samples; a crossing of ``S`` between
samples ``i`` and ``i + 1`` has ``|z - z_i| <= A dt^2 / 2`` (``v`` vanishes there and
changes at most at rate ``A``). Every inequality above is checked with these margins; the
region is stored as the lower bound of the arc radius per angle bin, so the test of a state
is conservative. A region that fails any check is not used (the old certificates remain).

The start radius ``rho_0`` is chosen by trying a descending ladder between the belt-speed
radius ``sqrt(M)`` and ``r_E``, then a few bisections between the first that passes every
check and the last that failed (a trial from outside an unstable slip cycle, or from a
motion that reaches the belt speed, fails when it sticks, oscillates or runs out of time).

Only one degree of freedom (the plane); for more, and for a law with a single band (Coulomb,
where the energy disk is already the whole certificate), no region is built and runs are
bit for bit those of :func:`stickslip.kernel.system.prepare_bands`.

Its complement outside the unstable slip cycle, the slip escape region of states that reach
the belt speed and stick, is :mod:`stickslip.kernel.outer_certificate`; between the two
regions a thin ring about the cycle is left to simulation.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel.dense_output import evaluate_prepared
from stickslip.kernel.engine import (
    F_T_CERTIFIED,
    F_T_END,
    I_STATUS,
    STATUS_STEADY,
    STATUS_STUCK,
    run_prepared,
)
from stickslip.kernel.system import (
    SLIP_I,
    TRAP_ENERGY_RADIUS,
    TRAP_R_MAX,
    TRAP_R_MIN,
    TRAP_RHO0,
    TRAP_SQRT_K,
    TRAP_SQRT_M,
    TRAP_V_BOUND,
    mode_kind,
    prepare_bands,
    secant_range,
)

#: Angle bins of the stored region.
TRAP_BINS = 1024
#: Samples of the bounding trajectory per undamped period.
SAMPLES_PER_PERIOD = 512
#: Start radii tried, as fractions of the way from the energy disk to the belt-speed radius.
LADDER = (0.9, 0.75, 0.6, 0.45, 0.3, 0.15)
#: Bisection steps between the first start radius that passes and the last that failed.
BISECTIONS = 2
#: Time allowed for a trial motion to reach the energy disk, in undamped periods.
TRIAL_PERIODS = 150.0
#: Most events of a trial motion (its recorded phases).
TRIAL_EVENTS = 200_000
#: Most samples of one bounding trajectory.
MAX_SAMPLES = 2_000_000


@njit(cache=True)
def prepare_certified(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes):
    """:func:`~stickslip.kernel.system.prepare_bands` with the slip trap region filled in.

    For runs of one system from many states (basin stability); the region costs a few runs
    of the system, once. Without a region (see :func:`slip_trap_region`) the result is
    exactly ``prepare_bands``'s.
    """
    prepared = prepare_bands(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes)
    radius, data = slip_trap_region(mass, damping, stiffness, lam, gamma, edges, intercepts,
                                    slopes, prepared)
    return prepared[:21] + (radius, data) + prepared[23:]  # noqa: RUF005 (numba: no starred tuple display)


@njit(cache=True)
def slip_trap_region(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, prepared):
    """The slip trap region of a 1-DOF system: ``(trap_radius (TRAP_BINS,), trap_data)``.

    See the module docstring for the argument. Returns an empty ``trap_radius`` (no region)
    for more than one degree of freedom, a one-band law, a discontinuous law, an equilibrium
    without an energy certificate, or when no start radius passes the checks.
    """
    data = prepared[22].copy()
    empty = np.zeros(0)
    r_e = data[TRAP_ENERGY_RADIUS]
    nb = intercepts.shape[0]
    if mass.shape[0] != 1 or nb < 2 or not r_e > 0.0:
        return empty, data
    for b in range(nb - 1):
        e = edges[b + 1]
        left = intercepts[b] + slopes[b] * e
        right = intercepts[b + 1] + slopes[b + 1] * e
        if abs(left - right) > 1e-9 * max(1.0, abs(left)):
            return empty, data
    sqrt_m = data[TRAP_SQRT_M]
    rho_top = sqrt_m  # on S with v = 0, a turn of radius sqrt(M) would touch v = 1
    if not rho_top > r_e:
        return empty, data
    f_fail = 1.0
    for f in LADDER:
        rho0 = r_e + f * (rho_top - r_e)
        radius, v_bound = _trial(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes,
                                 prepared, data, rho0)
        if radius.shape[0] == 0:
            f_fail = f
            continue
        # refine between the last failed and this start radius (a larger region certifies
        # earlier); every kept region passed every check
        f_ok = f
        for _ in range(BISECTIONS):
            f_mid = 0.5 * (f_ok + f_fail)
            rho_mid = r_e + f_mid * (rho_top - r_e)
            r_mid, v_mid = _trial(mass, damping, stiffness, lam, gamma, edges, intercepts,
                                  slopes, prepared, data, rho_mid)
            if r_mid.shape[0] > 0:
                f_ok, rho0, radius, v_bound = f_mid, rho_mid, r_mid, v_mid
            else:
                f_fail = f_mid
        data[TRAP_V_BOUND] = v_bound
        data[TRAP_RHO0] = rho0
        data[TRAP_R_MIN] = radius.min()
        data[TRAP_R_MAX] = radius.max()
        return radius, data
    return empty, data


# Longer than the house's 120 lines: one trial of the trap construction is one proof, step by
# step (follow a turn, close the region, follow on into the energy disk), each check beside the
# step it guards; split up, the conservative error bounds would travel between functions.
@njit(cache=True)
def _trial(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, prepared, data,
           rho0):
    """The region bounded by the motion from ``rho0`` on ``S``, or an empty array if a check fails."""
    empty = np.zeros(0)
    sqrt_k = data[TRAP_SQRT_K]
    sqrt_m = data[TRAP_SQRT_M]
    m00 = mass[0, 0]
    k00 = stiffness[0, 0]
    c00 = damping[0, 0]
    z_eq = prepared[15]
    period = 2.0 * np.pi * np.sqrt(m00 / k00)
    z0 = np.array([z_eq[0] + rho0 / sqrt_k, 0.0])
    dt = period / SAMPLES_PER_PERIOD
    # cheap rejection first: one turn, which must not stick nor come back further out
    seg_t, seg_mode, seg_state, _, fsum, isum, _ = run_prepared(
        mass, lam, gamma, edges, prepared, z0, 1.25 * period, np.int64(TRIAL_EVENTS), 1e-12,
        np.int64(4), np.bool_(True), np.bool_(False), np.bool_(True), np.bool_(False))
    if isum[I_STATUS] == STATUS_STUCK:
        return empty, 0.0
    if isum[I_STATUS] != STATUS_STEADY:
        times = np.arange(int(fsum[F_T_END] / dt) + 1) * dt
        states, _ = evaluate_prepared(prepared[0], prepared[1], prepared[2],
                             seg_t, seg_mode, seg_state, times)
        for i in range(times.shape[0] - 1):
            if states[i, 1] > 0.0 and states[i + 1, 1] <= 0.0 and states[i, 0] > z_eq[0]:
                if sqrt_k * (states[i, 0] - z_eq[0]) >= rho0:
                    return empty, 0.0
                break
    # the motion, recorded until the energy certificate holds (stop_at_stick: a stick ends it)
    seg_t, seg_mode, seg_state, _, fsum, isum, _ = run_prepared(
        mass, lam, gamma, edges, prepared, z0, TRIAL_PERIODS * period, np.int64(TRIAL_EVENTS), 1e-12,
        np.int64(4), np.bool_(True), np.bool_(False), np.bool_(True), np.bool_(False))
    if isum[I_STATUS] != STATUS_STEADY:
        return empty, 0.0
    n_samples = int(fsum[F_T_CERTIFIED] / dt) + 1
    if n_samples > MAX_SAMPLES:
        return empty, 0.0
    times = np.arange(n_samples) * dt
    states, modes = evaluate_prepared(prepared[0], prepared[1], prepared[2],
                             seg_t, seg_mode, seg_state, times)
    x = sqrt_k * (states[:, 0] - z_eq[0])
    y = sqrt_m * states[:, 1]
    for i in range(n_samples):
        if mode_kind(modes[i]) != SLIP_I:
            return empty, 0.0
    # the first return to S closes the arc
    i_arc = -1
    for i in range(n_samples - 1):
        if y[i] > 0.0 and y[i + 1] <= 0.0 and x[i] > 0.0:
            i_arc = i
            break
    if i_arc < 0:
        return empty, 0.0
    # sampled ranges: v over the arc and S (D's range), radius and |v| over the whole motion
    v_lo = 0.0
    v_hi = 0.0
    for i in range(i_arc + 2):
        v_lo = min(v_lo, states[i, 1])
        v_hi = max(v_hi, states[i, 1])
    rho_max = 0.0
    v_abs = 0.0
    for i in range(n_samples):
        rho_max = max(rho_max, np.sqrt(x[i] * x[i] + y[i] * y[i]))
        v_abs = max(v_abs, abs(states[i, 1]))
    # bootstrap bounds between samples: assume 10 % above the sampled extremes, then check
    v_lo_b = v_lo - 0.1 * (v_hi - v_lo) - 1e-6
    v_hi_b = v_hi + 0.1 * (v_hi - v_lo) + 1e-6
    if not v_hi_b < 1.0:
        return empty, 0.0
    sig_lo, sig_hi = secant_range(edges, intercepts, slopes, 1.0 - v_hi_b, 1.0 - v_lo_b)
    k_abs = max(abs(c00 + sig_lo), abs(c00 + sig_hi))
    if not k_abs < 2.0 * np.sqrt(k00 * m00):
        return empty, 0.0  # the motion may stop turning (point 1)
    v_abs_b = max(abs(v_lo_b), abs(v_hi_b))
    rho_max_b = 1.1 * rho_max
    g_max = k_abs * v_abs_b
    rate_v = (sqrt_k * rho_max_b + g_max) / m00  # bound of |v'|
    rate_rho = g_max / sqrt_m  # bound of |rho'|
    if not (v_lo - rate_v * dt >= v_lo_b and v_hi + rate_v * dt <= v_hi_b
            and rho_max + rate_rho * dt <= rho_max_b and v_abs + rate_v * dt <= v_abs_b):
        return empty, 0.0  # the bootstrap margin did not hold: refine dt
    # the chain of returns to S: strictly decreasing down into the energy disk (point 3)
    z_err = 0.5 * rate_v * dt * dt * sqrt_k  # on x at a crossing
    prev_lo = rho0
    for i in range(n_samples - 1):
        if y[i] > 0.0 and y[i + 1] <= 0.0 and x[i] > 0.0:
            r_hi = x[i] + z_err
            if not r_hi < prev_lo:
                return empty, 0.0
            prev_lo = x[i] - z_err
    # the arc as a lower bound of its radius per clockwise angle bin (point 2)
    radius = np.full(TRAP_BINS, np.inf)
    two_pi = 2.0 * np.pi
    scale = TRAP_BINS / two_pi
    phi_prev = 0.0
    for i in range(i_arc + 1):
        phi_a = np.arctan2(-y[i], x[i])
        if phi_a < 0.0:
            phi_a += two_pi
        if i == 0:
            phi_a = 0.0
        if i == i_arc:
            phi_b = two_pi
        else:
            phi_b = np.arctan2(-y[i + 1], x[i + 1])
            if phi_b < 0.0:
                phi_b += two_pi
        if phi_a < phi_prev or phi_b < phi_a:
            return empty, 0.0  # not monotone: contradicts point 1
        phi_prev = phi_a
        r_a = np.sqrt(x[i] * x[i] + y[i] * y[i])
        r_b = np.sqrt(x[i + 1] * x[i + 1] + y[i + 1] * y[i + 1])
        low = min(r_a, r_b) - rate_rho * dt
        b_a = min(int(phi_a * scale), TRAP_BINS - 1)
        b_b = min(int(phi_b * scale), TRAP_BINS - 1)
        for b in range(b_a, b_b + 1):
            radius[b] = min(radius[b], low)
    for b in range(TRAP_BINS):
        if not (radius[b] > 0.0 and np.isfinite(radius[b])):
            return empty, 0.0
    return radius, v_abs_b
