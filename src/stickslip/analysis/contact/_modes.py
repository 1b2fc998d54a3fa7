"""The modes of a machine with its contact as affine systems ``z' = A z + c`` (SI units).

The equations are those of :mod:`stickslip.analysis.contact.engine` (its docstring). Every
quantity that the modes need (the normal force, the friction force, the relative velocity,
the event functions) is affine in the state and kept here as a row ``r`` of length
``d + 1``: its value at ``z`` is ``r[:d] . z + r[d]``.

State layout: ``q`` (n, m), ``q'`` (n, m/s), then with a Jenkins element its extension
``e = q_t - p`` (m) and, when the contact point has a mass, its velocity ``p'`` (m/s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.contact._events import AffineFlow
from stickslip.model.contact import check_contact_stiffness

FloatArray = NDArray[np.float64]

STICK, SLIP_FORWARD, SLIP_BACKWARD, SEPARATED = 0, 1, 2, 3
#: How results name the modes.
MODE_LABELS = {STICK: "stick", SLIP_FORWARD: "slip forward", SLIP_BACKWARD: "slip backward",
               SEPARATED: "separation"}
#: Relative velocity (in units of ``V``) below which a re-contact is taken at the belt speed.
VELOCITY_TOLERANCE = 1e-12
#: Relative normal force under which a re-contact by the damper is not retried.
FORCE_TOLERANCE = 1e-12


@dataclass(frozen=True)
class ModeSystem:
    """One mode: its exact flow, its affine quantities and its sliding equilibrium.

    ``normal``, ``belt_force`` and ``relative_velocity`` are affine rows: the normal force
    (N), the belt's force on the contact point (N; the stick force in stick) and
    ``V - p'`` (m/s). ``equilibrium`` is :func:`_equilibrium`'s (slip modes), else None.
    """

    mode: int
    flow: AffineFlow
    normal: FloatArray
    belt_force: FloatArray
    relative_velocity: FloatArray
    rows: tuple[tuple[FloatArray, str], ...]
    compression: FloatArray
    candidate: FloatArray
    equilibrium: tuple[NDArray[np.intp], FloatArray, FloatArray] | None

    def surfaces(self, z: FloatArray) -> tuple[FloatArray, FloatArray, list[str]]:
        """Event functions (normals, levels) positive while the mode holds, and their kinds.

        In separation after a lift-off by the damper the spring may still be compressed
        (``W - k_n q_n > 0``): then the damper's re-contact (``W - k_n q_n - c_n q_n'``
        positive again) and the spring's release (its free length passed, a switch to
        separation again) are watched; once outside, the spring's re-contact, and the
        damper's only while that force is still negative at ``z``.
        """
        tol = FORCE_TOLERANCE * abs(float(self.candidate[-1]))
        # without a damper only the spring lifts off, so a compression left at the start is the
        # located lift-off's rounding: the spring's re-contact is watched (at once, if need be)
        damper = any(k == "spring released" for _, k in self.rows)
        inside = damper and _value(self.compression, z) > tol
        watch = {"re-contact": not inside, "spring released": inside,
                 "re-contact by the damper": inside or _value(self.candidate, z) < -tol}
        rows = [(r, k) for r, k in self.rows if watch.get(k, True)]
        stacked = np.array([r for r, _ in rows])
        return stacked[:, :-1], stacked[:, -1], [k for _, k in rows]


def _value(row: FloatArray, z: FloatArray) -> float:
    return float(row[:-1] @ z + row[-1])


@dataclass(frozen=True)
class ContactSystem:
    """A machine with its contact, in SI units (see :mod:`stickslip.analysis.contact.engine`).

    Parameters
    ----------
    mass, damping, stiffness : ndarray, shape (n, n)
        The structure's own matrices, kg, N s/m, N/m.
    tangential_dof : int
        DOF along the belt.
    normal_dof : int or None
        DOF across the belt, positive away from it; None: a constant normal load.
    load, speed : float
        Preload ``W`` (N, > 0) and belt speed ``V`` (m/s, > 0).
    mu_s, mu_k : float
        Static and kinetic friction coefficients (``mu_s > mu_k >= 0``), dimensionless.
    normal_stiffness, normal_damping : float
        Contact spring ``k_n`` (N/m) and damper ``c_n`` (N s/m); used with ``normal_dof``.
    tangential_stiffness, tangential_damping : float
        Jenkins element ``k_t`` (N/m; None: rigid contact) and ``c_t`` (N s/m).
    contact_mass : float or None
        Mass of the contact point, kg; None: massless.
    """

    mass: FloatArray
    damping: FloatArray
    stiffness: FloatArray
    tangential_dof: int
    normal_dof: int | None
    load: float
    speed: float
    mu_s: float
    mu_k: float
    normal_stiffness: float = 0.0
    normal_damping: float = 0.0
    tangential_stiffness: float | None = None
    tangential_damping: float = 0.0
    contact_mass: float | None = None
    _modes: dict[int, ModeSystem] = field(default_factory=dict, init=False, compare=False,
                                          repr=False)

    def __post_init__(self) -> None:
        n = self.mass.shape[0]
        for name in ("mass", "damping", "stiffness"):
            value = getattr(self, name)
            if value.shape != (n, n) or not np.all(np.isfinite(value)):
                raise ValueError(f"{name} must be a finite {n} x {n} matrix")
        if not 0 <= self.tangential_dof < n:
            raise ValueError(f"contact_dof = {self.tangential_dof} is beyond the {n} DOF")
        if self.normal_dof is not None and (not 0 <= self.normal_dof < n
                                            or self.normal_dof == self.tangential_dof):
            raise ValueError(f"normal_dof = {self.normal_dof} must be another DOF of the {n}")
        if self.normal_dof is not None and not self.normal_stiffness > 0.0:
            raise ValueError("a normal DOF needs a positive normal_stiffness (N/m)")
        if not (self.load > 0.0 and self.speed > 0.0):
            raise ValueError("load and speed must be positive")
        if not self.mu_s > self.mu_k >= 0.0:
            raise ValueError(f"need mu_s > mu_k >= 0 (got mu_s = {self.mu_s}, mu_k = {self.mu_k})")
        check_contact_stiffness(self.normal_stiffness, self.tangential_stiffness, self.stiffness)
        if self.tangential_stiffness is not None and self.contact_mass is None \
                and self.tangential_damping == 0.0 and self.normal_dof is not None \
                and self.normal_damping > 0.0:
            raise ValueError("a massless undamped Jenkins element with a normal damper is not "
                             "supported (its slip extension would follow the normal "
                             "acceleration); give tangential_damping or mass")

    @property
    def n_dof(self) -> int:
        """Number of structural DOF."""
        return int(self.mass.shape[0])

    @property
    def n_state(self) -> int:
        """Length of the state vector."""
        extra = 0 if self.tangential_stiffness is None else (
            1 if self.contact_mass is None else 2)
        return 2 * self.n_dof + extra

    @property
    def omega_ref(self) -> float:
        """``sqrt(K[t, t] / M[t, t])``, rad/s: the tangential DOF's own natural frequency."""
        t = self.tangential_dof
        return math.sqrt(max(float(self.stiffness[t, t]), 1e-300) / float(self.mass[t, t]))

    @property
    def state_scale(self) -> FloatArray:
        """Per-entry scale of the state: lengths in ``V / omega_ref``, velocities in ``V``."""
        n, length = self.n_dof, self.speed / self.omega_ref
        scale = np.concatenate([np.full(n, length), np.full(n, self.speed)])
        extra = [length, self.speed][: self.n_state - 2 * n]
        return np.concatenate([scale, extra])

    def startup_state(self) -> FloatArray:
        """Every spring at its natural length (the contact carrying ``W``), the contact at ``V``."""
        z = np.zeros(self.n_state)
        z[self.n_dof + self.tangential_dof] = self.speed
        if self.contact_mass is not None:
            z[-1] = self.speed
        return z

    def at(self, *, speed: float | None = None, load: float | None = None,
           mu_s: float | None = None, mu_k: float | None = None) -> ContactSystem:
        """The same machine at another operating point (belt speed m/s, preload N, friction).

        A new system with its own mode cache (the modes depend on every one of these).
        """
        return replace(self, speed=self.speed if speed is None else float(speed),
                       load=self.load if load is None else float(load),
                       mu_s=self.mu_s if mu_s is None else float(mu_s),
                       mu_k=self.mu_k if mu_k is None else float(mu_k))

    def mode(self, mode: int) -> ModeSystem:
        """The affine system of ``mode`` (built once)."""
        if mode not in self._modes:
            self._modes[mode] = _build_mode(self, mode)
        return self._modes[mode]

    def normal_force(self, z: FloatArray, mode: int) -> float:
        """``N`` at ``z`` in ``mode``, N (0 in separation)."""
        return _value(self.mode(mode).normal, z)

    def enter(self, mode: int, z: FloatArray) -> FloatArray:
        """The state as ``mode`` starts: the constraints of stick and of an undamped point set."""
        z = np.array(z, dtype=float)
        n, t = self.n_dof, self.tangential_dof
        if mode == STICK:
            if self.tangential_stiffness is None:
                z[n + t] = self.speed
            elif self.contact_mass is not None:
                z[-1] = self.speed
        elif self.tangential_stiffness is not None and self.contact_mass is None \
                and self.tangential_damping == 0.0:
            s = {SLIP_FORWARD: 1.0, SLIP_BACKWARD: -1.0}.get(mode, 0.0)
            z[2 * n] = -s * self.mu_k * _value(self.mode(mode).normal, z) / self.tangential_stiffness
        return z

    def initial_mode(self, z: FloatArray) -> int:
        """The mode of a state: separation off the belt, else by the relative velocity."""
        if self.normal_dof is not None and (_value(self.mode(STICK).normal, z) <= 0.0
                                            or _value(self.mode(STICK).compression, z) <= 0.0):
            return SEPARATED
        return self._contact_mode(z, SEPARATED)

    def switch(self, mode: int, kind: str, z: FloatArray) -> tuple[int, FloatArray]:
        """The mode after the event ``kind`` at ``z`` in ``mode``, and the state it starts from."""
        if kind == "breakaway forward":
            new = SLIP_FORWARD
        elif kind == "breakaway backward":
            new = SLIP_BACKWARD
        elif kind in ("lift-off", "spring released"):
            new = SEPARATED
        elif kind == "belt speed":
            new = self._stick_or_slip(z)
        elif kind == "re-contact by the damper" and _value(self.mode(SEPARATED).compression,
                                                           z) <= 0.0:
            new = SEPARATED  # the damper would push, but the spring is not yet compressed
        else:
            new = self._contact_mode(z, mode)
        return new, self.enter(new, z)

    def _contact_mode(self, z: FloatArray, velocity_mode: int) -> int:
        """Slip in the direction of ``V - p'`` (as ``velocity_mode`` gives it), or stick."""
        v_r = _value(self.mode(velocity_mode).relative_velocity, z)
        if abs(v_r) > VELOCITY_TOLERANCE * self.speed:
            slip = SLIP_FORWARD if v_r > 0.0 else SLIP_BACKWARD
            if self._consistent(slip, z):
                return slip
        return self._stick_or_slip(z)

    def _stick_or_slip(self, z: FloatArray) -> int:
        """At the belt speed: stick if the stick force is within ``mu_s N``, else slip its way.

        A slip whose own relative velocity would at once point the other way (an undamped
        massless element at a re-contact, where ``N`` and the cone start from zero) cannot
        start: the contact point then sticks (Filippov's choice), rather than switching
        between the two slips at one instant.
        """
        stick = self.mode(STICK)
        z = self.enter(STICK, z)
        force, normal = _value(stick.belt_force, z), _value(stick.normal, z)
        if abs(force) <= self.mu_s * normal:
            return STICK
        slip = SLIP_FORWARD if force > 0.0 else SLIP_BACKWARD
        return slip if self._consistent(slip, z) else STICK

    def _consistent(self, slip: int, z: FloatArray) -> bool:
        """True when ``slip``'s relative velocity has its sign at ``z`` (or moves into it)."""
        ms = self.mode(slip)
        z = self.enter(slip, z)
        sign = 1.0 if slip == SLIP_FORWARD else -1.0
        v_r = sign * _value(ms.relative_velocity, z)
        if abs(v_r) > VELOCITY_TOLERANCE * self.speed:
            return v_r > 0.0
        return sign * float(ms.relative_velocity[:-1] @ (ms.flow.a @ z + ms.flow.c)) >= 0.0


def _build_mode(sys: ContactSystem, mode: int) -> ModeSystem:
    """The affine system, quantities and events of ``mode`` (module and engine docstrings)."""
    n, d = sys.n_dof, sys.n_state
    t, nd = sys.tangential_dof, sys.normal_dof
    kn, cn, load, speed = sys.normal_stiffness, sys.normal_damping, sys.load, sys.speed
    jenkins, massive = sys.tangential_stiffness is not None, sys.contact_mass is not None
    in_contact = mode != SEPARATED
    s = {SLIP_FORWARD: 1.0, SLIP_BACKWARD: -1.0}.get(mode, 0.0)

    def unit(i: int, value: float = 1.0) -> FloatArray:
        row = np.zeros(d + 1)
        row[i] = value
        return row

    const = unit(d)
    compression = unit(d, load) - (unit(nd, kn) if nd is not None else 0.0)
    candidate = compression - (unit(n + nd, cn) if nd is not None else 0.0)
    normal = candidate if in_contact else 0.0 * const
    force = np.zeros((n, d + 1))
    force[:, :n], force[:, n:2 * n] = -sys.stiffness, -sys.damping
    if nd is not None:
        force[nd] -= (unit(nd, kn) + unit(n + nd, cn)) if in_contact else load * const
    slip_force = s * sys.mu_k * normal
    kt, ct = sys.tangential_stiffness or 0.0, sys.tangential_damping
    ie = 2 * n
    v_point = None
    if jenkins:
        v_point = unit(ie + 1) if massive else (speed * const if mode == STICK else None)
        element = (-(unit(ie, kt) + ct * (unit(n + t) - v_point)) if v_point is not None
                   else slip_force)  # the element's force on the slider
        force[t] += element
    elif mode != STICK:
        force[t] += slip_force
    rigid_stick = mode == STICK and not jenkins
    if rigid_stick:  # the belt force keeps q_t'' = 0: [[M, -e_t], [e_t^T, 0]] [q''; F] = [f; 0]
        kkt = np.zeros((n + 1, n + 1))
        kkt[:n, :n], kkt[t, n], kkt[n, t] = sys.mass, -1.0, 1.0
        sol = np.linalg.solve(kkt, np.vstack([force, np.zeros(d + 1)]))
        acc, belt = sol[:n], sol[n]
        acc[t] = 0.0
    else:
        acc = np.linalg.solve(sys.mass, force)
        belt = element if jenkins and mode == STICK else slip_force
    rows = np.zeros((d, d + 1))
    rows[:n, n:2 * n] = np.eye(n)
    rows[n:2 * n] = acc
    if jenkins:
        if massive:
            assert v_point is not None
            rows[ie] = unit(n + t) - v_point
            if mode != STICK:
                rows[ie + 1] = (slip_force - element) / sys.contact_mass  # type: ignore[operator]
        elif mode == STICK:
            rows[ie] = unit(n + t) - speed * const
        elif ct > 0.0:
            rows[ie] = (-slip_force - unit(ie, kt)) / ct
        elif mode != SEPARATED and nd is not None:  # e = -s mu_k N / k_t follows N
            rows[ie] = -s * sys.mu_k * (-unit(n + nd, kn) - cn * acc[nd]) / kt
        v_point = unit(n + t) - rows[ie] if v_point is None else v_point
    relative = speed * const - (unit(n + t) if v_point is None else v_point)
    events: list[tuple[FloatArray, str]] = []
    if mode == STICK:
        events += [(sys.mu_s * normal - belt, "breakaway forward"),
                   (sys.mu_s * normal + belt, "breakaway backward")]
    elif mode != SEPARATED:
        events.append((s * relative, "belt speed"))
    if nd is not None and in_contact:  # N = 0, or (with a damper) the spring at its length
        events += [(normal, "lift-off")] + ([(compression, "lift-off")] if cn > 0.0 else [])
    elif nd is not None:
        events += [(-compression, "re-contact")] + (
            [(-candidate, "re-contact by the damper"), (compression, "spring released")]
            if cn > 0.0 else [])
    flow = AffineFlow(rows[:, :d], rows[:, d])
    return ModeSystem(mode, flow, normal, belt, relative, tuple(events), compression, candidate,
                      _equilibrium(flow) if s != 0.0 else None)


def _equilibrium(flow: AffineFlow) -> tuple[NDArray[np.intp], FloatArray, FloatArray] | None:
    """``(moving, V, V^-1)`` of a slip mode whose moving part is Hurwitz, else None.

    ``moving`` are the state entries whose rows of ``A`` and ``c`` are not all zero (an
    undamped massless Jenkins element keeps its extension constant while it slips: that
    entry is a parameter of the mode, not a neutral direction); ``A`` restricted to them is
    ``V Lambda V^-1``.
    """
    moving = np.flatnonzero(np.any(flow.a != 0.0, axis=1) | (flow.c != 0.0))
    a = flow.a[np.ix_(moving, moving)]
    values, vectors = np.linalg.eig(a)
    if not np.all(values.real < 0.0):
        return None
    try:
        inverse = np.linalg.inv(vectors)
    except np.linalg.LinAlgError:
        return None
    return moving, vectors, inverse
