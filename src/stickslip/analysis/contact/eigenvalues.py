"""Complex-eigenvalue analysis (CEA) of a machine's steady sliding with normal-load coupling.

What finite-element codes call CEA: linearise the equations of motion about steady sliding,
where the friction force depends on the normal force and the normal force on the motion, and
read stability from the eigenvalues (in 1/s: frequencies in Hz, damping ratios). The
equations, their signs and units, and the search for the critical friction coefficient are
derived in :mod:`stickslip.analysis.contact.friction_coupling`; this module applies them to a
:class:`~stickslip.model.machine.Machine` and its :class:`~stickslip.model.contact.Contact`
(``stickslip stability --config machine.toml``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.blas_threads import one_blas_thread
from stickslip.analysis.contact.critical_coefficient import (
    MU_MAX,
    N_SCAN,
    CriticalFriction,
    critical_friction,
)
from stickslip.analysis.contact.eigenvalue_maps import RootLocus, root_locus
from stickslip.analysis.contact.friction_coupling import (
    FrictionCoupledSystem,
    coupled_system,
    verdict_of,
)

if TYPE_CHECKING:
    from collections.abc import Sequence

    from stickslip.analysis.contact._modes import ContactSystem
    from stickslip.model.contact import Contact
    from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True)
class StabilityResult:
    """Complex-eigenvalue analysis of a machine's steady sliding (:func:`complex_eigenvalue_analysis`).

    Attributes
    ----------
    mu : float
        Friction coefficient at the sliding speed, ``mu(V)``.
    slope : float
        ``d mu / d v_r`` at the sliding speed, s/m.
    normal_force : float
        ``N_0`` of steady sliding, N.
    eigenvalues : ndarray of complex
        ``s`` in 1/s, sorted by imaginary part then real part.
    bounds : ndarray
        Round-off bounds of the eigenvalues, 1/s.
    verdict : str
        ``"stable"``, ``"unstable"`` or ``"marginal"`` (an eigenvalue within its bound of the
        imaginary axis: neutral, e.g. an undamped structure).
    critical : CriticalFriction
        With the machine's damping.
    critical_undamped : CriticalFriction
        Without any damping (mode coalescence).
    natural_frequencies_hz : ndarray
        Frequencies of the structure pressed on the belt without friction (the modes the
        mode numbers count), Hz.
    system : FrictionCoupledSystem
        The linearisation's data.
    """

    mu: float
    slope: float
    normal_force: float
    eigenvalues: ComplexArray
    bounds: FloatArray
    verdict: str
    critical: CriticalFriction
    critical_undamped: CriticalFriction
    natural_frequencies_hz: FloatArray
    system: FrictionCoupledSystem = field(repr=False)

    @property
    def stable(self) -> bool:
        """True when every eigenvalue is proven in the open left half plane."""
        return self.verdict == "stable"

    def modes(self) -> list[dict[str, float]]:
        """One entry per eigenvalue with ``omega >= 0``: frequency (Hz), damping ratio, growth (1/s)."""
        out = []
        for s in self.eigenvalues:
            if s.imag < 0.0:
                continue
            out.append({"frequency_hz": abs(s.imag) / (2 * math.pi),
                        "damping_ratio": -s.real / abs(s) if s != 0 else 0.0,
                        "growth_rate_per_s": float(s.real)})
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the contract's ``eigenvalues``, ``stable``, ``critical_mu``,
        ``critical_mu_undamped`` and the details."""
        return {"eigenvalues": [[float(s.real), float(s.imag)] for s in self.eigenvalues],
                "stable": self.stable, "verdict": self.verdict,
                "critical_mu": self.critical.mu, "critical_mu_undamped": self.critical_undamped.mu,
                "critical": self.critical.to_dict(),
                "critical_undamped": self.critical_undamped.to_dict(),
                "mu": self.mu, "friction_slope_s_per_m": self.slope,
                "normal_force_N": self.normal_force, "modes": self.modes(),
                "natural_frequencies_hz": self.natural_frequencies_hz.tolist()}

    def root_locus(self, mus: Sequence[float] | FloatArray | None = None) -> RootLocus:
        """Eigenvalues along ``mus`` (default 0 to ``1.5 x`` the largest critical value)."""
        return root_locus(self.system, mus if mus is not None else _locus_range(self))

    def plot(self, **kwargs: Any) -> Any:
        """The root locus over mu (:func:`stickslip.plot.stability.root_locus_plot`)."""
        from stickslip.plot.stability import root_locus_plot

        return root_locus_plot(self.root_locus(), **kwargs)


def _locus_range(result: StabilityResult) -> FloatArray:
    found = [c.mu for c in (result.critical, result.critical_undamped) if c.mu]
    top = 1.5 * max([*found, result.mu]) if found or result.mu > 0 else result.critical.mu_max
    return np.linspace(0.0, top, 301)


@one_blas_thread
def complex_eigenvalue_analysis(machine: Machine, contact: Contact | None, *,
                                normal_dof: int | None = None, mu_max: float = MU_MAX,
                                n_scan: int = N_SCAN) -> StabilityResult:
    """Eigenvalues of steady sliding with the friction coupling, and the critical coefficients.

    Parameters
    ----------
    machine : Machine
        Structure (SI), contact DOF, friction law (``mu(V)`` and its slope are used) and the
        operating point (speed and load enter only through the slope term).
    contact : Contact or None
        Normal DOF and contact spring; None: the paper's constant load (no coupling).
    normal_dof : int, optional
        Index of the normal DOF in ``machine`` when it differs from the file's (reduction).
    mu_max : float
        Largest friction coefficient searched for the critical ones.
    n_scan : int
        Scan steps of that search.

    Returns
    -------
    StabilityResult
        Eigenvalues (1/s), verdict, critical ``mu`` with and without damping, modes involved.

    Raises
    ------
    ValueError
        No steady sliding (``N_0 <= 0``): the friction coupling is past its self-locking
        coefficient (``FrictionCoupledSystem.self_locking_mu``).
    """
    system, mu = coupled_system(machine, contact, normal_dof=normal_dof)
    n0 = system.normal_force(mu)
    if not n0 > 0.0:
        lock = system.self_locking_mu()
        where = (f"mu = {mu:.6g} is past the self-locking coefficient {lock:.6g}, where the normal "
                 "force of steady sliding grows without bound (divergence)" if lock is not None
                 else f"mu = {mu:.6g} is the self-locking coefficient (divergence)")
        raise ValueError(f"no steady sliding: {where}; its equilibrium would need N = {n0:.6g} N. "
                         "The friction wedges the slider into the belt (sprag): it sticks with "
                         "a growing normal force instead")
    values, bounds = system.eigenvalues(mu)
    verdict = {1: "unstable", -1: "stable", 0: "marginal"}[verdict_of(values, bounds)]
    import scipy.linalg

    w2 = scipy.linalg.eigh(system.contact_stiffness(), system.mass, eigvals_only=True)
    return StabilityResult(mu, system.slope, n0, values, bounds, verdict,
                           critical_friction(system, mu_max=mu_max, n_scan=n_scan),
                           critical_friction(system.undamped(), mu_max=mu_max, n_scan=n_scan),
                           np.sqrt(np.maximum(w2, 0.0)) / (2 * math.pi), system)


def self_locking_note(system: ContactSystem) -> str | None:
    """What a run of a machine without steady sliding should say, or None when it has one.

    Steady sliding at ``mu_k`` needs ``N_0 = W / (1 + a mu_k) > 0``
    (:meth:`FrictionCoupledSystem.self_locking_mu`); past the self-locking coefficient it has
    none: the friction wedges the slider into the belt, where it sticks with a growing normal
    force, which no horizon turns into one of the engine's verdicts.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).

    Returns
    -------
    str or None
        One sentence, or None when steady sliding exists (or there is no normal DOF).
    """
    if system.normal_dof is None:
        return None
    coupled = FrictionCoupledSystem(system.mass, system.damping, system.stiffness,
                                    system.tangential_dof, system.normal_dof,
                                    normal_stiffness=system.normal_stiffness, load=system.load)
    lock = coupled.self_locking_mu()
    if lock is None or system.mu_k < lock:
        return None
    return (f"no steady sliding: mu_k = {system.mu_k:.6g} is at or past the self-locking "
            f"coefficient {lock:.6g} (the friction wedges the slider into the belt, where it "
            "sticks with a growing normal force): steady sliding cannot be the verdict, and a "
            "longer horizon is unlikely to bring one")
