"""The coordinates a cycle proof's tube is bounded in (:mod:`stickslip.analysis._cycle_tube`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Coordinates:
    """The coordinates ``y = T^-1 z`` a tube is bounded in (the engine's state is ``z``).

    The tube's bounds are 2-norm bounds, true in any coordinates; their size is not. In the
    *energy coordinates* (:meth:`energy`) ``|y|^2 / 2`` is the structure's mechanical energy,
    so a passive mode's flow does not grow (``||expm(A t)||_2 <= 1``), where in the engine's
    coordinates it can grow by ``sqrt(cond)`` of the mass and stiffness matrices.
    """

    to_state: FloatArray  # T
    from_state: FloatArray  # T^-1

    @property
    def to_state_norm(self) -> float:
        """``||T||_2``: a deviation in ``y`` is at most this times larger in ``z``."""
        return float(np.linalg.norm(self.to_state, 2))

    @property
    def from_state_norm(self) -> float:
        """``||T^-1||_2``: a deviation in ``z`` is at most this times larger in ``y``."""
        return float(np.linalg.norm(self.from_state, 2))

    @classmethod
    def identity(cls, n2: int) -> Coordinates:
        """The engine's own coordinates."""
        return cls(np.eye(n2), np.eye(n2))

    @classmethod
    def energy(cls, mass: FloatArray, stiffness: FloatArray) -> Coordinates:
        """``y = (K^(1/2) q, M^(1/2) v)``; the identity unless both matrices are positive
        definite (a structure with a rigid-body mode has no energy norm)."""
        n = mass.shape[0]
        roots = []
        for matrix in (stiffness, mass):
            sym = 0.5 * (np.asarray(matrix, dtype=np.float64) + np.asarray(matrix).T)
            w, v = np.linalg.eigh(sym)
            if not (w.size and np.all(np.isfinite(w)) and w[0] > 1e-12 * w[-1] > 0.0):
                return cls.identity(2 * n)
            roots.append((v * np.sqrt(w), v / np.sqrt(w)))  # columns scaled: V W^(1/2)
        (k_half, k_inv_half), (m_half, m_inv_half) = roots
        from_state = np.zeros((2 * n, 2 * n))
        to_state = np.zeros((2 * n, 2 * n))
        from_state[:n, :n] = k_half.T  # W^(1/2) V^T: a square root of K with |y|^2 = q' K q
        from_state[n:, n:] = m_half.T
        to_state[:n, :n] = k_inv_half  # its inverse V W^(-1/2)
        to_state[n:, n:] = m_inv_half
        return cls(to_state, from_state)
