"""Exact local trajectories as Taylor polynomials, and their monotone pieces.

Within one engine sub-step of length ``h`` (with ``h * ||A|| <= 1/2``) the state is
``w(s) = sum_k U_k s^k`` with ``U_k = A^k w(0) / k!``; the degree-16 truncation error is
below ``0.5**17 / 17!`` (about 2e-20) relative. Any event function ``g = r . w`` is then a
polynomial in ``s``, and so are its derivatives.

Graze-proof event location: the interval is split into pieces on which ``g`` is monotone,
by finding the sign changes of ``g'``, ``g''`` and ``g'''`` level by level (on a piece where
``g^(j+1)`` is monotone, ``g^(j+1)`` has at most one root). The only assumption is that
``g'''`` is monotone on one sub-step, which holds because a sub-step is shorter than a
twelfth of the fastest period. A double crossing inside a step (the slider velocity only
touching the belt speed) is therefore never missed: its extremum is a breakpoint.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)

TAYLOR_DEGREE = 16
DERIVATIVE_DEPTH = 3
MAX_BREAKPOINTS = 8
N_POLYNOMIALS = DERIVATIVE_DEPTH + 2


#: ``1/k`` for ``k = 0..TAYLOR_DEGREE`` (entry 0 unused)
RECIPROCALS = np.array([0.0] + [1.0 / k for k in range(1, TAYLOR_DEGREE + 1)])


@njit(cache=True, _nrt=False)
def taylor_vectors(ahat: np.ndarray, w: np.ndarray, u: np.ndarray, quick: bool = False) -> None:
    """Fill ``u[k] = ahat^k w / k!`` for ``k = 0..TAYLOR_DEGREE``.

    ``quick`` (an engine matrix: the affine flow augmented by a constant coordinate, so the
    last row of ``ahat`` is zero and ``u[k, -1] = 0`` for ``k >= 1``): that row is not
    computed, and the division by ``k`` is a multiplication by the rounded ``1/k`` (the same
    accuracy, one more rounding per term). Runs that must stay bit-identical to the engine's
    history (the start-up runs of the paper's Coulomb law) divide.

    The paper's foundation (``m = 5``) has its loops written out with constant trip counts,
    as :func:`~stickslip.kernel.events.propagate` has: the same operations in the same order
    (bit for bit), which LLVM unrolls. Every band edge of a tabulated law costs one call, and
    this chain of products was the largest share of a 2-DOF basin's time (27 % in a profile
    of the "foundation weak" basin).
    """
    m = w.shape[0]
    for i in range(m):
        u[0, i] = w[i]
    if m == 5:
        if quick:
            for k in range(1, TAYLOR_DEGREE + 1):
                inv = RECIPROCALS[k]
                for i in range(4):
                    acc = 0.0
                    for j in range(5):
                        acc += ahat[i, j] * u[k - 1, j]
                    u[k, i] = acc * inv
                u[k, 4] = 0.0
        else:
            for k in range(1, TAYLOR_DEGREE + 1):
                for i in range(5):
                    acc = 0.0
                    for j in range(5):
                        acc += ahat[i, j] * u[k - 1, j]
                    u[k, i] = acc / k
        return
    rows = m - 1 if quick else m
    for k in range(1, TAYLOR_DEGREE + 1):
        inv = RECIPROCALS[k]
        for i in range(rows):
            acc = 0.0
            for j in range(m):
                acc += ahat[i, j] * u[k - 1, j]
            u[k, i] = acc * inv if quick else acc / k
        if quick:
            u[k, m - 1] = 0.0


@njit(cache=True, _nrt=False)
def taylor_state(u: np.ndarray, s: float, out: np.ndarray) -> None:
    """``out = w(s) = sum_k u[k] s^k`` by Horner's rule (``m = 5`` written out, as in
    :func:`taylor_vectors`)."""
    m = u.shape[1]
    if m == 5:
        for i in range(5):
            acc = u[TAYLOR_DEGREE, i]
            for k in range(TAYLOR_DEGREE - 1, -1, -1):
                acc = acc * s + u[k, i]
            out[i] = acc
        return
    for i in range(m):
        acc = u[TAYLOR_DEGREE, i]
        for k in range(TAYLOR_DEGREE - 1, -1, -1):
            acc = acc * s + u[k, i]
        out[i] = acc


@njit(cache=True, _nrt=False)
def functional_polynomials(u: np.ndarray, row: np.ndarray, coef: np.ndarray,
                           depth: int = DERIVATIVE_DEPTH + 1) -> None:
    """Coefficients of ``g(s) = row . w(s)`` and its first ``depth`` (default four) derivatives.

    ``coef[j, k]`` is the coefficient of ``s^k`` in ``g^(j)``.
    """
    m = u.shape[1]
    if m == 5:  # written out, as in taylor_vectors
        for k in range(TAYLOR_DEGREE + 1):
            acc = 0.0
            for i in range(5):
                acc += row[i] * u[k, i]
            coef[0, k] = acc
    else:
        for k in range(TAYLOR_DEGREE + 1):
            acc = 0.0
            for i in range(m):
                acc += row[i] * u[k, i]
            coef[0, k] = acc
    for j in range(1, depth + 1):
        for k in range(TAYLOR_DEGREE + 1):
            if k + 1 <= TAYLOR_DEGREE:
                coef[j, k] = (k + 1) * coef[j - 1, k + 1]
            else:
                coef[j, k] = 0.0


@njit(cache=True, _nrt=False)
def poly_value(coef: np.ndarray, j: int, s: float) -> float:
    """Value of the ``j``-th derivative polynomial at ``s``."""
    acc = coef[j, TAYLOR_DEGREE]
    for k in range(TAYLOR_DEGREE - 1, -1, -1):
        acc = acc * s + coef[j, k]
    return acc


@njit(cache=True, inline="always")
def _value_and_slope(coef: np.ndarray, j: int, s: float) -> tuple[float, float]:
    """:func:`poly_value` of ``g^(j)`` and ``g^(j+1)`` at ``s`` in one loop (the same
    operations as two calls, bit for bit: Newton's step needs both, and the two Horner chains
    run side by side)."""
    acc = coef[j, TAYLOR_DEGREE]
    dacc = coef[j + 1, TAYLOR_DEGREE]
    for k in range(TAYLOR_DEGREE - 1, -1, -1):
        acc = acc * s + coef[j, k]
        dacc = dacc * s + coef[j + 1, k]
    return acc, dacc


@njit(cache=True, _nrt=False)
def monotone_root(coef: np.ndarray, j: int, lo: float, hi: float, flo: float, fhi: float,
                  guess: float = np.nan) -> float:
    """Root of the monotone polynomial ``g^(j)`` on ``[lo, hi]`` where it changes sign.

    Safeguarded Newton iteration (bisection whenever Newton leaves the bracket) down to
    the resolution of double precision, from ``guess`` when it lies inside the bracket,
    else from the secant point.
    """
    if flo == 0.0:
        return lo
    if fhi == 0.0:
        return hi
    negative_low = flo < 0.0
    x = guess if lo < guess < hi else lo - flo * (hi - lo) / (fhi - flo)
    if not (lo < x < hi):
        x = 0.5 * (lo + hi)
    for _ in range(200):
        if j <= DERIVATIVE_DEPTH:
            fx, dfx = _value_and_slope(coef, j, x)
        else:
            fx, dfx = poly_value(coef, j, x), 0.0
        if fx == 0.0:
            return x
        if (fx < 0.0) == negative_low:
            lo = x
        else:
            hi = x
        if hi - lo <= 2.2e-16 * max(abs(lo), abs(hi), 1e-300):
            break
        xn = x - fx / dfx if dfx != 0.0 else 0.5 * (lo + hi)
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        if xn == x:
            break
        x = xn
    return x


@njit(cache=True, _nrt=False)
def monotone_breakpoints(coef: np.ndarray, a: float, b: float, bp: np.ndarray) -> int:
    """Sorted points ``a = x_0 < ... < x_p = b`` with ``g`` monotone on each piece.

    Returns the number of points written to ``bp[0]``; ``bp`` has shape
    ``(3, MAX_BREAKPOINTS)``, rows 1 and 2 are its scratch (the kernels of an event search
    allocate nothing, see the module notes). Level ``j`` (from the deepest derivative up) adds
    the roots of ``g^(j+1)``, each found on a piece where ``g^(j+1)`` is monotone and so has
    at most one root.
    """
    pts = bp[1]
    new = bp[2]
    pts[0] = a
    pts[1] = b
    npts = 2
    for level in range(DERIVATIVE_DEPTH - 1, -1, -1):
        d = level + 1
        nnew = 0
        new[nnew] = a
        nnew += 1
        f_prev = poly_value(coef, d, pts[0])
        for i in range(npts - 1):
            f_next = poly_value(coef, d, pts[i + 1])
            if (f_prev < 0.0 < f_next) or (f_prev > 0.0 > f_next):
                r = monotone_root(coef, d, pts[i], pts[i + 1], f_prev, f_next, np.nan)
                if new[nnew - 1] < r < b and nnew < MAX_BREAKPOINTS - 1:
                    new[nnew] = r
                    nnew += 1
            f_prev = f_next
        new[nnew] = b
        nnew += 1
        for i in range(nnew):
            pts[i] = new[i]
        npts = nnew
    for i in range(npts):
        bp[0, i] = pts[i]
    return npts
