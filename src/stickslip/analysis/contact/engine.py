r"""Exact time histories of a machine with its contact: normal load, separation, compliance.

The machine (SI units throughout): the structure ``M q'' + C q' + K q = f`` with its own
matrices, the tangential DOF ``t`` (``contact_dof``, along the belt, which moves at ``V`` in
its positive direction) and optionally the normal DOF ``n`` (``normal_dof``, positive away
from the belt). ``q`` is measured from where every structural spring is at its natural
length and the contact spring carries exactly the preload ``W`` (``load``).

Normal force
    In contact, ``N = W - k_n q_n - c_n q_n'`` and the force on ``n`` is ``-(k_n q_n +
    c_n q_n')`` (the preload and the contact's ``W`` cancel). In **separation** the contact
    carries nothing: no friction, and the force on ``n`` is the preload ``-W`` alone. The
    contact is unilateral: the force is ``max(0, W - k_n q_n - c_n q_n')`` while the spring
    is compressed (``q_n < W / k_n``) and zero otherwise. It separates when ``N`` reaches zero
    or (with a damper) when the spring reaches its free length (lift-off), and re-engages when
    both hold again: the spring compressed and ``W - k_n q_n - c_n q_n' > 0``.
    The re-contact law: **no impact**. The contact is a spring, so the velocities are
    continuous through re-contact and the normal force starts from ``max(0, -c_n q_n')``
    (zero without a contact damper); no restitution coefficient is needed or used. Without a
    normal DOF ``N = W``.

Friction (Coulomb, ``mu_s > mu_k``)
    Rigid contact: in stick the tangential DOF moves with the belt (``q_t' = V``) and the
    stick force ``F`` (the belt's force on it that keeps ``q_t'' = 0``) must stay within
    ``|F| <= mu_s N``; in slip forward (``v_r = V - q_t' > 0``) the friction is ``+mu_k N``,
    in slip backward ``-mu_k N``. Tangential compliance (a Jenkins element): a contact point
    joined to the slider by the spring ``k_t`` and damper ``c_t`` carries the friction; its
    extension ``e = q_t - p`` is a state. The point sticks to the belt (``p' = V``) while the
    element's force stays within ``mu_s N`` and slips at ``mu_k N`` otherwise. A massless
    point slips with ``k_t e + c_t e' = -s mu_k N`` (a first-order law for ``e``; with
    ``c_t = 0`` the extension is slaved to ``-s mu_k N / k_t`` and jumps at breakaway); a
    point of mass ``m_c`` is a DOF, ``m_c p'' = F_belt + k_t e + c_t e'``.

Every mode (stick, slip forward, slip backward, separation) is affine in the state,
``z' = A z + c``, and is solved exactly with the matrix exponential of the augmented system.
Events are found on the exact flow by the graze-proof search of
:mod:`stickslip.analysis.contact._events`; their kinds: ``breakaway forward`` and ``breakaway
backward`` (``F = +-mu_s N`` in stick), ``belt speed`` (``v_r = 0`` in slip: stick when the
stick force is within ``mu_s N``, else slip the other way), ``lift-off`` (``N = 0``),
``re-contact`` (the spring compressed again), ``re-contact by the damper`` (``N``
positive again while the spring is still compressed; outside it, no re-contact yet) and
``spring released`` (in separation, the spring passes its free length: nothing changes but
the re-contact watched next).

Verdicts
    A periodic motion is recognised when the state at an event (a breakaway, a lift-off, ...)
    repeats the state at one of the previous :data:`MAX_PERIOD` events of the same kind
    within :data:`REPEAT_TOLERANCE` (relative, lengths in ``V / omega_ref`` and velocities in
    ``V``): ``stick-slip`` when that period holds a stick phase, ``slip-oscillation`` when it
    does not (a slip-separation cycle, the sprag-slip and squeal regime). This is observed,
    not proven: no contraction bound is checked. ``steady-sliding`` when, in a slip mode whose
    matrix is Hurwitz, the state is so close to the mode's equilibrium ``z*`` that the
    eigenvector bound ``|g(z(t)) - g(z*)| <= sum_k |(a V)_k| max_k |(V^-1 (z - z*))_k|``
    (``A = V Lambda V^-1``, ``|exp(lambda_k t)| <= 1``) keeps every event function of the mode
    away from zero for all later time; the eigenvectors are floating-point, so the bound holds
    up to their rounding. ``undetermined`` when the horizon or a budget ends the run first.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.blas_threads import one_blas_thread
from stickslip.analysis.contact._events import (
    Found,
    SampleBudgetExhausted,
    Settled,
    first_event,
)
from stickslip.analysis.contact._modes import (
    MODE_LABELS,
    SLIP_BACKWARD,
    SLIP_FORWARD,
    STICK,
    ContactSystem,
    ModeSystem,
)
from stickslip.analysis.verdict import Verdict

if TYPE_CHECKING:
    from stickslip.model.contact import Contact
    from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]

__all__ = ["MODE_LABELS", "ContactEvent", "ContactRun", "ContactSystem", "contact_system",
           "simulate_contact"]

#: Breakaway states compared with the newest one (periods of up to this many stick phases).
MAX_PERIOD = 8
#: Relative distance (balanced state norm) under which two breakaway states are the same.
REPEAT_TOLERANCE = 1e-9
#: Looser tolerance under which a divisor of a matched period is taken instead (see ``_repeat``).
DIVISOR_TOLERANCE = 1e-6
#: Default horizon in natural times ``1 / omega_ref`` of the tangential DOF.
DEFAULT_HORIZON = 5000.0
#: Most mode switches at one instant before the run stops (accumulating switches).
MAX_AT_ONE_INSTANT = 20
#: Events closer than this, relative to the time, are at one instant: a few units of double
#: precision's rounding of ``t`` (a lift-off and a re-contact 1e-18 s apart at t = 2 ms are
#: the rounding of one event, not a motion with a period).
SAME_INSTANT = 1e-12
#: Default budget of sampled states over the whole run.
MAX_SAMPLES = 20_000_000


@dataclass(frozen=True)
class ContactEvent:
    """One mode switch: time (s), what happened, and the modes before and after."""

    t: float
    kind: str
    before: int
    after: int

    def to_dict(self) -> dict[str, Any]:
        """``t_s``, ``kind``, ``from``, ``to`` (mode labels)."""
        return {"t_s": self.t, "kind": self.kind, "from": MODE_LABELS[self.before],
                "to": MODE_LABELS[self.after]}


@dataclass(frozen=True)
class ContactRun:
    """A time history of :func:`simulate_contact`.

    Attributes
    ----------
    system : ContactSystem
        The machine.
    verdict : Verdict
        ``stick-slip``, ``slip-oscillation``, ``steady-sliding`` or ``undetermined``.
    certificate : str
        How the verdict was decided (or why there is none).
    period_s : float or None
        Period of the repeating motion, s.
    amplitude_m : float or None
        Half the peak-to-peak displacement of the tangential DOF over that period, m.
    separated : bool
        True when the contact lifted off at least once.
    events : tuple of ContactEvent
        Every mode switch.
    segment_times, segment_modes, segment_states : ndarray
        Start time (s), mode and state of every phase; ``t_end`` closes the last.
    t_end : float
        End of the run, s.
    """

    system: ContactSystem
    verdict: Verdict
    certificate: str
    period_s: float | None
    amplitude_m: float | None
    separated: bool
    events: tuple[ContactEvent, ...]
    segment_times: FloatArray
    segment_modes: NDArray[np.int64]
    segment_states: FloatArray
    t_end: float
    samples: int = field(default=0, compare=False)

    def state_at(self, times: FloatArray) -> tuple[FloatArray, NDArray[np.int64]]:
        """Exact states (rows) and modes at ``times`` (s, within ``[0, t_end]``)."""
        times = np.asarray(times, dtype=float)
        index = np.clip(np.searchsorted(self.segment_times, times, side="right") - 1, 0, None)
        out = np.empty((times.size, self.segment_states.shape[1]))
        for seg in np.unique(index):
            flow = self.system.mode(int(self.segment_modes[seg])).flow
            z0, t0 = self.segment_states[seg], float(self.segment_times[seg])
            picked = np.flatnonzero(index == seg)
            picked = picked[np.argsort(times[picked], kind="stable")]
            out[picked[0]] = flow.at(z0, float(times[picked[0]]) - t0)
            steps = np.diff(times[picked])
            if steps.size and np.all(np.abs(steps - steps[0]) <= 1e-12 * abs(steps[0])):
                # a uniform grid: one exponential, powered by products (a few ulp each)
                step = flow.propagator(float(steps[0]))
                n_s = z0.size
                for j_prev, j in itertools.pairwise(picked):
                    out[j] = step[:n_s, :n_s] @ out[j_prev] + step[:n_s, n_s]
            else:
                for j in picked[1:]:
                    out[j] = flow.at(z0, float(times[j]) - t0)
        return out, self.segment_modes[index]

    def history(self, times: FloatArray) -> dict[str, list[Any]]:
        """The time history at ``times`` (s): displacements (m), velocities, normal force (N)."""
        z, modes = self.state_at(times)
        sys = self.system
        out: dict[str, list[Any]] = {
            "t_s": [float(t) for t in times],
            "tangential_m": z[:, sys.tangential_dof].tolist(),
            "tangential_velocity_m_s": z[:, sys.n_dof + sys.tangential_dof].tolist(),
            "normal_force_N": [sys.normal_force(row, int(m)) for row, m in zip(z, modes, strict=True)],
            "mode": [MODE_LABELS[int(m)] for m in modes]}
        if sys.normal_dof is not None:
            out["normal_m"] = z[:, sys.normal_dof].tolist()
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON answer: verdict, certificate, period, amplitude, separation, events."""
        kinds: dict[str, int] = {}
        for event in self.events:
            kinds[event.kind] = kinds.get(event.kind, 0) + 1
        return {"verdict": self.verdict.value, "certificate": self.certificate,
                "period_s": self.period_s, "amplitude_m": self.amplitude_m,
                "separated": self.separated, "t_end_s": self.t_end,
                "n_events": len(self.events), "event_counts": kinds,
                "initial_mode": MODE_LABELS[int(self.segment_modes[0])] if len(self.segment_modes)
                else None,
                "events": [e.to_dict() for e in self.events[-20:]],
                "engine": "exact piecewise-affine (matrix exponential) with the contact"}


def start_description(mode: str | None) -> str:
    """How a run starts from the start-up state, in words.

    The start-up state has every spring at its natural length and the contact at the belt
    speed; it is stuck unless holding it there would take more than ``mu_s N`` (the dampers'
    force at the belt speed), in which case it slips at once.

    Parameters
    ----------
    mode : str or None
        The run's first mode (``initial_mode`` of :meth:`ContactRun.to_dict`); None for stuck.

    Returns
    -------
    str
        One line for the ``start`` row of a run's summary (CLI and app).
    """
    where = "the start-up state (springs at their natural length, the contact at the belt speed)"
    if mode is None or mode == "stick":
        return f"{where}, stuck to the belt"
    if mode == "separation":
        return f"{where}, off the belt"
    return (f"{where}, in {mode} at once: sticking would take more than mu_s N "
            "(the dampers' force at the belt speed)")


def contact_system(machine: Machine, contact: Contact | None, *,
                   normal_dof: int | None = None) -> ContactSystem:
    """The :class:`ContactSystem` of a machine and its contact (Coulomb friction only).

    Parameters
    ----------
    machine : Machine
        Structure (SI), ``contact_dof``, ``mu_s``, ``mu_k``, ``load`` (N), ``speed`` (m/s).
    contact : Contact or None
        Normal DOF, contact springs and Jenkins element.
    normal_dof : int, optional
        Index of the normal DOF in ``machine``'s matrices when they were reduced.

    Returns
    -------
    ContactSystem
        The machine's matrices (SI), its operating point and the contact's springs.

    Raises
    ------
    ValueError
        A friction law other than Coulomb (its slip force would not be affine in the state).
    """
    if machine.friction.law != "coulomb":
        raise ValueError(f"[friction] law = {machine.friction.law!r}: with a [contact] the time "
                         "history takes the Coulomb law (mu_s, mu_k) only in this version")
    index = normal_dof if normal_dof is not None else (
        None if contact is None else contact.normal_dof)
    return ContactSystem(
        np.asarray(machine.mass, float), np.asarray(machine.damping, float),
        np.asarray(machine.stiffness, float), machine.contact_dof, index,
        load=machine.load, speed=machine.speed, mu_s=machine.mu_s, mu_k=machine.mu_k,
        normal_stiffness=0.0 if contact is None or contact.normal_stiffness is None
        else contact.normal_stiffness,
        normal_damping=0.0 if contact is None else contact.normal_damping,
        tangential_stiffness=None if contact is None else contact.tangential_stiffness,
        tangential_damping=0.0 if contact is None else contact.tangential_damping,
        contact_mass=None if contact is None else contact.mass)


@one_blas_thread
def simulate_contact(system: ContactSystem, *, t_max: float | None = None,
                     max_events: int = 100_000, max_samples: int = MAX_SAMPLES,
                     initial: FloatArray | None = None) -> ContactRun:
    """One exact time history of a machine with its contact, from the startup state.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).
    t_max : float, optional
        Horizon, s (default :data:`DEFAULT_HORIZON` natural times of the tangential DOF).
    max_events : int
        Bound on mode switches.
    max_samples : int
        Bound on sampled states (the work of the event search).
    initial : ndarray, optional
        Initial state (``q``, ``q'``, then the Jenkins extension and the point's velocity);
        default :meth:`ContactSystem.startup_state` (all springs at their natural length, the
        contact preloaded, the contact moving with the belt, in stick).

    Returns
    -------
    ContactRun
    """
    horizon = DEFAULT_HORIZON / system.omega_ref if t_max is None else float(t_max)
    if not (math.isfinite(horizon) and horizon > 0.0):
        raise ValueError(f"t_max = {t_max!r} must be a positive number of seconds")
    if max_events < 1 or max_samples < 1:
        raise ValueError("max_events and max_samples must be at least 1")
    z = system.startup_state() if initial is None else np.array(initial, dtype=float)
    if z.shape != (system.n_state,) or not np.all(np.isfinite(z)):
        raise ValueError(f"initial state must be {system.n_state} finite numbers")
    mode = system.initial_mode(z)
    z = system.enter(mode, z)
    t, used, instant = 0.0, 0, 0
    events: list[ContactEvent] = []
    seg: tuple[list[float], list[int], list[FloatArray]] = ([], [], [])
    returns: dict[str, list[tuple[float, FloatArray]]] = {}
    verdict, certificate, period, amplitude = Verdict.UNDETERMINED, "", None, None
    while True:
        ms = system.mode(mode)
        _record(seg, t, mode, z)
        if len(events) >= max_events:
            certificate = f"maximum number of events ({max_events}) reached; increase max_events"
            break
        normals, levels, kinds = ms.surfaces(z)
        stop = _settled_check(ms, normals, levels) if mode in (SLIP_FORWARD, SLIP_BACKWARD) else None
        try:
            found = first_event(ms.flow, z, normals, levels, horizon - t,
                                max_samples=max_samples - used, stop=stop)
        except RuntimeError as exc:
            reason = str(exc)
            if isinstance(exc, SampleBudgetExhausted):  # no event before exc.dt: time reached
                t, used = t + exc.dt, used + exc.samples
                reason = f"sample budget of {max_samples} exhausted at t = {t:.6g} s"
            certificate = (f"{reason}: no verdict (a shorter horizon, t_max or --t-max, or a "
                           "less stiff contact needs fewer samples)")
            break
        used += found.samples
        if isinstance(found, Settled) or (stop is not None and not isinstance(found, Found)
                                          and stop(found.z)):
            t += found.dt if isinstance(found, Settled) else horizon - t
            verdict = Verdict.STEADY_SLIDING
            certificate = (f"steady sliding: at t = {t:.6g} s the state is within the "
                           "eigenvector bound of the sliding equilibrium that keeps every event "
                           "surface out of reach for all later time")
            break
        if not isinstance(found, Found):
            t = horizon
            certificate = "time horizon reached before a verdict; increase t_max"
            break
        t += found.dt
        kind = kinds[found.index]
        new_mode, z = system.switch(mode, kind, found.z)
        events.append(ContactEvent(t, kind, mode, new_mode))
        instant = instant + 1 if found.dt <= SAME_INSTANT * t else 0
        if instant > MAX_AT_ONE_INSTANT:
            certificate = (f"{instant} mode switches at t = {t:.9g} s without time passing (the "
                           "modes accumulate there); no verdict")
            break
        previous = returns.setdefault(kind, [])
        matched = _repeat(system, previous, z)
        repeat, within = matched if matched is not None else (None, REPEAT_TOLERANCE)
        if repeat is not None and t - previous[-repeat][0] <= SAME_INSTANT * t:
            repeat = None  # the same instant: not a period
        previous.append((t, z.copy()))
        if repeat is not None:
            period = t - previous[-1 - repeat][0]
            sticks = any(e.after == STICK for e in events if e.t > t - period)
            verdict = Verdict.STICK_SLIP if sticks else Verdict.SLIP_OSCILLATION
            certificate = (f"{verdict.value} observed, not proven: the state at the {kind} at "
                           f"t = {t:.6g} s repeats the one {repeat} {kind} event(s) earlier "
                           f"within {within:g} (relative)")
            _record(seg, t, new_mode, z)
            break
        mode = new_mode
    run = ContactRun(system, verdict, certificate, period, None,
                     any(e.kind == "lift-off" for e in events), tuple(events),
                     np.array(seg[0]), np.array(seg[1], dtype=np.int64), np.array(seg[2]), t, used)
    if period is not None:
        amplitude = _amplitude(run, t - period, t)
        run = ContactRun(**{**run.__dict__, "amplitude_m": amplitude})
    return run


def _record(seg: tuple[list[float], list[int], list[FloatArray]], t: float, mode: int,
            z: FloatArray) -> None:
    """Append a phase start (time, mode, state) to the run's segments."""
    seg[0].append(t)
    seg[1].append(mode)
    seg[2].append(z.copy())


def _repeat(system: ContactSystem, breakaways: list[tuple[float, FloatArray]],
            z: FloatArray) -> tuple[int, float] | None:
    """``(p, tolerance)`` when ``z`` repeats the state ``p`` events of its kind back (1..MAX_PERIOD).

    A state converging on a cycle along complex or near -1 multipliers can meet the
    tolerance ``p`` events back before it meets it one cycle back (seen on the brake pad at
    1 m/s: states 2e-9 apart, a match eight cycles back first). So once lag ``p`` matches,
    every proper divisor ``d`` of ``p`` is tried with the looser :data:`DIVISOR_TOLERANCE`:
    a distinct period-``p`` orbit has states ``d`` events apart that differ at the scale of
    the motion, far above it, while a settling period-``d`` motion meets it.
    """
    scale = system.state_scale
    size = float(np.linalg.norm(z / scale))

    def mismatch(p: int) -> float:
        return float(np.linalg.norm((z - breakaways[-p][1]) / scale))

    for p in range(1, min(MAX_PERIOD, len(breakaways)) + 1):
        if mismatch(p) <= REPEAT_TOLERANCE * size:
            for d in range(1, p):
                if p % d == 0 and mismatch(d) <= DIVISOR_TOLERANCE * size:
                    return d, DIVISOR_TOLERANCE
            return p, REPEAT_TOLERANCE
    return None


def _settled_check(ms: ModeSystem, normals: FloatArray, levels: FloatArray) -> Any:
    """``stop(z)``: True when the slip mode's events cannot be reached from ``z`` any more.

    The entries that do not move in this mode are held at their values at ``z``; the moving
    ones relax to the equilibrium ``z*`` with modal amplitudes that never grow (Hurwitz).
    """
    if ms.equilibrium is None:
        return None
    moving, vectors, inverse = ms.equilibrium
    a, c = ms.flow.a, ms.flow.c
    a_moving = a[np.ix_(moving, moving)]
    reach = np.abs(normals[:, moving] @ vectors).sum(axis=1)

    def stop(z: FloatArray) -> bool:
        z_star = z.copy()
        z_star[moving] = np.linalg.solve(a_moving, -(c[moving] + a[moving] @ z
                                                     - a_moving @ z[moving]))
        g_star = normals @ z_star + levels
        modal = float(np.max(np.abs(inverse @ (z[moving] - z_star[moving]))))
        return bool(np.all(g_star > 0.0) and np.all(reach * modal < g_star))

    return stop


def _amplitude(run: ContactRun, t0: float, t1: float) -> float:
    """Half the peak-to-peak displacement of the tangential DOF over ``[t0, t1]``, m.

    The exact flow is sampled densely (a step of ``1/50`` of the fastest mode's natural
    time) and each sampled extremum is refined by a bounded scalar search on the exact flow.
    """
    from scipy.optimize import minimize_scalar

    sys = run.system
    rate = max(ms.flow.norm for ms in (sys.mode(m) for m in set(run.segment_modes.tolist())))
    count = min(200_000, max(400, math.ceil((t1 - t0) * rate * 50.0 / (2.0 * math.pi))))
    times = np.linspace(t0, t1, count)
    q = run.state_at(times)[0][:, sys.tangential_dof]
    dt = times[1] - times[0]

    def refine(j: int, sign: float) -> float:
        a, b = max(t0, times[j] - dt), min(t1, times[j] + dt)
        res = minimize_scalar(lambda s: -sign * float(run.state_at(np.array([s]))[0][0, sys.tangential_dof]),
                              bounds=(a, b), method="bounded", options={"xatol": 1e-14 * t1})
        return max(sign * float(q[j]), -float(res.fun))

    top = refine(int(np.argmax(q)), 1.0)
    bottom = -refine(int(np.argmin(q)), -1.0)
    return 0.5 * (top - bottom)
