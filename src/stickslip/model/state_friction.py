"""Friction with memory: rate-and-state (Dieterich-Ruina) and LuGre (Canudas de Wit et al. 1995).

The laws of :mod:`stickslip.model.friction` are curves ``mu(v)``. The two families here carry
an internal state variable that remembers the sliding history, so friction lags the slip speed,
strengthens while the contact is (nearly) at rest and relaxes over a slip distance after a
velocity step. Neither has a true stick: the slip speed only becomes very small. They are
integrated by the smooth stiff engine (:mod:`stickslip.kernel.stiff`), not by the exact
piecewise-linear one.

Units are SI throughout: speeds in m/s, lengths in m, forces in N. The friction force on the
contact is ``F = load * mu`` for rate-and-state and ``F = sigma0 z + sigma1 z' + sigma2 v`` for
LuGre; ``v`` is the slip speed ``V - x'`` (drive speed minus the contact's velocity, the
convention of the rest of the package: the belt, or load point, drags the contact forward).

Rate-and-state
--------------
The classic law (Dieterich 1979; Ruina 1983) is::

    mu = mu_ref + a ln(v / v_ref) + b ln(v_ref theta / d_c)

with the state ``theta`` (s) evolving by the aging law ``theta' = 1 - v theta / d_c`` or the
slip law ``theta' = -(v theta / d_c) ln(v theta / d_c)``. It is singular at ``v = 0``. This
package writes the state as ``psi = mu_ref + b ln(v_ref theta / d_c)`` (dimensionless) and uses
the regularised form (Rice and Ben-Zion 1996; Lapusta et al. 2000)::

    mu = a asinh(v / (2 v_ref) exp(psi / a))

which is odd and smooth in ``v`` and equals the classic law to within
``a / (2 X^2)``, ``X = v exp(psi/a) / (2 v_ref)``, wherever ``X >> 1``: at laboratory values
(``psi / a`` of order 100) the two agree to round-off for every slip speed above
``1e-20 v_ref``. In ``psi`` the evolution laws read::

    aging:  psi' = (b / d_c) (v_ref exp((mu_ref - psi) / b) - |v|)
    slip:   psi' = -(|v| / d_c) (b ln(|v| / v_ref) + psi - mu_ref)

Steady sliding at ``V``: ``theta = d_c / V``, ``psi = mu_ref + b ln(v_ref / V)``,
``mu_ss = mu_ref + (a - b) ln(V / v_ref)``: velocity weakening when ``b > a``.

LuGre
-----
Bristles of mean deflection ``z`` (m), Canudas de Wit, Olsson, Astrom and Lischinsky (1995),
Eqs. (1)-(3)::

    z' = v - sigma0 |v| z / g(v),   g(v) = load (mu_c + (mu_s - mu_c) exp(-(v / v_s)^2))
    F  = sigma0 z + sigma1 z' + sigma2 v

Steady sliding at ``V``: ``z = g(V) / sigma0``, ``F = g(V) + sigma2 V``. ``mu = F / load``.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from stickslip.model._validate import finite, non_negative, positive, within

#: Supported magnitude of a memory law's parameters (in SI, or in the slider's units on the
#: dimensionless command line): ``[1e-50, 1e50]``, zero allowed where the law allows it. Beyond
#: it ``(v / v_s)^2`` or ``load * mu`` overflow a double (a Stribeck velocity of 1e-300 m/s
#: ended in "Array must not contain infs or NaNs").
PARAMETER_RANGE = (1e-50, 1e50)


def _parameter(name: str, value: float, *, zero: bool = False) -> float:
    """``value`` positive (or zero, with ``zero``) and within :data:`PARAMETER_RANGE`."""
    x = non_negative(name, value) if zero else positive(name, value)
    if zero and x == 0.0:
        return x
    return within(name, x, *PARAMETER_RANGE, "beyond it the friction law's terms overflow "
                  "double precision")

FloatArray = NDArray[np.float64]

#: Kernel codes of the laws (:mod:`stickslip.kernel.stiff`).
LAW_RATE_STATE_AGING = 0
LAW_RATE_STATE_SLIP = 1
LAW_LUGRE = 2

#: Evolution laws of rate-and-state friction.
EVOLUTIONS = ("aging", "slip")

#: Largest ``mu_ref / a`` accepted: ``exp(psi / a)`` must stay far from overflow (1e308).
MAX_PSI_OVER_A = 500.0


@dataclass(frozen=True)
class RateStateFriction:
    """Rate-and-state friction in the regularised form ``mu = a asinh(v/(2 v_ref) exp(psi/a))``.

    Parameters
    ----------
    a : float
        Direct-effect parameter (dimensionless, > 0): an instantaneous speed step from ``V1``
        to ``V2`` raises ``mu`` by ``a ln(V2 / V1)``.
    b : float
        Evolution-effect parameter (dimensionless, >= 0): the state then lowers ``mu`` by
        ``b ln(V2 / V1)`` over a slip of a few ``d_c``.
    d_c : float
        Characteristic slip distance, m (> 0).
    mu_ref : float
        Friction coefficient of steady sliding at ``v_ref`` (dimensionless, > 0).
    v_ref : float
        Reference slip speed, m/s (> 0).
    evolution : {"aging", "slip"}
        The state evolution law (Dieterich's aging law or Ruina's slip law).

    Notes
    -----
    See the module docstring for the law, its relation to the classic logarithmic form and
    the evolution laws in the state ``psi``; :meth:`theta` converts ``psi`` back to the
    classic state ``theta`` (s).
    """

    a: float
    b: float
    d_c: float
    mu_ref: float
    v_ref: float
    evolution: str = "aging"
    law: ClassVar[str] = "rate-state"

    def __post_init__(self) -> None:
        object.__setattr__(self, "a", _parameter("a", self.a))
        object.__setattr__(self, "b", _parameter("b", self.b, zero=True))
        object.__setattr__(self, "d_c", _parameter("d_c", self.d_c))
        object.__setattr__(self, "mu_ref", _parameter("mu_ref", self.mu_ref))
        object.__setattr__(self, "v_ref", _parameter("v_ref", self.v_ref))
        if self.evolution not in EVOLUTIONS:
            raise ValueError(f"evolution={self.evolution!r} must be 'aging' or 'slip'")
        if self.mu_ref / self.a > MAX_PSI_OVER_A:
            raise ValueError(f"mu_ref/a = {self.mu_ref / self.a:.4g} exceeds {MAX_PSI_OVER_A:g}: "
                             f"exp(psi/a) would overflow (a={self.a!r} is too small for "
                             f"mu_ref={self.mu_ref!r})")

    @property
    def code(self) -> int:
        """Kernel code of the law."""
        return LAW_RATE_STATE_AGING if self.evolution == "aging" else LAW_RATE_STATE_SLIP

    def parameters(self, load: float) -> FloatArray:
        """The kernel's parameter array ``[load, a, b, d_c, mu_ref, v_ref, 0]`` (SI)."""
        return np.array([load, self.a, self.b, self.d_c, self.mu_ref, self.v_ref, 0.0])

    def steady_state(self, speed: float, load: float) -> float:
        """State ``psi`` of steady sliding at ``speed`` (m/s): ``mu_ref + b ln(v_ref / V)``."""
        return self.mu_ref + self.b * math.log(self.v_ref / positive("speed", speed))

    def steady_mu(self, speed: float) -> float:
        """``mu`` of steady sliding at ``speed`` (regularised form, dimensionless)."""
        return float(self.mu(speed, self.steady_state(speed, 1.0)))

    def mu(self, v: Any, psi: Any) -> Any:
        """Friction coefficient at slip speed ``v`` (m/s) and state ``psi`` (dimensionless)."""
        v = np.asarray(v, dtype=np.float64)
        psi = np.asarray(psi, dtype=np.float64)
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            log_x = psi / self.a + np.log(np.abs(v) / (2.0 * self.v_ref))
            big = log_x > 30.0
            x = np.where(big, 0.0, np.sign(v) * np.exp(np.minimum(log_x, 30.0)))
            value = np.where(big, np.sign(v) * (log_x + math.log(2.0)), np.arcsinh(x))
        return self.a * value

    def theta(self, psi: Any) -> Any:
        """The classic state ``theta = (d_c / v_ref) exp((psi - mu_ref) / b)``, s (``b > 0``)."""
        if self.b == 0.0:
            return np.full(np.shape(psi), math.nan)
        return (self.d_c / self.v_ref) * np.exp((np.asarray(psi) - self.mu_ref) / self.b)

    def state_name(self) -> str:
        """What :meth:`state_output` returns: ``theta`` in seconds."""
        return "theta (s)"

    def state_output(self, psi: Any) -> Any:
        """The state as users of the law know it: ``theta`` (s)."""
        return self.theta(psi)

    def describe(self) -> str:
        """One line: the law and its parameters."""
        return (f"rate-state ({self.evolution} law), a = {self.a:g}, b = {self.b:g}, "
                f"d_c = {self.d_c:g} m, mu_ref = {self.mu_ref:g}, v_ref = {self.v_ref:g} m/s, "
                "regularised mu = a asinh(v/(2 v_ref) exp(psi/a))")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready parameters (SI)."""
        return {"law": "rate-state", "a": self.a, "b": self.b, "d_c_m": self.d_c,
                "mu_ref": self.mu_ref, "v_ref_m_s": self.v_ref, "evolution": self.evolution}


@dataclass(frozen=True)
class LuGreFriction:
    """The LuGre law (Canudas de Wit et al. 1995), SI.

    Parameters
    ----------
    sigma0 : float
        Bristle stiffness, N/m (> 0).
    sigma1 : float
        Bristle damping, N s/m (>= 0).
    sigma2 : float
        Viscous friction, N s/m (>= 0).
    mu_c : float
        Coulomb (kinetic) friction coefficient, ``F_c = mu_c load`` (> 0).
    mu_s : float
        Static friction coefficient, ``F_s = mu_s load`` (>= mu_c).
    stribeck_velocity : float
        Stribeck velocity ``v_s``, m/s (> 0).
    """

    sigma0: float
    sigma1: float
    sigma2: float
    mu_c: float
    mu_s: float
    stribeck_velocity: float
    law: ClassVar[str] = "lugre"

    def __post_init__(self) -> None:
        object.__setattr__(self, "sigma0", _parameter("sigma0", self.sigma0))
        object.__setattr__(self, "sigma1", _parameter("sigma1", self.sigma1, zero=True))
        object.__setattr__(self, "sigma2", _parameter("sigma2", self.sigma2, zero=True))
        object.__setattr__(self, "mu_c", _parameter("mu_c", self.mu_c))
        object.__setattr__(self, "mu_s", _parameter("mu_s", self.mu_s))
        object.__setattr__(self, "stribeck_velocity",
                           _parameter("stribeck_velocity", self.stribeck_velocity))
        if self.mu_s < self.mu_c:
            raise ValueError(f"mu_s={self.mu_s!r} must be at least mu_c={self.mu_c!r} "
                             "(static friction below Coulomb friction)")

    code: ClassVar[int] = LAW_LUGRE

    def parameters(self, load: float) -> FloatArray:
        """The kernel's parameter array ``[load, sigma0, sigma1, sigma2, mu_c, mu_s, v_s]``."""
        return np.array([load, self.sigma0, self.sigma1, self.sigma2, self.mu_c, self.mu_s,
                         self.stribeck_velocity])

    def g(self, v: Any, load: float) -> Any:
        """Stribeck curve ``g(v) = load (mu_c + (mu_s - mu_c) exp(-(v/v_s)^2))``, N."""
        v = np.asarray(v, dtype=np.float64)
        return load * (self.mu_c + (self.mu_s - self.mu_c) * np.exp(-(v / self.stribeck_velocity) ** 2))

    def steady_state(self, speed: float, load: float) -> float:
        """Bristle deflection of steady sliding at ``speed`` (m/s): ``g(V) / sigma0``, m."""
        return float(np.sign(speed) * self.g(speed, load) / self.sigma0)

    def steady_mu(self, speed: float, load: float = 1.0) -> float:
        """``mu = (g(V) sign(V) + sigma2 V) / load`` of steady sliding at ``speed`` (m/s).

        At steady sliding ``z' = 0``, so ``z = g(V) sign(V) / sigma0`` (:meth:`steady_state`)
        and ``F = sigma0 z + sigma2 V``: friction opposes the slip in either direction.
        """
        return float((np.sign(speed) * self.g(speed, load) + self.sigma2 * speed) / load)

    def state_name(self) -> str:
        """What :meth:`state_output` returns: ``z`` in metres."""
        return "z (m)"

    def state_output(self, z: Any) -> Any:
        """The bristle deflection ``z`` (m), unchanged."""
        return np.asarray(z, dtype=np.float64)

    def describe(self) -> str:
        """One line: the law and its parameters."""
        return (f"LuGre, sigma0 = {self.sigma0:g} N/m, sigma1 = {self.sigma1:g} N s/m, "
                f"sigma2 = {self.sigma2:g} N s/m, mu_c = {self.mu_c:g}, mu_s = {self.mu_s:g}, "
                f"v_s = {self.stribeck_velocity:g} m/s")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready parameters (SI)."""
        return {"law": "lugre", "sigma0_N_m": self.sigma0, "sigma1_N_s_m": self.sigma1,
                "sigma2_N_s_m": self.sigma2, "mu_c": self.mu_c, "mu_s": self.mu_s,
                "stribeck_velocity_m_s": self.stribeck_velocity}


StateFriction = RateStateFriction | LuGreFriction

#: Most steps of a speed schedule: velocity-step and slide-hold-slide protocols have tens; an
#: audit's 40,000-row schedule (a 0.8 MB machine file) kept the app's one worker busy for six
#: minutes.
MAX_SCHEDULE_STEPS = 1000


@dataclass(frozen=True)
class SpeedSchedule:
    """Piecewise-constant drive (load-point, belt) speed: ``speeds[i]`` from ``times[i]`` on.

    Parameters
    ----------
    times : tuple of float
        Start times of the steps, s, strictly increasing, ``times[0] = 0``.
    speeds : tuple of float
        Drive speeds, m/s: the first and the last > 0, those between >= 0 (0 is a hold, as in
        the slide-hold-slide tests of rate-and-state laboratories).
    """

    times: tuple[float, ...]
    speeds: tuple[float, ...]

    def __post_init__(self) -> None:
        if len(self.times) > MAX_SCHEDULE_STEPS:
            raise ValueError(f"a speed schedule has {len(self.times)} steps, more than the "
                             f"{MAX_SCHEDULE_STEPS} supported")
        times = tuple(finite("schedule time", t) for t in self.times)
        speeds = tuple(positive("speed", v) if i in (0, len(self.speeds) - 1) or v != 0.0
                       else 0.0 for i, v in enumerate(self.speeds))
        if not times or len(times) != len(speeds):
            raise ValueError(f"a speed schedule needs as many times as speeds, got {len(times)} "
                             f"and {len(speeds)}")
        if times[0] != 0.0:
            raise ValueError(f"a speed schedule starts at 0 s, not {times[0]!r} s")
        for t_a, t_b in itertools.pairwise(times):
            if not t_b > t_a:
                raise ValueError(f"speed schedule times must increase, got {t_a!r} s then {t_b!r} s")
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "speeds", speeds)

    @classmethod
    def constant(cls, speed: float) -> SpeedSchedule:
        """One speed (m/s) for all times."""
        return cls((0.0,), (speed,))

    @property
    def first(self) -> float:
        """The speed at 0 s, m/s."""
        return self.speeds[0]

    @property
    def last(self) -> float:
        """The speed after the last step, m/s."""
        return self.speeds[-1]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``times_s`` and ``speeds_m_s``."""
        return {"times_s": list(self.times), "speeds_m_s": list(self.speeds)}


@dataclass(frozen=True, eq=False)
class MemorySystem:
    """A linear structure with one frictional contact whose friction has memory, SI.

    ``M q'' + C q' + K q = e_c F``; the drive moves at the schedule's speed ``V(t)`` and the
    slip speed is ``v = V - q_c'``. A 1-DOF structure of zero mass is the quasi-static slider
    (``k x = F``; rate-and-state only, no damping).

    Parameters
    ----------
    mass, damping, stiffness : ndarray
        ``n x n`` matrices, kg, N s/m, N/m (``stiffness`` non-singular: the structure is held).
    contact_dof : int
        The DOF the drive rubs.
    load : float
        Normal load ``N``, N (> 0).
    friction : RateStateFriction or LuGreFriction
        The law.
    schedule : SpeedSchedule
        Drive speeds.
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    contact_dof: int
    load: float
    friction: StateFriction
    schedule: SpeedSchedule

    def __post_init__(self) -> None:
        m = np.atleast_2d(np.asarray(self.mass, dtype=np.float64))
        c = np.atleast_2d(np.asarray(self.damping, dtype=np.float64))
        k = np.atleast_2d(np.asarray(self.stiffness, dtype=np.float64))
        n = m.shape[0]
        for name, mat in (("mass", m), ("damping", c), ("stiffness", k)):
            if mat.shape != (n, n) or not np.all(np.isfinite(mat)):
                raise ValueError(f"the {name} matrix must be finite and {n}x{n}")
        object.__setattr__(self, "mass", m)
        object.__setattr__(self, "damping", c)
        object.__setattr__(self, "stiffness", k)
        object.__setattr__(self, "load", positive("load", self.load))
        if not 0 <= int(self.contact_dof) < n:
            raise ValueError(f"contact_dof={self.contact_dof!r} is not a DOF of the {n}-DOF structure")
        if self.quasi_static:
            if not isinstance(self.friction, RateStateFriction):
                raise ValueError("m = 0 (the quasi-static slider) needs law = \"rate-state\": the "
                                 "LuGre slider needs its mass")
            if c[0, 0] != 0.0:
                raise ValueError(f"m = 0 (the quasi-static slider) takes no damping, got "
                                 f"c = {float(c[0, 0])!r} N s/m")
            if not k[0, 0] > 0.0:
                raise ValueError(f"the quasi-static slider's k={float(k[0, 0])!r} N/m must be positive")
        else:
            if np.any(np.linalg.eigvalsh(0.5 * (m + m.T)) <= 0.0):
                raise ValueError("the mass matrix must be positive definite (m = 0 is the "
                                 "quasi-static slider: 1 DOF only)")
            if abs(np.linalg.det(k)) == 0.0 or np.linalg.cond(k) > 1e14:
                raise ValueError("the stiffness matrix is singular: the structure must be held")

    @property
    def n_dof(self) -> int:
        """Degrees of freedom of the structure."""
        return int(self.mass.shape[0])

    @property
    def quasi_static(self) -> bool:
        """True for the quasi-static slider (1 DOF, zero mass)."""
        return self.n_dof == 1 and float(self.mass[0, 0]) == 0.0

    def with_stiffness_scale(self, factor: float) -> MemorySystem:
        """The same system with every stiffness multiplied by ``factor``."""
        return MemorySystem(self.mass, self.damping, factor * self.stiffness, self.contact_dof,
                            self.load, self.friction, self.schedule)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description (SI)."""
        return {"n_dof": self.n_dof, "contact_dof": int(self.contact_dof),
                "quasi_static": self.quasi_static, "load_N": self.load,
                "mass_kg": self.mass.tolist(), "damping_N_s_m": self.damping.tolist(),
                "stiffness_N_m": self.stiffness.tolist(), "friction": self.friction.to_dict(),
                "schedule": self.schedule.to_dict()}
