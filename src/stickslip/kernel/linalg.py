"""Small dense linear algebra for the kernel (numba, arrays only).

The matrices here are tiny (a few rows), so explicit loops beat BLAS calls.

Compile time (issue 21.5): the kernels copy arrays with :func:`copy_vector` and
:func:`copy_matrix`, never by slice assignment (``a[:] = b``): numba compiles, with every
slice assignment of an array, a shape check whose error message formats both shapes, and that
brings in its string machinery (about 3.5 s of a cold first run). Constant integer and
boolean arguments of calls between kernels are passed as ``np.int64(...)`` or
``np.bool_(...)``: numba compiles a callee once more for every literal constant it is called
with.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)

TAYLOR_DEGREE_EXPM = 18

#: Upper bound on the squarings of :func:`expm`: halving any finite double (at most
#: 1.8e308 = 2**1024) 1100 times brings it below 1/2, so the bound is never reached for a
#: finite matrix and every loop of this module ends, whatever the input.
MAX_SQUARINGS_EXPM = 1100


@njit(cache=True)
def matvec(a: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    """``out = a @ x`` without allocation."""
    n, m = a.shape
    for i in range(n):
        acc = 0.0
        for j in range(m):
            acc += a[i, j] * x[j]
        out[i] = acc


@njit(cache=True)
def copy_vector(dst: np.ndarray, src: np.ndarray) -> None:
    """``dst[:] = src`` for vectors of equal length (see the module's note on compile time)."""
    for i in range(src.shape[0]):
        dst[i] = src[i]


@njit(cache=True)
def copy_matrix(dst: np.ndarray, src: np.ndarray) -> None:
    """``dst[:, :] = src`` for matrices of equal shape (see the module's note on compile time)."""
    for i in range(src.shape[0]):
        for j in range(src.shape[1]):
            dst[i, j] = src[i, j]


@njit(cache=True)
def dot(x: np.ndarray, y: np.ndarray) -> float:
    """Inner product of two vectors of equal length."""
    acc = 0.0
    for i in range(x.shape[0]):
        acc += x[i] * y[i]
    return acc


@njit(cache=True)
def inf_norm(a: np.ndarray) -> float:
    """Maximum absolute row sum."""
    best = 0.0
    for i in range(a.shape[0]):
        acc = 0.0
        for j in range(a.shape[1]):
            acc += abs(a[i, j])
        best = max(best, acc)
    return best


@njit(cache=True)
def matmul(a: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    """``out = a @ b`` for small square matrices, without allocation (``out`` distinct)."""
    n = a.shape[0]
    for i in range(n):
        for j in range(n):
            acc = 0.0
            for k in range(n):
                acc += a[i, k] * b[k, j]
            out[i, j] = acc


#: Largest number of DOFs whose arithmetic is the engine's original one (plain infinity norm for
#: the step, Kronecker Lyapunov solve): the paper's 1-2 DOF presets and the 3-DOF chain of
#: tests/data/coulomb_reference.json keep every bit (tests/test_coulomb_bit_identity.py);
#: larger structures take the O(n^3) paths, whose results agree to rounding.
ORIGINAL_ARITHMETIC_DOF = 3

#: Matrices of this size or more (larger than the augmented system of a structure of
#: ORIGINAL_ARITHMETIC_DOF DOFs) are multiplied row-wise in :func:`expm` (:func:`matmul_rowwise`);
#: smaller ones as always.
ROWWISE_MIN_SIZE = 2 * ORIGINAL_ARITHMETIC_DOF + 2


@njit(cache=True)
def matmul_rowwise(a: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    """``out = a @ b`` in the (i, k, j) loop order: contiguous rows, zero entries of ``a`` skipped.

    The sums run over ``k`` in the same order as :func:`matmul`; the inner loop walks rows of
    ``b`` and ``out`` (vectorisable) where :func:`matmul` strides down a column of ``b``, which
    is several times slower once a matrix outgrows the cache (a 300-DOF structure's 601 x 601).
    """
    n = a.shape[0]
    q = b.shape[1]
    for i in range(n):
        for j in range(q):
            out[i, j] = 0.0
        for k in range(a.shape[1]):
            f = a[i, k]
            if f != 0.0:
                for j in range(q):
                    out[i, j] += f * b[k, j]


@njit(cache=True)
def expm(a: np.ndarray) -> np.ndarray:
    """Matrix exponential by scaling and squaring of a degree-18 Taylor polynomial.

    The scaled matrix has infinity norm at most 1/2, so the truncation error is below
    ``0.5**19 / 19!`` (about 1e-23) relative, far below double precision. Checked against
    ``scipy.linalg.expm`` in the tests.

    A matrix with a NaN or infinite entry (norm not finite) has no exponential: the result
    is then all NaN, which the caller sees (and which the engine's step and event budgets
    absorb), instead of an endless halving loop.
    """
    n = a.shape[0]
    norm = inf_norm(a)
    if not np.isfinite(norm):
        return np.full((n, n), np.nan)
    squarings = 0
    while norm > 0.5 and squarings < MAX_SQUARINGS_EXPM:
        norm *= 0.5
        squarings += 1
    b = a / (2.0**squarings)
    result = np.eye(n)
    term = np.eye(n)
    tmp = np.empty((n, n))
    rowwise = n >= ROWWISE_MIN_SIZE
    for k in range(1, TAYLOR_DEGREE_EXPM + 1):
        if rowwise:
            matmul_rowwise(term, b, tmp)
        else:
            matmul(term, b, tmp)
        for i in range(n):
            for j in range(n):
                term[i, j] = tmp[i, j] / k
                result[i, j] += term[i, j]
    for _ in range(squarings):
        if rowwise:
            matmul_rowwise(result, result, tmp)
        else:
            matmul(result, result, tmp)
        copy_matrix(result, tmp)
    return result


@njit(cache=True)
def expm_at(a: np.ndarray, times: np.ndarray) -> np.ndarray:
    """``expm(a t)`` for every ``t`` of ``times``, stacked: shape ``(times.size, n, n)``.

    Each is :func:`expm` of the product ``a t`` formed as numpy forms it (one rounded
    product per entry), so the stack is bit for bit the exponentials taken one at a time,
    without a call through the dispatcher for each.
    """
    n = a.shape[0]
    out = np.empty((times.size, n, n))
    scaled = np.empty((n, n))
    for s in range(times.size):
        for i in range(n):
            for j in range(n):
                scaled[i, j] = a[i, j] * times[s]
        copy_matrix(out[s], expm(scaled))
    return out


@njit(cache=True)
def gauss_solve(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, bool]:
    """Solve ``a x = b`` by Gaussian elimination with partial pivoting.

    Returns ``(x, ok)``; ``ok`` is false for a (numerically) singular matrix, so callers
    inside compiled code can branch instead of raising.
    """
    n = a.shape[0]
    m = a.copy()
    x = b.copy()
    scale = 0.0
    for i in range(n):
        for j in range(n):
            scale = max(scale, abs(m[i, j]))
    if scale == 0.0:
        return x, False
    for col in range(n):
        piv = col
        for r in range(col + 1, n):
            if abs(m[r, col]) > abs(m[piv, col]):
                piv = r
        if abs(m[piv, col]) <= 1e-14 * scale:
            return x, False
        if piv != col:
            for c in range(n):
                m[col, c], m[piv, c] = m[piv, c], m[col, c]
            x[col], x[piv] = x[piv], x[col]
        for r in range(col + 1, n):
            f = m[r, col] / m[col, col]
            if f != 0.0:
                for c in range(col, n):
                    m[r, c] -= f * m[col, c]
                x[r] -= f * x[col]
    for r in range(n - 1, -1, -1):
        acc = x[r]
        for c in range(r + 1, n):
            acc -= m[r, c] * x[c]
        x[r] = acc / m[r, r]
    return x, True


@njit(cache=True)
def is_positive_definite(p: np.ndarray) -> bool:
    """Cholesky test of a symmetric matrix."""
    n = p.shape[0]
    low = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1):
            acc = p[i, j]
            for k in range(j):
                acc -= low[i, k] * low[j, k]
            if i == j:
                if acc <= 0.0:
                    return False
                low[i, i] = np.sqrt(acc)
            else:
                low[i, j] = acc / low[j, j]
    return True


@njit(cache=True)
def solve_lyapunov(a: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, bool]:
    """Solve ``a.T @ p + p @ a = -q`` for ``p`` through the Kronecker form.

    Returns ``(p, ok)``; ``ok`` is false when the Kronecker system is singular (``a`` has
    two eigenvalues summing to zero, e.g. an undamped mode).
    """
    n = a.shape[0]
    size = n * n
    lhs = np.zeros((size, size))
    rhs = np.empty(size)
    for i in range(n):
        for j in range(n):
            row = i * n + j
            rhs[row] = -q[i, j]
            for k in range(n):
                lhs[row, k * n + j] += a[k, i]
                lhs[row, i * n + k] += a[k, j]
    vec, ok = gauss_solve(lhs, rhs)
    p = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            p[i, j] = 0.5 * (vec[i * n + j] + vec[j * n + i])
    return p, ok


@njit(cache=True)
def inverse(a: np.ndarray) -> np.ndarray:
    """Inverse of a non-singular matrix, column by column with :func:`gauss_solve`.

    Written here rather than ``np.linalg.inv`` so that the compiled engine needs no LAPACK:
    numba would otherwise load SciPy's BLAS and LAPACK (about 0.2 s) in every process that
    runs it. For a diagonal matrix (every mass matrix of the paper's structures) the result
    is exactly ``1 / a_ii``, as LAPACK's. A singular matrix gives NaN entries.
    """
    n = a.shape[0]
    out = np.empty((n, n))
    e = np.zeros(n)
    for j in range(n):
        e[:] = 0.0
        e[j] = 1.0
        x, ok = gauss_solve(a, e)
        for i in range(n):
            out[i, j] = x[i] if ok else np.nan
    return out


#: Iterations of :func:`solve_lyapunov_sign` (quadratic convergence: about 10 for any stable
#: matrix of the engine's scale; the bound only ends a loop on a matrix that is not stable).
MAX_ITERATIONS_SIGN = 100


@njit(cache=True)
def inverse_lu(a: np.ndarray) -> tuple[np.ndarray, bool]:
    """Inverse by Gauss-Jordan elimination with partial pivoting, ``O(n^3)``; ``(inv, ok)``.

    One elimination for every column (:func:`inverse` eliminates once per column, ``O(n^4)``,
    which is negligible for the paper's 1-2 DOF and dominant for a structure of tens or
    hundreds of DOFs). ``ok`` is false for a (numerically) singular matrix.
    """
    n = a.shape[0]
    m = a.copy()
    inv = np.eye(n)
    scale = 0.0
    for i in range(n):
        for j in range(n):
            scale = max(scale, abs(m[i, j]))
    if scale == 0.0:
        return inv, False
    for col in range(n):
        piv = col
        for r in range(col + 1, n):
            if abs(m[r, col]) > abs(m[piv, col]):
                piv = r
        if abs(m[piv, col]) <= 1e-14 * scale:
            return inv, False
        if piv != col:
            for c in range(n):
                m[col, c], m[piv, c] = m[piv, c], m[col, c]
                inv[col, c], inv[piv, c] = inv[piv, c], inv[col, c]
        d = 1.0 / m[col, col]
        for c in range(n):
            m[col, c] *= d
            inv[col, c] *= d
        for r in range(n):
            f = m[r, col]
            if r != col and f != 0.0:
                for c in range(n):
                    m[r, c] -= f * m[col, c]
                    inv[r, c] -= f * inv[col, c]
    return inv, True


@njit(cache=True)
def solve_lyapunov_sign(a: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, bool]:
    """Solve ``a.T @ p + p @ a = -q`` by the matrix sign function (Roberts 1971), ``O(n^3)``.

    For a stable (Hurwitz) ``a`` the Newton iteration ``A <- (c A + A^-1 / c) / 2``,
    ``Q <- (c Q + A^-T Q A^-1 / c) / 2`` drives ``A`` to ``sign(a) = -I`` and ``Q`` to ``2 p``
    (Roberts, Int. J. Control 32 (1980) 677, the report of 1971; Benner & Quintana-Orti 1999
    for the scaling ``c = sqrt(||A^-1||_F / ||A||_F)``). Each iteration costs an inverse and
    two products where the Kronecker form of :func:`solve_lyapunov` solves an ``n^2 x n^2``
    system (``O(n^6)``: 0.1-0.2 s at ``n = 40``, a 20-DOF structure; out of memory at 600).
    The solutions agree to rounding (checked against ``scipy.linalg.solve_continuous_lyapunov``
    in the tests).

    Returns ``(p, ok)``; ``ok`` is false when ``a`` is not stable (the iteration does not reach
    ``-I`` within :data:`MAX_ITERATIONS_SIGN` steps, or meets a singular iterate), as
    :func:`solve_lyapunov` is for the cases where no unique solution exists.
    """
    n = a.shape[0]
    x = np.ascontiguousarray(a).copy()
    y = np.ascontiguousarray(q).copy()
    ok = False
    for _ in range(MAX_ITERATIONS_SIGN):
        xinv, inv_ok = inverse_lu(x)
        if not inv_ok:
            return y, False
        nx = 0.0
        ni = 0.0
        for i in range(n):
            for j in range(n):
                nx += x[i, j] * x[i, j]
                ni += xinv[i, j] * xinv[i, j]
        c = np.sqrt(np.sqrt(ni) / np.sqrt(nx))
        tmp = np.empty((n, n))
        y_new = np.empty((n, n))
        matmul_rowwise(y, xinv, tmp)
        matmul_rowwise(np.ascontiguousarray(xinv.T), tmp, y_new)
        change = 0.0
        for i in range(n):
            for j in range(n):
                x_new = 0.5 * (c * x[i, j] + xinv[i, j] / c)
                change = max(change, abs(x_new - x[i, j]))
                x[i, j] = x_new
                y[i, j] = 0.5 * (c * y[i, j] + y_new[i, j] / c)
        if change <= 1e-13 * max(1.0, inf_norm(x)) and c == c:
            ok = True
            break
    if not ok:
        return y, False
    dist = 0.0
    for i in range(n):
        for j in range(n):
            target = -1.0 if i == j else 0.0
            dist = max(dist, abs(x[i, j] - target))
    p = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            p[i, j] = 0.25 * (y[i, j] + y[j, i])
    return p, dist <= 1e-8




@njit(cache=True)
def step_norm(a, n):
    """The norm of a mode's ``2n x 2n`` matrix that sets its step ``h = STEP_THETA / norm``.

    Up to :data:`ORIGINAL_ARITHMETIC_DOF` DOFs: the infinity norm, as always. Beyond, the
    smaller of that and the infinity norm of the balanced matrix ``D^-1 a D``,
    ``D = diag(1, .., 1, s, .., s)`` (velocities in units of ``s``). Both are norms of a matrix
    similar to ``a``, so both bound its spectral radius, the fastest angular frequency of the
    structure: ``h`` stays below ``1 / (4 pi)`` of the fastest period, which is what the event
    search assumes (:mod:`stickslip.kernel.polynomial`), and the degree-16 Taylor polynomial of
    a step keeps its ``0.5**17 / 17!`` truncation error in the balanced coordinates (times
    ``max(s, 1/s)`` back in the state's). The plain norm of ``[[0, I], [-M^-1 K, -M^-1 C]]``
    grows like the *square* of the fastest frequency (a row sum of ``M^-1 K``), the balanced one
    like the frequency: with ``s`` the smallest value with ``s >= a_i / s + b_i`` for every
    velocity row ``i`` (``a_i``, ``b_i`` its absolute row sums over positions and velocities),
    ``s_i = (b_i + sqrt(b_i^2 + 4 a_i)) / 2``. The 20-DOF chain of benchmarks/bench_structure.py
    takes 3.8x fewer steps (39103 -> 10323 to its stick-slip verdict).
    """
    plain = inf_norm(a)
    if n <= ORIGINAL_ARITHMETIC_DOF:
        return plain
    s = 0.0
    for i in range(n, 2 * n):
        pos = 0.0
        vel = 0.0
        for j in range(n):
            pos += abs(a[i, j])
            vel += abs(a[i, n + j])
        s = max(s, 0.5 * (vel + np.sqrt(vel * vel + 4.0 * pos)))
    if not s > 0.0:
        return plain
    balanced = 0.0
    for i in range(2 * n):
        d_i = 1.0 if i < n else s
        acc = 0.0
        for j in range(2 * n):
            d_j = 1.0 if j < n else s
            acc += abs(a[i, j]) * d_j / d_i
        balanced = max(balanced, acc)
    return min(plain, balanced)


#: Bound on the terms of the series of :func:`forced_step` (about 25 reach rounding).
MAX_SERIES_TERMS = 100


@njit(cache=True)
def forced_step(phi_twin, ahat, h, out):
    """``out = expm(ahat h)`` from the step ``phi_twin`` of a mode with the same ``2n x 2n`` block.

    Slip-I and slip-II of a friction band differ only in their forcing column ``f`` (the last of
    ``ahat``): the block ``E = expm(A h)`` is ``phi_twin``'s, and the forcing column of the step
    is ``int_0^h expm(A s) ds f = sum_k (A h)^k h f / (k + 1)!``, summed until a term no longer
    changes it (its terms fall like ``0.5^k / (k + 1)!`` in the balanced norm of
    :func:`step_norm`). One ``2n x 2n`` exponential less per band (a third of the preparation of
    a Coulomb structure); used beyond :data:`ORIGINAL_ARITHMETIC_DOF` DOFs.
    """
    m = ahat.shape[0]
    nz = m - 1
    copy_matrix(out, phi_twin)
    term = np.empty(nz)
    nxt = np.empty(nz)
    col = np.empty(nz)
    for i in range(nz):
        term[i] = h * ahat[i, nz]
        col[i] = term[i]
    for k in range(1, MAX_SERIES_TERMS):
        size = 0.0
        total = 0.0
        for i in range(nz):
            acc = 0.0
            for j in range(nz):
                acc += ahat[i, j] * term[j]
            nxt[i] = acc * h / (k + 1)
        for i in range(nz):
            term[i] = nxt[i]
            col[i] += term[i]
            size = max(size, abs(term[i]))
            total = max(total, abs(col[i]))
        if size <= 1e-17 * total or size == 0.0:
            break
    for i in range(nz):
        out[i, nz] = col[i]


@njit(cache=True)
def lyapunov_solve(a, q):
    """``a' p + p a = -q``: the Kronecker form up to :data:`ORIGINAL_ARITHMETIC_DOF` DOFs
    (``2n <= 6`` states, bit for bit as always), the sign-function iteration beyond
    (``O(n^3)``; the Kronecker form is ``O(n^6)``). ``(p, ok)`` as both."""
    if a.shape[0] <= 2 * ORIGINAL_ARITHMETIC_DOF:
        return solve_lyapunov(a, q)
    return solve_lyapunov_sign(a, q)


@njit(cache=True)
def grown(a, size):
    """A copy of the vector ``a`` with room for ``size`` entries (the new ones unset)."""
    out = np.empty(size, dtype=a.dtype)
    copy_vector(out, a)
    return out


@njit(cache=True)
def grown_rows(a, size):
    """A copy of the matrix ``a`` with room for ``size`` rows (the new ones unset)."""
    out = np.empty((size, a.shape[1]), dtype=a.dtype)
    copy_matrix(out, a)
    return out
