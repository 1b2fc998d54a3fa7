"""Per-mode matrices of the augmented affine system, event rows and Lyapunov data.

State vector ``w = (q_0..q_{n-1}, v_0..v_{n-1}, 1)`` of length ``m = 2n + 1`` in the
shifted coordinates of Eqs. (15)-(16). Each mode is ``w' = A_hat w`` with constant
``A_hat`` (the constant last entry carries the forcing):

* slip-I (``SLIP_I``): ``Mass q'' + C q' + K q = 0`` (Eqs. 22-24);
* slip-II (``SLIP_II``): right-hand side ``-2 gamma lambda e_0`` (Eqs. 25-27);
* stick (``STICK``): ``q_0' = v_0 = 1`` held, the other DOFs driven (Eqs. 19-21).

With a velocity-dependent friction law (:mod:`stickslip.model.friction`) the sliding speed
``u = |1 - xi'|`` is split into bands on which the friction magnitude is affine,
``F(u) = a_b + s_b u``; each band has its own slip-I and slip-II mode (codes
:func:`mode_code`; band 0 keeps the codes above) and the band edges are events, located
like the belt speed. The Coulomb law is the single band ``F = gamma lambda``.

Event functions are affine in ``w`` and written so that the current mode is safe while
they are negative; they and their time derivatives are read off a per-mode "signature"
of the state (see :func:`prepare`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel.cycle_balls import no_balls
from stickslip.kernel.linalg import (
    ORIGINAL_ARITHMETIC_DOF,
    copy_matrix,
    copy_vector,
    gauss_solve,
    is_positive_definite,
    lyapunov_solve,
)
from stickslip.kernel.modes import (  # noqa: F401 (the mode names, imported from here by callers)
    F_VEL,
    F_XI,
    N_FUNCTIONALS,
    N_MODES,
    N_ROWS,
    N_SIGNATURE,
    NEXT_BELT,
    SLIP_I,
    SLIP_II,
    STEP_THETA,
    STICK,
    derivative_rows,
    fill_mode,
    find_band,
    is_coulomb_band,
    mode_band,
    mode_code,
    mode_kind,
    mode_kind_band,
    mode_matrices,
    mode_step,
    slip_matrices,
    structure_matrices,
    twin_mode_step,
)

# layout of the slip trap region's scalars (see :func:`trap_certifies` and
# :mod:`stickslip.kernel.certificate`)
TRAP_ENERGY_RADIUS = 0  # radius of the energy certificate's disk in (sqrt(K) z, sqrt(M) v)
TRAP_SQRT_K = 1
TRAP_SQRT_M = 2
TRAP_V_BOUND = 3  # bound on |xi'| over the region (hence over the future of a certified state)
TRAP_RHO0 = 4  # radius where the bounding trajectory starts on the section ray
TRAP_R_MIN = 5  # smallest and largest stored radius (quick tests before the angle)
TRAP_R_MAX = 6
N_TRAP = 7


@njit(cache=True)
def prepare(mass, damping, stiffness, lam, gamma):
    """:func:`prepare_bands` with the Coulomb law's band table (the signature before friction laws)."""
    edges = np.array([0.0, np.inf])
    intercepts = np.array([gamma * lam])
    slopes = np.array([0.0])
    return prepare_bands(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes)


@njit(cache=True)
def prepare_bands(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes):
    """Everything the run loop needs, computed once per parameter point: see :func:`prepare_point`.

    The structure's own part (:func:`structure_data`) is computed here too; a map computes it
    once per structure and calls :func:`prepare_point` for each cell.
    """
    return prepare_point(structure_data(mass, damping, stiffness), mass, damping, stiffness,
                         lam, gamma, edges, intercepts, slopes)


#: Slots of the two modes in :func:`structure_data` that depend on the structure alone.
SHARED_SLIP = 0
SHARED_STICK = 1


@njit(cache=True)
def structure_data(mass, damping, stiffness):
    """The part of :func:`prepare_point` that depends on the structure alone.

    Neither the stick mode nor a slip-I mode of a Coulomb band (slope 0, no forcing after the
    shift of Eqs. 15-16) depends on ``lambda``, ``gamma`` or the friction law, and neither
    does the Lyapunov data of a zero-slope equilibrium band; a map over ``lambda`` computes
    them once per structure (the exponentials and the Lyapunov solve were about a third of a
    Coulomb map's time). They are computed by the very functions :func:`prepare_point` uses
    otherwise, on the same inputs, so the prepared data is bit for bit the same.

    Returns ``(minv, acc_q, acc_v, base_ahat, stick_row, base_hstep, base_phi, base_sig, lyap,
    kappa, n_lyap)``: :func:`structure_matrices` (``base_ahat`` holds ``(2, m, m)``: slot
    ``SHARED_SLIP`` the Coulomb slip-I matrix, slot ``SHARED_STICK`` the stick matrix), then
    :func:`mode_step` of both slots and :func:`lyapunov_data` of the slip-I matrix with the
    energy function.
    """
    n = mass.shape[0]
    m = 2 * n + 1
    minv, acc_q, acc_v, stick, stick_row = structure_matrices(mass, damping, stiffness)
    # the Coulomb law at lambda = gamma = 1: its slip-I matrix is every Coulomb band's
    ahat = np.zeros((3, m, m))
    slip_matrices(ahat, minv, acc_q, acc_v, damping, 1.0, 1.0, np.ones(1), np.zeros(1))
    base_ahat = np.zeros((2, m, m))
    copy_matrix(base_ahat[SHARED_SLIP], ahat[SLIP_I])
    copy_matrix(base_ahat[SHARED_STICK], stick)
    base_hstep = np.empty(2)
    base_phi = np.empty((2, m, m))
    base_sig = np.zeros((2, N_SIGNATURE, m))
    deriv = np.zeros((N_ROWS, m))
    row = np.zeros(m)
    row[n] = 1.0
    base_hstep[SHARED_SLIP] = mode_step(base_ahat[SHARED_SLIP], row, base_phi[SHARED_SLIP],
                                        base_sig[SHARED_SLIP], deriv)
    base_hstep[SHARED_STICK] = mode_step(base_ahat[SHARED_STICK], stick_row, base_phi[SHARED_STICK],
                                         base_sig[SHARED_STICK], deriv)
    lyap, kappa, n_lyap = lyapunov_data(mass, damping, stiffness,
                                        base_ahat[SHARED_SLIP, : m - 1, : m - 1], np.bool_(True))
    return (minv, acc_q, acc_v, base_ahat, stick_row, base_hstep, base_phi, base_sig, lyap, kappa,
            n_lyap)


@njit(cache=True)
def structure_data_stack(masses, dampings, stiffnesses):
    """:func:`structure_data` of every structure of a stack, stacked (leading axis: structure).

    ``n_lyap`` becomes an integer array; :func:`structure_data_at` takes one structure back out.
    """
    n_struct = masses.shape[0]
    n = masses.shape[1]
    m = 2 * n + 1
    minv = np.empty((n_struct, n, n))
    acc_q = np.empty((n_struct, n, n))
    acc_v = np.empty((n_struct, n, n))
    base_ahat = np.empty((n_struct, 2, m, m))
    stick_row = np.empty((n_struct, m))
    base_hstep = np.empty((n_struct, 2))
    base_phi = np.empty((n_struct, 2, m, m))
    base_sig = np.empty((n_struct, 2, N_SIGNATURE, m))
    lyap = np.empty((n_struct, 2, 2 * n, 2 * n))
    kappa = np.empty((n_struct, 2))
    n_lyap = np.empty(n_struct, dtype=np.int64)
    for s in range(n_struct):
        one = structure_data(masses[s], dampings[s], stiffnesses[s])
        copy_matrix(minv[s], one[0])  # no slice assignment: see kernel.linalg's note
        copy_matrix(acc_q[s], one[1])
        copy_matrix(acc_v[s], one[2])
        copy_vector(stick_row[s], one[4])
        copy_vector(base_hstep[s], one[5])
        for k in range(2):
            copy_matrix(base_ahat[s, k], one[3][k])
            copy_matrix(base_phi[s, k], one[6][k])
            copy_matrix(base_sig[s, k], one[7][k])
            copy_matrix(lyap[s, k], one[8][k])
        copy_vector(kappa[s], one[9])
        n_lyap[s] = one[10]
    return (minv, acc_q, acc_v, base_ahat, stick_row, base_hstep, base_phi, base_sig, lyap, kappa,
            n_lyap)


@njit(cache=True)
def structure_data_at(stack, s):
    """Structure ``s`` of :func:`structure_data_stack`, as :func:`structure_data` returns it."""
    return (stack[0][s], stack[1][s], stack[2][s], stack[3][s], stack[4][s], stack[5][s],
            stack[6][s], stack[7][s], stack[8][s], stack[9][s], stack[10][s])


# Longer than the house's 120 lines: it fills every per-mode table of one parameter point in
# one pass over the modes (matrices, exponentials, signatures, event tables, certificates);
# each block is commented, and split into njit helpers it would pass a dozen arrays each way.
@njit(cache=True)
def prepare_point(structure, mass, damping, stiffness, lam, gamma, edges, intercepts, slopes,
                  lazy=False):
    """Everything the run loop needs, computed once per parameter point.

    ``structure``: :func:`structure_data` of ``(mass, damping, stiffness)``; the modes and the
    Lyapunov data that do not depend on the parameter point are taken from it.

    ``lazy``: the slip modes not taken from ``structure`` are left for the run to fill when it
    first enters them (:func:`fill_mode`; their ``hstep`` is NaN until then): a Coulomb map
    cell never enters slip-II in most of the paper's range, and its exponential was a tenth
    of the cell's time. Only for prepared data that one run uses (threads sharing it must
    not fill it); the filled mode is bit for bit the eager one.

    ``edges`` (n_bands + 1,), ``intercepts`` and ``slopes`` (n_bands,) are the friction
    law's band table: band ``b`` covers the sliding speed ``u`` in
    ``[edges[b], edges[b + 1])`` with ``F(u) = intercepts[b] + slopes[b] u``;
    ``edges[0] = 0`` and ``edges[-1] = inf``.

    Returns ``ahat (M,m,m)``, ``phi (M,m,m) = expm(ahat h)``, ``hstep (M,)``,
    ``sig_rows (M, N_SIGNATURE, m)``, the functional table ``f_start, f_sign, f_offset``
    (each ``(M, N_FUNCTIONALS)``), ``stick_row (m,)``, ``lyap (2, 2n, 2n)``, ``kappa (2,)``,
    the number of valid Lyapunov matrices, the event tables ``ev_count (M,)``,
    ``ev_next (M, 2)`` (next mode, ``NEXT_BELT`` for the belt speed) and ``ev_vel (M, 2)``
    (slider velocity on the band edge), and the steady-sliding data: the slip-I mode of the
    band holding ``u = 1`` (``eq_mode``), its equilibrium ``z_eq (2n,)``, for each Lyapunov
    function the slip-I bands ``lyap_lo..lyap_hi`` where it is valid and the ``margin``
    its bound on ``|xi'|`` must stay below (distance from ``u = 1`` to the edges of those
    bands), the mode and event used as Poincare section (-1: none), and the slip trap region
    ``trap_radius (0,)``, ``trap_data (N_TRAP,)``: here always empty (no region), with
    ``trap_data[TRAP_ENERGY_RADIUS]`` the radius of the energy certificate's disk (0 when there
    is none or ``n > 1``); :func:`stickslip.kernel.certificate.prepare_certified` fills it;
    and the proven contraction balls of stick-slip cycles ``ball_data, ball_norm``
    (:mod:`stickslip.kernel.cycle_balls`): here always empty, a basin fills them.

    The energy ``V = (q - q_eq)' K (q - q_eq)/2 + v' Mass v/2`` obeys
    ``dV/dt = -v' C v - sigma(u) v_0^2`` in slip-I with the secant slope
    ``sigma(u) = (F(u) - F(1)) / (u - 1)`` (``F`` continuous), so it never grows on bands
    where ``C + sigma e_0 e_0'`` is positive semi-definite; on a band ``sigma`` is monotone,
    so its extremes are at the band edges. The other function (``a' P + P a = -I``) is the
    equilibrium band's only.
    ``M = 2 n_bands + 1`` modes.

    Signature: the few scalars every event and monitor of a mode is made of, so that each
    state is projected once per step. Slip modes: ``xi`` and ``v_0`` with its first three
    derivatives; stick: ``xi`` and ``S`` with its first three derivatives. Functional ``f``
    has derivative ``j`` equal to ``f_sign * sig[f_start + j]``, plus ``f_offset`` for
    ``j = 0``.
    """
    n = mass.shape[0]
    m = 2 * n + 1
    nb = intercepts.shape[0]
    n_modes = 2 * nb + 1
    (minv, acc_q, acc_v, base_ahat, base_stick_row, base_hstep, base_phi, base_sig, base_lyap,
     base_kappa, base_n_lyap) = structure
    ahat = np.zeros((n_modes, m, m))
    slip_matrices(ahat, minv, acc_q, acc_v, damping, lam, gamma, intercepts, slopes)
    copy_matrix(ahat[STICK], base_ahat[SHARED_STICK])
    stick_row = base_stick_row.copy()
    hstep = np.empty(n_modes)
    phi = np.empty((n_modes, m, m))
    sig_rows = np.zeros((n_modes, N_SIGNATURE, m))
    row = np.zeros(m)
    row[n] = 1.0
    deriv = np.zeros((N_ROWS, m))
    for mode in range(n_modes):
        shared = -1
        if mode == STICK:
            shared = SHARED_STICK
        elif mode_kind(mode) == SLIP_I:
            band = mode_band(mode)
            if is_coulomb_band(intercepts[band], slopes[band], lam, gamma):
                shared = SHARED_SLIP
        if shared >= 0:
            hstep[mode] = base_hstep[shared]
            copy_matrix(phi[mode], base_phi[shared])
            copy_matrix(sig_rows[mode], base_sig[shared])
        elif lazy:
            hstep[mode] = np.nan  # filled by fill_mode when the run first enters it
        else:
            twin = mode_code(SLIP_I, mode_band(mode))
            if n > ORIGINAL_ARITHMETIC_DOF and mode_kind(mode) == SLIP_II and hstep[twin] == hstep[twin]:
                # slip-I and slip-II of a band share their 2n x 2n block (slip_matrices)
                hstep[mode] = twin_mode_step(ahat[mode], row, phi[twin], hstep[twin], phi[mode],
                                             sig_rows[mode], deriv)
            else:
                hstep[mode] = mode_step(ahat[mode], row, phi[mode], sig_rows[mode], deriv)
    f_start = np.ones((n_modes, N_FUNCTIONALS), dtype=np.int64)
    f_sign = np.ones((n_modes, N_FUNCTIONALS))
    f_offset = np.zeros((n_modes, N_FUNCTIONALS))
    ev_count = np.zeros(n_modes, dtype=np.int64)
    ev_next = np.full((n_modes, 2), NEXT_BELT, dtype=np.int64)
    ev_vel = np.ones((n_modes, 2))
    for mode in range(n_modes):
        f_start[mode, F_XI] = 0
    for b in range(nb):
        lo = edges[b]
        hi = edges[b + 1]
        m1 = mode_code(SLIP_I, b)
        m2 = mode_code(SLIP_II, b)
        # event 0: the sliding speed falls to the band's lower edge (the belt speed for b = 0)
        # slip-I ends when v_0 rises to 1 - lo; slip-II when v_0 falls to 1 + lo
        f_offset[m1, 0] = -(1.0 - lo)
        f_sign[m2, 0] = -1.0
        f_offset[m2, 0] = 1.0 + lo
        if b > 0:
            ev_next[m1, 0] = mode_code(SLIP_I, b - 1)
            ev_next[m2, 0] = mode_code(SLIP_II, b - 1)
            ev_vel[m1, 0] = 1.0 - lo
            ev_vel[m2, 0] = 1.0 + lo
        ev_count[m1] = 1
        ev_count[m2] = 1
        # event 1: the sliding speed rises to the band's upper edge
        if hi < np.inf:
            f_sign[m1, 1] = -1.0
            f_offset[m1, 1] = 1.0 - hi
            f_offset[m2, 1] = -(1.0 + hi)
            ev_next[m1, 1] = mode_code(SLIP_I, b + 1)
            ev_next[m2, 1] = mode_code(SLIP_II, b + 1)
            ev_vel[m1, 1] = 1.0 - hi
            ev_vel[m2, 1] = 1.0 + hi
            ev_count[m1] = 2
            ev_count[m2] = 2
    # stick ends when S rises to lambda or falls to -lambda (1 + 2 gamma), Eq. (20)
    f_offset[STICK, 0] = -lam
    f_sign[STICK, 1] = -1.0
    f_offset[STICK, 1] = -lam * (1.0 + 2.0 * gamma)
    ev_count[STICK] = 2
    ev_next[STICK, 0] = SLIP_I
    ev_next[STICK, 1] = SLIP_II
    # steady sliding: the slider rests (xi' = 0), u = 1, in the slip-I mode of its band
    b_eq = find_band(edges, 1.0)
    eq_mode = mode_code(SLIP_I, b_eq)
    s_eq = slopes[b_eq]
    force_eq = (intercepts[b_eq] + s_eq) - gamma * lam
    z_eq = np.zeros(2 * n)
    if not is_coulomb_band(intercepts[b_eq], s_eq, lam, gamma) and force_eq != 0.0:
        e0 = np.zeros(n)
        e0[0] = 1.0
        x, _ = gauss_solve(stiffness.copy(), e0)  # writable, as gauss_solve always gets
        for i in range(n):
            z_eq[i] = force_eq * x[i]
    # energy certificate: valid on the bands [e_lo, e_hi] around u = 1 where C + sigma e_0 e_0'
    # stays positive semi-definite for every secant slope sigma = (F(u) - F(1)) / (u - 1)
    f_one = intercepts[b_eq] + s_eq
    sigma_min = s_eq
    use_energy = _damping_ok(damping, sigma_min)
    e_lo = b_eq
    e_hi = b_eq
    if use_energy:
        if edges[b_eq] == 1.0 and b_eq > 0:
            # the band below also touches u = 1 (its secant is its slope, up to rounding)
            sigma_min = min(sigma_min, slopes[b_eq - 1],
                            _secant(intercepts, slopes, b_eq - 1, edges[b_eq - 1], f_one))
            if _damping_ok(damping, sigma_min):
                e_lo = b_eq - 1
            else:
                sigma_min = s_eq
        while e_lo > 0:
            sig = _secant(intercepts, slopes, e_lo - 1, edges[e_lo - 1], f_one)
            cand = min(sigma_min, sig)
            if not _damping_ok(damping, cand):
                break
            sigma_min = cand
            e_lo -= 1
        while e_hi < nb - 1:
            if edges[e_hi + 2] < np.inf:
                sig = _secant(intercepts, slopes, e_hi + 1, edges[e_hi + 2], f_one)
            else:
                sig = slopes[e_hi + 1]  # the secant tends to the last slope
            cand = min(sigma_min, sig)
            if not _damping_ok(damping, cand):
                break
            sigma_min = cand
            e_hi += 1
    if s_eq == 0.0:  # the structure's own slip-I matrix, and use_energy holds
        lyap, kappa, n_lyap = base_lyap, base_kappa, base_n_lyap
    else:
        lyap, kappa, n_lyap = lyapunov_data(mass, damping, stiffness,
                                            ahat[eq_mode, : m - 1, : m - 1], use_energy)
    # per Lyapunov function: the slip-I bands where it holds and the margin on |xi'| that
    # keeps the sliding speed inside them
    lyap_lo = np.full(3, b_eq, dtype=np.int64)
    lyap_hi = np.full(3, b_eq, dtype=np.int64)
    margin = np.full(3, min(1.0 - edges[b_eq], edges[b_eq + 1] - 1.0))
    if use_energy:
        lyap_lo[0] = e_lo
        lyap_hi[0] = e_hi
        margin[0] = min(1.0 - edges[e_lo], edges[e_hi + 1] - 1.0)
    lyap3 = np.zeros((3, 2 * n, 2 * n))
    kappa3 = np.zeros(3)
    for p in range(n_lyap):
        copy_matrix(lyap3[p], lyap[p])
        kappa3[p] = kappa[p]
    if b_eq > 0 and edges[b_eq] == 1.0:
        # the equilibrium sits on a band edge (e.g. a table point at u = 1): both bands share
        # it, so a common quadratic Lyapunov function of their slip-I matrices holds on both
        p_common, ok = _common_lyapunov(ahat[mode_code(SLIP_I, b_eq - 1), : m - 1, : m - 1],
                                        ahat[eq_mode, : m - 1, : m - 1])
        if ok:
            e_v = np.zeros(2 * n)
            e_v[n] = 1.0
            x, ok = gauss_solve(p_common, e_v)
            if ok and x[n] > 0.0:
                copy_matrix(lyap3[n_lyap], p_common)
                kappa3[n_lyap] = x[n]
                lyap_lo[n_lyap] = b_eq - 1
                lyap_hi[n_lyap] = b_eq
                margin[n_lyap] = min(1.0 - edges[b_eq - 1], edges[b_eq + 1] - 1.0)
                n_lyap += 1
    lyap = lyap3
    kappa = kappa3
    # Poincare section for slip oscillations: slip-I leaving, outwards, through the band edge
    # nearest to u = 1 at a positive distance (an oscillation that crosses it has a velocity
    # amplitude of at least that distance, so a motion settling on the equilibrium never
    # repeats there); not the belt speed, which is the stick logic
    sec_mode = -1
    sec_event = -1
    dist = np.inf
    if b_eq > 0 and edges[b_eq] < 1.0:
        sec_mode = eq_mode
        sec_event = 0
        dist = 1.0 - edges[b_eq]
    elif b_eq > 1 and edges[b_eq] == 1.0:
        sec_mode = mode_code(SLIP_I, b_eq - 1)
        sec_event = 0
        dist = 1.0 - edges[b_eq - 1]
    if edges[b_eq + 1] < np.inf and edges[b_eq + 1] - 1.0 < dist:
        sec_mode = eq_mode
        sec_event = 1
    trap_radius = np.zeros(0)
    trap_data = np.zeros(N_TRAP)
    if n == 1 and use_energy:
        # the energy certificate holds where sqrt(K z^2 + M v^2) < sqrt(M) margin[0]
        trap_data[TRAP_ENERGY_RADIUS] = np.sqrt(mass[0, 0]) * margin[0]
        trap_data[TRAP_SQRT_K] = np.sqrt(stiffness[0, 0])
        trap_data[TRAP_SQRT_M] = np.sqrt(mass[0, 0])
    ball_data, ball_norm = no_balls(n)
    return (ahat, phi, hstep, sig_rows, f_start, f_sign, f_offset, stick_row, lyap, kappa, n_lyap,
            ev_count, ev_next, ev_vel, eq_mode, z_eq, lyap_lo, lyap_hi, margin, sec_mode, sec_event,
            trap_radius, trap_data, ball_data, ball_norm)


@njit(cache=True)
def _common_lyapunov(a0, a1):
    """``P`` with ``a_i' P + P a_i`` negative definite for both matrices; ``(P, ok)``.

    Candidates: the solutions of ``a' P + P a = -I`` for ``a0``, ``a1`` and their mean; the
    first that works for both matrices is returned.
    """
    nz = a0.shape[0]
    a0 = np.ascontiguousarray(a0)
    a1 = np.ascontiguousarray(a1)
    mean = 0.5 * (a0 + a1)
    for c in range(3):
        cand = a0 if c == 0 else (a1 if c == 1 else mean)
        p, ok = lyapunov_solve(cand, np.eye(nz))
        if not ok or not is_positive_definite(p):
            continue
        good = True
        for a in (a0, a1):
            q = -(a.T @ p + p @ a)
            if not is_positive_definite(0.5 * (q + q.T)):
                good = False
        if good:
            return p, True
    return np.eye(nz), False


@njit(cache=True)
def _damping_ok(damping, sigma):
    """``C + sigma e_0 e_0'`` is positive semi-definite (``C`` is, by assumption, as before)."""
    if sigma >= 0.0:
        return True
    damp = damping.copy()
    damp[0, 0] += sigma
    return is_positive_definite(damp)


@njit(cache=True)
def _secant(intercepts, slopes, band, u, f_one):
    """``(F(u) - F(1)) / (u - 1)`` with ``F`` of ``band``."""
    return (intercepts[band] + slopes[band] * u - f_one) / (u - 1.0)


@njit(cache=True)
def lyapunov_data(mass, damping, stiffness, a, use_energy):
    """Quadratic Lyapunov functions ``V = z' P z`` of slip-I and ``kappa = (P^-1)_vv``.

    Along slip-I, ``V`` never increases, and ``|v_0| <= sqrt(kappa V)`` bounds the slider
    velocity for all future time (Cauchy-Schwarz in the ``P`` inner product). Two choices:
    the mechanical energy ``P = diag(K, Mass)/2`` (valid for any passive structure, since
    ``dV/dt = -v' C v <= 0``), and, when ``a`` is Hurwitz, the solution of
    ``a' P + P a = -I``. The run loop uses the smaller bound. ``use_energy`` is false when
    the friction slope makes the damping matrix indefinite (the energy may then grow).
    """
    n = mass.shape[0]
    nz = 2 * n
    lyap = np.zeros((2, nz, nz))
    kappa = np.zeros(2)
    for i in range(n):
        for j in range(n):
            lyap[0, i, j] = 0.5 * stiffness[i, j]
            lyap[0, n + i, n + j] = 0.5 * mass[i, j]
    e_v = np.zeros(nz)
    e_v[n] = 1.0
    n_lyap = 0
    if use_energy:
        x, _ = gauss_solve(lyap[0], e_v)
        kappa[0] = x[n]
        n_lyap = 1
    # Lyapunov's theorem: a is Hurwitz iff a' P + P a = -I has a positive definite solution
    # C order, as _common_lyapunov's: one compiled lyapunov_solve for both
    p, ok = lyapunov_solve(np.ascontiguousarray(a), np.eye(nz))
    if ok and is_positive_definite(p):
        x, ok = gauss_solve(p, e_v)
        if ok and x[n] > 0.0:
            copy_matrix(lyap[n_lyap], p)
            kappa[n_lyap] = x[n]
            n_lyap += 1
    return lyap, kappa, n_lyap


@njit(cache=True)
def secant_range(edges, intercepts, slopes, u_lo, u_hi):
    """Extremes of the secant slope ``sigma(u) = (F(u) - F(1)) / (u - 1)`` for ``u`` in ``[u_lo, u_hi]``.

    ``F`` is the band table's piecewise-affine law (continuous). On a band not holding
    ``u = 1``, ``sigma(u) = s + (a + s - F(1)) / (u - 1)`` is monotone on each side of
    ``u = 1``, so its extremes over the band are at its ends; on the band holding ``u = 1``,
    ``sigma = s``, its slope. The extremes over ``[u_lo, u_hi]`` are therefore among the values
    at ``u_lo``, ``u_hi``, the band edges between them and the slopes of the bands touching
    ``u = 1`` from the sides the interval reaches (the one-sided limits of ``sigma`` there).
    Returns ``(sigma_min, sigma_max)``.
    """
    nb = intercepts.shape[0]
    b1 = find_band(edges, 1.0)
    f_one = intercepts[b1] + slopes[b1]
    lo = np.inf
    hi = -np.inf
    if u_lo <= 1.0 < u_hi:  # the limit from above
        lo = min(lo, slopes[b1])
        hi = max(hi, slopes[b1])
    if u_lo < 1.0 <= u_hi:  # the limit from below
        below = b1 - 1 if (b1 > 0 and edges[b1] == 1.0) else b1
        lo = min(lo, slopes[below])
        hi = max(hi, slopes[below])
    for k in range(nb + 1):
        u = edges[k]
        if not (u_lo < u < u_hi) or u == 1.0 or not np.isfinite(u):
            continue
        b = find_band(edges, u)
        sig = (intercepts[b] + slopes[b] * u - f_one) / (u - 1.0)
        lo = min(lo, sig)
        hi = max(hi, sig)
    for u in (u_lo, u_hi):
        if u == 1.0 or not np.isfinite(u):
            continue
        b = find_band(edges, u)
        sig = (intercepts[b] + slopes[b] * u - f_one) / (u - 1.0)
        lo = min(lo, sig)
        hi = max(hi, sig)
    return lo, hi


@njit(cache=True)
def trap_certifies(w, z_eq, trap_radius, trap_data):
    """True when the 1-DOF state ``w`` lies inside the slip trap region (steady sliding for ever).

    The region (built by :func:`stickslip.kernel.certificate.slip_trap_region`, where the
    argument is derived) is star-shaped about the equilibrium in the coordinates
    ``x = sqrt(K) (q - q_eq)``, ``y = sqrt(M) v``: with ``phi`` the clockwise angle from the
    ray ``y = 0, x > 0`` and ``rho = |(x, y)|``, it holds every point with ``rho`` below the
    bounding trajectory's radius at ``phi``; ``trap_radius[b]`` is a lower bound of that radius
    over the angle bin ``b`` (of ``len(trap_radius)`` equal bins), so the test is conservative.
    Empty ``trap_radius``: no region, never true.
    """
    nbin = trap_radius.shape[0]
    if nbin == 0:
        return False
    x = trap_data[TRAP_SQRT_K] * (w[0] - z_eq[0])
    y = trap_data[TRAP_SQRT_M] * (w[1] - z_eq[1])
    rho2 = x * x + y * y
    r_max = trap_data[TRAP_R_MAX]
    if rho2 >= r_max * r_max:
        return False
    r_min = trap_data[TRAP_R_MIN]
    if rho2 < r_min * r_min:
        return True
    rho = np.sqrt(rho2)
    phi = np.arctan2(-y, x)
    if phi < 0.0:
        phi += 2.0 * np.pi
    b = int(phi * (nbin / (2.0 * np.pi)))
    b = min(max(b, 0), nbin - 1)
    return rho < trap_radius[b]
