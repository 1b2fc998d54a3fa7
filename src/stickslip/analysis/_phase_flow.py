"""One phase's affine flow at its sample times, for the tube bound of a cycle proof.

:func:`sampled_flow` gives the nominal states ``z(s)`` of a phase ``z' = A z + c`` and bounds
``M(s) >= ||expm(A s)||_2`` at the times of :func:`sample_times`; :func:`flow_work` is its
cost, checked against :data:`MAX_PHASE_WORK` before a proof samples anything
(:func:`stickslip.analysis._cycle_tube.phases`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from stickslip.kernel.linalg import expm, expm_at

FloatArray = NDArray[np.float64]

#: Largest number of samples of one phase's nominal trajectory (bounds the work).
MAX_SAMPLES = 20_000
#: ``||A||_F h`` of the sampling step: small, so the bounds between samples are tight.
SAMPLE_STEP = 0.02
#: Halvings of the first and last sample interval (down to ``h 2^-REFINE``).
REFINE = 40
#: Multiply-adds up to which a phase's propagators are all formed (``samples (2n + 1)^3``, by
#: doubling) and their norms taken exactly (Frobenius). Beyond it (structures of about 20 DOF
#: and more) they are factored (:func:`sampled_flow`): about ``2 sqrt(samples)`` products and
#: 2-norms instead of ``samples`` products; the 60-DOF audit machine's two phases took 9.8 s
#: formed, most of its 14 s run.
DENSE_WORK = 2e9
#: Multiply-adds one phase's sampling may take (:func:`flow_work`): beyond it the tube is not
#: built and the candidate stays unproven, so a proof never holds a run for long (about 50 s
#: at 10 GFlop/s).
MAX_PHASE_WORK = 2.5e11
#: Work charged for the 2-norm bound of a ``(2n + 1)``-square matrix (its Gram matrix and
#: that matrix's largest eigenvalue, :func:`two_norm_bounds`), in matrix products of that size
#: (measured: 3 to 7 on this project's machine at 60 to 300 DOF).
NORM_WORK = 5.0


def sample_times(duration: float, norm_a: float) -> tuple[FloatArray, float]:
    """Sample times of a phase: a uniform grid, refined geometrically towards both ends.

    The uniform step keeps ``||A|| h <= SAMPLE_STEP`` (at most ``MAX_SAMPLES`` steps); the
    refinement (``h 2^-k``, ``k = 1..REFINE``) resolves the windows next to the surfaces the
    phase starts and ends on, where a slow (nearly grazing) crossing needs short intervals.

    Parameters
    ----------
    duration : float
        The phase's duration (``tau``).
    norm_a : float
        ``||A||_F`` of its mode.

    Returns
    -------
    (ndarray, float)
        Increasing times from 0 to ``duration``, and the uniform step ``h``.
    """
    samples = int(min(MAX_SAMPLES, max(8, math.ceil(duration * norm_a / SAMPLE_STEP))))
    h = duration / samples
    fine = h * 2.0 ** -np.arange(1, REFINE + 1)
    grid = np.concatenate([np.arange(samples) * h, [duration], fine, duration - fine])
    return np.unique(grid), h


def flow_work(samples: int, size: int) -> float:
    """Multiply-adds :func:`sampled_flow` spends on ``samples`` propagators of ``size`` rows.

    ``samples size^3`` when they are formed (at most :data:`DENSE_WORK`); factored, ``2 K``
    products and 2-norm bounds (:data:`NORM_WORK`) with ``K = ceil(sqrt(samples))``, and one product
    with a vector per sample.

    Parameters
    ----------
    samples : int
        Sample times on the uniform grid (``sample_times(...)[0].size`` bounds them).
    size : int
        Rows of the augmented propagator (``2 n + 1``).

    Returns
    -------
    float
        The multiply-adds.
    """
    dense = float(samples) * float(size) ** 3
    if dense <= DENSE_WORK:
        return dense
    k = math.ceil(math.sqrt(samples))
    return 2.0 * k * (1.0 + NORM_WORK) * float(size) ** 3 + float(samples) * float(size) ** 2


def two_norm_bounds(x: FloatArray) -> FloatArray:
    """Upper bounds of the 2-norms of a stack of square matrices, with their rounding.

    ``||X||_2^2`` is the largest eigenvalue of ``G = X^T X``. The computed ``G`` and its
    computed eigenvalue are within ``m u ||X||_F^2`` (the product, ``|X|^T |X|`` bounded by
    the Frobenius norm) and ``p(m) u ||G||_2 <= p(m) u ||X||_F^2`` (the symmetric eigensolver's
    backward error) of the exact ones, ``u`` the unit round-off; both are covered by adding
    ``4 m eps ||X||_F^2`` (``eps = 2 u``) before the square root.

    Parameters
    ----------
    x : ndarray, shape (k, m, m)
        The matrices.

    Returns
    -------
    ndarray, shape (k,)
        Bounds ``>= ||X_i||_2``.
    """
    gram = np.matmul(np.swapaxes(x, 1, 2), x)
    largest = np.linalg.eigvalsh(gram)[:, -1]
    frobenius2 = np.sum(x**2, axis=(1, 2))
    eps = float(np.finfo(np.float64).eps)
    return np.sqrt(np.maximum(largest, 0.0) + 4.0 * x.shape[1] * eps * frobenius2)


def sampled_flow(a: FloatArray, c: FloatArray, z0: FloatArray, duration: float, norm_a: float,
                 two_norm: bool = False) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """The affine flow ``z' = A z + c`` of a phase from ``z0`` at its :func:`sample_times`.

    The augmented propagators ``E(s) = expm([[A, c], [0, 0]] s)`` of the uniform grid are the
    powers of one step ``E(h)``, and the refined times' each their own exponential. Up to
    :data:`DENSE_WORK` the powers are formed by doubling (a few batched products) and
    ``M(s) = ||expm(A s)||_F``. Beyond it they are factored: with ``K = ceil(sqrt(count))``,
    ``E((k K + j) h) = E(K h)^k E(h)^j``, the states are ``E(h)^j (E(K h)^k z0)`` (products
    with vectors) and ``M = ||expm(A K h)^k||_2 ||expm(A h)^j||_2`` (:func:`two_norm_bounds`), an
    upper bound of ``||expm(A s)||_2`` by submultiplicativity (the top-left block of a product
    of block upper-triangular matrices is the product of the blocks): ``2 K`` matrix products
    and 2-norms instead of ``count`` products, and the memory of ``K`` propagators.

    Parameters
    ----------
    a, c : ndarray
        The mode's matrix and constant (per unit ``tau``).
    z0 : ndarray
        The phase's start.
    duration, norm_a : float
        The phase's duration and ``||A||_F``.
    two_norm : bool
        Also tighter bounds of the 2-norms (up to :data:`TWO_NORM_SIZE` rows; the 2-norms
        themselves up to :data:`TWO_NORM_SVD`; beyond, the bounds ``M``).

    Returns
    -------
    (ndarray, ndarray, ndarray, ndarray)
        The times, the states ``z(s)`` there (shape ``(times, 2n)``), bounds ``M(s)`` of
        ``||expm(A s)||_2`` (Frobenius norms where the propagators are formed: the bounds
        every tube uses) and the tighter bounds asked for with ``two_norm`` (else ``M``).
    """
    times, h = sample_times(duration, norm_a)
    n2 = a.shape[0]
    aug = np.zeros((n2 + 1, n2 + 1))
    aug[:n2, :n2], aug[:n2, n2] = a, c
    index = np.rint(times / h)
    # on the grid: within a few units in the last place (``k h`` is computed alike, and the
    # duration within an ulp of ``samples h``); a refined time a few hundred ulps away has
    # its own propagator
    on_grid = np.abs(times - index * h) <= 4.0 * np.finfo(np.float64).eps * np.maximum(times, h)
    grid_index = index[on_grid].astype(np.int64)
    count = int(np.max(grid_index)) + 1
    step = expm(aug * h)
    zs = np.empty((times.size, n2))
    m_norm = np.empty(times.size)
    rows_on = np.flatnonzero(on_grid)
    z_aug = np.append(z0, 1.0)
    exact = two_norm and n2 <= TWO_NORM_SIZE
    kept = np.zeros((times.size, n2, n2)) if exact else None  # for one batched SVD

    def take(rows: NDArray[np.int64], props: FloatArray) -> None:
        zs[rows] = props[:, :n2, :n2] @ z0 + props[:, :n2, n2]
        m_norm[rows] = np.sqrt(np.sum(props[:, :n2, :n2] ** 2, axis=(1, 2)))
        if kept is not None:
            kept[rows] = props[:, :n2, :n2]

    if float(count) * float(n2 + 1) ** 3 <= DENSE_WORK:
        powers = np.eye(n2 + 1)[None]
        while powers.shape[0] < count:  # doubling: E^(j + m) = E^m E^j
            powers = np.concatenate([powers, np.linalg.matrix_power(step, powers.shape[0]) @ powers])
        take(rows_on, powers[grid_index])
    else:
        k_fine = math.ceil(math.sqrt(count))
        fine = np.empty((k_fine, n2 + 1, n2 + 1))  # E(j h), j < K
        fine[0] = np.eye(n2 + 1)
        for i in range(1, k_fine):
            fine[i] = step @ fine[i - 1]
        fine_norm = two_norm_bounds(fine[:, :n2, :n2])
        leap = step @ fine[-1]  # E(K h)
        lead = np.eye(n2 + 1)  # E(k K h)
        for k in range(-(-count // k_fine)):
            picked = (grid_index >= k * k_fine) & (grid_index < (k + 1) * k_fine)
            if np.any(picked):
                j = grid_index[picked] - k * k_fine
                zs[rows_on[picked]] = (fine[j] @ (lead @ z_aug))[:, :n2]
                m_norm[rows_on[picked]] = two_norm_bounds(lead[None, :n2, :n2])[0] * fine_norm[j]
            lead = leap @ lead
        # the refined times, within h of an end: Taylor series on the vector from the nearer
        # end, and ||expm(A s)||_2 <= exp(||A||_F s) (times M at the last grid point before
        # the end): products with vectors instead of their own exponentials
        m_before_end = float(m_norm[rows_on[grid_index == count - 2]][0]) if count > 1 else 1.0
        z_end = np.append(zs[rows_on[grid_index == count - 1]][0], 1.0)
        for off in np.flatnonzero(~on_grid):
            t = float(times[off])
            if t <= 0.5 * duration:
                zs[off] = _taylor_affine(aug, z_aug, t)[:n2]
                m_norm[off] = math.exp(norm_a * t)
            else:
                zs[off] = _taylor_affine(aug, z_end, t - duration)[:n2]
                m_norm[off] = m_before_end * math.exp(norm_a * (t - (count - 2) * h))
        return times, zs, m_norm, m_norm
    off_grid = np.flatnonzero(~on_grid)
    if off_grid.size:  # the refined times' own exponentials, taken in one batch
        take(off_grid, expm_at(aug, times[off_grid]))
    if kept is None:
        return times, zs, m_norm, m_norm
    if n2 <= TWO_NORM_SVD:
        m_two = np.asarray(np.linalg.svd(kept, compute_uv=False)[:, 0] * TWO_NORM_SLACK, dtype=np.float64)
    else:  # ||E||_2 <= sqrt(||E||_1 ||E||_inf), cheaper than singular values
        sums = np.abs(kept)
        m_two = np.minimum(m_norm, np.sqrt(sums.sum(axis=1).max(axis=1) * sums.sum(axis=2).max(axis=1))
                           * TWO_NORM_SLACK)
    return times, zs, m_norm, m_two


#: :func:`sampled_flow` computes 2-norms (singular values) of propagators up to this size.
TWO_NORM_SIZE = 16
#: ... by their singular values up to this size (beyond, by the 1- and infinity-norms' mean)
TWO_NORM_SVD = 8
#: ... and rounds them up by this factor (their relative error is a few ulps).
TWO_NORM_SLACK = 1.0 + 1e-12

#: Terms at most of :func:`_taylor_affine`'s series (it stops when a term is below rounding).
TAYLOR_TERMS = 200


def _taylor_affine(aug: FloatArray, w: FloatArray, t: float) -> FloatArray:
    """``expm(aug t) w`` by its Taylor series on the vector (``|t| ||aug||`` small).

    Summed until a term, past ``|t| ||aug||_F`` (where the terms decrease), is below the
    round-off of the sum; at most :data:`TAYLOR_TERMS` terms.
    """
    rho = abs(t) * float(np.linalg.norm(aug))
    term = w.copy()
    total = w.copy()
    for k in range(1, TAYLOR_TERMS + 1):
        term = (aug @ term) * (t / k)
        total += term
        if k > rho and float(np.linalg.norm(term)) <= 1e-17 * float(np.linalg.norm(total)):
            break
    return total
