"""Dimensionless parameters of the sliding system (paper Section 2.3).

The authoritative definitions are those printed after Eq. (27):

* ``M = m_a / m`` (mass ratio),
* ``K = sqrt(k_a / k)`` (stiffness ratio, a ratio of natural-frequency-like quantities),
* ``zeta = c / (2 sqrt(m k))``, ``zeta_a = c_a / (2 sqrt(m k))`` (damping ratios, both
  referred to the primary system),
* ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``,
* ``gamma = mu_k / (mu_s - mu_k)``.

The parenthetical definitions printed next to Eqs. (28)-(30) (``K = k_a/k``,
``zeta = c/sqrt(mk)``) disagree with these; ``tests/test_absorber.py`` settles which
reading reproduces Eq. (31).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from stickslip.model._validate import non_negative, positive
from stickslip.model.friction import CoulombFriction, FrictionLaw


@dataclass(frozen=True)
class Slider:
    """The frictional contact of the slider on the moving belt (dimensionless).

    The slider's own spring and damper belong to the linear structure
    (:class:`~stickslip.model.Structure`, whose :attr:`~stickslip.model.Structure.zeta` is the
    primary damping ratio); the slider object carries only what the friction contact adds.

    Parameters
    ----------
    lam : float
        ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``, dimensionless, > 0. Larger values mean a
        heavier load, a slower belt or a softer spring (paper Section 2.3).
    gamma : float, default 2, keyword-only
        ``mu_k / (mu_s - mu_k)``, dimensionless, >= 0. The paper uses 2 throughout.
    friction : FrictionLaw, keyword-only, default CoulombFriction()
        Friction magnitude while sliding as a function of the sliding speed
        (:mod:`stickslip.model.friction`); the default is the paper's two-valued law.
    """

    lam: float
    gamma: float = field(default=2.0, kw_only=True)
    friction: FrictionLaw = field(default_factory=CoulombFriction, kw_only=True)

    def __post_init__(self) -> None:
        object.__setattr__(self, "lam", positive("lambda", self.lam))
        object.__setattr__(self, "gamma", non_negative("gamma", self.gamma))
        if not callable(getattr(self.friction, "bands", None)):
            raise ValueError(f"friction={self.friction!r} is not a friction law (stickslip.model.friction)")


@dataclass(frozen=True)
class Foundation:
    """One elastic-foundation stage, the dynamic vibration absorber (dimensionless).

    Parameters
    ----------
    mass_ratio : float
        ``M = m_a / m``, > 0.
    stiffness_ratio : float
        ``K = sqrt(k_a / k)``, > 0.
    damping_ratio : float
        ``zeta_a = c_a / (2 sqrt(m k))``, >= 0.
    """

    mass_ratio: float
    stiffness_ratio: float
    damping_ratio: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass_ratio", positive("M", self.mass_ratio))
        object.__setattr__(self, "stiffness_ratio", positive("K", self.stiffness_ratio))
        object.__setattr__(self, "damping_ratio", non_negative("zeta_a", self.damping_ratio))

    def scaled(self, k_scale: float) -> Foundation:
        """Return the same foundation with ``K`` multiplied by ``k_scale`` (paper Figs. 11-15)."""
        return Foundation(
            self.mass_ratio,
            self.stiffness_ratio * positive("k_scale", k_scale),
            self.damping_ratio,
        )
