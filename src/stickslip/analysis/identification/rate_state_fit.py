"""Rate-and-state parameters from a velocity-step record: the test rate-and-state laboratories run.

The record holds, at times ``t`` (s), the load-point displacement ``x_lp`` (m) and the friction
coefficient ``mu`` (shear over normal force). The load point moves at piecewise-constant speeds
(the steps); the sample is the quasi-static spring-slider of the laboratories,
``k (x_lp - x) = N mu`` with the machine's stiffness ``k`` (N/m) and normal load ``N`` (N) known,
and the friction the regularised rate-and-state law of
:class:`~stickslip.model.state_friction.RateStateFriction` with the aging or the slip law.

The steps are read off the displacement: the speed of each sample interval,
``(x_lp[i+1] - x_lp[i]) / (t[i+1] - t[i])``, starts a new step where it changes by more than
:data:`STEP_CHANGE` of the larger of the two; each step's speed is its mean (its displacement over
its duration). A step between two samples shows as one interval whose speed lies between its
neighbours': the switch time is the one that gives its displacement,
``t_i + dt (v_i - v_after) / (v_before - v_after)``. A record whose speed changes at more than
:data:`MAX_STEPS` intervals (and :data:`MAX_STEP_SHARE` of them) is refused: a noisy
displacement, not steps. A step between two others slower than :data:`HOLD_FRACTION` of the fastest is a
hold (the load point stopped: the slide-hold-slide test, in which the contact heals); a
hold's noisy samples, which change sign, make one hold. ``v_ref`` is the first step's speed,
so ``mu_ref`` is the friction of steady sliding there.

The fit. The unknowns are ``a``, ``b``, ``d_c`` (positive; fitted as logarithms) and
``mu_ref``; the run starts from steady sliding at the first speed. The model is the stiff
engine's run of the quasi-static slider through the steps
(:func:`~stickslip.analysis.memory.friction.integrate_run`, ``rtol`` :data:`FIT_RTOL`), sampled
at the record's times; the residuals ``mu_model - mu`` are minimised by
``scipy.optimize.least_squares`` (trust-region reflective, finite-difference Jacobian) from
:data:`STARTS` first guesses, the best kept. Standard errors are those of the linearised
least-squares problem, ``sqrt(diag((J^T J)^-1) s^2)`` with ``s^2 = RSS / (n - p)``: exact for
Gaussian noise in ``mu`` to first order. A parameter whose standard error exceeds its value, or a
singular ``J^T J``, is reported *undetermined* (the record does not constrain it: for example
a record with one step cannot tell ``b`` from ``d_c`` well when it is short).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.identification.estimates import mismatch_warnings
from stickslip.analysis.identification.fit_statistics import (
    NOT_CONVERGED,
    checked_record,
    linearised_errors,
)
from stickslip.analysis.memory.friction import integrate_run
from stickslip.model.state_friction import (
    MAX_PSI_OVER_A,
    MemorySystem,
    RateStateFriction,
    SpeedSchedule,
)

FloatArray = NDArray[np.float64]

#: Relative change of the sample speed that starts a new load-point step.
STEP_CHANGE = 0.05
#: Speed changes a record may show, at most this many or this share of its intervals
#: (beyond, its load-point displacement is too noisy to read steps from: refused).
MAX_STEPS = 50
MAX_STEP_SHARE = 0.02
#: A step slower than this fraction of the fastest is a hold (speed 0, slide-hold-slide).
HOLD_FRACTION = 1e-3
#: Relative tolerance of the model's runs (their error must stay below the finite-difference
#: steps of the fit).
FIT_RTOL = 1e-10
#: First guesses ``(a, b/a, d_c in units of the record's slip per step)``.
STARTS = ((0.01, 1.2, 0.05), (0.005, 0.8, 0.2), (0.02, 1.5, 0.01))
#: A fit with ``mu_ref / a`` above this fraction of the law's limit
#: (:data:`stickslip.model.state_friction.MAX_PSI_OVER_A`) stopped against that limit: every
#: parameter is undetermined.
LIMIT_FRACTION = 0.99
#: Most function evaluations of one start.
MAX_EVALUATIONS = 400
NAMES = ("a", "b", "d_c", "mu_ref")


def load_point_steps(t: FloatArray, x_lp: FloatArray) -> SpeedSchedule:
    """The piecewise-constant load-point speeds of a record (module notes).

    Parameters
    ----------
    t : ndarray
        Times, s (strictly increasing, starting anywhere: the schedule starts at ``t[0]``).
    x_lp : ndarray
        Load-point displacement, m.

    Returns
    -------
    SpeedSchedule
        Step start times (from 0 at ``t[0]``) and speeds, m/s.
    """
    dt = np.diff(t)
    speed = np.diff(x_lp) / dt
    starts = [0]
    for i in range(1, speed.size):
        if abs(speed[i] - speed[i - 1]) > STEP_CHANGE * max(abs(speed[i]), abs(speed[i - 1])):
            starts.append(i)
    if len(starts) > max(MAX_STEPS, MAX_STEP_SHARE * speed.size):
        raise ValueError(f"the load-point speed changes by more than {STEP_CHANGE:.0%} at "
                         f"{len(starts) - 1} of its {speed.size} sample intervals: too noisy to "
                         "read its velocity steps (give the commanded load-point displacement, "
                         "or a smoothed one)")
    ends = [*starts[1:], speed.size]
    segments = [(s, e, float((x_lp[e] - x_lp[s]) / (t[e] - t[s]))) for s, e in zip(starts, ends, strict=True)]
    steps: list[tuple[int, int, float, float]] = []  # (first, last sample, speed, start time)
    switch: float | None = None  # a step found inside the interval just skipped
    for k, (s, e, v) in enumerate(segments):
        if switch is None and e - s == 1 and 0 < k < len(segments) - 1:
            before, after = segments[k - 1][2], segments[k + 1][2]
            if min(before, after) < v < max(before, after):
                # a step between two samples: the interval's mean speed mixes both, and the
                # load point switched at the time that gives its displacement
                switch = float(t[s] + (t[e] - t[s]) * (v - after) / (before - after))
                continue
        steps.append((s, e, v, float(t[s]) if switch is None else switch))
        switch = None
    fastest = max(abs(v) for _, _, v, _ in steps)
    times: list[float] = []
    speeds: list[float] = []
    for k, (s, e, v, start) in enumerate(steps):
        hold = abs(v) <= HOLD_FRACTION * fastest
        if hold and 0 < k < len(steps) - 1:
            if speeds[-1] != 0.0:  # a hold's noisy samples are one hold
                times.append(start - float(t[0]))
                speeds.append(0.0)
            continue
        if not v > 0.0 or hold:
            raise ValueError(f"the load point does not move forward from {t[s]:g} s to {t[e]:g} s "
                             f"(speed {v:.3g} m/s): velocity steps need positive speeds (a hold, "
                             "below 1e-3 of the fastest step, only between two of them)")
        times.append(start - float(t[0]))
        speeds.append(v)
    return SpeedSchedule(tuple(times), tuple(speeds))


def model_mu(t: FloatArray, schedule: SpeedSchedule, stiffness: float, load: float,
             law: RateStateFriction) -> FloatArray:
    """``mu`` of the quasi-static slider through ``schedule`` at the times ``t - t[0]``.

    Parameters
    ----------
    t : ndarray
        The record's times, s.
    schedule : SpeedSchedule
        Load-point steps (times from ``t[0]``).
    stiffness, load : float
        Machine stiffness (N/m) and normal load (N).
    law : RateStateFriction
        The law (``v_ref`` the first speed: steady sliding there at ``mu_ref``).

    Returns
    -------
    ndarray
        ``mu`` at every time (NaN where the run stopped).
    """
    system = MemorySystem(np.zeros((1, 1)), np.zeros((1, 1)), np.array([[stiffness]]), 0, load,
                          law, schedule)
    v1 = schedule.first
    psi = law.steady_state(v1, load)
    y0 = np.array([load * float(law.mu(v1, psi)) / stiffness, psi])
    times = t - t[0]
    run = integrate_run(system, y0, float(times[-1]), rtol=FIT_RTOL, history_times=times)
    assert run.history is not None
    return stiffness * run.history[:, 0] / load


@dataclass
class RateStateFit:
    """A rate-and-state fit to a velocity-step record (see module notes).

    Attributes
    ----------
    values, errors : dict
        Fitted ``a``, ``b``, ``d_c`` (m), ``mu_ref`` and their standard errors.
    undetermined : list of str
        The parameters the record does not constrain (standard error above the value, or a
        singular problem).
    rms : float
        Root-mean-square residual in ``mu``.
    schedule : SpeedSchedule
        The load-point steps read off the record.
    evolution : str
        ``aging`` or ``slip``.
    """

    values: dict[str, float]
    errors: dict[str, float]
    undetermined: list[str]
    rms: float
    schedule: SpeedSchedule = field(repr=False)
    evolution: str
    stiffness: float
    load: float
    n: int
    t: FloatArray = field(repr=False)
    mu: FloatArray = field(repr=False)
    mu_fit: FloatArray = field(repr=False)
    #: False when the optimiser stopped at its budget (the values are where it stopped)
    converged: bool = True
    #: Warnings on the fit (residuals beyond the record's noise:
    #: :func:`~stickslip.analysis.identification.estimates.mismatch_warnings`)
    warnings: tuple[str, ...] = ()

    @property
    def law(self) -> RateStateFriction:
        """The fitted law (``v_ref`` the first step's speed)."""
        return RateStateFriction(a=self.values["a"], b=self.values["b"], d_c=self.values["d_c"],
                                 mu_ref=self.values["mu_ref"], v_ref=self.schedule.first,
                                 evolution=self.evolution)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI)."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None
        return {"law": "rate-state", "evolution": self.evolution,
                # an undetermined parameter is null, as in the main fit; the optimiser's
                # numbers are kept under "estimates"
                "parameters": {k: None if k in self.undetermined else num(v)
                               for k, v in self.values.items()},
                "estimates": {k: num(v) for k, v in self.values.items()},
                "standard_errors": {k: num(v) for k, v in self.errors.items()},
                "undetermined": self.undetermined, "v_ref_m_per_s": self.schedule.first,
                "rms_residual_mu": self.rms, "n_samples": self.n,
                "steps": [[t, v] for t, v in zip(self.schedule.times, self.schedule.speeds,
                                                 strict=True)],
                "stiffness_N_per_m": self.stiffness, "load_N": self.load,
                "converged": self.converged, "warnings": list(self.warnings),
                "model": "quasi-static spring-slider, regularised rate-and-state law"}

    def summary(self) -> str:
        """A few lines for the terminal."""
        lines = [f"identify    rate-and-state ({self.evolution} law) from {self.n} samples, "
                 f"{len(self.schedule.speeds)} load-point speed(s) ({len(self.schedule.speeds) - 1} "
                 f"step(s)), k {self.stiffness:.6g} N/m, "
                 f"N {self.load:.6g} N"]
        units = {"d_c": " m"}
        for name in NAMES:
            flag = "  UNDETERMINED" if name in self.undetermined else ""
            lines.append(f"{name:<11} {self.values[name]:.6g}{units.get(name, '')} +- "
                         f"{self.errors[name]:.2g}{flag}")
        weakening = self.values["b"] > self.values["a"]
        lines.append(f"b - a       {self.values['b'] - self.values['a']:.4g} "
                     + ("(undetermined: the record does not fix a and b; it needs a speed step)"
                        if {"a", "b"} & set(self.undetermined)
                        else f"(velocity {'weakening' if weakening else 'strengthening'})"))
        lines.append(f"residual    rms {self.rms:.3g} in mu; v_ref {self.schedule.first:.6g} m/s "
                     "(the first step)")
        if not self.converged:
            lines.append(NOT_CONVERGED)
        lines += [f"warning     {w}" for w in self.warnings]
        return "\n".join(lines)


def fit_rate_state(t: FloatArray, x_lp: FloatArray, mu: FloatArray, *, stiffness: float,
                   load: float, evolution: str = "aging") -> RateStateFit:
    """Fit ``a``, ``b``, ``d_c`` and ``mu_ref`` to a velocity-step record (module notes).

    Parameters
    ----------
    t, x_lp, mu : ndarray
        Times (s, strictly increasing), load-point displacement (m) and friction coefficient.
    stiffness : float
        Machine stiffness, N/m (> 0).
    load : float
        Normal load, N (> 0).
    evolution : str
        ``aging`` or ``slip``.

    Returns
    -------
    RateStateFit
        Values, standard errors, the undetermined parameters and the fitted curve.
    """
    from scipy.optimize import least_squares

    t, x_lp, mu = checked_record((t, x_lp, mu), 8, "t, load-point displacement and mu")
    if not (stiffness > 0.0 and math.isfinite(stiffness) and load > 0.0 and math.isfinite(load)):
        raise ValueError(f"stiffness {stiffness!r} N/m and load {load!r} N must be positive")
    if evolution not in ("aging", "slip"):
        raise ValueError(f"evolution {evolution!r} must be 'aging' or 'slip'")
    schedule = load_point_steps(t, x_lp)
    slip_per_step = float(x_lp[-1] - x_lp[0]) / len(schedule.speeds)
    mu0 = float(np.median(mu[: max(3, t.size // 50)]))

    def law_of(p: FloatArray) -> RateStateFriction:
        return RateStateFriction(a=math.exp(p[0]), b=math.exp(p[1]), d_c=math.exp(p[2]),
                                 mu_ref=float(p[3]), v_ref=schedule.first, evolution=evolution)

    def residuals(p: FloatArray) -> FloatArray:
        try:  # a law the fit wanders into may not exist (exp overflows, mu_ref / a too large)
            predicted = model_mu(t, schedule, stiffness, load, law_of(p))
        except (ValueError, OverflowError):
            return np.full(t.size, 1e3)
        r = predicted - mu
        return np.where(np.isfinite(r), r, 1e3)

    best = None
    for a0, ratio, dc_frac in STARTS:
        p0 = np.array([math.log(a0), math.log(a0 * ratio), math.log(dc_frac * slip_per_step), mu0])
        try:
            sol = least_squares(residuals, p0, method="trf", x_scale=np.array([1.0, 1.0, 1.0, 0.01]),
                                diff_step=1e-6, max_nfev=MAX_EVALUATIONS)
        except (ValueError, OverflowError):
            continue
        if best is None or sol.cost < best.cost:
            best = sol
    if best is None:
        raise ValueError("no start of the fit ran: check the record and the stiffness and load")
    p = best.x
    try:
        fitted_law = law_of(p)
    except (ValueError, OverflowError):
        raise ValueError("the fit found no rate-and-state law that runs through this record "
                         f"with the {evolution} law: check --evolution, the stiffness and the "
                         "load") from None
    # d r / d a = (d r / d ln a) / a: the Jacobian in the parameters themselves
    jac = best.jac / np.array([math.exp(p[0]), math.exp(p[1]), math.exp(p[2]), 1.0])[None, :]
    values = dict(zip(NAMES, (math.exp(p[0]), math.exp(p[1]), math.exp(p[2]), float(p[3])),
                      strict=True))
    errors = linearised_errors(jac, float(best.cost), NAMES)
    undetermined: list[str] = []
    for name in NAMES:
        if not errors[name] <= abs(values[name]):
            undetermined.append(name)
    if values["mu_ref"] / values["a"] > LIMIT_FRACTION * MAX_PSI_OVER_A:
        # stopped against the law's own limit (mu_ref / a): its curvature there is the wall's,
        # not the record's, so the linearised errors mean nothing
        undetermined = list(NAMES)
    fitted = model_mu(t, schedule, stiffness, load, fitted_law)
    rms = float(np.sqrt(np.mean((fitted - mu) ** 2)))
    return RateStateFit(values, errors, undetermined, rms, schedule, evolution, stiffness, load,
                        int(t.size), t, mu, fitted, converged=best.status > 0,
                        warnings=mismatch_warnings(mu, fitted, "check --evolution (aging or slip), "
                                                    "the stiffness and the load"))




__all__ = ["RateStateFit", "fit_rate_state", "load_point_steps", "model_mu"]
