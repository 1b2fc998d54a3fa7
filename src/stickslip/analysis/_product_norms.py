"""Norms of a cycle tube's nominal products (:mod:`stickslip.analysis._cycle_tube`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis._phase_flow import TWO_NORM_SIZE, two_norm_bounds
from stickslip.analysis._tube_phase import Phase

FloatArray = NDArray[np.float64]

#: Products (``N (N + 1) / 2`` for ``N`` phases) up to which ``between`` takes exact 2-norms
#: (singular values); beyond, the Gram matrices' rigorous upper bounds
#: (:func:`~stickslip.analysis._phase_flow.two_norm_bounds`, within a few ulps of them, and
#: about twice as fast): a Stribeck cycle at tolerance 1e-6 has 2 million products.
SVD_PRODUCTS = 100_000


@dataclass
class ProductNorms:
    """Norms of the nominal products of a tube bound (independent of the radius).

    ``prefix[i] = ||G(0, i) L||`` (``i = 0..N``), ``suffix[i] = ||R G(i + 1, N)||`` and
    ``between[j, i] = ||G(j, i)||`` (``G(j, i) = X*_{i-1} ... X*_j``, the identity for
    ``j >= i``), ``flowed[i] = ||expm(A_i t_i) G(0, i) L||`` (before the saltation) and
    ``flowed_rate[i] = ||A_i expm(A_i t_i) G(0, i) L||``, 2-norms (these and the following
    only in a run with friction bands, up to ``TWO_NORM_SIZE`` rows; else empty: the
    equal-time variant then bounds as the band-by-band one); for a phase ``j`` that
    ends at a breakaway, ``flowed_from[j][k] = ||expm(A_j t_j)
    G(k, j)||`` and ``rate_from[j][k] = ||A_j expm(A_j t_j) G(k, j)||`` (``k = 0..j``).
    """

    prefix: list[float]
    suffix: list[float]
    between: FloatArray
    flowed: list[float] = field(default_factory=list)  # ||expm(A_i t_i) G(0, i) L||
    flowed_rate: list[float] = field(default_factory=list)  # ||A_i expm(A_i t_i) G(0, i) L||
    flowed_from: dict[int, FloatArray] = field(default_factory=dict)
    rate_from: dict[int, FloatArray] = field(default_factory=dict)

    @classmethod
    def of(cls, phases: list[Phase], lift: FloatArray, reduce_rows: FloatArray) -> ProductNorms:
        """The norms of the nominal run's products (the factors ``X* = S expm(A t)``).

        ``between`` has ``N^2 / 2`` entries: the products of ``d`` consecutive factors are
        formed for every start at once (``G(j, j + d) = X*_{j+d-1} G(j, j + d - 1)``, one
        stacked product per ``d``) and their 2-norms taken as one stacked SVD (beyond
        :data:`SVD_PRODUCTS` products, bounded from above through their Gram matrices).
        """
        n_ph = len(phases)
        factors = np.array([ph.salt @ ph.e_nominal for ph in phases])
        between = np.ones((n_ph + 1, n_ph + 1))
        product = factors.copy()  # G(j, j + 1) for j = 0..N-1
        exact = n_ph * (n_ph + 1) // 2 <= SVD_PRODUCTS
        for d in range(1, n_ph + 1):
            starts = np.arange(n_ph - d + 1)
            between[starts, starts + d] = (np.linalg.svd(product, compute_uv=False)[:, 0] if exact
                                           else two_norm_bounds(product))
            if d < n_ph:
                product = factors[d:] @ product[:-1]  # G(j, j + d + 1) = X*_{j+d} G(j, j + d)
        # the equal-time variant's norms (a run with friction bands), on small structures
        banded = any(ph.bands is not None for ph in phases) and factors.shape[1] <= TWO_NORM_SIZE
        # the products in order, their 2-norms in one stacked SVD each (the same LAPACK call
        # per matrix as ``np.linalg.norm(x, 2)``, so the same numbers)
        heads, moved, rates, current = [], [], [], lift.copy()
        for i in range(n_ph + 1):
            heads.append(current)
            if i < n_ph:
                if banded:
                    moved.append(phases[i].e_nominal @ current)
                    rates.append(phases[i].a @ moved[-1])
                current = factors[i] @ current
        prefix = _two_norms(heads)
        flowed, flowed_rate = (_two_norms(moved), _two_norms(rates)) if banded else ([], [])
        tails, current = [], reduce_rows.copy()
        for i in range(n_ph - 1, -1, -1):
            tails.append(current)
            current = current @ factors[i]
        suffix = _two_norms(tails)[::-1]
        flowed_from, rate_from = {}, {}
        if banded:
            for j in (j for j, ph in enumerate(phases) if ph.breakaway):
                ends = [phases[j].e_nominal, phases[j].a @ phases[j].e_nominal]
                stack = []
                for k in range(j, -1, -1):  # ends = expm(A_j t_j) G(k, j) and A_j times it
                    stack.append(ends)
                    if k > 0:
                        ends = [h @ factors[k - 1] for h in ends]
                norms = np.array(_two_norms([h for pair in stack for h in pair])).reshape(j + 1, 2)
                flowed_from[j], rate_from[j] = norms[::-1, 0].copy(), norms[::-1, 1].copy()
        return cls(prefix, suffix, between, flowed, flowed_rate, flowed_from, rate_from)


def _two_norms(matrices: list[FloatArray]) -> list[float]:
    """The 2-norms of equally shaped matrices (their largest singular values), as floats."""
    if not matrices:
        return []
    return [float(x) for x in np.linalg.svd(np.array(matrices), compute_uv=False)[:, 0]]
