"""Reduction of large finite-element structures before a run (issue 18 point 5).

Method (Craig-Bampton, the residual-flexibility attachment of the kept DOFs)
----------------------------------------------------------------------------
The kept DOFs ``b`` (the contact, and the absorber's attachment) stay physical coordinates;
the other DOFs ``i`` are described by

* the static constraint modes ``Psi = [I; -K_ii^-1 K_ib]``: the shape the structure takes,
  statically, when one kept DOF moves by one metre and no force acts elsewhere. They carry
  the whole static flexibility of the structure as seen from the kept DOFs: the reduced
  model's static receptance at the contact is *exact* (the residual flexibility of every
  dropped mode is in it);
* the fixed-interface modes ``Phi_i`` of ``K_ii, M_ii`` (kept DOFs held) below the cut-off
  frequency, from ``scipy.sparse.linalg.eigsh`` in shift-invert mode about 0 (sparse, never
  dense).

With ``T = [Psi, [0; Phi_i]]`` the reduced matrices are ``T' M T``, ``T' C T``, ``T' K T``
(a Ritz projection: symmetric, ``M`` and ``K`` stay positive definite, a grounded structure
stays grounded) and the contact force still enters the contact DOF alone.

Default cut-off (:func:`default_cutoff_hz`): ``CUTOFF_FACTOR`` times the larger of the contact
DOF's own frequency ``f_c = sqrt(K_cc / M_cc) / (2 pi)`` -- the engine's unit of time, the
frequency at which the contact would ring on its own spring (the "contact stiffness" ``K_cc``)
-- and the belt's loading rate ``1 / T_load``, where ``T_load = (mu_s - mu_k) W / (k_c V)`` is the
time the belt takes to load the contact, of static point stiffness ``k_c = 1 / [K^-1]_cc``,
from the kinetic to the static friction force (the shortest time scale of a stick phase).
Modes far above both respond quasi-statically to the contact force, and their static share
is kept exactly by the constraint modes. At most :data:`MAX_KEPT_MODES` modes are kept (the
lowest; :attr:`ReducedStructure.truncated` says so). For a lumped finite-element model the
contact node's own frequency is high, so the rule keeps many modes: it errs on the safe side.

The error of the reduction is measured by ``tests/test_structure_reduction.py`` on a 301-DOF
structure (receptance at the contact below the cut-off; critical friction-weakening slope; the
Coulomb critical belt speed of the full model, simulated, within 2 % of the reduced model's)
and stated by ``benchmarks/bench_structure.py``: critical speed reduced 0.303267 m/s (50 DOF)
against full 0.303422 m/s (bisected to 1e-3), relative error -5.1e-4 (docs/structures.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: Cut-off frequency in units of ``max(f_c, 1 / T_load)`` (module docstring).
CUTOFF_FACTOR = 3.0

#: Most fixed-interface modes kept (the reduced model must stay runnable directly: 60 DOF).
MAX_KEPT_MODES = 56

#: Highest cut-off frequency accepted, Hz: 1 GHz, far above any structural mode a friction
#: contact excites (a higher one only keeps the lowest :data:`MAX_KEPT_MODES` modes, as this
#: one does); beyond, ``(2 pi f)**2`` would leave the floating-point range.
MAX_CUTOFF_HZ = 1e9


def check_cutoff(cutoff_hz: float, *, source: str = "cutoff_hz") -> float:
    """``cutoff_hz`` if it is a frequency in ``(0, MAX_CUTOFF_HZ]`` Hz, else one ``ValueError`` line.

    Parameters
    ----------
    cutoff_hz : float
        The cut-off frequency, Hz.
    source : str
        How the message names the value.

    Returns
    -------
    float
        The cut-off, Hz.
    """
    if not (isinstance(cutoff_hz, (int, float)) and 0.0 < cutoff_hz <= MAX_CUTOFF_HZ):
        raise ValueError(f"{source} must be a positive frequency up to {MAX_CUTOFF_HZ:g} Hz (1 GHz, "
                         f"far above any structural mode); got {cutoff_hz!r} Hz")
    return float(cutoff_hz)


@dataclass(frozen=True)
class ReducedStructure:
    """A structure reduced to its kept DOFs and fixed-interface modes below a cut-off.

    Attributes
    ----------
    mass, stiffness : ndarray, shape (r, r)
        Reduced matrices (SI), kept DOFs first in the order given, then the modal coordinates.
    basis : ndarray, shape (n, r)
        The Ritz basis ``T``: full displacements ``x = T q``; reduce a damping matrix with
        :meth:`project`.
    kept_dofs : tuple of int
        The full model's DOFs kept as physical coordinates (reduced DOFs ``0 .. len - 1``).
    cutoff_hz : float
        Cut-off frequency of the fixed-interface modes, Hz.
    n_modes : int
        Fixed-interface modes kept.
    n_full : int
        DOFs of the full model.
    truncated : bool
        True when more modes lay below the cut-off than :data:`MAX_KEPT_MODES` (the lowest
        were kept).
    default_cutoff_hz : float or None
        The default cut-off of the operating point (:func:`default_cutoff_hz`) when the
        machine file gave its own, else None.
    """

    mass: FloatArray
    stiffness: FloatArray
    basis: FloatArray
    kept_dofs: tuple[int, ...]
    cutoff_hz: float
    n_modes: int
    n_full: int
    truncated: bool
    default_cutoff_hz: float | None = None

    def project(self, matrix: Any) -> FloatArray:
        """``T' A T`` of a full ``n x n`` matrix (dense or sparse), symmetrised."""
        at = matrix @ self.basis
        out = np.asarray(self.basis.T @ at, dtype=np.float64)
        return 0.5 * (out + out.T)

    def truncation_warning(self) -> str | None:
        """What a truncated reduction costs, in one line (None when every mode below the
        cut-off was kept).

        The engine runs at most 60 DOF, so a model with more than :data:`MAX_KEPT_MODES`
        modes below the cut-off keeps the lowest: the dropped ones' static flexibility stays
        exact, their dynamics do not. An independent audit's 120-DOF chain (contact in its
        middle) had the Coulomb critical speed 11.7 % above the full model's and the peak
        receptance 9.7 % high that way, whatever the cut-off.
        """
        if not self.truncated:
            return None
        return (f"the {self.n_full}-DOF model was reduced to {self.mass.shape[0]} DOF keeping only "
                f"the lowest {MAX_KEPT_MODES} of the modes below {self.cutoff_hz:.4g} Hz (the "
                "engine runs at most 60 DOF): the answers carry the truncation's error (several "
                "per cent on an audit's 120-DOF chain); check them against a coarser model whose "
                "modes below the cut-off all fit")

    def cutoff_warning(self) -> str | None:
        """One line when the machine file's cut-off lies below the operating point's default
        (None otherwise).

        Modes between the two respond dynamically to the contact and are dropped: an
        independent audit's 120-DOF chain, reduced at 130-200 Hz (the default 1,584 Hz), had its
        steady sliding called unstable (growth rates +4.4 to +12.3 1/s under a weakening law)
        where the full model's is stable (-5.65 1/s).
        """
        if self.default_cutoff_hz is None or self.cutoff_hz >= self.default_cutoff_hz:
            return None
        return (f"the cut-off {self.cutoff_hz:.4g} Hz lies below the default {self.default_cutoff_hz:.4g} Hz "
                "of this operating point (3 times the larger of the contact's own frequency and "
                "the belt's loading rate): the modes between them are dropped though they respond "
                "dynamically, and the reduced model's answers, its stability included, may differ "
                "from the full model's")

    def summary(self) -> str:
        """One line: sizes, cut-off and what the reduction keeps."""
        more = f" (more lay below; the lowest {MAX_KEPT_MODES} kept)" if self.truncated else ""
        return (f"reduced {self.n_full} DOF to {self.mass.shape[0]}: kept DOFs "
                f"{', '.join(map(str, self.kept_dofs))} with their static flexibility (exact) "
                f"and {self.n_modes} fixed-interface modes below {self.cutoff_hz:.4g} Hz{more}")


def _sparse(matrix: Any) -> Any:
    import scipy.sparse

    return scipy.sparse.csc_matrix(matrix, dtype=np.float64)


def default_cutoff_hz(mass: Any, stiffness: Any, contact_dof: int, *, speed: float, load: float,
                      mu_s: float, mu_k: float) -> float:
    """``CUTOFF_FACTOR * max(f_c, 1 / T_load)``, Hz (module docstring), one sparse solve.

    Parameters
    ----------
    mass, stiffness : array_like or sparse matrix
        Mass (kg) and stiffness (N/m) of the full model.
    contact_dof : int
        The DOF the belt rubs.
    speed, load : float
        Belt speed (m/s) and normal load (N).
    mu_s, mu_k : float
        Static and kinetic friction coefficients.

    Returns
    -------
    float
        The cut-off frequency, Hz.
    """
    from scipy.sparse.linalg import splu

    k = _sparse(stiffness)
    m = _sparse(mass)
    n = k.shape[0]
    e = np.zeros(n)
    e[contact_dof] = 1.0
    k_c = 1.0 / float(splu(k).solve(e)[contact_dof])
    t_load = (mu_s - mu_k) * load / (k_c * speed)
    f_c = math.sqrt(float(k[contact_dof, contact_dof]) / float(m[contact_dof, contact_dof])) / (2.0 * math.pi)
    return CUTOFF_FACTOR * max(f_c, 1.0 / t_load)


def reduce_structure(mass: Any, stiffness: Any, kept_dofs: tuple[int, ...] | list[int], *,
                     cutoff_hz: float) -> ReducedStructure:
    """Craig-Bampton reduction to ``kept_dofs`` plus fixed-interface modes below ``cutoff_hz``.

    Parameters
    ----------
    mass, stiffness : ndarray or scipy.sparse matrix, shape (n, n)
        Full symmetric matrices (SI), stiffness grounded.
    kept_dofs : sequence of int
        DOFs kept as physical coordinates (the contact first, then an absorber's DOF).
    cutoff_hz : float
        Keep the fixed-interface modes below this frequency, Hz (at most
        :data:`MAX_KEPT_MODES`, the lowest).

    Returns
    -------
    ReducedStructure
    """
    from scipy.sparse.linalg import eigsh, splu

    k = _sparse(stiffness)
    m = _sparse(mass)
    n = k.shape[0]
    kept = tuple(dict.fromkeys(int(d) for d in kept_dofs))
    if not kept or min(kept) < 0 or max(kept) >= n:
        raise ValueError(f"kept DOFs {kept} must lie in 0..{n - 1}")
    cutoff_hz = check_cutoff(cutoff_hz)
    b = np.array(kept)
    interior = np.setdiff1d(np.arange(n), b)
    nb, ni = b.size, interior.size
    k_ii = k[interior][:, interior].tocsc()
    m_ii = m[interior][:, interior].tocsc()
    k_ib = k[interior][:, b].toarray()
    try:
        lu = splu(k_ii) if ni else None
    except RuntimeError:  # "Factor is exactly singular"
        raise ValueError("the stiffness matrix with the kept DOFs held is singular: part of the "
                         "structure is free (not grounded)") from None
    psi_i = -lu.solve(k_ib) if lu is not None else np.zeros((0, nb))
    modes = np.zeros((ni, 0))
    truncated = False
    if ni:
        w_cut2 = (2.0 * math.pi * cutoff_hz) ** 2
        n_ask = min(MAX_KEPT_MODES + 1, ni - 1) if ni > 2 else 0
        if n_ask > 0:
            w2, vec = eigsh(k_ii, k=n_ask, M=m_ii, sigma=0.0, which="LM")
        else:
            from scipy.linalg import eigh

            w2, vec = eigh(k_ii.toarray(), m_ii.toarray())
        order = np.argsort(w2)
        w2, vec = w2[order], vec[:, order]
        below = w2 <= w_cut2
        truncated = bool(below.sum() > MAX_KEPT_MODES)
        keep = np.flatnonzero(below)[:MAX_KEPT_MODES]
        modes = vec[:, keep]
    basis = np.zeros((n, nb + modes.shape[1]))
    basis[b, np.arange(nb)] = 1.0
    basis[np.ix_(interior, np.arange(nb))] = psi_i
    basis[np.ix_(interior, np.arange(nb, nb + modes.shape[1]))] = modes
    red = ReducedStructure(np.zeros(0), np.zeros(0), basis, kept, float(cutoff_hz),
                           int(modes.shape[1]), n, truncated)
    return ReducedStructure(red.project(m), red.project(k), basis, kept, float(cutoff_hz),
                            int(modes.shape[1]), n, truncated)


def reduce_at_operating_point(mass: Any, stiffness: Any, kept_dofs: list[int], *,
                              cutoff_hz: float | None,
                              operating_point: tuple[float, float, float, float] | None,
                              ) -> ReducedStructure:
    """:func:`reduce_structure` at the given cut-off, or at the operating point's default.

    The contact is ``kept_dofs[0]``. With both a cut-off and an operating point the default is
    recorded (:attr:`ReducedStructure.default_cutoff_hz`), so a cut-off below it is said
    (:meth:`ReducedStructure.cutoff_warning`).

    Parameters
    ----------
    mass, stiffness : ndarray or scipy.sparse matrix, shape (n, n)
        The full model (SI).
    kept_dofs : list of int
        The DOFs kept as physical coordinates, the contact first.
    cutoff_hz : float or None
        The machine file's cut-off, Hz (None: the default).
    operating_point : tuple or None
        ``(speed m/s, load N, mu_s, mu_k)``, for :func:`default_cutoff_hz`.

    Returns
    -------
    ReducedStructure
        The reduction.
    """
    default = None
    if operating_point is not None:
        speed, load, mu_s, mu_k = operating_point
        default = default_cutoff_hz(mass, stiffness, kept_dofs[0], speed=speed, load=load,
                                    mu_s=mu_s, mu_k=mu_k)
    if cutoff_hz is None:
        if default is None:
            raise ValueError("a cut-off or an operating point is needed")
        return reduce_structure(mass, stiffness, kept_dofs, cutoff_hz=default)
    reduced = reduce_structure(mass, stiffness, kept_dofs, cutoff_hz=cutoff_hz)
    return replace(reduced, default_cutoff_hz=default)
