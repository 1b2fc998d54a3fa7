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
        return _estimable_errors(jac, s2, names)
    gram = (jac / norms).T @ (jac / norms)
    try:
        if np.linalg.cond(gram) > 1e14:
            raise np.linalg.LinAlgError
        cov = np.linalg.inv(gram) / np.outer(norms, norms) * s2
    except np.linalg.LinAlgError:
        return _estimable_errors(jac, s2, names)
    return {name: math.sqrt(max(float(cov[i, i]), 0.0)) for i, name in enumerate(names)}


#: Singular values below this fraction of the largest span the Jacobian's null space, and a
#: parameter whose unit vector has a component above :data:`NULL_COMPONENT` in it is not
#: determined by the record.
RANK_TOLERANCE = 1e-7
NULL_COMPONENT = 1e-6


def _estimable_errors(jac: FloatArray, s2: float, names: tuple[str, ...]) -> dict[str, float]:
    """Standard errors where ``J^T J`` is singular: finite for the parameters the record still
    determines, ``inf`` for the others.

    A parameter ``p_i`` is determined (estimable) when its unit vector ``e_i`` lies in the row
    space of ``J``, i.e. has no component in the null space (the right singular vectors of the
    column-scaled ``J`` whose singular values fall below :data:`RANK_TOLERANCE` of the
    largest); its variance is then ``s^2 e_i^T (J^T J)^+ e_i`` with the pseudo-inverse, which
    does not depend on the undetermined directions. Example: a rate-and-state record without
    a speed step is steady sliding at ``v_ref``, where ``mu = mu_ref`` and the columns of ``a``,
    ``b`` and ``d_c`` vanish: ``mu_ref`` is the record's level, the other three undetermined.
    """
    norms = np.linalg.norm(jac, axis=0)
    scale = np.where(norms > 0.0, norms, 1.0)
    _, sv, vt = np.linalg.svd(jac / scale, full_matrices=True)
    keep = np.zeros(vt.shape[0], dtype=bool)
    keep[: sv.size] = sv > RANK_TOLERANCE * (float(sv[0]) if sv.size and sv[0] > 0 else 1.0)
    null = vt[~keep]
    out = {}
    for i, name in enumerate(names):
        if not keep.any() or (null.size and float(np.max(np.abs(null[:, i]))) > NULL_COMPONENT):
            out[name] = math.inf
            continue
        rows = vt[keep]
        variance = float(np.sum((rows[:, i] / sv[keep]) ** 2)) / scale[i] ** 2 * s2
        out[name] = math.sqrt(max(variance, 0.0))
    return out
