"""The linear structure carrying one frictional contact, in matrix form.

Eqs. (19)-(27) of the paper are, for ``q = (xi, xi_a)`` measured from the kinetic-friction
equilibrium (Eqs. 15-16),

    Mass q'' + Damping q' + Stiffness q = f,

with ``f = 0`` in slip-I, ``f = (-2 gamma lambda, 0)`` in slip-II and ``xi' = 1`` in stick.
Any number of degrees of freedom is allowed; the frictional contact is on DOF 0. The rigid
base (1DOF) and the elastic foundation (2DOF) are presets; a chain of several foundation
masses is obtained by passing several :class:`Foundation` stages.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from stickslip.model.parameters import Foundation

FloatArray = NDArray[np.float64]


#: Largest magnitude of a matrix entry: a chain of foundations at the parameter bounds
#: (``K <= 1e6``, so springs ``K**2 <= 1e12``) stays well inside it, and the products the
#: engine forms (``Mass^-1 Stiffness``, the matrix exponential, the Lyapunov solve) stay far
#: from overflow.
MAX_MATRIX_ENTRY = 1e13


def _matrix(name: str, value: object, n: int | None = None) -> FloatArray:
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
    if np.abs(a).max() > MAX_MATRIX_ENTRY:
        raise ValueError(
            f"{name} has an entry of magnitude {np.abs(a).max():.3g}, beyond the supported "
            f"{MAX_MATRIX_ENTRY:g} (the engine's products would overflow)"
        )
    if not np.allclose(a, a.T, rtol=1e-12, atol=1e-14):
        raise ValueError(f"{name} must be symmetric")
    a = 0.5 * (a + a.T)
    a.setflags(write=False)
    return a


@dataclass(frozen=True)
class Structure:
    """Dimensionless mass, damping and stiffness matrices with the contact on DOF 0.

    Parameters
    ----------
    mass, damping, stiffness : array_like, shape (n, n)
        Symmetric matrices. ``mass`` and ``stiffness`` must be positive definite (the
        structure is anchored), ``damping`` positive semi-definite. Dimensionless: masses
        are referred to ``m``, stiffnesses to ``k``, damping to ``sqrt(m k)``.
    name : str
        A label used in plots and output files.
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    name: str = field(default="structure", compare=False)

    def __post_init__(self) -> None:
        mass = _matrix("mass matrix", self.mass)
        n = mass.shape[0]
        damping = _matrix("damping matrix", self.damping, n)
        stiffness = _matrix("stiffness matrix", self.stiffness, n)
        if np.linalg.eigvalsh(mass).min() <= 0.0:
            raise ValueError("mass matrix must be positive definite (every mass > 0)")
        if np.linalg.eigvalsh(stiffness).min() <= 0.0:
            raise ValueError("stiffness matrix must be positive definite (every spring > 0)")
        scale = max(1.0, float(np.abs(damping).max()))
        if np.linalg.eigvalsh(damping).min() < -1e-12 * scale:
            raise ValueError("damping matrix must be positive semi-definite (dampers >= 0)")
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "damping", damping)
        object.__setattr__(self, "stiffness", stiffness)

    @property
    def zeta(self) -> float:
        """Primary damping ratio ``zeta = c / (2 sqrt(m k))``: half the damping on DOF 0.

        ``C_00 / 2`` counts every damper attached to the slider; for the paper's structures
        (:func:`chain_structure`) that is the slider's own damper ``c``. This is the one place
        ``zeta`` lives: every result reads it from here.
        """
        return 0.5 * float(self.damping[0, 0])

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom (1 for the rigid base, 2 with one foundation)."""
        return int(self.mass.shape[0])

    def kinetic_equilibrium_offset(self) -> FloatArray:
        """Displacement of each DOF per unit force on DOF 0: ``Stiffness^-1 e_0``.

        The shift of Eqs. (15)-(16) is ``gamma lambda`` times this vector: the deflection
        under the kinetic friction force ``mu_k W`` in units of ``V / omega_n``.
        """
        e0 = np.zeros(self.n_dof)
        e0[0] = 1.0
        return np.asarray(np.linalg.solve(self.stiffness, e0), dtype=np.float64)


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
