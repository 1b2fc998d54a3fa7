"""The linear structure carrying one frictional contact, in matrix form.

Eqs. (19)-(27) of the paper are, for ``q = (xi, xi_a)`` measured from the kinetic-friction
equilibrium (Eqs. 15-16),

    Mass q'' + Damping q' + Stiffness q = f,

with ``f = 0`` in slip-I, ``f = (-2 gamma lambda, 0)`` in slip-II and ``xi' = 1`` in stick.
Any number of degrees of freedom is allowed; the frictional contact is on DOF
``contact_dof`` (0 for the presets). The rigid base (1DOF) and the elastic foundation (2DOF)
are presets; a chain of several foundation masses is obtained by passing several
:class:`Foundation` stages.

The engine keeps the contact as its first coordinate. :meth:`Structure.contact_first` is the
one place that reorders a structure for it: a permutation is exact, so a structure given in
any order gives the answers of its contact-first twin, and the presets (already contact
first) are untouched.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.model.parameters import Foundation

FloatArray = NDArray[np.float64]


#: Largest magnitude of a matrix entry: a chain of foundations at the parameter bounds
#: (``K <= 1e6``, so springs ``K**2 <= 1e12``) stays well inside it, and the products the
#: engine forms (``Mass^-1 Stiffness``, the matrix exponential, the Lyapunov solve) stay far
#: from overflow.
MAX_MATRIX_ENTRY = 1e13


#: Relative asymmetry accepted (then symmetrised): ``max|A - A^T| <= 1e-9 max|A|``, what a
#: finite-element export written with 10 significant digits keeps.
SYMMETRY_RTOL = 1e-9

#: A stiffness eigenvalue at or below this fraction of the largest is a free (rigid-body)
#: mode: the round-off of a free-free assembly is ~1e-16 of the largest, while a grounded
#: preset at the parameter bounds (springs 1e-12 beside 1) stays above 1e-13.
FREE_MODE_RTOL = 1e-14


def _moving_dofs(vector: FloatArray) -> str:
    """The DOFs that take part in a mode shape (above 1e-6 of its largest entry)."""
    big = np.abs(vector)
    moving = np.flatnonzero(big > 1e-6 * big.max())
    return ", ".join(str(int(i)) for i in moving)


def _matrix(name: str, value: object, n: int | None = None,
            limit: float | None = MAX_MATRIX_ENTRY) -> FloatArray:
    raw = np.asarray(value)
    if raw.dtype == np.bool_:
        raise ValueError(f"{name} has boolean entries; the matrices must be real numbers")
    if np.iscomplexobj(raw):
        raise ValueError(f"{name} has complex entries; the matrices must be real")
    try:
        a = np.array(raw, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a matrix of real numbers") from None
    if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] == 0:
        raise ValueError(f"{name} must be a non-empty square matrix, got shape {a.shape}")
    if n is not None and a.shape[0] != n:
        raise ValueError(f"{name} is {a.shape[0]}x{a.shape[0]}, expected {n}x{n}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} has NaN or infinite entries")
    if limit is not None and np.abs(a).max() > limit:
        raise ValueError(
            f"{name} has an entry of magnitude {np.abs(a).max():.3g}, beyond the supported "
            f"{MAX_MATRIX_ENTRY:g} (the engine's products would overflow)"
        )
    check_symmetric(name, a)
    a = 0.5 * (a + a.T)
    a.setflags(write=False)
    return a


def check_symmetric(name: str, matrix: Any) -> None:
    """Refuse a matrix (dense or ``scipy.sparse``) that is not symmetric beyond round-off.

    The one symmetry rule of the package, whatever the size of the model:
    ``max|A - A^T| <= SYMMETRY_RTOL max|A|``; what passes is symmetrised by the caller.

    Parameters
    ----------
    name : str
        How the message names the matrix.
    matrix : ndarray or scipy.sparse matrix
        Square and finite.

    Returns
    -------
    None
        Raises ``ValueError`` (one line) for an asymmetric matrix.
    """
    import scipy.sparse

    if scipy.sparse.issparse(matrix):
        a = scipy.sparse.csr_matrix(matrix)
        diff = abs(a - a.T)
        asym = float(diff.max()) if diff.nnz else 0.0
        top = float(abs(a).max()) if a.nnz else 0.0
    else:
        a = np.asarray(matrix)
        asym = float(np.abs(a - a.T).max())
        top = float(np.abs(a).max())
    if asym > SYMMETRY_RTOL * top:
        raise ValueError(f"{name} is not symmetric: |A - A^T| reaches {asym:.3g}, beyond "
                         f"{SYMMETRY_RTOL:g} of its largest entry {top:.3g}")


def _first_nonpositive_diagonal(matrix: Any) -> int | None:
    diag = np.asarray(matrix.diagonal(), dtype=np.float64)
    bad = np.flatnonzero(~(diag > 0.0))
    return int(bad[0]) if bad.size else None


def check_large_matrices(mass: Any, damping: Any, stiffness: Any, *,
                         names: tuple[str, str, str] = ("mass matrix", "damping matrix",
                                                        "stiffness matrix")) -> None:
    """The checks of :func:`check_matrices` for a model too large for dense eigenvalues.

    Each matrix symmetric (:func:`check_symmetric`); ``mass`` and ``stiffness`` positive
    definite, tested by Sylvester's law of inertia: with a symmetric ordering and no row
    exchange, ``A = P L D L' P'`` and ``A`` has as many negative eigenvalues as ``D`` has
    negative pivots (a zero pivot forces a row exchange, or stops the factorisation: the
    matrix is singular). A pivot at or below ``max(FREE_MODE_RTOL, n eps)`` of the largest is
    a singular stiffness, a free rigid-body mode (the rank tolerance of ``numpy.linalg.
    matrix_rank`` is ``n eps`` of the largest singular value). ``damping``: its diagonal
    ``>= 0`` here; its reduction is checked by :func:`check_matrices`.

    Parameters
    ----------
    mass, damping, stiffness : ndarray or scipy.sparse matrix
        Square, same size, finite; ``damping`` may be None.
    names : tuple of str
        How the messages name them.

    Returns
    -------
    None
        Raises ``ValueError`` (one line) naming the matrix, the DOF and why.
    """
    for name, matrix in zip(names, (mass, damping, stiffness), strict=True):
        if matrix is not None:
            check_symmetric(name, matrix)
    dof = _first_nonpositive_diagonal(mass)
    if dof is not None:
        raise ValueError(f"{names[0]} must be positive definite (every mass > 0): the mass at DOF "
                         f"{dof} (its diagonal entry) is {float(mass.diagonal()[dof]):.3g}")
    if damping is not None:
        diag = np.asarray(damping.diagonal(), dtype=np.float64)
        if diag.min() < 0.0:
            raise ValueError(f"{names[1]} must be positive semi-definite (dampers >= 0): its "
                             f"diagonal entry at DOF {int(np.argmin(diag))} is {diag.min():.3g}")
    for name, matrix, what in ((names[0], mass, "mass"), (names[2], stiffness, "stiffness")):
        _check_definite(name, matrix, what)


def _check_definite(name: str, matrix: Any, what: str) -> None:
    """Positive definiteness of a large symmetric matrix by the signs of its LDL' pivots."""
    import scipy.sparse
    from scipy.sparse.linalg import splu

    a = scipy.sparse.csc_matrix(matrix, dtype=np.float64)
    n = a.shape[0]
    free = ("the structure is not grounded: a free rigid-body mode (zero stiffness); add a "
            "spring to the ground" if what == "stiffness" else "a mass-less motion")
    try:
        lu = splu(a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                  options={"SymmetricMode": True})
    except RuntimeError:  # SuperLU: "Factor is exactly singular"
        raise ValueError(f"{name} is singular: {free}") from None
    pivots = np.asarray(lu.U.diagonal(), dtype=np.float64)
    order = np.asarray(lu.perm_c)
    if not np.array_equal(np.asarray(lu.perm_r), order):  # a zero pivot forced a row exchange
        raise ValueError(f"{name} is not positive definite: its symmetric elimination meets a zero "
                         f"pivot (a singular or indefinite {what})")
    top = float(np.abs(pivots).max())
    negative = np.flatnonzero(pivots < 0.0)
    if negative.size:
        dof = int(np.flatnonzero(order == negative[0])[0])
        raise ValueError(f"{name} is not positive definite: it has {negative.size} negative "
                         f"eigenvalue(s) (negative pivots of its LDL' factorisation, Sylvester's "
                         f"law of inertia), the first met at DOF {dof}")
    tol = max(FREE_MODE_RTOL, n * np.finfo(float).eps) * top
    small = np.flatnonzero(pivots <= tol)
    if small.size:
        dof = int(np.flatnonzero(order == small[0])[0])
        raise ValueError(f"{name} is singular (a pivot of its LDL' factorisation at DOF {dof} is "
                         f"{float(pivots[small[0]]):.3g}, at most {tol:.3g}): {free}")


def checked_matrices(mass: object, damping: object, stiffness: object, *,
                     names: tuple[str, str, str] = ("mass matrix", "damping matrix",
                                                    "stiffness matrix"),
                     limit: float | None = MAX_MATRIX_ENTRY,
                     ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``(mass, damping, stiffness)`` as checked, symmetrised, read-only float arrays.

    Square, same size, real, finite, symmetric to :data:`SYMMETRY_RTOL` (relative), entries
    below ``limit`` (None: no bound, for matrices in SI units), then :func:`check_matrices`.
    ``names`` label the matrices in the one-line messages (e.g. the files they came from).

    Parameters
    ----------
    mass, damping, stiffness : array_like
        The matrices.
    names : tuple of str
        Their labels in messages.
    limit : float or None
        Largest magnitude of an entry (None: no bound).

    Returns
    -------
    mass, damping, stiffness : ndarray
        Checked, symmetrised, read-only.
    """
    m = _matrix(names[0], mass, limit=limit)
    n = m.shape[0]
    c = _matrix(names[1], damping, n, limit=limit)
    k = _matrix(names[2], stiffness, n, limit=limit)
    check_matrices(m, c, k)
    return m, c, k


def check_matrices(mass: FloatArray, damping: FloatArray, stiffness: FloatArray) -> None:
    """Refuse matrices the engine cannot take, with one line saying which and why.

    ``mass`` positive definite; ``stiffness`` positive semi-definite *and* grounded: a null
    vector of ``stiffness`` is a free rigid-body mode (the structure would drift away under
    the friction force), refused naming the DOFs that move in it; ``damping`` positive
    semi-definite. The matrices are already square, symmetric and finite (``_matrix``).

    Parameters
    ----------
    mass, damping, stiffness : ndarray
        Square, symmetric, finite matrices.

    Returns
    -------
    None
        Raises ``ValueError`` (one line) for a matrix the engine cannot take.
    """
    dof = _first_nonpositive_diagonal(mass)
    if dof is not None:
        raise ValueError(f"mass matrix must be positive definite (every mass > 0): the mass at DOF "
                         f"{dof} (its diagonal entry) is {float(mass[dof, dof]):.3g}")
    m_eig = np.linalg.eigvalsh(mass)
    if m_eig.min() <= 0.0:
        raise ValueError(f"mass matrix must be positive definite (every mass > 0): its smallest "
                         f"eigenvalue is {m_eig.min():.3g}")
    if m_eig.min() <= FREE_MODE_RTOL * m_eig.max():
        raise ValueError(f"mass matrix is numerically singular: its eigenvalues span "
                         f"{m_eig.min():.3g} to {m_eig.max():.3g}, a ratio beyond "
                         f"{1 / FREE_MODE_RTOL:.0e} (check the units of the masses)")
    k_eig, k_vec = np.linalg.eigh(stiffness)
    if not np.any(stiffness):
        raise ValueError("stiffness matrix is all zeros: the structure has no spring (every "
                         "DOF is free); give the springs, to the ground among them")
    k_top = max(float(np.abs(k_eig).max()), np.finfo(float).tiny)
    if k_eig.min() < -FREE_MODE_RTOL * k_top:
        raise ValueError(f"stiffness matrix is not positive semi-definite: eigenvalue "
                         f"{k_eig.min():.3g} < 0 (its mode moves DOFs {_moving_dofs(k_vec[:, 0])})")
    if k_eig.min() <= FREE_MODE_RTOL * k_top:
        raise ValueError(f"the structure is not grounded: a free rigid-body mode (stiffness "
                         f"eigenvalue {k_eig.min():.3g}, at most {FREE_MODE_RTOL:g} of the largest "
                         f"{k_top:.3g}) moves DOFs {_moving_dofs(k_vec[:, 0])}; add a spring to "
                         "the ground")
    scale = max(1.0, float(np.abs(damping).max()))
    if np.linalg.eigvalsh(damping).min() < -1e-12 * scale:
        raise ValueError("damping matrix must be positive semi-definite (dampers >= 0)")


@dataclass(frozen=True)
class Structure:
    """Dimensionless mass, damping and stiffness matrices with the contact on ``contact_dof``.

    Parameters
    ----------
    mass, damping, stiffness : array_like, shape (n, n)
        Symmetric matrices. ``mass`` must be positive definite, ``stiffness`` positive
        definite (the structure is grounded: no free rigid-body mode), ``damping`` positive
        semi-definite. Dimensionless: masses are referred to ``m``, stiffnesses to ``k``,
        damping to ``sqrt(m k)`` (for a machine: ``m = M[c, c]``, ``k = K[c, c]`` of the
        contact DOF ``c``, see :class:`stickslip.model.machine.Machine`).
    name : str
        A label used in plots and output files.
    contact_dof : int
        Index of the degree of freedom the belt rubs (0-based; 0 for every preset).
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    name: str = field(default="structure", compare=False)
    contact_dof: int = 0

    def __post_init__(self) -> None:
        mass, damping, stiffness = checked_matrices(self.mass, self.damping, self.stiffness)
        n = mass.shape[0]
        cd = self.contact_dof
        if isinstance(cd, bool) or not isinstance(cd, (int, np.integer)) or not 0 <= cd < n:
            raise ValueError(f"contact_dof={cd!r} must be a whole number from 0 to {n - 1} "
                             f"(the structure has {n} degrees of freedom)")
        object.__setattr__(self, "contact_dof", int(cd))
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "damping", damping)
        object.__setattr__(self, "stiffness", stiffness)

    def contact_first(self) -> tuple[Structure, NDArray[np.int64]]:
        """The same structure with its contact DOF moved to position 0, and the permutation.

        Returns
        -------
        structure : Structure
            ``mass[perm][:, perm]`` etc. with ``contact_dof = 0``: the engine's ordering.
            ``self`` itself when the contact is already first (the presets), so their
            answers cannot move.
        perm : ndarray of int, shape (n,)
            ``perm[i]`` is the user's DOF at engine position ``i``: the contact first, the
            others in their order. A per-DOF vector ``x`` in the user's order is
            ``x[perm]`` in the engine's; back with ``y[np.argsort(perm)]``
            (:func:`to_user_order`).
        """
        n, c = self.n_dof, self.contact_dof
        perm = np.array([c] + [i for i in range(n) if i != c], dtype=np.int64)
        if c == 0:
            return self, perm
        ix = np.ix_(perm, perm)
        return Structure(self.mass[ix], self.damping[ix], self.stiffness[ix], name=self.name), perm

    @property
    def zeta(self) -> float:
        """Primary damping ratio ``zeta = c / (2 sqrt(m k))``: half the damping on the contact DOF.

        ``C_cc / 2`` counts every damper attached to the slider; for the paper's structures
        (:func:`chain_structure`) that is the slider's own damper ``c``. This is the one place
        ``zeta`` lives: every result reads it from here.
        """
        return 0.5 * float(self.damping[self.contact_dof, self.contact_dof])

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom (1 for the rigid base, 2 with one foundation)."""
        return int(self.mass.shape[0])

    def kinetic_equilibrium_offset(self) -> FloatArray:
        """Displacement of each DOF per unit force on the contact DOF: ``Stiffness^-1 e_c``.

        The shift of Eqs. (15)-(16) is ``gamma lambda`` times this vector: the deflection
        under the kinetic friction force ``mu_k W`` in units of ``V / omega_n``.
        """
        e0 = np.zeros(self.n_dof)
        e0[self.contact_dof] = 1.0
        return np.asarray(np.linalg.solve(self.stiffness, e0), dtype=np.float64)


def state_permutation(perm: NDArray[np.int64]) -> NDArray[np.int64]:
    """The permutation of a state ``(q, q')`` of ``2n`` entries from a DOF permutation ``perm``.

    Parameters
    ----------
    perm : ndarray of int, shape (n,)
        DOF permutation (:meth:`Structure.contact_first`).

    Returns
    -------
    ndarray of int, shape (2n,)
        ``perm`` for the positions, then for the velocities.
    """
    return np.concatenate([perm, perm + perm.size])


def to_user_order(values: FloatArray, perm: NDArray[np.int64], axis: int = -1) -> FloatArray:
    """Per-DOF (``n``) or per-state (``2n``) values along ``axis`` back from engine order.

    The inverse of indexing with ``perm`` (or :func:`state_permutation` of it).

    Parameters
    ----------
    values : ndarray
        Values in the engine's order along ``axis`` (``n`` or ``2n`` long there).
    perm : ndarray of int
        DOF permutation (:meth:`Structure.contact_first`).
    axis : int
        The axis to reorder.

    Returns
    -------
    ndarray
        The values in the user's order.
    """
    a = np.asarray(values)
    p = perm if a.shape[axis] == perm.size else state_permutation(perm)
    return np.take(a, np.argsort(p), axis=axis)


def chain_structure(zeta: float, foundations: Sequence[Foundation] = ()) -> Structure:
    """Slider on a chain of foundation masses; the last one is anchored to the rigid base.

    Parameters
    ----------
    zeta : float
        Damping ratio of the primary system, ``c / (2 sqrt(m k))``.
    foundations : sequence of Foundation
        Empty: the rigid base (paper's 1DOF system). One stage: the paper's Fig. 1, whose
        matrices reproduce Eqs. (23)-(24). Each stage ``i`` connects mass ``i`` to mass
        ``i + 1`` through the next spring-damper; the last stage connects to the ground.

    Returns
    -------
    Structure
        ``mass = diag(1, M_1, M_2, ...)``; springs ``1, K_1^2, K_2^2, ...`` and dampers
        ``2 zeta, 2 zeta_a1, ...`` in series.
    """
    from stickslip.model._validate import at_most, non_negative, ratio

    zeta = at_most("zeta", non_negative("zeta", zeta))
    for f in foundations:  # before squaring K: 1e200**2 overflows
        ratio("M", f.mass_ratio)
        ratio("K", f.stiffness_ratio)
        at_most("zeta_a", f.damping_ratio)
    n = 1 + len(foundations)
    masses = [1.0] + [f.mass_ratio for f in foundations]
    springs = [1.0] + [f.stiffness_ratio**2 for f in foundations]
    dampers = [2.0 * zeta] + [2.0 * f.damping_ratio for f in foundations]
    mass = np.diag(masses)
    stiffness = np.zeros((n, n))
    damping = np.zeros((n, n))
    # element i joins DOF i to DOF i+1 (or to the ground for the last element)
    for i in range(n):
        for mat, value in ((stiffness, springs[i]), (damping, dampers[i])):
            mat[i, i] += value
            if i + 1 < n:
                mat[i + 1, i + 1] += value
                mat[i, i + 1] -= value
                mat[i + 1, i] -= value
    if n == 1:
        name = "rigid base"
    elif n == 2:
        name = "elastic foundation"
    else:
        name = f"{n - 1}-stage foundation chain"
    return Structure(mass, damping, stiffness, name=name)


def rigid_base(zeta: float) -> Structure:
    """The paper's 1DOF system: the slider on a spring-damper anchored to a rigid base.

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.

    Returns
    -------
    Structure
        The 1DOF structure.
    """
    return chain_structure(zeta, ())


def elastic_foundation(zeta: float, foundation: Foundation) -> Structure:
    """The paper's 2DOF system (Fig. 1): the slider on an elastic foundation, Eqs. (23)-(24).

    Parameters
    ----------
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless, >= 0.
    foundation : Foundation
        ``(M, K, zeta_a)``, dimensionless.

    Returns
    -------
    Structure
        The 2DOF structure.
    """
    return chain_structure(zeta, (foundation,))
