"""The modes of the augmented affine system: codes, matrices, step propagators, signatures.

State vector ``w = (q_0..q_{n-1}, v_0..v_{n-1}, 1)`` of length ``m = 2n + 1`` in the
shifted coordinates of Eqs. (15)-(16); each mode is ``w' = A_hat w`` (slip-I, slip-II and
stick per friction band, see :mod:`stickslip.kernel.system`, which prepares every table of a
parameter point from these and re-exports their names).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel.linalg import copy_matrix, copy_vector, expm, forced_step, inverse, step_norm

SLIP_I = 0
SLIP_II = 1
STICK = 2
N_MODES = 3  # with one friction band (Coulomb)
N_ROWS = 4
N_SIGNATURE = N_ROWS + 1
# functionals of each mode: events 0 and 1, then the monitors of xi and v_0
N_FUNCTIONALS = 4
F_XI = 2
F_VEL = 3
STEP_THETA = 0.5
#: next-mode code of an event that reaches the belt speed (decided by Eq. 20)
NEXT_BELT = -1


@njit(cache=True)
def mode_code(kind, band):
    """Mode code of slip kind ``kind`` (``SLIP_I`` or ``SLIP_II``) in friction band ``band``.

    Band 0 keeps the codes 0 and 1 (stick is 2), so that a one-band (Coulomb) law has the
    mode codes it always had; band ``b >= 1`` has slip-I ``1 + 2b`` and slip-II ``2 + 2b``.
    """
    if band == 0:
        return kind
    return 1 + 2 * band + kind


@njit(cache=True)
def mode_kind(code):
    """``SLIP_I``, ``SLIP_II`` or ``STICK`` of a mode code."""
    if code <= STICK:
        return code
    return (code - 3) % 2


@njit(cache=True)
def mode_band(code):
    """Friction band of a mode code (0 for stick)."""
    if code <= STICK:
        return 0
    return (code - 3) // 2 + 1


def mode_kind_band(code: int) -> tuple[int, int]:
    """``(kind, band)`` of a mode code (plain Python, for result objects)."""
    code = int(code)
    if code <= STICK:
        return code, 0
    return (code - 3) % 2, (code - 3) // 2 + 1


@njit(cache=True)
def find_band(edges, u):
    """Band ``b`` with ``edges[b] <= u < edges[b + 1]`` (the last band is unbounded)."""
    nb = edges.shape[0] - 1
    for b in range(nb - 1, -1, -1):
        if u >= edges[b]:
            return b
    return 0


@njit(cache=True)
def is_coulomb_band(intercept, slope, lam, gamma):
    return slope == 0.0 and intercept == gamma * lam


@njit(cache=True)
def structure_matrices(mass, damping, stiffness):
    """The parts of every mode's matrix that depend on the structure alone.

    Returns ``minv = Mass^-1``, ``acc_q = -Mass^-1 K``, ``acc_v = -Mass^-1 C`` (each
    ``(n, n)``), the stick mode's augmented matrix ``(m, m)`` and the stick-force row
    ``(m,)`` (see :func:`mode_matrices`): none of them depends on ``lambda``, ``gamma`` or
    the friction law.
    """
    n = mass.shape[0]
    m = 2 * n + 1
    minv = inverse(mass.copy())  # a writable C-order copy, as every matrix inverse() gets
    acc_q = -(minv @ stiffness)
    acc_v = -(minv @ damping)
    # stick: q' = v for every DOF, v_0' = 0, the rest driven with q_0'' = 0
    stick = np.zeros((m, m))
    for i in range(n):
        stick[i, n + i] = 1.0
    if n > 1:
        mrr_inv = inverse(mass[1:, 1:].copy())
        for i in range(n - 1):
            for j in range(n):
                sq = 0.0
                sv = 0.0
                for k in range(n - 1):
                    sq += mrr_inv[i, k] * stiffness[1 + k, j]
                    sv += mrr_inv[i, k] * damping[1 + k, j]
                stick[n + 1 + i, j] = -sq
                stick[n + 1 + i, n + j] = -sv
    stick_row = np.zeros(m)
    for j in range(n):
        stick_row[j] = stiffness[0, j]
        stick_row[n + j] = damping[0, j]
    for i in range(n - 1):
        coupling = mass[0, 1 + i]
        if coupling != 0.0:
            for j in range(m):
                stick_row[j] += coupling * stick[n + 1 + i, j]
    return minv, acc_q, acc_v, stick, stick_row


@njit(cache=True)
def slip_matrices(ahat, minv, acc_q, acc_v, damping, lam, gamma, intercepts, slopes):
    """Fill the slip modes of ``ahat`` (``(2 n_bands + 1, m, m)``, zeros there) for a band table.

    ``minv``, ``acc_q``, ``acc_v``: :func:`structure_matrices`. See :func:`mode_matrices`.
    """
    n = minv.shape[0]
    m = 2 * n + 1
    for b in range(intercepts.shape[0]):
        a = intercepts[b]
        s = slopes[b]
        coulomb = is_coulomb_band(a, s, lam, gamma)
        if s != 0.0:
            damp_b = damping.copy()
            damp_b[0, 0] += s
            acc_vb = -(minv @ damp_b)
        else:
            acc_vb = acc_v
        for kind in range(2):
            mode = mode_code(kind, b)
            for i in range(n):
                ahat[mode, i, n + i] = 1.0
                for j in range(n):
                    ahat[mode, n + i, j] = acc_q[i, j]
                    ahat[mode, n + i, n + j] = acc_vb[i, j]
        mode_1 = mode_code(SLIP_I, b)
        mode_2 = mode_code(SLIP_II, b)
        if coulomb:
            for i in range(n):
                ahat[mode_2, n + i, m - 1] = -2.0 * gamma * lam * minv[i, 0]
        else:
            force_1 = (a + s) - gamma * lam
            force_2 = -(a - s) - gamma * lam
            for i in range(n):
                ahat[mode_1, n + i, m - 1] = force_1 * minv[i, 0]
                ahat[mode_2, n + i, m - 1] = force_2 * minv[i, 0]


@njit(cache=True)
def mode_matrices(mass, damping, stiffness, lam, gamma, intercepts, slopes):
    """Augmented matrices ``A_hat[mode]`` (2 n_bands + 1, m, m) and the stick-force row (m,).

    Friction band ``b`` has ``F(u) = a + s u`` (``a = intercepts[b]``, ``s = slopes[b]``)
    with the sliding speed ``u = |1 - xi'|``. Slip-I (``u = 1 - xi'``) adds ``s`` to
    ``C_00`` and the forcing ``(a + s - gamma lambda) e_0``; slip-II (``u = xi' - 1``) adds
    ``s`` to ``C_00`` and the forcing ``-(a - s + gamma lambda) e_0``. A band with
    ``s = 0`` and ``a = gamma lambda`` (Coulomb) uses the paper's expressions unchanged.

    The stick force ``S = (Mass q'' + C q' + K q)_0`` with ``q_0'' = 0``, evaluated on a
    state with ``v_0 = 1``; stick holds while ``-lambda (1 + 2 gamma) <= S <= lambda``
    (Eq. 20).
    """
    n = mass.shape[0]
    m = 2 * n + 1
    minv, acc_q, acc_v, stick, stick_row = structure_matrices(mass, damping, stiffness)
    ahat = np.zeros((2 * intercepts.shape[0] + 1, m, m))
    slip_matrices(ahat, minv, acc_q, acc_v, damping, lam, gamma, intercepts, slopes)
    ahat[STICK] = stick
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
def mode_signature(ahat_mode, row, sig_out, deriv):
    """Signature rows of one mode into ``sig_out`` (N_SIGNATURE, m), zero on entry: ``xi`` and
    ``row @ ahat_mode^j`` for ``j = 0..N_ROWS-1`` (``row`` picks ``v_0`` in slip, the stick
    force in stick)."""
    sig_out[0, 0] = 1.0
    derivative_rows(row, ahat_mode, deriv)
    for j in range(N_ROWS):
        copy_vector(sig_out[1 + j], deriv[j])


@njit(cache=True)
def mode_step(ahat_mode, row, phi_out, sig_out, deriv):
    """Step length ``h``, propagator ``expm(ahat_mode h)`` and signature rows of one mode.

    ``h = STEP_THETA / norm`` with the norm of :func:`~stickslip.kernel.linalg.step_norm` of
    ``A``, the mode's matrix without the forcing column (the infinity norm up to
    ``ORIGINAL_ARITHMETIC_DOF`` DOFs); ``phi_out`` (m, m) receives the propagator and
    ``sig_out`` the signature rows (:func:`mode_signature`). Returns ``h``.
    """
    m = ahat_mode.shape[0]
    norm = step_norm(ahat_mode[: m - 1, : m - 1], (m - 1) // 2)
    h = STEP_THETA / max(norm, 1e-12)
    copy_matrix(phi_out, expm(ahat_mode * h))
    mode_signature(ahat_mode, row, sig_out, deriv)
    return h


@njit(cache=True)
def twin_mode_step(ahat_mode, row, phi_twin, h, phi_out, sig_out, deriv):
    """:func:`mode_step` of a slip-II mode from its band's slip-I propagator ``phi_twin``.

    The two share their ``2n x 2n`` block, hence the step ``h``; only the forcing column of
    the propagator differs (:func:`~stickslip.kernel.linalg.forced_step`: one exponential
    less per band, used beyond ``ORIGINAL_ARITHMETIC_DOF`` DOFs). Returns ``h``.
    """
    forced_step(phi_twin, ahat_mode, h, phi_out)
    mode_signature(ahat_mode, row, sig_out, deriv)
    return h


@njit(cache=True)
def fill_mode(ahat, phi, hstep, sig_rows, mode):
    """Fill a slip mode that :func:`prepare_point` left to the run (``lazy``); no-op otherwise.

    The same :func:`mode_step` on the same matrix as an eager preparation.
    """
    if hstep[mode] == hstep[mode]:  # not NaN: prepared already
        return
    m = ahat.shape[1]
    row = np.zeros(m)
    row[(m - 1) // 2] = 1.0  # v_0, as for every slip mode
    hstep[mode] = mode_step(ahat[mode], row, phi[mode], sig_rows[mode], np.zeros((N_ROWS, m)))
