"""Per-mode matrices of the augmented affine system, event rows and Lyapunov data.

State vector ``w = (q_0..q_{n-1}, v_0..v_{n-1}, 1)`` of length ``m = 2n + 1`` in the
shifted coordinates of Eqs. (15)-(16). Each mode is ``w' = A_hat w`` with constant
``A_hat`` (the constant last entry carries the forcing):

* slip-I (``SLIP_I``): ``Mass q'' + C q' + K q = 0`` (Eqs. 22-24);
* slip-II (``SLIP_II``): right-hand side ``-2 gamma lambda e_0`` (Eqs. 25-27);
* stick (``STICK``): ``q_0' = v_0 = 1`` held, the other DOFs driven (Eqs. 19-21).

Event functions are affine in ``w`` and written so that the current mode is safe while
they are negative; they and their time derivatives are read off a per-mode "signature"
of the state (see :func:`prepare`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel.linalg import (
    expm,
    gauss_solve,
    inf_norm,
    is_positive_definite,
    solve_lyapunov,
)

SLIP_I = 0
SLIP_II = 1
STICK = 2
N_MODES = 3
N_ROWS = 4
N_SIGNATURE = N_ROWS + 1
# functionals of each mode: events 0 and 1 (stick has two), then the monitors of xi and v_0
N_FUNCTIONALS = 4
F_XI = 2
F_VEL = 3
STEP_THETA = 0.5


@njit(cache=True)
def mode_matrices(mass, damping, stiffness, lam, gamma):
    """Augmented matrices ``A_hat[mode]`` (3, m, m) and the stick-force row (m,).

    The stick force ``S = (Mass q'' + C q' + K q)_0`` with ``q_0'' = 0``, evaluated on a
    state with ``v_0 = 1``; stick holds while ``-lambda (1 + 2 gamma) <= S <= lambda``
    (Eq. 20).
    """
    n = mass.shape[0]
    m = 2 * n + 1
    minv = np.linalg.inv(mass)
    acc_q = -(minv @ stiffness)
    acc_v = -(minv @ damping)
    ahat = np.zeros((N_MODES, m, m))
    for mode in range(2):
        for i in range(n):
            ahat[mode, i, n + i] = 1.0
            for j in range(n):
                ahat[mode, n + i, j] = acc_q[i, j]
                ahat[mode, n + i, n + j] = acc_v[i, j]
    for i in range(n):
        ahat[SLIP_II, n + i, m - 1] = -2.0 * gamma * lam * minv[i, 0]
    # stick: q' = v for every DOF, v_0' = 0, the rest driven with q_0'' = 0
    for i in range(n):
        ahat[STICK, i, n + i] = 1.0
    if n > 1:
        mrr_inv = np.linalg.inv(mass[1:, 1:])
        for i in range(n - 1):
            for j in range(n):
                sq = 0.0
                sv = 0.0
                for k in range(n - 1):
                    sq += mrr_inv[i, k] * stiffness[1 + k, j]
                    sv += mrr_inv[i, k] * damping[1 + k, j]
                ahat[STICK, n + 1 + i, j] = -sq
                ahat[STICK, n + 1 + i, n + j] = -sv
    stick_row = np.zeros(m)
    for j in range(n):
        stick_row[j] = stiffness[0, j]
        stick_row[n + j] = damping[0, j]
    for i in range(n - 1):
        coupling = mass[0, 1 + i]
        if coupling != 0.0:
            for j in range(m):
                stick_row[j] += coupling * ahat[STICK, n + 1 + i, j]
    return ahat, stick_row


@njit(cache=True)
def derivative_rows(row0, ahat, out):
    """``out[j] = row0 @ ahat^j`` for ``j = 0..N_ROWS-1``."""
    m = row0.shape[0]
    for i in range(m):
        out[0, i] = row0[i]
    for j in range(1, N_ROWS):
        for c in range(m):
            acc = 0.0
            for i in range(m):
                acc += out[j - 1, i] * ahat[i, c]
            out[j, c] = acc


@njit(cache=True)
def prepare(mass, damping, stiffness, lam, gamma):
    """Everything the run loop needs, computed once per parameter point.

    Returns ``ahat (3,m,m)``, ``phi (3,m,m) = expm(ahat h)``, ``hstep (3,)``,
    ``sig_rows (3, N_SIGNATURE, m)``, the functional table ``f_start, f_sign, f_offset``
    (each ``(3, N_FUNCTIONALS)``), ``stick_row (m,)``, ``lyap (2, 2n, 2n)``, ``kappa (2,)``
    and the number of valid Lyapunov matrices.

    Signature: the few scalars every event and monitor of a mode is made of, so that each
    state is projected once per step. Slip modes: ``xi`` and ``v_0`` with its first three
    derivatives; stick: ``xi`` and ``S`` with its first three derivatives. Functional ``f``
    has derivative ``j`` equal to ``f_sign * sig[f_start + j]``, plus ``f_offset`` for
    ``j = 0``.
    """
    n = mass.shape[0]
    m = 2 * n + 1
    ahat, stick_row = mode_matrices(mass, damping, stiffness, lam, gamma)
    hstep = np.empty(N_MODES)
    phi = np.empty((N_MODES, m, m))
    for mode in range(N_MODES):
        norm = inf_norm(ahat[mode, : m - 1, : m - 1])
        hstep[mode] = STEP_THETA / max(norm, 1e-12)
        phi[mode] = expm(ahat[mode] * hstep[mode])
    sig_rows = np.zeros((N_MODES, N_SIGNATURE, m))
    row = np.zeros(m)
    deriv = np.zeros((N_ROWS, m))
    for mode in range(N_MODES):
        sig_rows[mode, 0, 0] = 1.0
        row[:] = 0.0
        if mode == STICK:
            row[:] = stick_row
        else:
            row[n] = 1.0
        derivative_rows(row, ahat[mode], deriv)
        for j in range(N_ROWS):
            sig_rows[mode, 1 + j] = deriv[j]
    f_start = np.ones((N_MODES, N_FUNCTIONALS), dtype=np.int64)
    f_sign = np.ones((N_MODES, N_FUNCTIONALS))
    f_offset = np.zeros((N_MODES, N_FUNCTIONALS))
    for mode in range(N_MODES):
        f_start[mode, F_XI] = 0
    # slip-I ends when v_0 rises to 1; slip-II when v_0 falls to 1
    f_offset[SLIP_I, 0] = -1.0
    f_sign[SLIP_II, 0] = -1.0
    f_offset[SLIP_II, 0] = 1.0
    # stick ends when S rises to lambda or falls to -lambda (1 + 2 gamma), Eq. (20)
    f_offset[STICK, 0] = -lam
    f_sign[STICK, 1] = -1.0
    f_offset[STICK, 1] = -lam * (1.0 + 2.0 * gamma)
    lyap, kappa, n_lyap = lyapunov_data(mass, damping, stiffness, ahat[SLIP_I, : m - 1, : m - 1])
    return ahat, phi, hstep, sig_rows, f_start, f_sign, f_offset, stick_row, lyap, kappa, n_lyap


@njit(cache=True)
def lyapunov_data(mass, damping, stiffness, a):
    """Quadratic Lyapunov functions ``V = z' P z`` of slip-I and ``kappa = (P^-1)_vv``.

    Along slip-I, ``V`` never increases, and ``|v_0| <= sqrt(kappa V)`` bounds the slider
    velocity for all future time (Cauchy-Schwarz in the ``P`` inner product). Two choices:
    the mechanical energy ``P = diag(K, Mass)/2`` (valid for any passive structure, since
    ``dV/dt = -v' C v <= 0``), and, when ``a`` is Hurwitz, the solution of
    ``a' P + P a = -I``. The run loop uses the smaller bound.
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
    x, _ = gauss_solve(lyap[0], e_v)
    kappa[0] = x[n]
    n_lyap = 1
    # Lyapunov's theorem: a is Hurwitz iff a' P + P a = -I has a positive definite solution
    p, ok = solve_lyapunov(a, np.eye(nz))
    if ok and is_positive_definite(p):
        x, ok = gauss_solve(p, e_v)
        if ok and x[n] > 0.0:
            lyap[1] = p
            kappa[1] = x[n]
            n_lyap = 2
    return lyap, kappa, n_lyap
