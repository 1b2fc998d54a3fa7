r"""The attractors of a machine with its contact, reached from a few deterministic starts.

``stickslip cycles --config`` for a machine with a ``[contact]`` (normal DOF, separation, a
Jenkins element). Each start is one run of the exact contact engine
(:func:`~stickslip.analysis.contact.engine.simulate_contact`) to its verdict. The starts
(:func:`contact_starts`, always 8):

* the **start-up** state (every spring at its natural length, the contact preloaded, moving
  with the belt, in stick);
* **steady sliding** (the slip-forward mode's equilibrium ``z*``: the slider at rest, the
  belt sliding past; the start-up state where it does not exist or has lifted off) with the
  contact DOF's velocity kicked to ``F V`` for ``F`` in :data:`VELOCITY_KICKS` (``F = 1``
  reaches the belt's speed, ``F > 1`` overtakes it);
* with a normal DOF, steady sliding with the normal displacement moved by ``G N_0 / k_n``
  for ``G`` in :data:`NORMAL_KICKS` (``N_0`` the steady normal force: ``G = 0.5`` halves the
  contact's compression, ``G = -0.5`` adds half of it); without one, two more velocity
  kicks (:data:`EXTRA_VELOCITY_KICKS`).

Periodic outcomes are the same attractor when their verdicts agree, their periods agree
within :data:`SAME_PERIOD` (relative) and the state at one's repeating event lies within
:data:`SAME_STATE` (relative, balanced norm) of the state at an event of the same kind on the
other's last period. Their verdicts are **observed, not proven** (a state repeated to 1e-9):
the engine checks no contraction bound.

Stability (estimated): the return map over one period ``T`` from a point ``z_0`` in the middle
of the orbit's longest phase (off every event surface), ``P(z) = phi_T(z)``, is differentiated
by forward differences through the engine (``n_state`` runs of one period, step
:data:`JACOBIAN_STEP` of each entry's scale); its nontrivial multipliers are the eigenvalues of
``U^T J U`` with ``U`` an orthonormal basis orthogonal to the flow ``f(z_0)`` (balanced units),
the trivial one, ``f^T J f / |f|^2 = 1``, is reported as a check. The engine is exact, the
Jacobian is a finite-difference estimate: the moduli are reported as "estimated". Stick
phases and the constraint of a massless undamped Jenkins element give zero multipliers (their
directions are reset). A perturbed orbit that changes its sequence of events within one
period (a grazing orbit) makes the estimate meaningless: it is then left out, and said so.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.contact._modes import SLIP_FORWARD, ContactSystem
from stickslip.analysis.contact._pool import ContactOutcome, run_many
from stickslip.analysis.contact.engine import simulate_contact

FloatArray = NDArray[np.float64]

#: Velocities ``F V`` given to the contact DOF at steady sliding.
VELOCITY_KICKS = (0.25, 0.5, 0.75, 1.0, 1.5)
#: Two more without a normal DOF.
EXTRA_VELOCITY_KICKS = (-0.5, 2.0)
#: Normal displacements ``G N_0 / k_n`` added at steady sliding (positive: away from the belt).
NORMAL_KICKS = (-0.5, 0.5)
#: Relative tolerances under which two periodic outcomes are one attractor.
SAME_PERIOD = 1e-6
SAME_STATE = 1e-6
#: Forward-difference step of the return map, as a share of each entry's scale.
JACOBIAN_STEP = 1e-6
#: Moduli below this are zero to the estimate's resolution: a forward difference of step
#: ``h`` errs by ``O(h)`` (curvature) plus the engine's rounding over ``h``; the summary
#: prints them as ``< 1e-05`` (their digits, which differ between machines, are noise).
MULTIPLIER_RESOLUTION = 10.0 * JACOBIAN_STEP
#: What a periodic verdict of the engine is.
OBSERVED = "observed, not proven: a state repeated to 1e-9; no contraction bound is checked"


def steady_sliding_state(system: ContactSystem) -> FloatArray | None:
    """The slip-forward equilibrium ``z*`` (slider at rest, belt sliding past), SI state.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).

    Returns
    -------
    ndarray or None
        The state (m, m/s, then the Jenkins entries); None when the slip mode has no unique
        equilibrium or the contact would carry no load there (lift-off).
    """
    ms = system.mode(SLIP_FORWARD)
    a, c = ms.flow.a, ms.flow.c
    moving = np.flatnonzero(np.any(a != 0.0, axis=1) | (c != 0.0))
    z = system.enter(SLIP_FORWARD, np.zeros(system.n_state))
    try:
        for _ in range(2):  # an undamped massless element's extension follows N: settle it
            rest = a[np.ix_(moving, moving)]
            z[moving] = np.linalg.solve(rest, -(c[moving] + a[moving] @ z - rest @ z[moving]))
            z = system.enter(SLIP_FORWARD, z)
    except np.linalg.LinAlgError:
        return None
    if not np.all(np.isfinite(z)) or system.normal_force(z, SLIP_FORWARD) <= 0.0:
        return None
    return z


def contact_starts(system: ContactSystem) -> list[tuple[str, FloatArray]]:
    """The 8 labelled starts of :func:`find_contact_cycles` (module notes), SI states.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).

    Returns
    -------
    list of (str, ndarray)
        Label and state of each start.
    """
    n, t, speed = system.n_dof, system.tangential_dof, system.speed
    found = steady_sliding_state(system)
    base = system.startup_state() if found is None else found
    where = "start-up" if found is None else "steady sliding"
    starts = [("start-up", system.startup_state())]
    kicks = VELOCITY_KICKS + (() if system.normal_dof is not None else EXTRA_VELOCITY_KICKS)
    for f in kicks:
        z = base.copy()
        z[n + t] = f * speed
        starts.append((f"{where}, v = {f:g} V", z))
    if system.normal_dof is not None:
        load = system.normal_force(base, SLIP_FORWARD) if found is not None else system.load
        for g in NORMAL_KICKS:
            z = base.copy()
            z[system.normal_dof] += g * load / system.normal_stiffness
            starts.append((f"{where}, q_n {'+' if g > 0 else '-'} {abs(g):g} N0/k_n", z))
    return starts


@dataclass
class ContactCycle:
    """One periodic attractor: a representative outcome, the starts that reach it, stability."""

    outcome: ContactOutcome = field(repr=False)
    starts: list[str]
    multipliers: NDArray[np.complex128] | None = field(default=None, repr=False)
    stability_note: str = "not estimated"
    closure: float | None = None
    trivial: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI)."""
        o, m = self.outcome, self.multipliers
        return {"kind": o.verdict, "period_s": o.period_s, "amplitude_m": o.amplitude_m,
                "separated": o.separated, "stick_phases_per_period": o.stick_phases,
                "events_per_period": o.event_counts, "repeating_event": o.repeat_kind,
                "starts": list(self.starts), "n_starts": len(self.starts),
                "certificate": o.certificate, "status": OBSERVED,
                "multipliers_estimated": None if m is None
                else [[float(x.real), float(x.imag)] for x in m],
                "multiplier_moduli_estimated": None if m is None
                else [float(abs(x)) for x in m],
                "multiplier_resolution": MULTIPLIER_RESOLUTION,
                "stable_estimated": None if m is None else bool(np.all(np.abs(m) < 1.0)),
                "stability": self.stability_note, "return_map_closure": self.closure,
                "trivial_multiplier_estimated": self.trivial}


@dataclass
class ContactCycleSearch:
    """Result of :func:`find_contact_cycles`."""

    system: ContactSystem = field(repr=False)
    cycles: list[ContactCycle]
    steady_starts: list[str]
    undetermined: dict[str, str]
    n_starts: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the attractors, the starts that end in steady sliding, the undecided."""
        return {"cycles": [c.to_dict() for c in self.cycles], "n_cycles": len(self.cycles),
                "steady_sliding_starts": self.steady_starts,
                "undetermined_starts": self.undetermined, "n_starts": self.n_starts,
                "status": f"periodic attractors {OBSERVED}",
                "searched": "attractors reached from the start-up state and kicked steady "
                            "sliding (stable orbits only; unstable orbits are not searched)",
                "engine": "exact piecewise-affine contact engine, one run per start"}

    def summary(self) -> str:
        """A few lines for the terminal."""
        lines = [f"cycles      {len(self.cycles)} periodic attractor(s) from {self.n_starts} "
                 f"starts (observed, not proven)"]
        for i, c in enumerate(self.cycles, start=1):
            d = c.to_dict()
            events = ", ".join(f"{k} {v}" for k, v in d["events_per_period"].items())
            mods = d["multiplier_moduli_estimated"]
            stab = ("|multipliers| " + ", ".join(f"{x:.4g}" if x >= MULTIPLIER_RESOLUTION
                                                 else f"< {MULTIPLIER_RESOLUTION:.0e}"
                                                 for x in mods) + " (estimated: "
                    + ("stable" if d["stable_estimated"] else "UNSTABLE") + ")"
                    if mods is not None else f"stability {c.stability_note}")
            lines.append(
                f"cycle {i}     {d['kind']}: period {d['period_s']:.9g} s, amplitude "
                f"{d['amplitude_m']:.6g} m, {'separates' if d['separated'] else 'no separation'}, "
                f"{d['stick_phases_per_period']} stick phase(s) per period; per period: {events}")
            lines.append(f"            {stab}; reached from {d['n_starts']} start(s): "
                         + "; ".join(c.starts))
        if self.steady_starts:
            lines.append(f"steady      {len(self.steady_starts)} start(s) end in steady sliding: "
                         + "; ".join(self.steady_starts))
        for label, why in self.undetermined.items():
            lines.append(f"undecided   {label}: {why}")
        lines.append("search      attractors only (stable orbits reached by runs); a periodic "
                     "verdict is a state repeated to 1e-9, observed, not proven")
        return "\n".join(lines)


def _same(a: ContactOutcome, b: ContactOutcome, scale: FloatArray) -> bool:
    """One attractor: verdict, period and a state of ``b``'s repeat on ``a``'s orbit."""
    if a.verdict != b.verdict or a.period_s is None or b.period_s is None:
        return False
    if abs(a.period_s - b.period_s) > SAME_PERIOD * a.period_s:
        return False
    z = next((s for k, s in reversed(b.orbit_events) if k == b.repeat_kind), None)
    if z is None:
        return False
    size = float(np.linalg.norm(z / scale))
    return any(k == b.repeat_kind and float(np.linalg.norm((s - z) / scale)) <= SAME_STATE * size
               for k, s in a.orbit_events)


def return_map_multipliers(system: ContactSystem, point: FloatArray, period: float, *,
                           step: float = JACOBIAN_STEP, max_events: int = 10_000
                           ) -> tuple[NDArray[np.complex128] | None, str, float | None,
                                      float | None]:
    """Estimated multipliers of the one-period return map through ``point`` (module notes).

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).
    point : ndarray
        A state on the orbit, off every event surface (SI).
    period : float
        The orbit's period, s.
    step : float
        Forward-difference step, a share of each entry's scale (``state_scale``).
    max_events : int
        Bound on the events of each one-period run.

    Returns
    -------
    multipliers : ndarray of complex or None
        The ``n_state - 1`` nontrivial multipliers (estimated), None when not estimated.
    note : str
        How they were estimated, or why not.
    closure : float or None
        ``|phi_T(z_0) - z_0| / |z_0|`` (balanced norm): how well the point closes on itself.
    trivial : float or None
        ``f^T J f / |f|^2``, the trivial multiplier (1 for a consistent estimate).
    """
    scale = system.state_scale

    def flow(z: FloatArray) -> tuple[FloatArray, tuple[str, ...]] | None:
        run = simulate_contact(system, t_max=period, max_events=max_events, initial=z)
        if run.t_end < period or run.period_s is not None:
            return None
        return run.state_at(np.array([period]))[0][0], tuple(e.kind for e in run.events)

    base = flow(point)
    if base is None:
        return None, "not estimated: the one-period run from the orbit ended early", None, None
    end, kinds = base
    size = float(np.linalg.norm(point / scale))
    closure = float(np.linalg.norm((end - point) / scale)) / size
    d = point.size
    jac = np.empty((d, d))
    for j in range(d):
        z = point.copy()
        z[j] += step * scale[j]
        moved = flow(z)
        if moved is None or moved[1] != kinds:
            return (None, "not estimated: a perturbed run changed its sequence of events "
                    "within one period (a grazing orbit: the return map is not smooth there)",
                    closure, None)
        jac[:, j] = (moved[0] - end) / scale / step
    mode = system.initial_mode(point)
    ms = system.mode(mode)
    f = (ms.flow.a @ system.enter(mode, point) + ms.flow.c) / scale
    f_hat = f / float(np.linalg.norm(f))
    basis = np.linalg.svd(np.eye(d) - np.outer(f_hat, f_hat))[0][:, : d - 1]
    multipliers = np.linalg.eigvals(basis.T @ jac @ basis).astype(np.complex128)
    order = np.argsort(-np.abs(multipliers), kind="stable")
    trivial = float(f_hat @ jac @ f_hat)
    note = (f"estimated: forward differences (step {step:g} of each entry's scale) of the "
            f"one-period map through the engine, {d + 1} runs")
    return multipliers[order], note, closure, trivial


def find_contact_cycles(system: ContactSystem, *,
                        starts: Sequence[tuple[str, FloatArray]] | None = None,
                        t_max: float | None = None, max_events: int = 100_000,
                        workers: int = 1, stability: bool = True,
                        progress: Callable[[int, int], None] | None = None) -> ContactCycleSearch:
    """The attractors that runs from :func:`contact_starts` settle on (module notes).

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).
    starts : sequence of (str, ndarray), optional
        Labelled initial states (default :func:`contact_starts`).
    t_max : float, optional
        Horizon of each run, s (default the engine's).
    max_events : int
        Bound on the events of each run.
    workers : int
        Worker processes (1: this process).
    stability : bool
        Estimate each attractor's return-map multipliers.
    progress : callable, optional
        ``progress(done, total)`` after each run.

    Returns
    -------
    ContactCycleSearch
        The distinct periodic attractors with the starts that reach them, the starts that end
        in steady sliding and the undetermined ones.
    """
    chosen = list(contact_starts(system) if starts is None else starts)
    if not chosen:
        raise ValueError("no starts to run")
    outcomes = run_many([(system, z) for _, z in chosen], t_max=t_max, max_events=max_events,
                        workers=workers, progress=progress)
    cycles: list[ContactCycle] = []
    steady: list[str] = []
    undetermined: dict[str, str] = {}
    scale = system.state_scale
    for (label, _), outcome in zip(chosen, outcomes, strict=True):
        if outcome.verdict == "steady-sliding":
            steady.append(label)
        elif not outcome.periodic:
            undetermined[label] = outcome.certificate
        else:
            match = next((c for c in cycles if _same(c.outcome, outcome, scale)), None)
            if match is not None:
                match.starts.append(label)
            else:
                cycles.append(ContactCycle(outcome, [label]))
    cycles.sort(key=lambda c: (c.outcome.amplitude_m or 0.0, c.outcome.period_s or 0.0))
    if stability:
        for c in cycles:
            point, period = c.outcome.orbit_point, c.outcome.period_s
            assert point is not None and period is not None and math.isfinite(period)
            c.multipliers, c.stability_note, c.closure, c.trivial = return_map_multipliers(
                system, point, period)
    return ContactCycleSearch(system, cycles, steady, undetermined, len(chosen))


__all__ = ["EXTRA_VELOCITY_KICKS", "NORMAL_KICKS", "VELOCITY_KICKS", "ContactCycle",
           "ContactCycleSearch", "contact_starts", "find_contact_cycles",
           "return_map_multipliers", "steady_sliding_state"]
