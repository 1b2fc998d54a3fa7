"""The least-squares problem of an identification: segments, residuals, Jacobian, covariance.

One :class:`FitProblem` per friction law holds the record, what is known and what is free,
and evaluates the weighted residuals of the whole signal through the exact engine (multiple
shooting over the record's segments, see :mod:`stickslip.analysis.identification.record_fit`, whose
docstring gives the method). Split from that module, which runs the fits and reports them.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares
from scipy.signal import savgol_filter

from stickslip.analysis.identification.estimates import (
    MeasuredRecord,
    RecordEstimates,
)
from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.model.friction import STRIBECK_RANGES
from stickslip.model.initial import InitialState
from stickslip.model.physical import PhysicalFriction, PhysicalSystem

FloatArray = NDArray[np.float64]

#: Parameters of each law beyond ``mu_s`` and ``mu_k`` (the machine file's ``[friction]`` keys).
LAW_PARAMETERS: dict[str, tuple[str, ...]] = {
    "coulomb": (),
    "linear": ("slope",),
    "stribeck": ("stribeck_velocity", "exponent", "viscous"),
    "table": (),
}
#: Law approximation tolerance of the Stribeck interpolant during a fit (units of lambda).
STRIBECK_TOLERANCE = 1e-4
#: Iteration budget of one least-squares fit (function evaluations). A five-parameter Stribeck
#: fit can crawl along the valley of its Stribeck velocity and exponent: an audit's record
#: (v_s 1 cm/s, exponent 1, 0.1 % noise) converged after 189 evaluations, and at 100 it had
#: stopped at exponent 0.55 +/- 0.09 with mu_s 7.8 standard errors off.
MAX_EVALUATIONS = 400
#: Forward-difference step of the Jacobian in the scaled coordinates (parameters over their
#: natural scales, segment states over ``V / omega_n``).
FD_STEP = 1e-6
#: ``ftol``, ``xtol`` and ``gtol`` of ``least_squares``.
TOLERANCE = 1e-8
TR_SOLVER = "exact"


@dataclass(frozen=True)
class Segment:
    """Samples ``[start, stop)`` simulated from one initial state."""

    start: int
    stop: int
    in_stick: bool  # the state is (x_j, V); otherwise (x_0, v_0) both free


@dataclass
class FitProblem:
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
    segments: list[Segment]
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
              ) -> tuple[list[Segment], list[float], list[float], list[list[int]]]:
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
    segments: list[Segment] = []
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
        segments.append(Segment(0, anchors[0], in_stick=False))
        slots.append([len(ref), len(ref) + 1])
        ref += [position(0) if "x" in sm else float((sm["F"][0] - start["force_offset"] - c * v0) / k), v0]
        scale += [length, speed]
    bounds = [*anchors, n]
    for a, b in itertools.pairwise(bounds):
        if b - a < 2:
            continue
        segments.append(Segment(a, b, in_stick=True))
        slots.append([len(ref)])
        ref.append(position(a))
        scale.append(length)
    return segments, ref, scale, slots


def build_problem(record: MeasuredRecord, est: RecordEstimates, *, mass: float, load: float,
                  speed: float, law: str, known: Mapping[str, float], fit_offset: bool,
                  start: Mapping[str, float] | None, table_v: tuple[float, ...] = ()) -> FitProblem:
    """Free parameters, their scales, bounds and starting values for one law.

    Parameters
    ----------
    record : MeasuredRecord
        The measured record (SI).
    est : RecordEstimates
        Starting estimates read from the record (stick slope, breakaway and lowest force).
    mass, load, speed : float
        The known mass (kg), normal load (N) and drive speed (m/s).
    law : str
        One of ``LAW_PARAMETERS``' keys.
    known : mapping
        Parameters held fixed, by machine-file name, in SI.
    fit_offset : bool
        Whether the force zero's offset is a free nuisance parameter.
    start : mapping or None
        Starting values that replace the estimates (e.g. a Coulomb fit's optimum).
    table_v : tuple of float
        Knot speeds of a ``table`` law, m/s.

    Returns
    -------
    FitProblem
        The problem, with ``start`` the scaled starting vector.
    """
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
    if record.F is None:  # no force channel: its zero (offset and drift) acts on nothing
        fixed.setdefault("force_offset", 0.0)
        fixed.setdefault("force_drift", 0.0)
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
    problem = FitProblem(
        record=record, mass=mass, load=load, speed=speed, law=law, names=names, fixed=fixed,
        scales=scales, lower=lo / scales, upper=hi / scales, segments=segments,
        seg_ref=np.array(ref), seg_scale=np.array(seg_scale), seg_slots=slots, sigma=sigma,
        table_v=table_v,
    )
    z0 = np.concatenate([np.array(values) / scales, np.zeros(len(ref))])
    problem_start = np.clip(z0[: len(names)], problem.lower + 1e-12, problem.upper - 1e-12)
    problem.start = np.concatenate([problem_start, z0[len(names):]])
    return problem


def solve_fit(problem: FitProblem, z0: FloatArray, weights: FloatArray | None = None,
              max_nfev: int = MAX_EVALUATIONS) -> Any:
    """Trust-region reflective least squares of the problem's residuals from ``z0``.

    Parameters
    ----------
    problem : FitProblem
        The problem.
    z0 : ndarray
        Scaled starting vector (global parameters, then segment states).
    weights : ndarray or None
        Per-sample weights (the bootstrap's cycle resampling), or None for all ones.
    max_nfev : int
        Budget of residual evaluations.

    Returns
    -------
    scipy.optimize.OptimizeResult
        ``least_squares``' result (``x``, ``fun``, ``jac``, ``cost``).
    """
    n_seg = problem.seg_ref.size
    lower = np.concatenate([problem.lower, np.full(n_seg, -np.inf)])
    upper = np.concatenate([problem.upper, np.full(n_seg, np.inf)])
    return least_squares(problem.residuals, z0, jac=problem.jacobian, bounds=(lower, upper),
                         method="trf", tr_solver=TR_SOLVER, x_scale=1.0, ftol=TOLERANCE, xtol=TOLERANCE,
                         gtol=TOLERANCE, max_nfev=max_nfev, kwargs={"weights": weights})


def bootstrap_intervals(problem: FitProblem, res: Any, n_boot: int, seed: int,
                        progress: Callable[[int, int], None] | None = None
                        ) -> dict[str, tuple[float, float]]:
    """95 % percentile intervals of the reported parameters over cycles drawn with replacement.

    Each refit weighs every segment (cycle) by how often it was drawn and starts from the
    optimum; the segment states of undrawn cycles drop out of the residual.

    Parameters
    ----------
    problem : FitProblem
        The fitted problem.
    res : scipy.optimize.OptimizeResult
        Its optimum (``x``).
    n_boot : int
        Resamples.
    seed : int
        Seed of the draws.
    progress : callable, optional
        ``progress(done, n_boot)`` after each refit.

    Returns
    -------
    dict
        ``name -> (2.5 %, 97.5 %)`` percentiles of each reported parameter.
    """
    rng = np.random.default_rng(seed)
    n = problem.record.t.size
    n_ch = len(problem.record.channels)
    samples: list[dict[str, float]] = []
    for done in range(n_boot):
        if progress is not None:
            progress(done, n_boot)
        draw = rng.integers(0, len(problem.segments), len(problem.segments))
        counts = np.bincount(draw, minlength=len(problem.segments)).astype(np.float64)
        w = np.empty(n)
        for seg, count in zip(problem.segments, counts, strict=True):
            w[seg.start:seg.stop] = math.sqrt(count)
        refit = solve_fit(problem, res.x, weights=np.tile(w, n_ch), max_nfev=60)
        samples.append(problem.values(refit.x))
    if progress is not None:
        progress(n_boot, n_boot)
    out: dict[str, tuple[float, float]] = {}
    for name in samples[0] if samples else []:
        vals = np.array([s[name] for s in samples])
        out[name] = (float(np.percentile(vals, 2.5)), float(np.percentile(vals, 97.5)))
    return out



def two_sided_jacobian(problem: FitProblem, res: Any) -> FloatArray:
    """The optimiser's Jacobian at the optimum with each global parameter's column checked
    against the backward difference; the one with the smaller norm is kept.

    The exact engine's signals are smooth in the parameters except where an event appears
    or vanishes (a grazing stick onset, a band of a tabulated law): a forward step that
    crosses such a point overstates the sensitivity by orders of magnitude and so understates
    the standard error. Where the two one-sided differences disagree the smaller one gives the
    larger (conservative) standard error; where the model is smooth they agree to ``O(h)``.

    Parameters
    ----------
    problem : FitProblem
        The problem.
    res : scipy.optimize.OptimizeResult
        The optimum, as :func:`solve_fit` returns it.

    Returns
    -------
    ndarray
        The Jacobian, samples by scaled parameters.
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


def parameter_covariance(problem: FitProblem, jac: FloatArray, chi2: float, n_obs: int
                         ) -> tuple[list[str], FloatArray, FloatArray, list[bool]]:
    """Covariance of the reported global parameters and which ones are near-singular.

    ``cov = s^2 (J^T J)^-1`` with ``s^2 = chi^2 / (N - p)`` (lmfit's ``scale_covar``), from the
    SVD of the column-scaled Jacobian.

    Parameters
    ----------
    problem : FitProblem
        The problem.
    jac : ndarray
        Jacobian at the optimum (:func:`two_sided_jacobian`).
    chi2 : float
        Weighted sum of squared residuals at the optimum.
    n_obs : int
        Number of residuals.

    Returns
    -------
    names : list of str
        The reported names (``mu_s`` in place of the internal ``delta_mu``).
    cov : ndarray
        Their covariance, physical units.
    singular : ndarray
        The scaled Jacobian's singular values.
    weak : list of bool
        Per name, whether it loads on a numerically null direction (singular values below
        ``1e-8`` of the largest after column scaling).
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
