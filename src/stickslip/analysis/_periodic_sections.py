"""Poincare sections of periodic motions, for continuation.

* **Stick-slip cycles** on the breakaway section of :mod:`stickslip.analysis.cycles`
  (``xi' = 1``, ``S`` at the level of a breakaway onto slip-I or onto slip-II; unknowns ``b``,
  the foundation's coordinates, ``2 n - 2`` of them): ``G(b) = P^k(b) - b`` with the exact
  Jacobian of saltation matrices (:meth:`stickslip.analysis.return_map.ReturnMap.linearise`).
* **Slip oscillations** (never sticking, velocity-dependent friction) on the section of a
  velocity maximum of the slider, ``xi'' = 0`` with ``xi''' < 0``: the unknowns are the
  slider's peak velocity ``xi'`` and the foundation's coordinates (``2 n - 1``), ``xi`` follows
  from ``xi'' = 0``. The map is evaluated exactly by the engine (the next velocity maximum is
  the root of ``xi''`` on the recorded run); its Jacobian by central differences (the section
  is crossed transversally and the flow is smooth in slip: a piecewise-linear friction law is
  continuous across its band edges), one-sided within a step of grazing the belt speed.

Both give ``G``, its Jacobian, ``G`` alone (for differences in the parameter), the phase
signature (the sequence of slip-I, slip-II and stick phases: a change is a grazing) and the
period, amplitude and stick ratio of the motion. All quantities are dimensionless.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.return_map import ReturnMap
from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.analysis.stability import slip_matrix
from stickslip.analysis.verdict import Verdict
from stickslip.kernel.system import SLIP_I, STICK, mode_kind_band
from stickslip.model._validate import friction_range
from stickslip.model.friction import CoulombFriction, FrictionLaw, LinearFriction, evaluate_bands
from stickslip.model.initial import InitialState
from stickslip.model.machine import Machine
from stickslip.model.parameters import Foundation, Slider
from stickslip.model.structure import Structure, chain_structure

FloatArray = NDArray[np.float64]

#: Parameters a branch can be continued in (``delta`` needs the linear law; ``K``, ``M``,
#: ``zeta_a`` a foundation).
PARAMETERS = ("lam", "zeta", "gamma", "delta", "K", "M", "zeta_a")


@dataclass(frozen=True)
class ContinuationSystem:
    """The system continued: the options of ``stickslip cycles`` as one value.

    Parameters
    ----------
    lam, zeta, gamma : float
        The slider (Eqs. 19-27, dimensionless).
    foundation : Foundation or None
        The elastic foundation (None: rigid base).
    friction : FrictionLaw
        The friction law.
    """

    lam: float
    zeta: float
    gamma: float = 2.0
    foundation: Foundation | None = None
    friction: FrictionLaw = field(default_factory=CoulombFriction)

    def value(self, name: str) -> float:
        """The current value of parameter ``name`` (one of :data:`PARAMETERS`)."""
        check_parameter(self, name)
        if name in ("lam", "zeta", "gamma"):
            return float(getattr(self, name))
        if name == "delta":
            assert isinstance(self.friction, LinearFriction)
            return float(self.friction.delta)
        f = self.foundation
        assert f is not None
        return float({"K": f.stiffness_ratio, "M": f.mass_ratio, "zeta_a": f.damping_ratio}[name])

    def with_value(self, name: str, value: float) -> ContinuationSystem:
        """The same system with parameter ``name`` set to ``value``."""
        check_parameter(self, name)
        if name == "lam":
            return replace(self, lam=float(value))
        if name == "zeta":
            return replace(self, zeta=float(value))
        if name == "gamma":
            return replace(self, gamma=float(value))
        if name == "delta":
            return replace(self, friction=LinearFriction(float(value)))
        f = self.foundation
        assert f is not None
        if name == "K":
            return replace(self, foundation=replace(f, stiffness_ratio=float(value)))
        if name == "M":
            return replace(self, foundation=replace(f, mass_ratio=float(value)))
        return replace(self, foundation=replace(f, damping_ratio=float(value)))

    def build(self) -> tuple[Structure, Slider]:
        """The engine's structure and slider (``ValueError`` beyond the engine's range)."""
        structure = chain_structure(self.zeta, () if self.foundation is None else (self.foundation,))
        friction_range(self.lam, self.gamma)  # as simulate: 2 gamma lambda must not overflow
        return structure, Slider(self.lam, gamma=self.gamma, friction=self.friction)

    def check(self, name: str) -> None:
        """Refuse a parameter this system cannot be continued in (:func:`check_parameter`)."""
        check_parameter(self, name)

    def si_scales(self) -> tuple[float, float] | None:
        """None: the system is dimensionless (no seconds or metres)."""
        return None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the dimensionless groups, the foundation and the law."""
        f = self.foundation
        return {"lam": self.lam, "zeta": self.zeta, "gamma": self.gamma,
                "foundation": None if f is None else {
                    "M": f.mass_ratio, "K": f.stiffness_ratio, "zeta_a": f.damping_ratio},
                "friction": self.friction.describe()}


#: Parameters a machine (``--config``) can be continued in, with their SI units.
MACHINE_PARAMETERS = {"speed": "m/s", "load": "N", "mu_s": "1", "mu_k": "1"}


@dataclass(frozen=True)
class MachineSystem:
    """A machine in SI (any linear structure, contact on any DOF) continued in one of
    :data:`MACHINE_PARAMETERS`: belt speed (m/s), normal load (N) or a friction coefficient.

    The engine runs the contact-first twin of its dimensionless structure (the contact's own
    ``m_ref``, ``k_ref`` as the reference, :meth:`stickslip.model.machine.Machine.to_dimensionless`),
    so the dimensionless answers are converted with the scales of the machine at each
    parameter value (the length scale ``V / omega_n`` moves with the speed).
    """

    machine: Machine

    def check(self, name: str) -> None:
        """Refuse a parameter that is not one of :data:`MACHINE_PARAMETERS` (``ValueError``)."""
        if name not in MACHINE_PARAMETERS:
            raise ValueError(f"parameter {name!r} of a machine is not one of {', '.join(MACHINE_PARAMETERS)}")

    def value(self, name: str) -> float:
        """The machine's value of parameter ``name`` (SI)."""
        self.check(name)
        return float(getattr(self.machine, name))

    def with_value(self, name: str, value: float) -> MachineSystem:
        """The machine with parameter ``name`` set to ``value`` (SI; ``ValueError`` if invalid)."""
        self.check(name)
        m, v = self.machine, float(value)
        if name in ("speed", "load"):
            return MachineSystem(m.with_operating_point(**{name: v}))
        return MachineSystem(replace(m, mu_s=v) if name == "mu_s" else replace(m, mu_k=v))

    def build(self) -> tuple[Structure, Slider]:
        """The contact-first dimensionless structure and the slider of the contact."""
        structure, slider = self.machine.to_dimensionless()
        friction_range(slider.lam, slider.gamma)  # as simulate: 2 gamma lambda must not overflow
        return structure.contact_first()[0], slider

    @property
    def friction(self) -> FrictionLaw:
        """The dimensionless friction law at the machine's operating point."""
        return self.machine.slider().friction

    def si_scales(self) -> tuple[float, float]:
        """``(time_scale_s, length_scale_m)``: ``1/omega_n`` and ``V/omega_n`` of the contact."""
        ref = self.machine.reference_system()
        return float(ref.time_scale), float(ref.length_scale)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the machine in SI."""
        return {"machine": self.machine.to_dict()}


@dataclass(frozen=True)
class ScaledMachine:
    """A :class:`MachineSystem` whose parameter is measured in units of ``scale`` (SI).

    The pseudo-arclength tangent mixes the branch's dimensionless coordinates with the
    parameter: in SI a belt speed of 0.5 mm/s is 5e-4 while the coordinates are of order one, so
    every step advanced the speed by a hair (a 2-DOF machine took 800 steps and 221 s to cross
    0.1-2.5 mm/s, and stopped at the step bound). Continued in ``value / scale`` (``scale`` the
    larger end of the range) the two are of one size; :func:`continue_cycles` converts the
    branches back.
    """

    inner: MachineSystem
    scale: float

    def check(self, name: str) -> None:
        """As :meth:`MachineSystem.check`."""
        self.inner.check(name)

    def value(self, name: str) -> float:
        """The machine's value of ``name`` in units of ``scale``."""
        return self.inner.value(name) / self.scale

    def with_value(self, name: str, value: float) -> ScaledMachine:
        """The machine with ``name`` set to ``value * scale`` (SI)."""
        return ScaledMachine(self.inner.with_value(name, value * self.scale), self.scale)

    def build(self) -> tuple[Structure, Slider]:
        """As :meth:`MachineSystem.build`."""
        return self.inner.build()

    @property
    def friction(self) -> FrictionLaw:
        """As :attr:`MachineSystem.friction`."""
        return self.inner.friction

    def si_scales(self) -> tuple[float, float]:
        """As :meth:`MachineSystem.si_scales`."""
        return self.inner.si_scales()

    def to_dict(self) -> dict[str, Any]:
        """As :meth:`MachineSystem.to_dict`, with the scale."""
        return {**self.inner.to_dict(), "parameter_scale": self.scale}


#: Either kind of continued system (and a machine in a scaled parameter).
AnySystem = ContinuationSystem | MachineSystem | ScaledMachine


def check_parameter(system: ContinuationSystem, name: str) -> None:
    """Refuse a parameter the system cannot be continued in (``ValueError``, one line)."""
    if name not in PARAMETERS:
        raise ValueError(f"parameter {name!r} is not one of {', '.join(PARAMETERS)}")
    if name == "delta" and not isinstance(system.friction, LinearFriction):
        raise ValueError("parameter 'delta' needs the linear friction law (--friction linear:DELTA)")
    if name in ("K", "M", "zeta_a") and system.foundation is None:
        raise ValueError(f"parameter {name!r} needs a foundation (--dva), not the rigid base")


class StickSlipSection:
    """``G(b) = P^k(b) - b`` on the breakaway section, exact Jacobian."""

    kind = "stick-slip"

    def __init__(self, system: AnySystem, k: int, options: EngineOptions,
                 direction: int = SLIP_I) -> None:
        self.structure, self.slider = system.build()
        self.k = k
        self.pmap = ReturnMap(self.structure, self.slider, options, direction)
        self.dim = 2 * self.structure.n_dof - 2

    def residual(self, y: FloatArray) -> tuple[FloatArray, FloatArray] | None:
        if self.dim == 0:
            return (np.zeros(0), np.zeros((0, 0))) if self.pmap(np.zeros(0), self.k) is not None else None
        out = self.pmap.linearise(y, self.k)
        if out is None:
            return None
        pb, jac = out
        return pb - y, jac

    def gap(self, y: FloatArray) -> FloatArray | None:
        """``P^k(y) - y`` without the Jacobian."""
        py = self.pmap(y, self.k)
        return None if py is None else py - y

    def signature(self, y: FloatArray) -> tuple[int, ...] | None:
        return self.pmap.signature(y, self.k)

    def full_state(self, y: FloatArray) -> FloatArray:
        return self.pmap.state(y)

    def measure(self, y: FloatArray) -> tuple[float, float, float] | None:
        """Period, amplitude and stick ratio of the cycle, from a certifying run.

        Where the run's certificate is not given (next to a grazing, where the proof's ball
        shrinks to nothing) they are read off the run of the map itself, whose ``k``-th
        breakaway returns to the fixed point: the period is its time, the amplitude half the
        peak-to-peak of ``xi`` over it (extrema at the roots of ``xi'``), the stick ratio the
        share of stick phases.
        """
        n = self.structure.n_dof
        z = self.full_state(y)
        run = simulate(self.structure, self.slider, initial=InitialState(z[:n], z[n:]),
                       options=self.pmap.options, record=False)
        if run.verdict is Verdict.STICK_SLIP and run.period is not None and run.amplitude is not None:
            return float(run.period), float(run.amplitude), float(run.stick_ratio or 0.0)
        mapped = self.pmap.recorded_run(z, self.k)
        if mapped is None:
            return None
        result, times = mapped
        period = float(times[-1])
        xs = xi_extrema(result, period)
        seg_t = np.append(result.segment_times, np.inf)
        stuck = sum(max(0.0, min(float(seg_t[i + 1]), period) - float(seg_t[i]))
                    for i, m in enumerate(result.segment_modes)
                    if mode_kind_band(int(m))[0] == STICK and seg_t[i] < period)
        return period, 0.5 * (max(xs) - min(xs)), stuck / period


class SlipSection:
    """``G(y) = P(y) - y`` on the section of a velocity maximum, ``y = (xi', foundation)``."""

    kind = "slip-oscillation"

    def __init__(self, system: AnySystem, options: EngineOptions) -> None:
        self.structure, self.slider = system.build()
        st = self.structure
        self.n = st.n_dof
        self.dim = 2 * self.n - 1
        self.minv = np.linalg.inv(st.mass)
        self.bands = self.slider.friction.bands(float(self.slider.lam), float(self.slider.gamma))
        self.f_ref = float(self.slider.lam * self.slider.gamma)
        self.options = EngineOptions(t_max=options.t_max, max_events=min(
            100_000, 400 * len(self.bands[1]) + 400))
        self.last: tuple[float, float, float] | None = None

    def _force(self, v0: float) -> float:
        """Friction on the slider in slip-I in shifted coordinates, ``F(1 - xi') - gamma lambda``."""
        return float(evaluate_bands(self.bands, 1.0 - v0)) - self.f_ref

    def accel(self, z: FloatArray) -> FloatArray:
        n, st = self.n, self.structure
        f = np.zeros(n)
        f[0] = self._force(float(z[n]))
        return np.asarray(self.minv @ (f - st.damping @ z[n:] - st.stiffness @ z[:n]))

    def full_state(self, y: FloatArray) -> FloatArray:
        """The state with ``xi'' = 0`` (solved for ``xi``, linear in it)."""
        n, st = self.n, self.structure
        q = np.zeros(n)
        v = np.zeros(n)
        v[0] = y[0]
        q[1:], v[1:] = y[1:n], y[n:]
        # row 0 of M^-1 (f - C v - K q) = 0, linear in q0
        r = self.minv[0]
        rest = r @ (np.eye(n)[0] * self._force(v[0]) - st.damping @ v - st.stiffness @ q)
        coef = float(r @ st.stiffness[:, 0])
        q[0] = rest / coef
        return np.concatenate([q, v])

    def reduce(self, z: FloatArray) -> FloatArray:
        n = self.n
        return np.concatenate([z[n:n + 1], z[1:n], z[n + 1:]])

    def step(self, y: FloatArray) -> FloatArray | None:
        """The next velocity maximum (reduced), or None when the slider sticks or no maximum.

        Also keeps ``(period, amplitude, max velocity)`` of the run in :attr:`last`.
        """
        return self.first_maximum(self.full_state(y))

    def first_maximum(self, z0: FloatArray) -> FloatArray | None:
        """The first velocity maximum after ``tau = 0`` of the motion from the full state ``z0``
        (reduced), or None when the slider reaches the belt speed within three periods of the
        slowest mode or has no maximum."""
        n = self.n
        if not np.all(np.isfinite(z0)) or z0[n] >= 1.0:
            return None
        # a period of the slowest mode bounds the search for the next maximum
        omega = np.abs(np.linalg.eigvals(slip_matrix(self.structure, 0.0)).imag)
        omega = omega[omega > 1e-9]
        horizon = 3.0 * 2.0 * math.pi / float(omega.min()) if omega.size else 60.0
        run = simulate(self.structure, self.slider, initial=InitialState(z0[:n], z0[n:]),
                       options=self.options.with_t_max(horizon), record=True, run_to_t_max=True)
        if any(mode_kind_band(int(m))[0] != SLIP_I for m in np.unique(run.segment_modes)):
            # it sticks or slides faster than the belt: not a slip oscillation. Its phases, not
            # samples: an audit's orbit touched the belt between two of 400 samples, its next
            # "maximum" the stick's start (xi' = 1), and the multiplier at the grazing end of
            # a branch came out 1.37 for 1.74
            return None
        t_end = float(run.t_end)
        grid = np.linspace(0.0, t_end, 400)
        q, v, _ = run.state_at(grid)
        st = self.structure
        force = np.zeros_like(q)
        force[:, 0] = evaluate_bands(self.bands, 1.0 - v[:, 0]) - self.f_ref
        acc = ((force - v @ st.damping.T - q @ st.stiffness.T) @ self.minv.T)[:, 0]
        start = int(np.argmax(grid > 1e-6 * t_end + 1e-9))
        for i in range(max(start, 1), grid.size - 1):
            if acc[i] > 0.0 >= acc[i + 1]:
                t_peak = refined_root(lambda t: self._accel_at(run, t), grid[i], grid[i + 1])
                zq, zv, _ = run.state_at(np.array([t_peak]))
                z1 = np.concatenate([zq[0], zv[0]])
                x_ext = xi_extrema(run, t_peak)
                self.last = (t_peak, 0.5 * (max(x_ext) - min(x_ext)), float(z1[n]))
                return self.reduce(z1)
        return None

    def _accel_at(self, run: Any, t: float) -> float:
        q, v, _ = run.state_at(np.array([t]))
        return float(self.accel(np.concatenate([q[0], v[0]]))[0])

    def residual(self, y: FloatArray) -> tuple[FloatArray, FloatArray] | None:
        py = self.step(y)
        if py is None:
            return None
        last = self.last
        jac = np.zeros((self.dim, self.dim))
        for j in range(self.dim):
            h = 1e-6 * max(1.0, abs(float(y[j])))
            e = np.zeros(self.dim)
            e[j] = h
            plus, minus = self.step(y + e), self.step(y - e)
            if plus is not None and minus is not None:
                jac[:, j] = (plus - minus) / (2.0 * h)
            elif minus is not None:  # within h of grazing the belt: the one-sided difference
                jac[:, j] = (py - minus) / h
            elif plus is not None:
                jac[:, j] = (plus - py) / h
            else:
                return None
        self.last = last
        return py - y, jac

    def gap(self, y: FloatArray) -> FloatArray | None:
        """``P(y) - y`` without the Jacobian."""
        py = self.step(y)
        return None if py is None else py - y

    def signature(self, y: FloatArray) -> tuple[int, ...] | None:
        return (0,) if self.step(y) is not None else None

    def measure(self, y: FloatArray) -> tuple[float, float, float] | None:
        if self.step(y) is None or self.last is None:
            return None
        return self.last[0], self.last[1], 0.0


def xi_extrema(run: Any, t_end: float, points: int = 400) -> list[float]:
    """The slider's ``xi`` at the roots of ``xi'`` in ``[0, t_end]`` (and at the ends) of a
    recorded run (sign changes on a grid of ``points``, refined by Brent's method)."""
    grid = np.linspace(0.0, t_end, points)
    q, v, _ = run.state_at(grid)
    out = [float(q[0, 0]), float(q[-1, 0])]
    for i in range(grid.size - 1):
        if v[i, 0] * v[i + 1, 0] < 0.0:
            t = refined_root(lambda s: float(run.state_at(np.array([s]))[1][0, 0]), grid[i], grid[i + 1])
            out.append(float(run.state_at(np.array([t]))[0][0, 0]))
    return out


def refined_root(f: Callable[[float], float], a: float, b: float) -> float:
    from scipy.optimize import brentq

    return float(brentq(f, a, b, xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=200))
