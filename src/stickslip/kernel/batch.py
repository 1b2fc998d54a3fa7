"""Many independent runs at once, in parallel over numba threads (arrays only)."""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from stickslip.kernel.engine import N_FLOAT, N_INT, run, run_prepared
from stickslip.kernel.linalg import gauss_solve
from stickslip.kernel.system import prepare_bands


@njit(cache=True)
def startup_vector(stiffness, lam, gamma):
    """Startup state ``(q, v)``: ``q = -gamma lam K^-1 e_0``, ``v = e_0`` (DESIGN.md section 1).

    ``K^-1 e_0`` by :func:`~stickslip.kernel.linalg.gauss_solve` (no LAPACK in the engine): for
    the rigid base and one foundation stage its arithmetic is that of LAPACK's ``gesv``, so a
    map cell starts from bit for bit the state :func:`stickslip.model.startup_state` gives
    (``tests/test_kernel_linalg.py``).
    """
    n = stiffness.shape[0]
    e0 = np.zeros(n)
    e0[0] = 1.0
    offset, _ = gauss_solve(stiffness, e0)
    z0 = np.zeros(2 * n)
    for i in range(n):
        z0[i] = -gamma * lam * offset[i]
    z0[n] = 1.0
    return z0


@njit(parallel=True, cache=True)
def run_cells(masses, dampings, stiffnesses, structure_index, lams, gammas, edges, intercepts,
              slopes, n_bands, t_max, max_events, cycle_tol, max_period):
    """Run every cell from the startup state; cell ``c`` uses structure ``structure_index[c]``.

    Cell ``c`` has the friction band table ``edges[c, :n_bands[c] + 1]``,
    ``intercepts[c, :n_bands[c]]``, ``slopes[c, :n_bands[c]]`` (padded arrays of shapes
    ``(n_cells, max_bands + 1)``, ``(n_cells, max_bands)``, ``(n_cells, max_bands)``); see
    :func:`coulomb_tables` for the Coulomb law.

    Returns the float and integer summaries, shapes ``(n_cells, N_FLOAT)`` and
    ``(n_cells, N_INT)``, with the layouts of :mod:`stickslip.kernel.engine`.
    """
    n_cells = lams.shape[0]
    float_summary = np.empty((n_cells, N_FLOAT))
    int_summary = np.empty((n_cells, N_INT), dtype=np.int64)
    for c in prange(n_cells):
        s = structure_index[c]
        z0 = startup_vector(stiffnesses[s], lams[c], gammas[c])
        nb = n_bands[c]
        result = run(masses[s], dampings[s], stiffnesses[s], lams[c], gammas[c],
                     edges[c, : nb + 1], intercepts[c, :nb], slopes[c, :nb], z0, t_max,
                     max_events, cycle_tol, max_period, False, False)
        float_summary[c] = result[4]
        int_summary[c] = result[5]
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


@njit(parallel=True, cache=True)
def run_states(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes, z0s, t_max,
               max_events, cycle_tol, max_period):
    """Run one system from many initial states ``z0s`` (shape ``(n_states, 2 n)``) in parallel.

    The system is prepared once (:func:`stickslip.kernel.system.prepare_bands`) and shared by
    the threads. Returns the float and integer summaries, shapes ``(n_states, N_FLOAT)`` and
    ``(n_states, N_INT)`` (layouts of :mod:`stickslip.kernel.engine`).
    """
    prepared = prepare_bands(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes)
    n_states = z0s.shape[0]
    float_summary = np.empty((n_states, N_FLOAT))
    int_summary = np.empty((n_states, N_INT), dtype=np.int64)
    for c in prange(n_states):
        result = run_prepared(mass, lam, gamma, edges, prepared, z0s[c], t_max, max_events,
                              cycle_tol, max_period, False, False)
        float_summary[c] = result[4]
        int_summary[c] = result[5]
    return float_summary, int_summary
