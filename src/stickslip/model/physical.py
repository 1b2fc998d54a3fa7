"""Physical parameters (SI) and their dimensionless groups, both ways (paper Eqs. 15-18).

Everything here is in SI units: kg, N/m, N s/m, N, m/s. Units given as text ("2 kg",
"50 kN/m") are parsed at the outer boundary (command line, configuration files), not here.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from stickslip.model._validate import MAX_PARAMETER, MIN_RATIO, non_negative, positive, within
from stickslip.model.friction import (
    CoulombFriction,
    FrictionLaw,
    LinearFriction,
    StribeckFriction,
    TableFriction,
)
from stickslip.model.parameters import Foundation, Slider
from stickslip.model.structure import Structure, chain_structure

#: Supported magnitudes of a physical input in SI units, ``[MIN_SI, MAX_SI]``. The report
#: multiplies and divides up to three inputs (the energy scale ``m V^2``, the force scale
#: ``V sqrt(m k)``, ``lambda`` itself) and a double overflows beyond 1.8e308: 1e50 keeps each
#: such product within 1e150, far from overflow, and spans any machine (from a 1e-9 kg MEMS
#: slider to a 1e8 kg ship). Beyond it ``--speed 1e300`` used to end in an ``OverflowError``.
MAX_SI = 1e50
MIN_SI = 1e-50


def si_input(name: str, value: float, unit: str, *, zero: bool = False) -> float:
    """``value`` as a float whose magnitude lies in ``[MIN_SI, MAX_SI]``.

    A quantity that may be zero (``zero``: a damping, a kinetic coefficient) has no lower
    bound: a tiny damping only makes a tiny damping ratio.

    Parameters
    ----------
    name : str
        The quantity's name in messages (``"speed V"``).
    value : float
        The value in SI units.
    unit : str
        Its SI unit, for the message (``"m/s"``; empty for a dimensionless coefficient).
    zero : bool
        Accept exactly zero (a damping, a kinetic coefficient).

    Returns
    -------
    float
        The value, in the unit given.

    Raises
    ------
    ValueError
        One line naming the value, the range and why.
    """
    x = non_negative(name, value) if zero else positive(name, value)
    return within(name, x, 0.0 if zero else MIN_SI, MAX_SI, f"in {unit or 'dimensionless units'}; "
                  "beyond it products of the inputs such as m V^2 overflow double precision")


@dataclass(frozen=True)
class PhysicalFoundation:
    """An elastic foundation in SI units.

    Parameters
    ----------
    m_a : float
        Foundation mass, kg (> 0).
    k_a : float
        Foundation stiffness to the rigid base, N/m (> 0).
    c_a : float
        Foundation damping coefficient, N s/m (>= 0).
    """

    m_a: float
    k_a: float
    c_a: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "m_a", si_input("m_a", self.m_a, "kg"))
        object.__setattr__(self, "k_a", si_input("k_a", self.k_a, "N/m"))
        object.__setattr__(self, "c_a", si_input("c_a", self.c_a, "N s/m", zero=True))


@dataclass(frozen=True)
class PhysicalFriction:
    """A velocity-dependent friction law in SI units (the ``[friction]`` table, ``docs/friction.md``).

    Parameters
    ----------
    law : {"coulomb", "linear", "table", "stribeck"}
        The law's shape; ``mu_s`` and ``mu_k`` come from the system (for ``stribeck``
        ``mu_k`` is the high-speed limit, for ``table`` the kinetic reference).
    slope : float
        ``linear``: ``sigma`` in ``mu = mu_k - sigma v_r``, s/m (> 0 weakening).
    mu_0 : float or None
        ``stribeck``: friction coefficient at vanishing sliding speed, ``mu_k <= ... <= mu_s``
        (default ``mu_s``).
    stribeck_velocity : float
        ``stribeck``: ``v_s``, m/s (> 0).
    exponent : float
        ``stribeck``: ``n`` (> 0).
    viscous : float
        ``stribeck``: ``sigma_v``, s/m.
    table_v, table_mu : tuple of float
        ``table``: sliding speeds, m/s, and friction coefficients of a measured curve.
    tolerance : float
        ``stribeck``: law approximation error in units of lambda (see
        :class:`~stickslip.model.friction.StribeckFriction`).
    """

    law: str = "coulomb"
    slope: float = 0.0
    mu_0: float | None = None
    stribeck_velocity: float = 1.0
    exponent: float = 1.0
    viscous: float = 0.0
    table_v: tuple[float, ...] = ()
    table_mu: tuple[float, ...] = ()
    tolerance: float = 1e-4

    def __post_init__(self) -> None:
        if self.law not in ("coulomb", "linear", "table", "stribeck"):
            raise ValueError(f"friction law {self.law!r} is not one of coulomb, linear, table, stribeck")
        if self.law == "table" and not self.table_v:
            raise ValueError("the table friction law needs a curve (table = \"curve.csv\")")
        if self.law == "stribeck":  # checked here, where a file's [friction] is read
            si_input("stribeck_velocity", self.stribeck_velocity, "m/s")

    def dimensionless(self, m: float, k: float, mu_s: float, mu_k: float, load: float,
                      speed: float) -> FrictionLaw:
        """The law in the engine's units: ``delta = sigma W / (2 sqrt(m k))``, ``u = v / V``.

        Stribeck: ``u_s = v_s / V``, ``r0 = (mu_0 - mu_k) / (mu_s - mu_k)``,
        ``d_v = sigma_v W / (2 sqrt(m k))``. Table: ``u_i = v_i / V``,
        ``f_i = (mu_i - mu_k) / (mu_s - mu_k)``.
        """
        weight = load / (2.0 * math.sqrt(m * k))
        if self.law == "linear":
            return LinearFriction(self.slope * weight)
        if self.law == "table":
            return TableFriction.from_physical(self.table_v, self.table_mu, mu_s, mu_k, speed)
        if self.law == "stribeck":
            mu_0 = mu_s if self.mu_0 is None else self.mu_0
            return StribeckFriction(
                positive("stribeck_velocity", self.stribeck_velocity) / speed,
                exponent=self.exponent,
                viscous=self.viscous * weight,
                mu0_ratio=(mu_0 - mu_k) / (mu_s - mu_k),
                tolerance=self.tolerance,
            )
        return CoulombFriction()


@dataclass(frozen=True, init=False)
class PhysicalSystem:
    """The sliding system of the paper's Fig. 1 in SI units.

    Parameters
    ----------
    mass : float
        Slider mass ``m``, kg (> 0).
    stiffness : float
        Stiffness ``k`` of the spring holding the slider, N/m (> 0).
    damping : float
        Damping coefficient ``c`` of the slider's dashpot, N s/m (>= 0).
    mu_s, mu_k : float
        Static and kinetic friction coefficients, ``mu_s > mu_k >= 0``.
    load : float
        Normal load ``W``, N (> 0).
    speed : float
        Belt speed ``V``, m/s (> 0).
    foundation : PhysicalFoundation or None
        The elastic foundation; ``None`` is the rigid base.
    friction : PhysicalFriction
        The friction law while sliding (default: the paper's Coulomb law, ``mu = mu_k``).

    Notes
    -----
    The keywords ``m``, ``k``, ``c`` and the attributes of those names are the former
    spelling of ``mass``, ``stiffness``, ``damping``; they still work for one release, with a
    ``DeprecationWarning``.
    """

    mass: float
    stiffness: float
    damping: float
    mu_s: float
    mu_k: float
    load: float
    speed: float
    foundation: PhysicalFoundation | None = None
    friction: PhysicalFriction = PhysicalFriction()

    def __init__(self, mass: float | None = None, stiffness: float | None = None,
                 damping: float | None = None, mu_s: float | None = None, mu_k: float | None = None,
                 load: float | None = None, speed: float | None = None,
                 foundation: PhysicalFoundation | None = None,
                 friction: PhysicalFriction = PhysicalFriction(), **former: float) -> None:
        values: dict[str, float | None] = {
            "mass": mass, "stiffness": stiffness, "damping": damping, "mu_s": mu_s,
            "mu_k": mu_k, "load": load, "speed": speed,
        }
        for old, given in former.items():
            if old not in _FORMER_NAMES:
                raise TypeError(f"PhysicalSystem() got an unexpected keyword argument {old!r}")
            new = _FORMER_NAMES[old]
            _warn_former(old, new)
            if values[new] is not None:
                raise TypeError(f"PhysicalSystem() got both {new}= and its former name {old}=")
            values[new] = given
        missing = [name for name, entry in values.items() if entry is None]
        if missing:
            raise TypeError(f"PhysicalSystem() missing {', '.join(missing)}")
        for name, entry in values.items():
            object.__setattr__(self, name, entry)
        object.__setattr__(self, "foundation", foundation)
        object.__setattr__(self, "friction", friction)
        self.__post_init__()

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", si_input("m", self.mass, "kg"))
        object.__setattr__(self, "stiffness", si_input("k", self.stiffness, "N/m"))
        object.__setattr__(self, "damping", si_input("c", self.damping, "N s/m", zero=True))
        object.__setattr__(self, "mu_s", si_input("mu_s", self.mu_s, ""))
        object.__setattr__(self, "mu_k", si_input("mu_k", self.mu_k, "", zero=True))
        object.__setattr__(self, "load", si_input("load W", self.load, "N"))
        object.__setattr__(self, "speed", si_input("speed V", self.speed, "m/s"))
        if self.mu_k >= self.mu_s:
            raise ValueError(
                f"mu_k={self.mu_k!r} must be smaller than mu_s={self.mu_s!r} "
                "(stick-slip needs static friction above kinetic friction)"
            )
        mu_0 = self.friction.mu_0
        if self.friction.law == "stribeck" and mu_0 is not None and not self.mu_k <= mu_0 <= self.mu_s:
            raise ValueError(f"[friction] mu_0 = {mu_0!r} must lie in [mu_k, mu_s] = "
                             f"[{self.mu_k!r}, {self.mu_s!r}] (friction at rest between kinetic "
                             "and static)")

    @property
    def m(self) -> float:
        """Deprecated name of :attr:`mass`, kg."""
        _warn_former("m", "mass")
        return self.mass

    @property
    def k(self) -> float:
        """Deprecated name of :attr:`stiffness`, N/m."""
        _warn_former("k", "stiffness")
        return self.stiffness

    @property
    def c(self) -> float:
        """Deprecated name of :attr:`damping`, N s/m."""
        _warn_former("c", "damping")
        return self.damping

    @property
    def natural_frequency(self) -> float:
        """``omega_n = sqrt(k / m)``, rad/s (Eq. 18)."""
        return math.sqrt(self.stiffness / self.mass)

    @property
    def time_scale(self) -> float:
        """Seconds per unit of dimensionless time, ``1 / omega_n`` (Eq. 17)."""
        return 1.0 / self.natural_frequency

    @property
    def length_scale(self) -> float:
        """Metres per unit of dimensionless displacement, ``V / omega_n`` (Eqs. 15-16)."""
        return self.speed / self.natural_frequency

    @property
    def force_scale(self) -> float:
        """Newtons per unit of dimensionless force, ``V sqrt(m k)``."""
        return self.speed * math.sqrt(self.mass * self.stiffness)

    def slider(self) -> Slider:
        """Dimensionless ``lambda``, ``gamma`` and friction law of the contact (after Eq. 27)."""
        root_mk = math.sqrt(self.mass * self.stiffness)
        return Slider(
            (self.mu_s - self.mu_k) * self.load / (self.speed * root_mk),
            gamma=self.mu_k / (self.mu_s - self.mu_k),
            friction=self.friction.dimensionless(self.mass, self.stiffness, self.mu_s, self.mu_k, self.load,
                                                 self.speed),
        )

    @property
    def zeta(self) -> float:
        """Primary damping ratio ``zeta = c / (2 sqrt(m k))``, dimensionless (Section 2.3)."""
        return self.damping / (2.0 * math.sqrt(self.mass * self.stiffness))

    def structure(self) -> Structure:
        """The dimensionless structure: rigid base, or the slider on its foundation (Fig. 1)."""
        found = self.dimensionless_foundation()
        return chain_structure(self.zeta, () if found is None else (found,))

    def dimensionless_foundation(self) -> Foundation | None:
        """Dimensionless ``M``, ``K``, ``zeta_a`` of the foundation, or ``None`` (rigid base)."""
        if self.foundation is None:
            return None
        return foundation_to_dimensionless(self.foundation, self.mass, self.stiffness)

    def speed_for_lambda(self, lam: float) -> float:
        """Belt speed ``V`` (m/s) at which ``lambda`` takes the value ``lam``."""
        lam = positive("lambda", lam)
        return (self.mu_s - self.mu_k) * self.load / (lam * math.sqrt(self.mass * self.stiffness))

    def load_for_lambda(self, lam: float) -> float:
        """Normal load ``W`` (N) at which ``lambda`` takes the value ``lam``."""
        lam = positive("lambda", lam)
        return lam * self.speed * math.sqrt(self.mass * self.stiffness) / (self.mu_s - self.mu_k)

    @classmethod
    def from_dimensionless(
        cls,
        slider: Slider,
        *,
        zeta: float,
        m: float,
        k: float,
        mu_s: float,
        speed: float,
        foundation: Foundation | None = None,
    ) -> PhysicalSystem:
        """Build the physical system with given ``m``, ``k``, ``mu_s``, ``V`` and groups.

        The inverse of :meth:`slider`, :attr:`zeta` and :meth:`dimensionless_foundation`:
        ``mu_k = mu_s gamma / (1 + gamma)``, ``W = lambda V sqrt(m k) / (mu_s - mu_k)``,
        ``c = 2 zeta sqrt(m k)``.
        """
        m, k = positive("m", m), positive("k", k)
        mu_s, speed = positive("mu_s", mu_s), positive("speed V", speed)
        root_mk = math.sqrt(m * k)
        mu_k = mu_s * slider.gamma / (1.0 + slider.gamma)
        load = slider.lam * speed * root_mk / (mu_s - mu_k)
        phys_foundation = None
        if foundation is not None:
            phys_foundation = foundation_to_physical(foundation, m, k)
        return cls(
            mass=m,
            stiffness=k,
            damping=2.0 * non_negative("zeta", zeta) * root_mk,
            mu_s=mu_s,
            mu_k=mu_k,
            load=load,
            speed=speed,
            foundation=phys_foundation,
        )


_FORMER_NAMES = {"m": "mass", "k": "stiffness", "c": "damping"}


def _warn_former(old: str, new: str) -> None:
    warnings.warn(f"PhysicalSystem.{old} is deprecated: use PhysicalSystem.{new}",
                  DeprecationWarning, stacklevel=3)


def foundation_to_dimensionless(foundation: PhysicalFoundation, m: float, k: float) -> Foundation:
    """``M = m_a/m``, ``K = sqrt(k_a/k)``, ``zeta_a = c_a/(2 sqrt(m k))`` (after Eq. 27).

    Parameters
    ----------
    foundation : PhysicalFoundation
        The foundation in SI units.
    m, k : float
        Slider mass, kg, and spring stiffness, N/m (> 0).

    Returns
    -------
    Foundation
        ``(M, K, zeta_a)``, dimensionless.
    """
    m, k = positive("m", m), positive("k", k)
    mass_ratio, stiffness_ratio = foundation.m_a / m, math.sqrt(foundation.k_a / k)
    for name, value, inputs in (("M = m_a/m", mass_ratio, f"m_a = {foundation.m_a:g} kg, m = {m:g} kg"),
                                ("K = sqrt(k_a/k)", stiffness_ratio,
                                 f"k_a = {foundation.k_a:g} N/m, k = {k:g} N/m")):
        if not MIN_RATIO <= value <= MAX_PARAMETER:  # the paper's ratios, bounded
            raise ValueError(f"the foundation's {name} = {value:.3g} ({inputs}) is outside the "
                             f"supported range [{MIN_RATIO:g}, {MAX_PARAMETER:g}]")
    return Foundation(
        mass_ratio=mass_ratio,
        stiffness_ratio=stiffness_ratio,
        damping_ratio=foundation.c_a / (2.0 * math.sqrt(m * k)),
    )


def foundation_to_physical(foundation: Foundation, m: float, k: float) -> PhysicalFoundation:
    """``m_a = M m``, ``k_a = K^2 k``, ``c_a = 2 zeta_a sqrt(m k)``: inverse of the above.

    Parameters
    ----------
    foundation : Foundation
        ``(M, K, zeta_a)``, dimensionless.
    m, k : float
        Slider mass, kg, and spring stiffness, N/m (> 0).

    Returns
    -------
    PhysicalFoundation
        ``m_a`` [kg], ``k_a`` [N/m], ``c_a`` [N s/m].
    """
    m, k = positive("m", m), positive("k", k)
    return PhysicalFoundation(
        m_a=foundation.mass_ratio * m,
        k_a=foundation.stiffness_ratio**2 * k,
        c_a=2.0 * foundation.damping_ratio * math.sqrt(m * k),
    )


def physical_friction_from_config(table: Mapping[str, Any], *, base_dir: Path | None = None,
                                  source: str = "[friction]",
                                  table_columns: tuple[list[float], list[float]] | None = None,
                                  ) -> PhysicalFriction:
    """The ``[friction]`` table of a TOML configuration in SI units.

    Keys: ``law`` (coulomb | linear | table | stribeck), ``slope`` (linear, s/m), ``mu_0``,
    ``stribeck_velocity`` (m/s), ``exponent``, ``viscous`` (s/m), ``tolerance`` (stribeck), and
    ``table`` (a CSV with columns ``v`` [m/s] and ``mu``, relative to ``base_dir``). Values
    may carry units (``"0.02 s/m"``). Raises ``ValueError`` naming the key and the value.

    Parameters
    ----------
    table : mapping
        The ``[friction]`` table.
    base_dir : Path, optional
        Directory against which a relative ``table`` path is read.
    source : str
        Its name in error messages.
    table_columns : tuple of list of float, optional
        The ``v`` [m/s] and ``mu`` columns of the file ``table`` names, already read by the
        caller (an uploaded file): then nothing is read from disk.

    Returns
    -------
    PhysicalFriction
        The law in SI units.
    """
    from stickslip.model.friction_input import read_friction_csv_columns
    from stickslip.model.inputs import friction_fields

    columns = table_columns
    if columns is None and isinstance(table, Mapping) and "table" in table:
        path = table["table"]
        if not isinstance(path, str):
            raise ValueError(f"{source}: table = {path!r} must be the path of a CSV file")
        full = Path(path) if base_dir is None or Path(path).is_absolute() else base_dir / path
        columns = read_friction_csv_columns(full)
    return PhysicalFriction(**friction_fields(table, source=lambda key: f"{source}: {key} =",
                                              table_columns=columns, where=source))
