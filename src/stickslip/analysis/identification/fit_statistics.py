"""Shared by the friction fits to records (rate-and-state, LuGre): input checks and the
standard errors of a least-squares fit."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: The terminal's line for a fit whose optimiser stopped at its evaluation budget.
NOT_CONVERGED = ("warning     the fit did not converge (its evaluation budget ran out): the "
                 "values and errors are where the optimiser stopped, not an optimum")


def checked_record(columns: tuple[FloatArray, ...], minimum: int, what: str) -> tuple[FloatArray, ...]:
    """The record's columns as float arrays: equal lengths of at least ``minimum``, finite, the
    first (time) strictly increasing; else ``ValueError`` naming ``what`` (the columns).

    Parameters
    ----------
    columns : tuple of array_like
        Time first, then the measured columns.
    minimum : int
        Fewest samples.
    what : str
        The columns in words, for the message.

    Returns
    -------
    tuple of ndarray
        The columns, contiguous float64.
    """
    out = tuple(np.ascontiguousarray(c, dtype=np.float64) for c in columns)
    if not (out[0].ndim == 1 and all(c.shape == out[0].shape for c in out) and out[0].size >= minimum):
        raise ValueError(f"the record needs at least {minimum} samples of {what}")
    if not all(np.all(np.isfinite(c)) for c in out):
        raise ValueError("the record holds a value that is not a finite number")
    if not np.all(np.diff(out[0]) > 0.0):
        raise ValueError("the record's times must increase strictly")
    return out


def linearised_errors(jac: FloatArray, cost: float, names: tuple[str, ...]) -> dict[str, float]:
    """Standard errors ``sqrt(diag((J^T J)^-1) s^2)``, ``s^2 = 2 cost / (n - p)``.

    ``J`` (rows: residuals, columns: the parameters themselves) is scaled by its column norms
    before the inversion, so the conditioning is the problem's, not its units'. A column of
    zeros (a parameter the residuals do not depend on) or a condition number above 1e14 gives
    infinite errors for every parameter.

    Parameters
    ----------
    jac : ndarray, shape (n, p)
        Jacobian of the residuals at the optimum.
    cost : float
        Half the sum of squared residuals (``scipy.optimize.least_squares``' ``cost``).
    names : tuple of str
        The parameters, in column order.

    Returns
    -------
    dict
        Name -> standard error (``inf`` where undetermined).
    """
    s2 = 2.0 * cost / max(jac.shape[0] - len(names), 1)
    norms = np.linalg.norm(jac, axis=0)
    if not np.all(norms > 0.0):
        return {name: math.inf for name in names}
    gram = (jac / norms).T @ (jac / norms)
    try:
        if np.linalg.cond(gram) > 1e14:
            raise np.linalg.LinAlgError
        cov = np.linalg.inv(gram) / np.outer(norms, norms) * s2
    except np.linalg.LinAlgError:
        return {name: math.inf for name in names}
    return {name: math.sqrt(max(float(cov[i, i]), 0.0)) for i, name in enumerate(names)}
