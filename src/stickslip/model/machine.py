"""A real machine in SI units: any linear structure with the friction contact on one DOF.

``Mass x'' + Damping x' + Stiffness x = f`` in kg, N s/m and N/m, the
belt rubbing DOF ``contact_dof`` with static and kinetic coefficients ``mu_s``, ``mu_k``,
under the normal load ``W`` at the belt speed ``V``, and a friction law.

Dimensionless groups (the contact DOF's view)
---------------------------------------------
The paper scales everything by the slider's mass ``m`` and spring ``k`` (Eqs. 15-18). A
machine has no single slider, so the reference is the contact DOF's own diagonal entries:

    m_ref = Mass[c, c],    k_ref = Stiffness[c, c],    omega_n = sqrt(k_ref / m_ref),

the mass that moves when only the contact DOF moves and the force per metre needed to move
it alone (every other DOF held). For every chain of the paper (rigid base, foundation, chains
of foundations) the slider spring joins DOF 0 to DOF 1, so ``Mass[0, 0] = m`` and
``Stiffness[0, 0] = k`` exactly: the choice reduces to the paper's scaling, and
``lambda = (mu_s - mu_k) W / (V sqrt(m_ref k_ref))``, ``gamma = mu_k / (mu_s - mu_k)``,
``zeta = Damping[c, c] / (2 sqrt(m_ref k_ref))`` are the paper's groups. The dimensionless
structure is ``Mass / m_ref``, ``Damping / sqrt(m_ref k_ref)``, ``Stiffness / k_ref``; times
are ``tau = omega_n t`` and displacements are in units of ``V / omega_n``.

Damping may be given as a matrix, as Rayleigh damping ``C = alpha M + beta K``
(:func:`rayleigh_damping`) or as modal damping ratios (:func:`modal_damping`). A structure
known only by its modes at the contact (modal test) is built by :func:`modal_structure`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.model._validate import MAX_PARAMETER, non_negative, positive, within
from stickslip.model.parameters import Slider
from stickslip.model.physical import MAX_SI, PhysicalFriction, PhysicalSystem
from stickslip.model.structure import Structure, checked_matrices

FloatArray = NDArray[np.float64]

#: Structures up to this many DOF run directly; larger ones are reduced first
#: (:mod:`stickslip.analysis.reduction`).
MAX_DIRECT_DOF = 60


def rayleigh_damping(mass: ArrayLike, stiffness: ArrayLike, alpha: float, beta: float) -> FloatArray:
    """``C = alpha M + beta K`` (N s/m for ``alpha`` in 1/s and ``beta`` in s), both >= 0.

    Parameters
    ----------
    mass, stiffness : array_like
        kg and N/m.
    alpha, beta : float
        Rayleigh coefficients, 1/s and s (>= 0).

    Returns
    -------
    ndarray
        The damping matrix, N s/m.
    """
    a, b = non_negative("rayleigh alpha", alpha), non_negative("rayleigh beta", beta)
    with np.errstate(over="ignore", invalid="ignore"):
        c = np.asarray(a * np.asarray(mass, dtype=np.float64) + b * np.asarray(stiffness, dtype=np.float64))
    largest = float(np.max(np.abs(c))) if c.size else 0.0
    if not largest <= MAX_SI:  # inf and nan too
        raise ValueError(f"[alpha, beta] = [{a:g}, {b:g}] gives damping entries of magnitude "
                         f"{largest:.3g} N s/m, beyond the {MAX_SI:g} supported")
    return c


def modal_damping(mass: ArrayLike, stiffness: ArrayLike, ratios: float | Sequence[float]) -> FloatArray:
    """Damping matrix with the damping ratio ``ratios[i]`` in mode ``i`` (one value: every mode).

    With the mass-normalised modes ``Phi`` (``Phi' M Phi = I``, ``Phi' K Phi = diag(w_i^2)``,
    ascending ``w_i``), ``C = M Phi diag(2 zeta_i w_i) Phi' M``: then ``Phi' C Phi`` is
    diagonal with ``2 zeta_i w_i``, which is the definition of modal damping.

    Parameters
    ----------
    mass, stiffness : array_like
        kg and N/m.
    ratios : float or sequence of float
        One damping ratio for every mode, or one per mode (ascending frequency), >= 0.

    Returns
    -------
    ndarray
        The damping matrix, N s/m.
    """
    from scipy.linalg import eigh

    m = np.asarray(mass, dtype=np.float64)
    k = np.asarray(stiffness, dtype=np.float64)
    w2, phi = eigh(k, m)
    z = np.broadcast_to(np.asarray(ratios, dtype=np.float64), w2.shape) if np.ndim(ratios) == 0 \
        else np.asarray(ratios, dtype=np.float64)
    if z.shape != w2.shape:
        raise ValueError(f"modal_damping has {z.size} ratios for {w2.size} modes (give one, or one per mode)")
    for value in z.tolist():
        within("modal damping ratio", non_negative("modal damping ratio", value), 0.0,
               MAX_PARAMETER, "a ratio beyond it is no damping a structure has")
    mphi = m @ phi
    return np.asarray(mphi @ np.diag(2.0 * z * np.sqrt(np.maximum(w2, 0.0))) @ mphi.T)


def modal_structure(frequencies_hz: Sequence[float], damping_ratios: Sequence[float],
                    shapes_at_contact: Sequence[float]) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Mass, damping and stiffness (SI) of the structure as seen from the contact, from modes.

    Parameters
    ----------
    frequencies_hz : sequence of float
        Natural frequencies ``f_i``, Hz (> 0).
    damping_ratios : sequence of float
        Modal damping ratios ``zeta_i`` (>= 0).
    shapes_at_contact : sequence of float
        Mass-normalised mode shape values at the contact, ``phi_i``, 1/sqrt(kg) (non-zero:
        a mode with a node at the contact does not move it and is left out by the caller).

    Returns
    -------
    mass, damping, stiffness : ndarray, shape (n, n)
        In the coordinates ``q = (x_c, eta_2, ..., eta_n)``: the contact displacement
        ``x_c = sum phi_i eta_i`` replaces the modal coordinate ``eta_1`` of the mode with
        the largest ``|phi|``. With ``eta = T q`` (``T`` invertible since ``phi_1 != 0``),
        ``M = T'T``, ``C = T' diag(2 zeta_i w_i) T``, ``K = T' diag(w_i^2) T``; since
        ``phi' T = e_0'``, the contact force enters DOF 0 alone and the receptance at the
        contact is exactly ``sum phi_i^2 / (w_i^2 - w^2 + 2 i zeta_i w_i w)``. The contact is
        DOF 0. A start-up state at rest in these coordinates (``eta_i' = 0``, the contact at the
        belt speed) is not a matrix model's physical rest: start-up verdicts can differ between
        the two (docs/structures.md).
    """
    f = np.asarray(frequencies_hz, dtype=np.float64).reshape(-1)
    z = np.asarray(damping_ratios, dtype=np.float64).reshape(-1)
    phi = np.asarray(shapes_at_contact, dtype=np.float64).reshape(-1)
    if not (f.size == z.size == phi.size) or f.size == 0:
        raise ValueError(f"modes: {f.size} frequencies, {z.size} damping ratios and {phi.size} "
                         "mode shape values must be as many, at least one")
    for value in f.tolist():
        positive("modal frequency (Hz)", value)
    for value in z.tolist():
        within("modal damping ratio", non_negative("modal damping ratio", value), 0.0,
               MAX_PARAMETER, "a ratio beyond it is no damping a structure has")
    for value in phi.tolist():
        if not math.isfinite(value) or value == 0.0:
            raise ValueError(f"mode shape value {value!r} at the contact must be finite and non-zero "
                             "(a mode with a node at the contact does not take part)")
    order = np.argsort(-np.abs(phi), kind="stable")
    f, z, phi = f[order], z[order], phi[order]
    n = f.size
    w = 2.0 * math.pi * f
    t = np.eye(n)
    t[0, 0] = 1.0 / phi[0]
    t[0, 1:] = -phi[1:] / phi[0]
    mass = t.T @ t
    damping = t.T @ np.diag(2.0 * z * w) @ t
    stiffness = t.T @ np.diag(w**2) @ t
    return mass, damping, stiffness


@dataclass(frozen=True)
class Machine:
    """A linear structure in SI units with one frictional contact.

    Parameters
    ----------
    mass, damping, stiffness : array_like, shape (n, n)
        kg, N s/m, N/m. Symmetric (to 1e-9 relative), mass positive definite, stiffness
        positive definite (grounded: a free rigid-body mode is refused naming its DOFs),
        damping positive semi-definite.
    contact_dof : int
        The DOF the belt rubs (0-based index in the matrices).
    mu_s, mu_k : float
        Static and kinetic friction coefficients, ``mu_s > mu_k >= 0``.
    load : float
        Normal load ``W``, N.
    speed : float
        Belt speed ``V``, m/s.
    friction : PhysicalFriction
        Velocity-dependent law while sliding (default: the paper's Coulomb law).
    name : str
        Label for plots and reports.
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    contact_dof: int
    mu_s: float
    mu_k: float
    load: float
    speed: float
    friction: PhysicalFriction = field(default_factory=PhysicalFriction)
    name: str = field(default="machine", compare=False)

    def __post_init__(self) -> None:
        m, c, k = checked_matrices(self.mass, self.damping, self.stiffness, limit=None)
        object.__setattr__(self, "mass", m)
        object.__setattr__(self, "damping", c)
        object.__setattr__(self, "stiffness", k)
        cd = self.contact_dof
        if isinstance(cd, bool) or not isinstance(cd, (int, np.integer)) or not 0 <= cd < m.shape[0]:
            raise ValueError(f"contact_dof={cd!r} must be a whole number from 0 to {m.shape[0] - 1} "
                             f"(the structure has {m.shape[0]} degrees of freedom)")
        object.__setattr__(self, "contact_dof", int(cd))
        self.reference_system()  # checks mu_s, mu_k, load, speed and the friction law

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom."""
        return int(self.mass.shape[0])

    @property
    def reference_mass(self) -> float:
        """``m_ref = Mass[c, c]``, kg: the contact DOF's own mass (module docstring)."""
        return float(self.mass[self.contact_dof, self.contact_dof])

    @property
    def reference_stiffness(self) -> float:
        """``k_ref = Stiffness[c, c]``, N/m: the contact DOF's own stiffness (module docstring)."""
        return float(self.stiffness[self.contact_dof, self.contact_dof])

    def reference_system(self) -> PhysicalSystem:
        """The paper's 1DOF system of the contact: ``m_ref``, ``k_ref``, ``c = Damping[c, c]``.

        Its :meth:`~PhysicalSystem.slider`, time, length and force scales are the machine's.
        """
        cd = self.contact_dof
        return PhysicalSystem(mass=self.reference_mass, stiffness=self.reference_stiffness,
                              damping=float(self.damping[cd, cd]), mu_s=self.mu_s, mu_k=self.mu_k,
                              load=self.load, speed=self.speed, friction=self.friction)

    def structure(self, scale: tuple[float, float] | None = None) -> Structure:
        """Dimensionless structure: ``Mass/m_ref``, ``Damping/sqrt(m_ref k_ref)``, ``Stiffness/k_ref``.

        ``scale = (m_ref, k_ref)`` imposes another machine's reference (e.g. the bare machine's
        when an absorber changes the contact DOF's own entries), so that receptances of
        several machines are in one unit, ``1 / k_ref``.
        """
        m_ref, k_ref = scale or (self.reference_mass, self.reference_stiffness)
        return Structure(self.mass / m_ref, self.damping / math.sqrt(m_ref * k_ref),
                         self.stiffness / k_ref, name=self.name, contact_dof=self.contact_dof)

    def slider(self) -> Slider:
        """Dimensionless ``lambda``, ``gamma`` and friction law of the contact."""
        return self.reference_system().slider()

    def to_dimensionless(self) -> tuple[Structure, Slider]:
        """``(structure, slider)`` for :func:`stickslip.simulate` and every analysis."""
        return self.structure(), self.slider()

    def with_operating_point(self, *, speed: float | None = None, load: float | None = None) -> Machine:
        """The same machine at another belt speed (m/s) and/or normal load (N)."""
        from dataclasses import replace

        return replace(self, speed=self.speed if speed is None else speed,
                       load=self.load if load is None else load)

    def with_absorber(self, mass: float, stiffness: float, damping: float, attach_dof: int) -> Machine:
        """The machine with an absorber (kg, N/m, N s/m) on DOF ``attach_dof``, as DOF ``n``.

        The absorber mass is a new last DOF joined to ``attach_dof`` by a spring and a
        dashpot: the usual element stamp ``[[1, -1], [-1, 1]]`` on ``(attach_dof, n)``.
        """
        n = self.n_dof
        if isinstance(attach_dof, bool) or not 0 <= int(attach_dof) < n:
            raise ValueError(f"attach_dof={attach_dof!r} must be a DOF of the structure, 0 to {n - 1}")
        a = int(attach_dof)
        mats = []
        for matrix, value in ((self.mass, 0.0), (self.damping, non_negative("absorber damping", damping)),
                              (self.stiffness, positive("absorber stiffness", stiffness))):
            big = np.zeros((n + 1, n + 1))
            big[:n, :n] = matrix
            big[a, a] += value
            big[n, n] += value
            big[a, n] -= value
            big[n, a] -= value
            mats.append(big)
        mats[0][n, n] = positive("absorber mass", mass)
        from dataclasses import replace

        return replace(self, mass=mats[0], damping=mats[1], stiffness=mats[2],
                       name=f"{self.name} + absorber on DOF {a}")

    def speed_for_lambda(self, lam: float) -> float:
        """Belt speed (m/s) at which ``lambda`` takes the value ``lam``."""
        return self.reference_system().speed_for_lambda(lam)

    def load_for_lambda(self, lam: float) -> float:
        """Normal load (N) at which ``lambda`` takes the value ``lam``."""
        return self.reference_system().load_for_lambda(lam)

    def natural_frequencies_hz(self) -> FloatArray:
        """Undamped natural frequencies of the structure, Hz, ascending."""
        from scipy.linalg import eigh

        w2 = eigh(self.stiffness, self.mass, eigvals_only=True)
        return np.asarray(np.sqrt(np.maximum(w2, 0.0)) / (2.0 * math.pi))

    def summary(self) -> str:
        """One paragraph: size, contact, reference scales and dimensionless groups."""
        sl = self.slider()
        ref = self.reference_system()
        return (f"{self.name}: {self.n_dof} DOF, contact on DOF {self.contact_dof}; "
                f"m_ref={self.reference_mass:.4g} kg, k_ref={self.reference_stiffness:.4g} N/m, "
                f"omega_n={ref.natural_frequency:.4g} rad/s; lambda={sl.lam:.4g}, "
                f"gamma={sl.gamma:.4g}, zeta={ref.zeta:.4g}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description (SI, units in the key names)."""
        return {"name": self.name, "n_dof": self.n_dof, "contact_dof": self.contact_dof,
                "reference_mass_kg": self.reference_mass,
                "reference_stiffness_N_per_m": self.reference_stiffness,
                "natural_frequencies_hz": self.natural_frequencies_hz().tolist(),
                "mu_s": self.mu_s, "mu_k": self.mu_k, "load_N": self.load, "speed_m_per_s": self.speed}


def machine_from_physical_system(system: PhysicalSystem) -> Machine:
    """The paper's system (rigid base or foundation, SI) as a :class:`Machine`, contact on DOF 0.

    Slider mass ``m`` on spring ``k`` and dashpot ``c`` to the foundation mass ``m_a`` (or the
    ground), the foundation on ``k_a``, ``c_a`` to the ground (Fig. 1).

    Parameters
    ----------
    system : PhysicalSystem
        The paper's system in SI.

    Returns
    -------
    Machine
        Its 1- or 2-DOF machine.
    """
    f = system.foundation
    m, k, c = system.mass, system.stiffness, system.damping
    if f is None:
        mass, damping, stiffness = [[m]], [[c]], [[k]]
    else:
        mass = [[m, 0.0], [0.0, f.m_a]]
        damping = [[c, -c], [-c, c + f.c_a]]
        stiffness = [[k, -k], [-k, k + f.k_a]]
    return Machine(np.array(mass, dtype=float), np.array(damping, dtype=float),
                   np.array(stiffness, dtype=float), 0, system.mu_s, system.mu_k, system.load,
                   system.speed, system.friction,
                   name="rigid base" if f is None else "elastic foundation")
