"""Dense output: the exact state at any times from a run's recorded phases.

Arrays in, arrays out; see :mod:`stickslip.kernel.engine` for the run that records the phases.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel.linalg import copy_vector, matvec
from stickslip.kernel.polynomial import TAYLOR_DEGREE, taylor_state, taylor_vectors
from stickslip.kernel.prepared import prepared_tables


def evaluate(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, seg_t, seg_mode,
             seg_state, times):
    """Exact states at sorted ``times`` from the recorded phases (dense output).

    Reproduces the run loop's own step grid: full steps with ``expm(A_hat h)`` from the
    start of each phase, then the Taylor polynomial for the remainder. The tables come from
    the compiled steps :func:`stickslip.kernel.engine.run` uses (loaded from the cache after a
    run), the stepping from :func:`evaluate_prepared`; returns ``(states (len(times), 2n),
    modes)``.
    """
    ahat, phi, hstep = prepared_tables(mass, damping, stiffness, lam, gamma, edges, intercepts,
                                       slopes)[:3]
    return evaluate_prepared(ahat, phi, hstep, seg_t, seg_mode, seg_state, times)


@njit(cache=True)
def evaluate_prepared(ahat, phi, hstep, seg_t, seg_mode, seg_state, times):
    """:func:`evaluate` on the tables ``ahat``, ``phi``, ``hstep`` of the run's preparation.

    The first three entries of :func:`~stickslip.kernel.system.prepare_bands`' data (prepared
    eagerly: a lazily prepared mode the run never entered has no step yet).
    """
    m = ahat.shape[1]
    nz = m - 1
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
            copy_vector(w, seg_state[p])  # w[:nz] (see kernel.linalg on slice assignment)
            w[m - 1] = 1.0
            t_k = seg_t[p]
        mode = seg_mode[p]
        h = hstep[mode]
        while t_k + h <= t:
            matvec(phi[mode], w, tmp)
            copy_vector(w, tmp)
            t_k += h
        taylor_vectors(ahat[mode], w, u, np.bool_(False))
        taylor_state(u, t - t_k, res)
        copy_vector(out[idx], res[:nz])
        modes[idx] = mode
    return out, modes
