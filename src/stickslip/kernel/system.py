"""Per-mode matrices of the augmented affine system, event rows and Lyapunov data.

State vector ``w = (q_0..q_{n-1}, v_0..v_{n-1}, 1)`` of length ``m = 2n + 1`` in the
shifted coordinates of Eqs. (15)-(16). Each mode is ``w' = A_hat w`` with constant
``A_hat`` (the constant last entry carries the forcing):

* slip-I (``SLIP_I``): ``Mass q'' + C q' + K q = 0`` (Eqs. 22-24);
* slip-II (``SLIP_II``): right-hand side ``-2 gamma lambda e_0`` (Eqs. 25-27);
* stick (``STICK``): ``q_0' = v_0 = 1`` held, the other DOFs driven (Eqs. 19-21).

Event functions are affine in ``w`` and written so that the current mode is safe while
they are negative. ``rows[mode, e, j]`` is the row of the ``j``-th time derivative of
event ``e``, i.e. ``row_0 @ A_hat^j``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel.linalg import expm, inf_norm, solve_lyapunov

SLIP_I = 0
SLIP_II = 1
STICK = 2
N_MODES = 3
MAX_EVENTS_PER_MODE = 2
N_ROWS = 4
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
    ``rows (3, 2, 4, m)`` event rows, ``n_events (3,)``, ``xi_rows (3, 4, m)``,
    ``vel_rows (3, 4, m)``, ``stick_row (m,)``, ``lyap (2, 2n, 2n)``, ``kappa (2,)`` and the
    number of valid Lyapunov matrices.
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
    rows = np.zeros((N_MODES, MAX_EVENTS_PER_MODE, N_ROWS, m))
    n_events = np.array([1, 1, 2])
    row = np.zeros(m)
    # slip-I ends when v_0 rises to 1
    row[n] = 1.0
    row[m - 1] = -1.0
    derivative_rows(row, ahat[SLIP_I], rows[SLIP_I, 0])
    # slip-II ends when v_0 falls to 1
    row[:] = 0.0
    row[n] = -1.0
    row[m - 1] = 1.0
    derivative_rows(row, ahat[SLIP_II], rows[SLIP_II, 0])
    # stick ends when S rises to lambda or falls to -lambda (1 + 2 gamma)
    row[:] = stick_row
    row[m - 1] = -lam
    derivative_rows(row, ahat[STICK], rows[STICK, 0])
    row[:] = -stick_row
    row[m - 1] = -lam * (1.0 + 2.0 * gamma)
    derivative_rows(row, ahat[STICK], rows[STICK, 1])
    xi_rows = np.zeros((N_MODES, N_ROWS, m))
    vel_rows = np.zeros((N_MODES, N_ROWS, m))
    for mode in range(N_MODES):
        row[:] = 0.0
        row[0] = 1.0
        derivative_rows(row, ahat[mode], xi_rows[mode])
        row[:] = 0.0
        row[n] = 1.0
        derivative_rows(row, ahat[mode], vel_rows[mode])
    lyap, kappa, n_lyap = lyapunov_data(mass, damping, stiffness, ahat[SLIP_I, : m - 1, : m - 1])
    return ahat, phi, hstep, rows, n_events, xi_rows, vel_rows, stick_row, lyap, kappa, n_lyap


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
    kappa[0] = 2.0 * np.linalg.inv(mass)[0, 0]
    n_lyap = 1
    eig = np.linalg.eigvals(a.astype(np.complex128))
    if np.max(eig.real) < -1e-9:
        p = solve_lyapunov(a, np.eye(nz))
        if np.min(np.linalg.eigvalsh(p)) > 0.0:
            lyap[1] = p
            kappa[1] = np.linalg.inv(p)[n, n]
            n_lyap = 2
    return lyap, kappa, n_lyap
