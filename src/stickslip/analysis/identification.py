"""Identify stiffness, damping and a friction law from a measured stick-slip record (issue 19).

The forward model is the package's exact engine (:func:`stickslip.simulate` on the structure
and slider of a :class:`~stickslip.model.physical.PhysicalSystem`, evaluated at the record's
sample times), so event times are exact, not smeared by a regularised law. The fit is a
weighted least-squares problem (``scipy.optimize.least_squares``, trust-region reflective)
over the whole signal:

* **Multiple shooting over cycles.** The record is cut into segments, each starting inside a
  stick phase (where the state is known up to one number: ``x' = V`` and the position
  ``x_j``) and running through the breakaway, the slip phase and the next stick onset. Each
  ``x_j`` is a nuisance parameter; the physics of every breakaway (``k x + c V = mu_s W``),
  every slip phase and every stick onset is fitted exactly. Cycles that are not quite equal
  (jitter of the breakaway) then do not accumulate a phase error, and the fit converges from
  rough starting values. A record that starts in the middle of a slip phase gets a first
  segment from its first sample with the free state ``(x_0, v_0)`` (the engine's
  :class:`~stickslip.model.initial.InitialState`).
* **Nuisance parameters of the force zero**: ``F_measured = F + force_offset + force_drift t``.
  With a displacement record both are fitted (``F - k x - c x'`` fixes them); with a force
  record alone an offset cannot be told apart from a common shift of ``mu_s`` and ``mu_k``
  (the motion only depends on ``mu_s - mu_k`` and on where the kinetic equilibrium sits), so
  the offset is then fixed at 0 unless asked for, and reported as such.
* **Weights**: each channel (``F``, ``x``, ``v``) is divided by its white-noise level
  estimated from the record itself (:func:`noise_level`), so the channels count by their
  information and the information criteria of several laws are comparable.

Standard errors come from the Jacobian at the optimum, ``cov = s^2 (J^T J)^-1`` with
``s^2 = chi^2 / (N - p)`` (lmfit's ``scale_covar``). The rule for an undetermined parameter
is documented in :data:`UNDETERMINED_RULE`.

Dimensionless mapping (DESIGN.md section 1, paper Section 2.3): ``omega_n = sqrt(k/m)``,
``tau = omega_n t``, ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``,
``gamma = mu_k / (mu_s - mu_k)``, ``zeta = c / (2 sqrt(m k))``, and the shifted coordinate
``xi = x omega_n / V - gamma lambda`` (measured from the kinetic equilibrium ``k x = mu_k W``).
"""

from __future__ import annotations

import itertools
import math
import threading
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares
from scipy.signal import savgol_filter
from threadpoolctl import threadpool_limits

from stickslip.analysis.identification_estimates import (
    MeasuredRecord,
    RecordError,
    RecordEstimates,
    estimate,
)
from stickslip.analysis.identification_result import (
    PARAMETER_UNITS,
    UNDETERMINED_RULE,
    FitParameter,
    IdentificationResult,
    undetermined,
)
from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.model.friction import STRIBECK_RANGES
from stickslip.model.initial import InitialState
from stickslip.model.physical import PhysicalFriction, PhysicalSystem

FloatArray = NDArray[np.float64]

LAWS = ("coulomb", "linear", "stribeck", "table")
#: Parameters of each law beyond ``mu_s`` and ``mu_k`` (the machine file's ``[friction]`` keys).
LAW_PARAMETERS: dict[str, tuple[str, ...]] = {
    "coulomb": (),
    "linear": ("slope",),
    "stribeck": ("stribeck_velocity", "exponent", "viscous"),
    "table": (),
}
#: Knots of a fitted ``table`` law beyond ``v_r = 0``: these quantiles of the sliding speeds
#: ``v_r = V - x'`` that the slip phases of the record visit (time-weighted: the samples are
#: uniform in time), read from the model of a preliminary Coulomb fit (noise-free). Knots sit
#: where the record spends its slip time, so each one has data; the last is the largest
#: sliding speed of the record.
TABLE_QUANTILES = (0.2, 0.4, 0.6, 0.8, 1.0)
#: Parameters whose bounds are limits of the search, not of the physics: an optimum on such
#: a bound is undetermined (the record does not bracket it; see UNDETERMINED_RULE).
SEARCH_LIMITED = ("stribeck_velocity", "exponent")
#: How close to such a limit (relative, in the fit's scaled coordinates) counts as on it: the
#: trust-region method approaches a bound without reaching it.
LIMIT_TOLERANCE = 1e-3
#: Most knots of a ``table`` law (the engine's band limit leaves room for 15).
MAX_TABLE_KNOTS = 12
#: A sample is in slip when its sliding speed exceeds this fraction of the drive speed.
SLIP_FRACTION = 1e-3
#: BLAS threads during a fit (``identify(blas_threads=...)``): the fit's linear algebra is a few
#: products and an SVD of an ``N x p`` matrix with ``p`` about 20, where a threaded BLAS on a
#: small shared machine waits for cores (``benchmarks/bench_identify.py`` measures both).
BLAS_THREADS = 1
#: Law approximation tolerance of the Stribeck interpolant during a fit (units of lambda).
STRIBECK_TOLERANCE = 1e-4
#: Iteration budget of one least-squares fit (function evaluations).
MAX_EVALUATIONS = 100
#: Iteration budget of each trial start of a Stribeck fit.
MULTISTART_EVALUATIONS = 12
#: Forward-difference step of the Jacobian in the scaled coordinates (parameters over their
#: natural scales, segment states over ``V / omega_n``).
FD_STEP = 1e-6
#: ``ftol``, ``xtol`` and ``gtol`` of ``least_squares``.
TOLERANCE = 1e-8
TR_SOLVER = "exact"

__all__ = ["LAWS", "UNDETERMINED_RULE", "IdentificationResult", "MeasuredRecord", "RecordError",
           "identify"]


@dataclass(frozen=True)
class _Segment:
    """Samples ``[start, stop)`` simulated from one initial state."""

    start: int
    stop: int
    in_stick: bool  # the state is (x_j, V); otherwise (x_0, v_0) both free


@dataclass
class _Problem:
    """Everything the residual function needs, built once per law."""

    record: MeasuredRecord
    mass: float
    load: float
    speed: float
    law: str
    names: list[str]  # free global parameters (internal: mu_s is delta_mu when mu_k is free)
    fixed: dict[str, float]
    scales: FloatArray
    lower: FloatArray
    upper: FloatArray
    segments: list[_Segment]
    seg_ref: FloatArray  # starting values of the segment states (x_j [, v_0])
    seg_scale: FloatArray
    seg_slots: list[list[int]]  # indices of each segment's parameters in the segment block
    sigma: dict[str, float]
    table_v: tuple[float, ...] = ()
    start: FloatArray = field(default_factory=lambda: np.zeros(0))
    n_calls: int = 0
    engine_seconds: float = 0.0

    @property
    def n_global(self) -> int:
        return len(self.names)

    def values(self, z: FloatArray) -> dict[str, float]:
        """Physical values of every global parameter (free and fixed) at the point ``z``."""
        out = dict(self.fixed)
        for name, zi, s in zip(self.names, z[: self.n_global], self.scales, strict=True):
            out[name] = float(zi * s)
        if "delta_mu" in out:
            out["mu_s"] = out["mu_k"] + out.pop("delta_mu")
        return out

    def segment_states(self, z: FloatArray) -> FloatArray:
        return self.seg_ref + z[self.n_global:] * self.seg_scale

    def system(self, v: Mapping[str, float]) -> PhysicalSystem:
        if self.law == "linear":
            friction = PhysicalFriction(law="linear", slope=v["slope"])
        elif self.law == "stribeck":
            friction = PhysicalFriction(law="stribeck", stribeck_velocity=v["stribeck_velocity"],
                                        exponent=v["exponent"], viscous=v["viscous"],
                                        tolerance=STRIBECK_TOLERANCE)
        elif self.law == "table":
            mus = [min(v[f"table_mu_{i}"], v["mu_s"]) for i in range(len(self.table_v))]
            friction = PhysicalFriction(law="table", table_v=self.table_v, table_mu=tuple(mus))
        else:
            friction = PhysicalFriction()
        return PhysicalSystem(mass=self.mass, stiffness=v["k"], damping=v["c"], mu_s=v["mu_s"],
                              mu_k=v["mu_k"], load=self.load, speed=self.speed, friction=friction)

    def simulate_record(self, z: FloatArray) -> dict[str, FloatArray]:
        """Model signals ``F`` (with its offset and drift), ``x`` and ``v`` at every sample."""
        import time

        v = self.values(z)
        system = self.system(v)
        structure, slider = system.structure(), system.slider()
        omega, length = system.natural_frequency, system.length_scale
        shift = slider.gamma * slider.lam
        states = self.segment_states(z)
        t = self.record.t
        x = np.empty_like(t)
        xv = np.empty_like(t)
        tic = time.perf_counter()
        for seg, slots in zip(self.segments, self.seg_slots, strict=True):
            x0 = states[slots[0]]
            v0 = self.speed if seg.in_stick else states[slots[1]]
            tau = omega * (t[seg.start:seg.stop] - t[seg.start])
            initial = InitialState(np.array([x0 / length - shift]), np.array([v0 / self.speed]),
                                   "measured state")
            horizon = EngineOptions(t_max=tau[-1] * (1 + 1e-12) + 1e-12)
            res = simulate(structure, slider, initial=initial, options=horizon, run_to_t_max=True)
            q, qd, _ = res.state_at(np.minimum(tau, res.t_end))
            x[seg.start:seg.stop] = (q[:, 0] + shift) * length
            xv[seg.start:seg.stop] = qd[:, 0] * self.speed
            self.n_calls += 1
        self.engine_seconds += time.perf_counter() - tic
        force = v["k"] * x + v["c"] * xv + v["force_offset"] + v["force_drift"] * t
        return {"F": force, "x": x, "v": xv}

    def residuals(self, z: FloatArray, weights: FloatArray | None = None) -> FloatArray:
        model = self.simulate_record(z)
        parts = [(model[n] - getattr(self.record, n)) / self.sigma[n] for n in self.record.channels]
        r = np.concatenate(parts)
        return r if weights is None else r * weights

    def jacobian(self, z: FloatArray, weights: FloatArray | None = None) -> FloatArray:
        """Forward differences, grouped: one evaluation per global parameter, and one per
        segment-state slot for all segments at once (a segment's state moves only its own
        samples), so ``n_global + 2`` evaluations instead of one per parameter."""
        r0 = self.residuals(z, weights)
        n = self.record.t.size
        n_ch = len(self.record.channels)
        p = z.size
        jac = np.zeros((r0.size, p))
        for i in range(self.n_global):
            h = FD_STEP * max(1.0, abs(z[i]))
            if z[i] + h > self.upper[i]:
                h = -h
            zp = z.copy()
            zp[i] += h
            jac[:, i] = (self.residuals(zp, weights) - r0) / h
        width = max((len(s) for s in self.seg_slots), default=0)
        for slot in range(width):
            zp = z.copy()
            cols = [self.n_global + s[slot] for s in self.seg_slots if len(s) > slot]
            zp[cols] += FD_STEP
            diff = (self.residuals(zp, weights) - r0) / FD_STEP
            for seg, s in zip(self.segments, self.seg_slots, strict=True):
                if len(s) > slot:
                    for c in range(n_ch):
                        rows = slice(c * n + seg.start, c * n + seg.stop)
                        jac[rows, self.n_global + s[slot]] = diff[rows]
        return jac


def _smooth_derivative(y: FloatArray, dt: float, period: float) -> tuple[FloatArray, FloatArray]:
    half = max(2, round(period / dt / 60.0))
    return savgol_filter(y, 2 * half + 1, 2), savgol_filter(y, 2 * half + 1, 2, deriv=1, delta=dt)


def _segments(record: MeasuredRecord, est: RecordEstimates, start: dict[str, float]
              ) -> tuple[list[_Segment], list[float], list[float], list[list[int]]]:
    """Cut the record at a point inside each stick phase; starting states of each piece."""
    n = record.t.size
    dt = record.t[-1] / (n - 1)
    k, c, speed = start["k"], start["c"], start["speed"]
    sm: dict[str, FloatArray] = {}
    dsm: dict[str, FloatArray] = {}
    for name in record.channels:
        sm[name], dsm[name] = _smooth_derivative(getattr(record, name), dt, est.period)

    def position(i: int) -> float:
        if "x" in sm:
            return float(sm["x"][i])
        force = sm["F"][i] - start["force_offset"] - start["force_drift"] * record.t[i]
        return float((force - c * speed) / k)

    anchors = [ph.anchor for ph in est.stick_phases]
    segments: list[_Segment] = []
    ref: list[float] = []
    scale: list[float] = []
    slots: list[list[int]] = []
    length = speed / math.sqrt(k / start["mass"])
    if est.starts_in_stick:
        anchors[0] = 0
    elif anchors[0] > 0:
        if "v" in sm:
            v0 = float(sm["v"][0])
        elif "x" in dsm:
            v0 = float(dsm["x"][0])
        else:
            v0 = float(dsm["F"][0] / k)
        segments.append(_Segment(0, anchors[0], in_stick=False))
        slots.append([len(ref), len(ref) + 1])
        ref += [position(0) if "x" in sm else float((sm["F"][0] - start["force_offset"] - c * v0) / k), v0]
        scale += [length, speed]
    bounds = [*anchors, n]
    for a, b in itertools.pairwise(bounds):
        if b - a < 2:
            continue
        segments.append(_Segment(a, b, in_stick=True))
        slots.append([len(ref)])
        ref.append(position(a))
        scale.append(length)
    return segments, ref, scale, slots


def _problem(record: MeasuredRecord, est: RecordEstimates, *, mass: float, load: float, speed: float,
             law: str, known: Mapping[str, float], fit_offset: bool, start: Mapping[str, float] | None,
             table_v: tuple[float, ...] = ()) -> _Problem:
    """Free parameters, their scales, bounds and starting values for one law."""
    duration = float(record.t[-1])
    main = record.F if record.F is not None else est.k * record.x  # type: ignore[operator]
    f_range = float(np.ptp(main))
    c_crit = 2.0 * math.sqrt(mass * est.k)
    gap = est.mu_s - est.mu_k
    guess: dict[str, float] = {
        "k": est.k, "c": 0.02 * c_crit, "mu_s": est.mu_s, "mu_k": est.mu_k,
        "force_offset": est.force_offset if fit_offset else 0.0, "force_drift": 0.0,
        "slope": 0.0, "stribeck_velocity": 0.3 * est.max_sliding_speed, "exponent": 1.0, "viscous": 0.0,
    }
    if start:
        guess.update({k: v for k, v in start.items() if k in guess})
        if "force_offset" in guess and not fit_offset:
            guess["force_offset"] = 0.0
    if law == "table":  # a flat curve at the (Coulomb) kinetic level
        for i in range(len(table_v)):
            guess[f"table_mu_{i}"] = guess["mu_k"]
    natural = {
        "k": est.k, "c": 0.1 * c_crit, "mu_s": est.mu_s, "mu_k": est.mu_s, "delta_mu": gap,
        "force_offset": 0.01 * f_range, "force_drift": 0.01 * f_range / duration,
        "slope": 0.1 * gap / speed, "stribeck_velocity": est.max_sliding_speed, "exponent": 1.0,
        "viscous": 0.1 * gap / speed,
    }
    limits = {
        "k": (1e-6 * est.k, np.inf), "c": (0.0, np.inf), "mu_k": (0.0, np.inf), "delta_mu": (1e-9, np.inf),
        "mu_s": (0.0, np.inf), "force_offset": (-np.inf, np.inf), "force_drift": (-np.inf, np.inf),
        "slope": (-np.inf, np.inf), "stribeck_velocity": (1e-4 * speed, 1e3 * est.max_sliding_speed),
        "exponent": (STRIBECK_RANGES["exponent"][0], 5.0), "viscous": (-np.inf, np.inf),
    }
    candidates = ["k", "c", "mu_s", "mu_k", *LAW_PARAMETERS[law], "force_offset", "force_drift"]
    if law == "table":
        candidates += [f"table_mu_{i}" for i in range(len(table_v))]
        candidates.remove("mu_k")
    fixed: dict[str, float] = {}
    if law == "table":
        fixed["mu_k"] = 0.0  # replaced by the table's high-speed value in the result
    for name, value in known.items():
        fixed[name] = float(value)
    if not fit_offset and "force_offset" not in fixed:
        fixed["force_offset"] = 0.0
    free = [n for n in candidates if n not in fixed]
    names: list[str] = []
    values: list[float] = []
    for n in free:
        internal = n
        value = guess.get(n, est.mu_k)
        if n == "mu_s" and "mu_k" in free:
            internal, value = "delta_mu", guess["mu_s"] - guess["mu_k"]
        names.append(internal)
        values.append(value)
    scales = np.array([natural.get(n, est.mu_s) for n in names], dtype=np.float64)
    lo = np.array([limits.get(n, (0.0, np.inf))[0] for n in names], dtype=np.float64)
    hi = np.array([limits.get(n, (0.0, np.inf))[1] for n in names], dtype=np.float64)
    for i, n in enumerate(names):
        if n == "mu_s":  # mu_k fixed
            lo[i] = fixed["mu_k"] * (1 + 1e-9) + 1e-12
        if n == "mu_k" and "mu_s" in fixed:
            hi[i] = fixed["mu_s"] * (1 - 1e-9)
    start_values = dict(fixed)
    start_values.update(zip(free, [guess.get(n, est.mu_k) for n in free], strict=True))
    start_values.update(mass=mass, speed=speed)
    segments, ref, seg_scale, slots = _segments(record, est, start_values)
    sigma = {n: est.noise[n] for n in record.channels}
    problem = _Problem(
        record=record, mass=mass, load=load, speed=speed, law=law, names=names, fixed=fixed,
        scales=scales, lower=lo / scales, upper=hi / scales, segments=segments,
        seg_ref=np.array(ref), seg_scale=np.array(seg_scale), seg_slots=slots, sigma=sigma,
        table_v=table_v,
    )
    z0 = np.concatenate([np.array(values) / scales, np.zeros(len(ref))])
    problem_start = np.clip(z0[: len(names)], problem.lower + 1e-12, problem.upper - 1e-12)
    problem.start = np.concatenate([problem_start, z0[len(names):]])
    return problem


def _solve(problem: _Problem, z0: FloatArray, weights: FloatArray | None = None,
           max_nfev: int = MAX_EVALUATIONS) -> Any:
    n_seg = problem.seg_ref.size
    lower = np.concatenate([problem.lower, np.full(n_seg, -np.inf)])
    upper = np.concatenate([problem.upper, np.full(n_seg, np.inf)])
    return least_squares(problem.residuals, z0, jac=problem.jacobian, bounds=(lower, upper),
                         method="trf", tr_solver=TR_SOLVER, x_scale=1.0, ftol=TOLERANCE, xtol=TOLERANCE,
                         gtol=TOLERANCE, max_nfev=max_nfev, kwargs={"weights": weights})


def _two_sided_jacobian(problem: _Problem, res: Any) -> FloatArray:
    """The optimiser's Jacobian at the optimum with each global parameter's column checked
    against the backward difference; the one with the smaller norm is kept.

    The exact engine's signals are smooth in the parameters except where an event appears
    or vanishes (a grazing stick onset, a band of a tabulated law): a forward step that
    crosses such a point overstates the sensitivity by orders of magnitude and so understates
    the standard error. Where the two one-sided differences disagree the smaller one gives the
    larger (conservative) standard error; where the model is smooth they agree to ``O(h)``.
    """
    jac = np.array(res.jac.toarray() if hasattr(res.jac, "toarray") else res.jac, dtype=np.float64)
    z = res.x
    r0 = problem.residuals(z)
    for i in range(problem.n_global):
        h = FD_STEP * max(1.0, abs(z[i]))
        if z[i] - h < problem.lower[i]:
            continue
        zm = z.copy()
        zm[i] -= h
        backward = (r0 - problem.residuals(zm)) / h
        if np.linalg.norm(backward) < np.linalg.norm(jac[:, i]):
            jac[:, i] = backward
    return jac


def _covariance(problem: _Problem, jac: FloatArray, chi2: float, n_obs: int
                ) -> tuple[list[str], FloatArray, FloatArray, list[bool]]:
    """Covariance of the reported global parameters and which ones are near-singular.

    Returns the reported names, their values' covariance (physical units), the scaled
    Jacobian's singular values and, per name, whether it loads on a numerically null
    direction (smallest singular values below ``1e-8`` of the largest after column scaling).
    """
    p = jac.shape[1]
    norms = np.linalg.norm(jac, axis=0)
    norms[norms == 0.0] = 1.0
    _u, s, vt = np.linalg.svd(jac / norms, full_matrices=False)
    null = s < 1e-8 * s[0]
    s_inv = np.where(null, 0.0, 1.0 / np.where(s == 0.0, 1.0, s))
    cov_scaled = (vt.T * s_inv**2) @ vt / np.outer(norms, norms)
    dof = max(n_obs - p, 1)
    cov_z = cov_scaled * (chi2 / dof)
    g = problem.n_global
    weak = np.any(np.abs(vt[null, :g]) > 0.1, axis=0) if np.any(null) else np.zeros(g, dtype=bool)
    # transform internal (scaled, delta_mu) coordinates to the reported names
    reported = [("mu_s" if n == "delta_mu" else n) for n in problem.names]
    t = np.diag(problem.scales)
    if "delta_mu" in problem.names:
        i, j = problem.names.index("delta_mu"), problem.names.index("mu_k")
        t[i, j] = problem.scales[j]  # mu_s = mu_k + delta_mu
        weak[i] = weak[i] or weak[j]
    cov = t @ cov_z[:g, :g] @ t.T
    return reported, cov, s, [bool(w) for w in weak]


def _fit_law(record: MeasuredRecord, est: RecordEstimates, *, mass: float, load: float, speed: float,
             law: str, known: Mapping[str, float], fit_offset: bool,
             start: Mapping[str, float] | None = None, table_v: tuple[float, ...] = ()
             ) -> tuple[_Problem, Any]:
    problem = _problem(record, est, mass=mass, load=load, speed=speed, law=law, known=known,
                       fit_offset=fit_offset, start=start, table_v=table_v)
    z0 = problem.start
    # Stribeck: the optimiser can stall with the Stribeck velocity far off; two more starts
    if law != "stribeck" or "stribeck_velocity" in known:
        return problem, _solve(problem, z0)
    # short trial fits from three Stribeck velocities; the best one is carried to convergence
    i = problem.names.index("stribeck_velocity")
    best = None
    for frac in (0.05, 0.3, 1.0):
        z1 = z0.copy()
        z1[i] = np.clip(frac * est.max_sliding_speed / problem.scales[i], problem.lower[i] * 1.001,
                        problem.upper[i] * 0.999)
        trial = _solve(problem, z1, max_nfev=MULTISTART_EVALUATIONS)
        if best is None or trial.cost < best.cost:
            best = trial
    assert best is not None
    return problem, _solve(problem, best.x)


def table_knots(sliding_speed: FloatArray, speed: float,
                quantiles: Sequence[float] = TABLE_QUANTILES) -> tuple[float, ...]:
    """Knot speeds of a fitted ``table`` law from the sliding speeds a record visits.

    Parameters
    ----------
    sliding_speed : ndarray
        Sliding speed ``v_r = V - x'`` at every sample, m/s (from a model of the record: the
        measured velocity is too noisy near ``v_r = 0``).
    speed : float
        Drive speed ``V``, m/s; samples with ``v_r <= SLIP_FRACTION V`` are stick.
    quantiles : sequence of float
        Quantiles in ``(0, 1]`` of the slip samples' sliding speeds (time-weighted, the
        samples being uniform in time).

    Returns
    -------
    tuple of float
        ``0`` and the quantiles, m/s, strictly increasing (coinciding quantiles merged).

    Raises
    ------
    RecordError
        When the record has no slip samples.
    """
    slip = np.asarray(sliding_speed, dtype=np.float64)
    slip = slip[slip > SLIP_FRACTION * speed]
    if slip.size == 0:
        raise RecordError("the record shows no slip phase: no sliding speeds to place the table's knots")
    knots = [0.0]
    for value in np.quantile(slip, quantiles):
        if value > knots[-1] * (1.0 + 1e-6) + 1e-12:
            knots.append(float(value))
    return tuple(knots)


def visited_knots(table_v: Sequence[float], max_sliding_speed: float) -> list[bool]:
    """Which knots of a ``table`` law the record's slip phases reach.

    The friction between two knots is interpolated linearly, so knot ``i`` acts on the
    samples with ``v_{i-1} < v_r < v_{i+1}``, with a weight above one half only for
    ``v_r > (v_{i-1} + v_i) / 2``. A knot counts as visited when the largest sliding speed
    of the record reaches that midpoint (the first knot always: every slip starts at
    ``v_r = 0``); the others are undetermined whatever their standard error.

    Parameters
    ----------
    table_v : sequence of float
        Knot speeds, m/s, increasing.
    max_sliding_speed : float
        Largest sliding speed of the fitted model over the record, m/s.

    Returns
    -------
    list of bool
        One flag per knot.
    """
    flags = [True]
    for lo, hi in itertools.pairwise(table_v):
        flags.append(max_sliding_speed >= 0.5 * (lo + hi))
    return flags[: len(table_v)]


def _check_table_speeds(table_speeds: Sequence[float]) -> tuple[float, ...]:
    knots = tuple(float(v) for v in table_speeds)
    if not 2 <= len(knots) <= MAX_TABLE_KNOTS:
        raise ValueError(f"table_speeds has {len(knots)} speeds; a table law needs 2 to {MAX_TABLE_KNOTS}")
    if not all(math.isfinite(v) and v >= 0.0 for v in knots):
        raise ValueError(f"table_speeds {list(knots)} must be finite and non-negative (m/s)")
    if any(b <= a for a, b in itertools.pairwise(knots)):
        raise ValueError(f"table_speeds {list(knots)} must increase strictly")
    return knots


def identify(record: MeasuredRecord, known: Mapping[str, Any], law: str = "coulomb", *,
             bootstrap: int = 0, seed: int = 0, fit_offset: bool | None = None,
             table_speeds: Sequence[float] | None = None,
             blas_threads: int | None = BLAS_THREADS) -> IdentificationResult:
    """Fit stiffness, damping and a friction law to a measured stick-slip record.

    Parameters
    ----------
    record : MeasuredRecord
        Times [s] and at least one of the load-cell force ``F`` [N] and the displacement ``x``
        [m] (optionally the velocity ``v`` [m/s]); see :mod:`stickslip.io.record` to read one.
    known : mapping
        What the user knows, SI floats: ``m`` (mass, kg), ``load`` (normal load W, N) and
        ``speed`` (drive speed V, m/s) are required; any fitted parameter (``k``, ``c``,
        ``mu_s``, ``mu_k``, ``slope``, ``stribeck_velocity``, ``exponent``, ``viscous``,
        ``force_offset``, ``force_drift``) given here is held fixed.
    law : {"coulomb", "linear", "stribeck", "table", "auto"}
        Friction law to fit; ``auto`` fits coulomb, linear and stribeck (its exponent held at
        1 unless known) and keeps the one with the lowest Bayesian information criterion (each
        one's AIC, BIC, chi-square and parameter count are reported).
    bootstrap : int
        Number of bootstrap refits over resampled cycles (0: none); gives 95 % percentile
        intervals.
    seed : int
        Seed of the bootstrap's random generator.
    fit_offset : bool, optional
        Fit a force offset (default: when the record has a displacement channel).
    table_speeds : sequence of float, optional
        ``table`` law: the knot speeds, m/s (2 to :data:`MAX_TABLE_KNOTS`, increasing). By
        default ``0`` and the :data:`TABLE_QUANTILES` of the sliding speeds the record
        visits (:func:`table_knots`). Knots the record does not reach
        (:func:`visited_knots`) come back undetermined.
    blas_threads : int or None
        BLAS threads while fitting (``threadpoolctl``); ``None`` leaves the process's setting.
        One by default (:data:`BLAS_THREADS`): the fit runs inside thread and process pools
        on small machines, where more BLAS threads oversubscribe the cores.

    Returns
    -------
    IdentificationResult

    Raises
    ------
    RecordError
        When the record cannot support the fit (fewer than two stick phases, too coarse).
    """
    known = dict(known)
    missing = [n for n in ("m", "load", "speed") if n not in known]
    if missing:
        raise ValueError(f"identify needs the known {', '.join(missing)} (mass, normal load, drive speed)")
    mass, load, speed = (float(known.pop(n)) for n in ("m", "load", "speed"))
    for name, value in (("m", mass), ("load", load), ("speed", speed)):
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name}={value!r} must be positive")
    allowed = set(PARAMETER_UNITS)
    unknown = sorted(set(known) - allowed)
    if unknown:
        raise ValueError(f"cannot hold {', '.join(unknown)} fixed: not a fitted parameter "
                         f"(one of {', '.join(sorted(allowed))})")
    law = law.strip().lower()
    if law not in (*LAWS, "auto"):
        raise ValueError(f"law {law!r} is not one of {', '.join(LAWS)}, auto")
    knots = _check_table_speeds(table_speeds) if table_speeds is not None else None
    if knots is not None and law != "table":
        raise ValueError(f"table_speeds are the knots of the table law, not of {law!r}")
    if blas_threads is not None and blas_threads < 1:
        raise ValueError(f"blas_threads={blas_threads!r} must be at least 1 (or None)")
    if fit_offset is None:
        fit_offset = record.x is not None and record.F is not None
    with _blas_limited(blas_threads):
        return _identify(record, known, law, mass=mass, load=load, speed=speed, bootstrap=bootstrap,
                         seed=seed, fit_offset=fit_offset, knots=knots)


_BLAS_LOCK = threading.Lock()
_blas_state: dict[str, Any] = {"users": 0, "limiter": None}


@contextmanager
def _blas_limited(threads: int | None) -> Iterator[None]:
    """Hold the BLAS libraries at ``threads`` threads while any fit runs (``None``: as they are).

    ``threadpoolctl`` sets a process-wide number, so fits running at once share one limit:
    the first fit to start sets it, the last to finish restores the process's own setting (a
    plain ``with threadpool_limits`` per fit would let the first fit to finish lift the limit
    under the others). The OpenBLAS that numpy and scipy ship ignores a limit set from a
    worker thread (measured: ``threadpool_info`` still reports the cores there), so a program
    that runs fits in a thread pool sets the limit around the pool, in its main thread:
    ``with threadpoolctl.threadpool_limits(1, user_api="blas"): ...``.
    """
    if threads is None:
        yield
        return
    with _BLAS_LOCK:
        if _blas_state["users"] == 0:
            _blas_state["limiter"] = threadpool_limits(limits=threads, user_api="blas")
        _blas_state["users"] += 1
    try:
        yield
    finally:
        with _BLAS_LOCK:
            _blas_state["users"] -= 1
            if _blas_state["users"] == 0:
                _blas_state["limiter"].restore_original_limits()
                _blas_state["limiter"] = None


def _identify(record: MeasuredRecord, known: Mapping[str, float], law: str, *, mass: float, load: float,
              speed: float, bootstrap: int, seed: int, fit_offset: bool,
              knots: tuple[float, ...] | None) -> IdentificationResult:
    """:func:`identify` after its arguments are checked: the Coulomb fit that starts the others,
    the law(s) asked for, the result."""
    est = estimate(record, mass=mass, load=load, speed=speed)
    laws = ("coulomb", "linear", "stribeck") if law == "auto" else (law,)
    fits: dict[str, tuple[_Problem, Any]] = {}
    coulomb_values: dict[str, float] | None = None
    table_v: tuple[float, ...] = ()
    for name in laws:
        start = None
        if name != "coulomb" and coulomb_values is None:
            problem, res = _fit_law(record, est, mass=mass, load=load, speed=speed, law="coulomb",
                                    known={k: v for k, v in known.items()
                                           if k not in LAW_PARAMETERS["stribeck"] + ("slope",)},
                                    fit_offset=fit_offset)
            coulomb_values = problem.values(res.x)
            if name == "table":
                sliding = speed - problem.simulate_record(res.x)["v"]
                table_v = knots if knots is not None else table_knots(sliding, speed)
            if law == "auto":
                fits["coulomb"] = (problem, res)
        if name == "coulomb" and name in fits:
            continue
        if coulomb_values is not None:
            start = dict(coulomb_values)
            if name == "stribeck":  # Coulomb's mu_k averages the curve; the high-speed limit is lower
                gap = coulomb_values["mu_s"] - coulomb_values["mu_k"]
                start["mu_k"] = coulomb_values["mu_k"] - 0.3 * gap
        law_known = dict(known)
        if law == "auto" and name == "stribeck":
            law_known.setdefault("exponent", 1.0)  # the comparison: exponential Stribeck decay
        problem, res = _fit_law(record, est, mass=mass, load=load, speed=speed, law=name, known=law_known,
                                fit_offset=fit_offset, start=start, table_v=table_v)
        if name == "coulomb":
            coulomb_values = problem.values(res.x)
        fits[name] = (problem, res)
    return _result(record, est, fits, chosen=min(fits, key=lambda n: _bic(*fits[n])) if law == "auto"
                   else law, bootstrap=bootstrap, seed=seed, known=known, mass=mass, load=load,
                   speed=speed, fit_offset=fit_offset)


def _n_params(problem: _Problem) -> int:
    return problem.n_global + problem.seg_ref.size


def _criteria(problem: _Problem, res: Any) -> tuple[float, float]:
    n = res.fun.size
    chi2 = max(2.0 * res.cost, 1e-300)
    p = _n_params(problem)
    base = n * math.log(chi2 / n)
    return base + 2.0 * p, base + p * math.log(n)


def _criteria_report(problem: _Problem, res: Any) -> dict[str, float]:
    """``aic``, ``bic``, the weighted ``chi2`` and the parameter count ``n_params`` of one fit."""
    aic, bic = _criteria(problem, res)
    return {"aic": aic, "bic": bic, "chi2": 2.0 * float(res.cost), "n_params": _n_params(problem)}


def _bic(problem: _Problem, res: Any) -> float:
    return _criteria(problem, res)[1]


def _bootstrap(problem: _Problem, res: Any, n_boot: int, seed: int) -> dict[str, tuple[float, float]]:
    """95 % percentile intervals of the reported parameters over cycles drawn with replacement.

    Each refit weighs every segment (cycle) by how often it was drawn and starts from the
    optimum; the segment states of undrawn cycles drop out of the residual.
    """
    rng = np.random.default_rng(seed)
    n = problem.record.t.size
    n_ch = len(problem.record.channels)
    samples: list[dict[str, float]] = []
    for _ in range(n_boot):
        draw = rng.integers(0, len(problem.segments), len(problem.segments))
        counts = np.bincount(draw, minlength=len(problem.segments)).astype(np.float64)
        w = np.empty(n)
        for seg, count in zip(problem.segments, counts, strict=True):
            w[seg.start:seg.stop] = math.sqrt(count)
        refit = _solve(problem, res.x, weights=np.tile(w, n_ch), max_nfev=60)
        samples.append(problem.values(refit.x))
    out: dict[str, tuple[float, float]] = {}
    for name in samples[0] if samples else []:
        vals = np.array([s[name] for s in samples])
        out[name] = (float(np.percentile(vals, 2.5)), float(np.percentile(vals, 97.5)))
    return out


def _result(record: MeasuredRecord, est: RecordEstimates, fits: Mapping[str, tuple[_Problem, Any]],
            *, chosen: str, bootstrap: int, seed: int, known: Mapping[str, Any], mass: float,
            load: float, speed: float, fit_offset: bool) -> IdentificationResult:
    problem, res = fits[chosen]
    values = problem.values(res.x)
    jac = _two_sided_jacobian(problem, res)
    chi2 = 2.0 * res.cost
    reported, cov, singular, weak = _covariance(problem, jac, chi2, res.fun.size)
    stderr = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        corr = cov / np.outer(stderr, stderr)
    intervals = _bootstrap(problem, res, bootstrap, seed) if bootstrap > 0 else {}
    model = problem.simulate_record(res.x)
    knot_names = [f"table_mu_{i}" for i in range(len(problem.table_v))]
    visited = visited_knots(problem.table_v, float(np.max(speed - model["v"]))) if knot_names else []
    outside = {n for n, seen in zip(knot_names, visited, strict=True) if not seen}
    at_limit = {n for n, z, lo, hi in zip(problem.names, res.x, problem.lower, problem.upper, strict=False)
                if n in SEARCH_LIMITED and min(z - lo, hi - z) <= LIMIT_TOLERANCE * max(abs(z), 1.0)}
    params: dict[str, FitParameter] = {}
    order = ["k", "c", "mu_s", "mu_k", *LAW_PARAMETERS[chosen], "force_offset", "force_drift", *knot_names]
    for name in order:
        if chosen == "table" and name == "mu_k":
            params[name] = FitParameter(name, None, None, "", free=True)  # filled in below
        elif name in reported:
            i = reported.index(name)
            se = float(stderr[i])
            bad = (weak[i] or name in outside or name in at_limit
                   or undetermined(name, values[name], se, values, mass=mass, speed=speed))
            params[name] = FitParameter(name, None if bad else values[name], None if bad else se,
                                        PARAMETER_UNITS[name], free=True, estimate=values[name],
                                        interval=intervals.get(name))
        else:
            params[name] = FitParameter(name, values[name], None, PARAMETER_UNITS[name], free=False,
                                        estimate=values[name])
    if chosen == "table":  # mu_k: the lowest knot the record determines (kinetic reference)
        lowest = min(knot_names, key=lambda n: values[n])
        determined = [n for n in knot_names if params[n].value is not None]
        if determined:
            lowest = min(determined, key=lambda n: values[n])
        knot = params[lowest]
        params["mu_k"] = FitParameter("mu_k", knot.value, knot.stderr, "", free=knot.free,
                                      estimate=values[lowest], interval=knot.interval)
    criteria = {name: _criteria_report(p, r) for name, (p, r) in fits.items()}
    rms = {n: float(np.sqrt(np.mean((model[n] - getattr(record, n)) ** 2))) for n in record.channels}
    stick_cycles = sum(1 for seg in problem.segments if seg.in_stick and seg.stop - seg.start > 1)
    return IdentificationResult(
        law=chosen, parameters=params, correlations={
            (a, b): float(corr[i, j]) for i, a in enumerate(reported) for j, b in enumerate(reported) if i < j
        },
        residual_rms=rms, noise=dict(problem.sigma), cycles_used=len(est.stick_phases),
        segments=len(problem.segments), stick_segments=stick_cycles, n_samples=record.t.size,
        n_free=_n_params(problem), chi2=chi2, criteria=criteria, mass=mass, load=load, speed=speed,
        table_v=problem.table_v, t=record.t, measured={n: getattr(record, n) for n in record.channels},
        fitted=model, engine_calls=sum(p.n_calls for p, _ in fits.values()),
        engine_seconds=sum(p.engine_seconds for p, _ in fits.values()), n_evaluations=int(res.nfev),
        success=bool(res.success), message=str(res.message), source=record.source,
        fit_offset=fit_offset, condition=float(singular[0] / singular[-1]) if singular[-1] > 0 else math.inf,
        covariance=cov, covariance_names=tuple(reported), bootstrap=bootstrap, table_visited=tuple(visited),
    )
