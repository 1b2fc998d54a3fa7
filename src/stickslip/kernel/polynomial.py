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
from stickslip.kernel._leaf import leaf_kernel

TAYLOR_DEGREE = 16
DERIVATIVE_DEPTH = 3
MAX_BREAKPOINTS = 8
N_POLYNOMIALS = DERIVATIVE_DEPTH + 2


#: ``1/k`` for ``k = 0..TAYLOR_DEGREE`` (entry 0 unused)
RECIPROCALS = np.array([0.0] + [1.0 / k for k in range(1, TAYLOR_DEGREE + 1)])


@leaf_kernel()
def _taylor_vectors_5(ahat: np.ndarray, w: np.ndarray, u: np.ndarray, quick: bool) -> None:
    """:func:`taylor_vectors` for ``m = 5`` (the paper's foundation), its chain in registers.

    The matrix and the previous vector are held in local variables: written to ``u`` and read
    back, each product waited for the store (``u`` and ``ahat`` may alias, so the compiler
    must reload). The full form keeps the engine's order of operations (``0 + a_0 u_0 + ...
    + a_4 u_4``, then ``/ k``: bit for bit); the quick form adds the products in pairs, and
    drops the constant coordinate's column after ``k = 1`` (``u[k, 4] = 0``).
    """
    a00, a01, a02, a03, a04 = ahat[0, 0], ahat[0, 1], ahat[0, 2], ahat[0, 3], ahat[0, 4]
    a10, a11, a12, a13, a14 = ahat[1, 0], ahat[1, 1], ahat[1, 2], ahat[1, 3], ahat[1, 4]
    a20, a21, a22, a23, a24 = ahat[2, 0], ahat[2, 1], ahat[2, 2], ahat[2, 3], ahat[2, 4]
    a30, a31, a32, a33, a34 = ahat[3, 0], ahat[3, 1], ahat[3, 2], ahat[3, 3], ahat[3, 4]
    p0, p1, p2, p3, p4 = w[0], w[1], w[2], w[3], w[4]
    if quick:
        n0 = ((a00 * p0 + a01 * p1) + (a02 * p2 + a03 * p3)) + a04 * p4
        n1 = ((a10 * p0 + a11 * p1) + (a12 * p2 + a13 * p3)) + a14 * p4
        n2 = ((a20 * p0 + a21 * p1) + (a22 * p2 + a23 * p3)) + a24 * p4
        n3 = ((a30 * p0 + a31 * p1) + (a32 * p2 + a33 * p3)) + a34 * p4
        u[1, 0], u[1, 1], u[1, 2], u[1, 3], u[1, 4] = n0, n1, n2, n3, 0.0
        for k in range(2, TAYLOR_DEGREE + 1):
            inv = RECIPROCALS[k]
            m0 = ((a00 * n0 + a01 * n1) + (a02 * n2 + a03 * n3)) * inv
            m1 = ((a10 * n0 + a11 * n1) + (a12 * n2 + a13 * n3)) * inv
            m2 = ((a20 * n0 + a21 * n1) + (a22 * n2 + a23 * n3)) * inv
            m3 = ((a30 * n0 + a31 * n1) + (a32 * n2 + a33 * n3)) * inv
            n0, n1, n2, n3 = m0, m1, m2, m3
            u[k, 0], u[k, 1], u[k, 2], u[k, 3], u[k, 4] = n0, n1, n2, n3, 0.0
        return
    a40, a41, a42, a43, a44 = ahat[4, 0], ahat[4, 1], ahat[4, 2], ahat[4, 3], ahat[4, 4]
    for k in range(1, TAYLOR_DEGREE + 1):
        n0 = (0.0 + a00 * p0 + a01 * p1 + a02 * p2 + a03 * p3 + a04 * p4) / k
        n1 = (0.0 + a10 * p0 + a11 * p1 + a12 * p2 + a13 * p3 + a14 * p4) / k
        n2 = (0.0 + a20 * p0 + a21 * p1 + a22 * p2 + a23 * p3 + a24 * p4) / k
        n3 = (0.0 + a30 * p0 + a31 * p1 + a32 * p2 + a33 * p3 + a34 * p4) / k
        n4 = (0.0 + a40 * p0 + a41 * p1 + a42 * p2 + a43 * p3 + a44 * p4) / k
        p0, p1, p2, p3, p4 = n0, n1, n2, n3, n4
        u[k, 0], u[k, 1], u[k, 2], u[k, 3], u[k, 4] = p0, p1, p2, p3, p4


@leaf_kernel()
def taylor_vectors(ahat: np.ndarray, w: np.ndarray, u: np.ndarray, quick: bool = False) -> None:
    """Fill ``u[k] = ahat^k w / k!`` for ``k = 0..TAYLOR_DEGREE``.

    ``quick`` (an engine matrix: the affine flow augmented by a constant coordinate, so the
    last row of ``ahat`` is zero and ``u[k, -1] = 0`` for ``k >= 1``): that row is not
    computed, and the division by ``k`` is a multiplication by the rounded ``1/k`` (the same
    accuracy, one more rounding per term). Runs that must stay bit-identical to the engine's
    history (the start-up runs of the paper's Coulomb law) divide.

    The paper's foundation (``m = 5``) has its own form (:func:`_taylor_vectors_5`). Every
    band edge of a tabulated law costs one call, and this chain of products was the largest
    share of a 2-DOF basin's time (27 % in a profile of the "foundation weak" basin).
    """
    m = w.shape[0]
    for i in range(m):
        u[0, i] = w[i]
    if m == 5:
        _taylor_vectors_5(ahat, w, u, quick)
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


@leaf_kernel()
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


if TAYLOR_DEGREE != 16:  # pragma: no cover - the quick evaluation below is written for 16
    raise ImportError("the quick polynomial evaluation (_estrin) is written for TAYLOR_DEGREE = 16")


@njit(cache=True, inline="always")
def _estrin(c: np.ndarray, x: float, x2: float, x4: float, x8: float, x16: float) -> float:
    """Value at ``x`` of the degree-16 polynomial with coefficients ``c[0..16]``.

    Estrin's scheme: the terms in pairs, the pairs in pairs with ``x^2``, ``x^4`` and ``x^8``
    (the powers given): a dependency chain of about 8 operations where Horner's rule has 32.
    For the quick event search, whose polynomials are Taylor series with ``|A| s <= 1/2``
    (terms falling geometrically), it is as accurate as Horner's rule to a few units of the
    last place.
    """
    q0 = (c[0] + c[1] * x) + (c[2] + c[3] * x) * x2
    q1 = (c[4] + c[5] * x) + (c[6] + c[7] * x) * x2
    q2 = (c[8] + c[9] * x) + (c[10] + c[11] * x) * x2
    q3 = (c[12] + c[13] * x) + (c[14] + c[15] * x) * x2
    return ((q0 + q1 * x4) + (q2 + q3 * x4) * x8) + c[16] * x16


@leaf_kernel()
def quick_state(u: np.ndarray, s: float, out: np.ndarray) -> None:
    """:func:`taylor_state` by Estrin's scheme (:func:`_estrin`): the quick event search's."""
    s2 = s * s
    s4 = s2 * s2
    s8 = s4 * s4
    s16 = s8 * s8
    for i in range(u.shape[1]):
        out[i] = _estrin(u[:, i], s, s2, s4, s8, s16)


@leaf_kernel()
def quick_value(coef: np.ndarray, s: float) -> float:
    """:func:`poly_value` of ``g`` (row 0) by Estrin's scheme."""
    s2 = s * s
    s4 = s2 * s2
    s8 = s4 * s4
    return _estrin(coef[0], s, s2, s4, s8, s8 * s8)


#: Newton's step below this fraction of ``|s|`` ends :func:`quick_root`: the next error is of
#: the order of the square of the step times ``|g''/(2 g')|``, far below rounding.
NEWTON_SETTLED = 1e-11


@leaf_kernel()
def quick_root(coef: np.ndarray, lo: float, hi: float, flo: float, fhi: float,
               guess: float) -> float:
    """:func:`monotone_root` of ``g`` (rows 0 and 1 of ``coef``) for the quick event search.

    The same safeguarded Newton iteration, with the polynomials evaluated by Estrin's scheme
    and ending as soon as a step is below ``NEWTON_SETTLED`` of the root (quadratic
    convergence: the step after it would change the root below rounding). Measured on 9,872
    band-edge crossings of the "foundation weak" basin: 3 to 4 evaluations where the engine's
    :func:`monotone_root` takes 4.5 on average and up to 55 (a Newton step below the spacing
    of doubles falls back to bisection there; its arithmetic is kept for the bit-identical
    runs).
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
        x2 = x * x
        x4 = x2 * x2
        x8 = x4 * x4
        x16 = x8 * x8
        fx = _estrin(coef[0], x, x2, x4, x8, x16)
        dfx = _estrin(coef[1], x, x2, x4, x8, x16)
        if fx == 0.0:
            return x
        if (fx < 0.0) == negative_low:
            lo = x
        else:
            hi = x
        if hi - lo <= 2.2e-16 * max(abs(lo), abs(hi), 1e-300):
            break
        step = fx / dfx if dfx != 0.0 else np.inf
        xn = x - step
        if abs(step) <= NEWTON_SETTLED * abs(x):
            # settled; a step below the spacing of doubles (xn == x) ends here too, where the
            # bracket test would turn it into bisection steps
            return xn if lo <= xn <= hi else x
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        x = xn
    return x


@leaf_kernel()
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


@leaf_kernel()
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


@leaf_kernel()
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


@leaf_kernel()
def monotone_breakpoints(coef: np.ndarray, a: float, b: float, bp: np.ndarray) -> int:
    """Sorted points ``a = x_0 < ... < x_p = b`` with ``g`` monotone on each piece.

    Returns the number of points written to ``bp[0]``; ``bp`` has shape
    ``(3, MAX_BREAKPOINTS)``, rows 1 and 2 are its scratch (a leaf kernel allocates nothing,
    :mod:`stickslip.kernel._leaf`). Level ``j`` (from the deepest derivative up) adds
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
