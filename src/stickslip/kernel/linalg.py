"""Small dense linear algebra for the kernel (numba, arrays only).

The matrices here are tiny (a few rows), so explicit loops beat BLAS calls.
"""

from __future__ import annotations

import numpy as np
from numba import njit

TAYLOR_DEGREE_EXPM = 18


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
def expm(a: np.ndarray) -> np.ndarray:
    """Matrix exponential by scaling and squaring of a degree-18 Taylor polynomial.

    The scaled matrix has infinity norm at most 1/2, so the truncation error is below
    ``0.5**19 / 19!`` (about 1e-23) relative, far below double precision. Checked against
    ``scipy.linalg.expm`` in the tests.
    """
    n = a.shape[0]
    norm = inf_norm(a)
    squarings = 0
    while norm > 0.5:
        norm *= 0.5
        squarings += 1
    b = a / (2.0**squarings)
    result = np.eye(n)
    term = np.eye(n)
    for k in range(1, TAYLOR_DEGREE_EXPM + 1):
        term = (term @ b) / k
        result += term
    for _ in range(squarings):
        result = result @ result
    return result


@njit(cache=True)
def solve_lyapunov(a: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Solve ``a.T @ p + p @ a = -q`` for ``p`` through the Kronecker form."""
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
    vec = np.linalg.solve(lhs, rhs)
    p = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            p[i, j] = vec[i * n + j]
    return 0.5 * (p + p.T)
