"""Slip motions compared at equal times across friction-band edges (a tube's second variant).

A tabulated friction law (Stribeck, a table, the floored linear law) is piecewise linear in
the sliding speed ``u`` and continuous at its band edges. The cycle tube of
:mod:`stickslip.analysis._cycle_tube` follows a motion band by band: every edge is an event
whose time moves with the start, so a perturbed motion must stay in the nominal band and the
bound on the return map's Jacobian pays ``||A||`` times every crossing's time shift. Its
*equal-time* variant compares a perturbed slip motion with the nominal one at the same
phase time instead, whatever band each is in. This module holds what that comparison needs.

Derivation. In slip the motion obeys ``z' = A_k z + c_k`` in band ``k``; the bands differ
only in the friction force, which acts through one column: ``A_k - A_i = w_k e_v^T`` (``e_v``
selects the slider's velocity, ``u = 1 -+ v``). With the nominal motion ``z*`` in band ``i``
and ``delta = z - z*``, ``delta' = A_i delta + r`` with ``r = f(z) - A_i z - c_i``, the
difference of the true law and band ``i``'s affine extension acting at ``z``. Continuity of
the law gives ``|F(u) - F_i(u)| = |int (s(w) - s_i) dw| <= max_k |s_k - s_i| |u - u*|``
over the bands ``k`` between ``u*`` and ``u``, so ``||r|| <= kappa ||delta||`` with
``kappa = max_k ||A_k - A_i||`` over the bands the perturbed speed can reach (those within
``d >= |u - u*|`` of band ``i``). With ``M_bar >= ||expm(A_i s)||`` on the phase,
variation of constants and Gronwall's inequality give, on ``0 <= s <= t``,

``||delta(s)|| <= M_bar Z exp(M_bar kappa s)``  and
``||delta(s) - expm(A_i s) delta(0)|| <= M_bar (exp(M_bar kappa s) - 1) Z``

(``Z >= ||delta(0)||``), and the same bound holds for ``||Psi(s) - expm(A_i s)||``, ``Psi``
the perturbed motion's fundamental matrix (``Psi' = A_k(s) Psi``; the saltation at an edge of
a continuous law is the identity). ``kappa`` depends on ``d``, ``d`` on the bound: a value
``d`` with ``||e_v T|| M_bar Z exp(M_bar kappa(d) t) < d`` is consistent (the first time
the speed deviation reached ``d`` the bound, valid until then, would already be below it),
which :func:`band_growth` finds by widening ``d``. Only while the nominal speed is within
``d`` of an edge of its band can the perturbed one be in another band: ``kappa t`` is
replaced by ``kappa tau``, ``tau`` the time the nominal spends there (at most ``2 d / rho``
per sample interval on which the speed changes at a rate ``rho`` or more), a sliver of each
crossing.

The law must be continuous: :meth:`BandVariation.of` checks that the bands differ in the
velocity column alone and that the force jumps at every edge are rounding (``1e-12`` of
the flow's scale), as the event tube assumes for its projector at a band edge.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from stickslip.kernel.modes import mode_code
from stickslip.kernel.system import SLIP_I, SLIP_II

FloatArray = NDArray[np.float64]

#: A band table counts as continuous (and its bands as differing in one column) when its
#: force jumps and other differences are within this fraction of the flow's scale.
CONTINUITY = 1e-12
#: Widenings of the speed deviation ``d`` tried by :func:`band_growth`, each by at least
#: the factor ``MARGIN`` (the first ``d`` is ``MARGIN`` times the linear bound).
WIDENINGS = 24
MARGIN = 1.05


@dataclass
class BandVariation:
    """The friction bands' flow matrices as seen by the equal-time comparison.

    ``columns[kind][k]`` is ``T^-1 w_k`` (band ``k``'s velocity column of ``A``, in the
    tube's coordinates ``y = T^-1 z``) and ``speed_norm = ||e_v T||``, so that
    ``||T^-1 (A_k - A_i) T||_2 = ||columns[k] - columns[i]|| speed_norm`` (rank one).
    """

    edges: FloatArray  # the bands' edges in the sliding speed u, edges[0] = 0
    columns: dict[int, FloatArray]
    speed_norm: float
    _spreads: dict[tuple[int, int], FloatArray] = field(default_factory=dict, repr=False)

    @classmethod
    def of(cls, edges: FloatArray, flow_matrix: FloatArray, flow_constant: FloatArray,
           n: int, to_y: FloatArray, to_z: FloatArray) -> BandVariation | None:
        """The variation of a return map's slip modes, or None (one band, or a law that is
        not continuous at an edge: the equal-time comparison does not apply).

        Parameters
        ----------
        edges : ndarray
            The bands' edges in ``u`` (``edges[-1]`` may be infinite).
        flow_matrix, flow_constant : ndarray
            ``A`` and ``c`` per mode code (the engine's coordinates ``z``).
        n : int
            Degrees of freedom (``z[n]`` is the slider's velocity).
        to_y, to_z : ndarray
            ``T^-1`` and ``T`` of the tube's coordinates.

        Returns
        -------
        BandVariation or None
        """
        nb = int(edges.size) - 1
        if nb < 2 or float(edges[0]) != 0.0:
            return None
        columns = {}
        for kind, sign in ((SLIP_I, -1.0), (SLIP_II, 1.0)):
            codes = [int(mode_code(kind, b)) for b in range(nb)]
            a, c = flow_matrix[codes], flow_constant[codes]
            scale = max(1.0, float(np.max(np.abs(a))), float(np.max(np.abs(c))))
            off = a - a[:1]
            off[:, :, n] = 0.0
            v_edge = 1.0 + sign * edges[1:nb]
            jump = (a[1:, :, n] - a[:-1, :, n]) * v_edge[:, None] + (c[1:] - c[:-1])
            if float(np.max(np.abs(off))) > CONTINUITY * scale or \
                    float(np.max(np.abs(jump))) > CONTINUITY * scale:
                return None
            columns[kind] = a[:, :, n] @ to_y.T
        return cls(np.asarray(edges, dtype=np.float64), columns, float(np.linalg.norm(to_z[n, :])))

    def spread(self, kind: int, band: int) -> FloatArray:
        """``||A_k - A_band||_2`` in the tube's coordinates, for every band ``k``."""
        key = (kind, band)
        if key not in self._spreads:
            cols = self.columns[kind]
            self._spreads[key] = np.linalg.norm(cols - cols[band], axis=1) * self.speed_norm
        return self._spreads[key]

    def kappa(self, kind: int, band: int, d: float) -> float:
        """``max ||A_k - A_band||`` over the bands within ``d`` in ``u`` of band ``band``."""
        edges = self.edges
        nb = edges.size - 1
        lo = float(edges[band]) - d
        hi = float(edges[band + 1]) + d if band + 1 < nb else math.inf
        first = int(np.searchsorted(edges[1:nb], lo, side="right"))  # edges[k+1] > lo
        last = nb - 1 if not math.isfinite(hi) else int(np.searchsorted(edges[:nb], hi, side="left")) - 1
        last = min(max(last, band), nb - 1)
        first = min(first, band)
        return float(np.max(self.spread(kind, band)[first:last + 1]))


def band_growth(bands: BandVariation, kind: int, band: int, z_dev: float, m_bar: float,
                exposure: Callable[[float], float]) -> tuple[float, float] | None:
    """``(kappa, exp(M_bar kappa tau))`` for a phase, or None.

    ``exposure(d)`` bounds ``tau``, the time the nominal speed spends within ``d`` of one of
    its band's edges: only then can the perturbed motion be in another band, so
    ``int ||A_k(s) - A_i|| ds <= kappa(d) tau(d)`` replaces ``kappa t`` in the module's
    derivation. Widens the speed deviation ``d`` from :data:`MARGIN` times the linear bound until it is
    consistent; None when no widening of :data:`WIDENINGS` is.

    Parameters
    ----------
    bands : BandVariation
        The run's bands.
    kind, band : int
        The nominal phase's slip kind and band.
    z_dev : float
        ``Z``: the deviation bound at the phase's start.
    m_bar : float
        A bound of ``||expm(A_i s)||`` over the phase.
    exposure : callable
        ``d -> tau(d)``.

    Returns
    -------
    (float, float) or None
    """
    base = bands.speed_norm * m_bar * z_dev
    if base == 0.0:
        return 0.0, 1.0
    d = MARGIN * base
    for _ in range(WIDENINGS):
        kap = bands.kappa(kind, band, d)
        grow = math.exp(min(m_bar * kap * exposure(d), 700.0))
        if base * grow < d:
            return kap, grow
        d = max(MARGIN * d, MARGIN * base * grow)
    return None
