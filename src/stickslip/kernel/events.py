"""Events and extremes on one step of the run loop: the cheap tests and the exact searches.

Within a step of length ``h`` (``h ||A|| <= 1/2``) every event function and monitor of a mode
is ``g = sign * sig[start] + offset`` with ``sig`` the mode's signature of the state (see
:func:`stickslip.kernel.system.prepare_bands`); its derivatives are the next signature
entries. The cheap tests settle most steps from the end values; the others use the Taylor
polynomial of the step (:mod:`stickslip.kernel.polynomial`). The small helpers are inlined
into the run loop (``inline="always"``): numba counts a reference for every array passed to
a call, which costs more than these tests.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel._leaf import leaf_kernel
from stickslip.kernel.polynomial import (
    DERIVATIVE_DEPTH,
    N_POLYNOMIALS,
    TAYLOR_DEGREE,
    functional_polynomials,
    monotone_breakpoints,
    monotone_root,
    poly_value,
    quick_root,
    quick_value,
    taylor_vectors,
)
from stickslip.kernel.system import N_ROWS, N_SIGNATURE

# Both products below are the step's main arithmetic. For the paper's two systems (state of
# length m = 5 with the foundation, 3 on the rigid base) they are written out again with
# constant trip counts, which LLVM unrolls: the same multiplications and additions in the same
# order (bit for bit), at about half the time (micro-benchmark: a 5 x 5 product and copy,
# 35 ns with the length read at run time, 19 ns with it constant).


@njit(cache=True, inline="always")
def signature(sig_rows, mode, w, out):
    """Project the state on the signature rows of ``mode`` (once per state):
    ``out[b] = sig_rows[mode, b] . w``.

    The per-mode tables are indexed, not sliced: a slice in the run loop costs numba two
    atomic reference counts, more than the product itself.
    """
    m = w.shape[0]
    if m == 5:
        for b in range(N_SIGNATURE):
            acc = 0.0
            for j in range(5):
                acc += sig_rows[mode, b, j] * w[j]
            out[b] = acc
    elif m == 3:
        for b in range(N_SIGNATURE):
            acc = 0.0
            for j in range(3):
                acc += sig_rows[mode, b, j] * w[j]
            out[b] = acc
    else:
        for b in range(N_SIGNATURE):
            acc = 0.0
            for j in range(m):
                acc += sig_rows[mode, b, j] * w[j]
            out[b] = acc


@njit(cache=True, inline="always")
def propagate(phi, mode, w, out):
    """``out = phi[mode] @ w``: one full step (the arithmetic of
    :func:`~stickslip.kernel.linalg.matvec`; indexed, not sliced, as in :func:`signature`)."""
    m = w.shape[0]
    if m == 5:
        for i in range(5):
            acc = 0.0
            for j in range(5):
                acc += phi[mode, i, j] * w[j]
            out[i] = acc
    elif m == 3:
        for i in range(3):
            acc = 0.0
            for j in range(3):
                acc += phi[mode, i, j] * w[j]
            out[i] = acc
    else:
        for i in range(m):
            acc = 0.0
            for j in range(m):
                acc += phi[mode, i, j] * w[j]
            out[i] = acc


@njit(cache=True, inline="always")
def _no_sign_change(sig0, sig1, start):
    """True when ``g'``, ``g''`` and ``g'''`` keep their sign between the two states."""
    for j in range(1, N_ROWS):
        if sig0[start + j] * sig1[start + j] < 0.0:
            return False
    return True


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
def event_free(sig0, sig1, start, sign, offset, h):
    """The cheap test: ``g = sign * sig[start] + offset`` provably stays negative on the step.

    Either ``g`` is negative at both ends and ``g'``, ``g''``, ``g'''`` keep their signs
    between them (``g'''`` is monotone on a step, so each derivative in turn has one sign and
    ``g`` is monotone: its end values bound it), or the Taylor bound of :func:`_taylor_bounds`
    is negative. Most steps are settled here. It is inlined into the run loop, as are the
    other helpers of a step: a call with array arguments costs numba a reference count per
    array, more than the test itself.
    """
    g0 = sign * sig0[start] + offset
    g1 = sign * sig1[start] + offset
    if g1 < 0.0 and g0 <= 0.0 and _no_sign_change(sig0, sig1, start):
        return True
    return g0 <= 0.0 and _taylor_bounds(sig0, sig1, start, sign, offset, h)[1] < 0.0


#: Rows of an event search's scratch (:func:`poly_scratch`): the coefficients of the event
#: function and its derivatives (``N_POLYNOMIALS`` rows), the monotone breakpoints and their
#: scratch (3 rows), the functional's row (the state's length) and a flag (column 0: the
#: Taylor vectors of the step's start are computed, 1.0).
P_BP = N_POLYNOMIALS
P_ROW = P_BP + 3
P_FLAG = P_ROW + 1


@njit(cache=True)
def poly_scratch(m):
    """An event search's scratch for states of length ``m`` (rows ``P_*``), zeroed."""
    return np.zeros((P_FLAG + 1, max(TAYLOR_DEGREE + 1, m)))


@njit(cache=True, inline="always")
def _scratch_views(poly, m):
    """The coefficients, breakpoints and row of a scratch (views; see :func:`poly_scratch`)."""
    return poly[:N_POLYNOMIALS], poly[P_BP:P_ROW], poly[P_ROW, :m]


@leaf_kernel()
def mode_taylor_vectors(ahat_table, mode, w, u, quick):
    """:func:`~stickslip.kernel.polynomial.taylor_vectors` of ``ahat_table[mode]`` (the mode's
    matrix taken without reference counts, as in :func:`first_reach`)."""
    taylor_vectors(ahat_table[mode], w, u, quick)


@leaf_kernel()
def _polynomials(sig_rows, start, sign, offset, u, row, coef, depth=DERIVATIVE_DEPTH + 1):
    """Taylor coefficients of the functional and its first ``depth`` derivatives over the step."""
    m = row.shape[0]
    for i in range(m):
        row[i] = sign * sig_rows[start, i]
    row[m - 1] += offset
    functional_polynomials(u, row, coef, depth)


@leaf_kernel()
def first_reach(sig_table, mode, start, sign, offset, sig0, sig1, w0, h, ahat_table, u, poly,
                departing, quick=False):
    """First ``s`` in ``[0, h]`` where the event function ``g`` reaches 0 (``inf``: never).

    Called for the steps that :func:`event_free` does not settle. ``g = sign * sig[start] +
    offset``; ``g <= 0`` is the safe side. The step is split into monotone pieces so that a
    graze (``g`` touching 0 between two negative end values) is found at its extremum.

    ``departing``: the state has just left ``g = 0`` (a breakaway onto a slip mode whose
    belt-speed event this is); a rise of ``g`` from exactly 0 on the first monotone piece is
    then rounding noise of a departure with zero acceleration (``mu(0+) = mu_s``), not an
    event. A departure with nonzero acceleration never has such a piece.

    ``quick`` (the runs of :func:`stickslip.kernel.batch.run_states` that stop at the first
    stick): when the end signs of ``g'``, ``g''`` and ``g'''`` agree, ``g`` is monotone on the
    step (the cheap test's argument), so the search for monotone pieces is skipped and
    Newton's iteration starts from the left end's tangent; the Taylor vectors use
    their quick form (:func:`~stickslip.kernel.polynomial.taylor_vectors`) and the
    polynomials Estrin's scheme (:func:`~stickslip.kernel.polynomial.quick_root`). The root
    is the same to rounding; the other runs keep the engine's historical arithmetic bit for bit.

    ``sig_table`` and ``ahat_table`` are the per-mode tables, ``u`` the Taylor vectors of the
    step's start and ``poly`` the search's scratch (:func:`poly_scratch`). This function,
    like the rest of an event search, is a leaf kernel (:mod:`stickslip.kernel._leaf`: no
    reference counts), so the views taken here are free; the run loop's call counts two per
    array argument, hence the packing.
    """
    sig_rows = sig_table[mode]
    ahat = ahat_table[mode]
    coef, bp, row = _scratch_views(poly, w0.shape[0])
    if poly[P_FLAG, 0] == 0.0:
        taylor_vectors(ahat, w0, u, quick)
        poly[P_FLAG, 0] = 1.0
    if quick and _no_sign_change(sig0, sig1, start):
        _polynomials(sig_rows, start, sign, offset, u, row, coef, np.int64(1))  # g and g' (Newton)
        ga = coef[0, 0]
        gb = quick_value(coef, h)
        if gb >= 0.0 and gb > ga:
            if ga >= 0.0:
                return np.inf if departing else 0.0
            slope = coef[1, 0]
            tangent = -ga / slope if slope != 0.0 else np.nan  # Newton's first point from s = 0
            return quick_root(coef, 0.0, h, ga, gb, tangent)
        return np.inf
    _polynomials(sig_rows, start, sign, offset, u, row, coef, np.int64(DERIVATIVE_DEPTH + 1))
    npts = monotone_breakpoints(coef, 0.0, h, bp)
    ga = poly_value(coef, np.int64(0), bp[0, 0])
    for i in range(npts - 1):
        gb = poly_value(coef, np.int64(0), bp[0, i + 1])
        if gb >= 0.0 and gb > ga:
            if ga >= 0.0:
                if not (departing and i == 0):
                    return bp[0, i]
            else:
                return monotone_root(coef, np.int64(0), bp[0, i], bp[0, i + 1], ga, gb, np.nan)
        ga = gb
    return np.inf


@leaf_kernel()
def interior_range(sig_table, mode, start, sig0, sig1, w0, s_end, ahat_table, u, poly, known_lo,
                   known_hi, lo, hi):
    """Extend the end range ``[lo, hi]`` of ``sig[start]`` by its interior extrema on ``[0, s_end]``.

    They are only located when they could extend ``[known_lo, known_hi]``. The tables are
    per mode, as in :func:`first_reach`.
    """
    sig_rows = sig_table[mode]
    ahat = ahat_table[mode]
    bound_lo, bound_hi = _taylor_bounds(sig0, sig1, start, 1.0, 0.0, s_end)
    if bound_lo >= known_lo and bound_hi <= known_hi:
        return lo, hi
    coef, bp, row = _scratch_views(poly, w0.shape[0])
    if poly[P_FLAG, 0] == 0.0:
        taylor_vectors(ahat, w0, u, np.bool_(False))
        poly[P_FLAG, 0] = 1.0
    _polynomials(sig_rows, start, 1.0, 0.0, u, row, coef, np.int64(DERIVATIVE_DEPTH + 1))
    npts = monotone_breakpoints(coef, 0.0, s_end, bp)
    for i in range(1, npts - 1):
        g = poly_value(coef, np.int64(0), bp[0, i])
        lo = min(lo, g)
        hi = max(hi, g)
    return lo, hi


@njit(cache=True, inline="always")
def end_range(sig0, sig1, start):
    """Range of ``sig[start]`` over the step's ends, and whether that is its range on the step.

    It is when ``sig[start]``'s derivatives keep their signs (it is then monotone, see
    :func:`event_free`); otherwise :func:`interior_range` looks inside. Together they give
    the exact minimum and maximum on the step.
    """
    lo = min(sig0[start], sig1[start])
    hi = max(sig0[start], sig1[start])
    return lo, hi, _no_sign_change(sig0, sig1, start)
