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

Dimensionless mapping (paper Section 2.3): ``omega_n = sqrt(k/m)``,
``tau = omega_n t``, ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``,
``gamma = mu_k / (mu_s - mu_k)``, ``zeta = c / (2 sqrt(m k))``, and the shifted coordinate
``xi = x omega_n / V - gamma lambda`` (measured from the kinetic equilibrium ``k x = mu_k W``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.blas_threads import blas_limited
from stickslip.analysis.identification.estimates import (
    MeasuredRecord,
    RecordError,
    RecordEstimates,
    estimate,
)
from stickslip.analysis.identification.fit_judgement import judge, mass_note
from stickslip.analysis.identification.problem import (
    LAW_PARAMETERS,
    FitProblem,
    bootstrap_intervals,
    build_problem,
    parameter_covariance,
    solve_fit,
    two_sided_jacobian,
)
from stickslip.analysis.identification.result import (
    PARAMETER_UNITS,
    UNDETERMINED_RULE,
    FitParameter,
    IdentificationResult,
    undetermined,
)
from stickslip.model.friction import STRIBECK_RANGES

FloatArray = NDArray[np.float64]

LAWS = ("coulomb", "linear", "stribeck", "table")
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
#: Iteration budget of each trial start of a Stribeck fit.
MULTISTART_EVALUATIONS = 12
#: The Stribeck law's shape parameters at the exponential decay without viscous term, the
#: law nested in it whose optimum starts one more fit of the full law (:func:`_fit_law`).
NESTED_STRIBECK = {"exponent": 1.0, "viscous": 0.0}
#: The stated rule for long records (:func:`fit_window`): the fit uses at most this many
#: stick-slip periods, the middle ones of the record, ...
MAX_FIT_PERIODS = 30
#: ... and at most about this many samples per channel, taking every d-th sample of that
#: window, while keeping at least :data:`MIN_KEPT_PER_PERIOD` samples per period (the
#: estimates need 40). The cost of a fit grows with samples times periods (each period is a
#: segment of the multiple shooting, with a column of the Jacobian): a 1e6-row record of 380
#: periods would need a 1e6 x 400 Jacobian; the window keeps it below 20,000 x 40. The noise
#: stays white and of the same level under decimation, so the weights and the standard errors
#: are those of the samples used (larger than all samples would give, never smaller).
MAX_FIT_SAMPLES = 20_000
MIN_KEPT_PER_PERIOD = 200
#: A load-cell force beyond this many times the normal load is refused before any fit: the
#: spring holds the slider against friction, ``|F| <= mu_s W`` in stick plus the slip's
#: overshoot, so a friction coefficient of a thousand means wrong units (of F or --load).
FORCE_FACTOR = 1e3

__all__ = ["LAWS", "UNDETERMINED_RULE", "IdentificationResult", "MeasuredRecord", "RecordError",
           "identify"]


def _fit_law(record: MeasuredRecord, est: RecordEstimates, *, mass: float, load: float, speed: float,
             law: str, known: Mapping[str, float], fit_offset: bool,
             start: Mapping[str, float] | None = None, table_v: tuple[float, ...] = ()
             ) -> tuple[FitProblem, Any]:
    problem = build_problem(record, est, mass=mass, load=load, speed=speed, law=law, known=known,
                            fit_offset=fit_offset, start=start, table_v=table_v)
    z0 = problem.start
    # Stribeck: the optimiser can stall with the Stribeck velocity far off; two more starts
    if law != "stribeck" or "stribeck_velocity" in known:
        return problem, solve_fit(problem, z0)
    # short trial fits from three Stribeck velocities; the best one is carried to convergence
    i = problem.names.index("stribeck_velocity")
    best = None
    for frac in (0.05, 0.3, 1.0):
        z1 = z0.copy()
        z1[i] = np.clip(frac * est.max_sliding_speed / problem.scales[i], problem.lower[i] * 1.001,
                        problem.upper[i] * 0.999)
        trial = solve_fit(problem, z1, max_nfev=MULTISTART_EVALUATIONS)
        if best is None or trial.cost < best.cost:
            best = trial
    assert best is not None
    res = solve_fit(problem, best.x)
    nested = {name: value for name, value in NESTED_STRIBECK.items() if name not in known}
    if not nested:
        return problem, res
    # the exponential decay without viscous term is nested in this law: its optimum is a
    # point of this problem, so the fit from there ends at least as low. Short fits from the
    # estimates stopped near the exponent's lower limit on noisy records, chi-square above
    # the nested optimum's (an independent audit: exponent 0.51 for a record of n = 1)
    inner, inner_res = _fit_law(record, est, mass=mass, load=load, speed=speed, law=law,
                                known={**known, **nested}, fit_offset=fit_offset, start=start)
    carried = _carried_start(problem, inner, inner_res.x)
    if carried is not None:
        res1 = solve_fit(problem, carried)
        if res1.cost < res.cost:
            res = res1
    return problem, res


def _carried_start(problem: FitProblem, inner: FitProblem, z: FloatArray) -> FloatArray | None:
    """The point of ``problem`` (scaled) where the nested problem ``inner`` is at ``z``: its
    global parameters by name (the held ones at their fixed values), its segment states
    through their physical values. None when the segments differ."""
    values = inner.values(z)
    states = inner.segment_states(z)
    if states.size != problem.seg_ref.size:
        return None
    if "delta_mu" in problem.names:
        values["delta_mu"] = values["mu_s"] - values["mu_k"]
    glob = np.array([values[n] for n in problem.names]) / problem.scales
    glob = np.clip(glob, problem.lower + 1e-12, problem.upper - 1e-12)
    return np.concatenate([glob, (states - problem.seg_ref) / problem.seg_scale])


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
             blas_threads: int | None = BLAS_THREADS,
             progress: Callable[[int, int], None] | None = None) -> IdentificationResult:
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
    progress : callable, optional
        ``progress(done, total)`` after each bootstrap refit (a bar for long bootstraps).

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
    check_known(known, law)
    knots = _check_table_speeds(table_speeds) if table_speeds is not None else None
    if knots is not None and law != "table":
        raise ValueError(f"table_speeds are the knots of the table law, not of {law!r}")
    if blas_threads is not None and blas_threads < 1:
        raise ValueError(f"blas_threads={blas_threads!r} must be at least 1 (or None)")
    if fit_offset is None:
        fit_offset = record.x is not None and record.F is not None
    try:
        if record.F is not None and float(np.max(np.abs(record.F))) > FORCE_FACTOR * load:
            peak = float(np.max(np.abs(record.F)))
            raise RecordError(f"the force F reaches {peak:.3g} N, {peak / load:.3g} times the "
                              f"normal load {load:.4g} N; friction that strong is not a sliding "
                              f"contact (beyond {FORCE_FACTOR:g} times): check the force's units "
                              "and --load")
        with blas_limited(blas_threads):
            used, window = fit_window(record, estimate(record, mass=mass, load=load, speed=speed))
            return _identify(used, known, law, mass=mass, load=load, speed=speed, bootstrap=bootstrap,
                             seed=seed, fit_offset=fit_offset, knots=knots, window=window,
                             progress=progress)
    except RecordError as exc:  # a refusal names the record it refuses
        text = str(exc)
        named = text if text.startswith("record ") else f"record {record.source}: {text}"
        raise RecordError(named) from None


def fit_window(record: MeasuredRecord, est: RecordEstimates) -> tuple[MeasuredRecord, str]:
    """The part of a long record the fit uses, by the stated rule, and a sentence saying so.

    At most :data:`MAX_FIT_PERIODS` stick-slip periods (the middle ones: from the onset of one
    stick phase to the onset of the stick phase that many later) and, within them, every
    ``d``-th sample, ``d`` the smallest whole number that leaves at most
    :data:`MAX_FIT_SAMPLES` samples, but no larger than keeps :data:`MIN_KEPT_PER_PERIOD`
    samples per period. A record within both limits is used whole.

    Parameters
    ----------
    record : MeasuredRecord
        The whole record.
    est : RecordEstimates
        Its estimates (period and stick phases).

    Returns
    -------
    record : MeasuredRecord
        The samples used (times from 0 at the first one), or ``record`` itself.
    window : str
        What was used, in words ("" for the whole record).
    """
    n = record.t.size
    phases = est.stick_phases
    lo, hi, first = 0, n, 0
    if len(phases) > MAX_FIT_PERIODS + 1:
        first = (len(phases) - MAX_FIT_PERIODS - 1) // 2
        lo, hi = phases[first].start, phases[first + MAX_FIT_PERIODS].start
    per_period = est.period / (record.t[-1] / (n - 1))
    step = max(1, min(math.ceil((hi - lo) / MAX_FIT_SAMPLES), int(per_period // MIN_KEPT_PER_PERIOD)))
    if (lo, hi, step) == (0, n, 1):
        return record, ""
    index = np.arange(lo, hi, step)
    periods = (f"stick-slip periods {first + 1} to {first + MAX_FIT_PERIODS} of {len(phases)}"
               if hi - lo < n else f"all {len(phases)} stick-slip periods")
    return record.subset(index), (
        f"fitted on {index.size} of {n} samples: {periods}, every {step} sample(s) (at most "
        f"{MAX_FIT_PERIODS} periods and {MAX_FIT_SAMPLES} samples, at least {MIN_KEPT_PER_PERIOD} "
        "per period; times from the first sample used)")


#: What a value held fixed must be: positive, non-negative or just finite (any sign).
_KNOWN_SIGN = {"k": "positive", "mu_s": "positive", "stribeck_velocity": "positive",
               "exponent": "positive", "c": "non-negative", "mu_k": "non-negative"}


def check_known(known: Mapping[str, Any], law: str) -> None:
    """Refuse, in one line, a value held fixed that the fit cannot take.

    Each is a finite real number (``force_offset = inf`` is not); ``k``, ``mu_s``,
    ``stribeck_velocity`` and ``exponent`` positive, ``c`` and ``mu_k`` non-negative,
    ``mu_s > mu_k`` when both are given; and a parameter of the law fitted (``slope`` belongs
    to the linear law, not to ``coulomb``; ``auto`` fits coulomb, linear and stribeck).

    Parameters
    ----------
    known : mapping
        Parameters held fixed, by name, SI.
    law : str
        The law asked for (``auto`` included).

    Returns
    -------
    None
        Raises ``ValueError`` naming the parameter, its value and why.
    """
    laws = ("coulomb", "linear", "stribeck") if law == "auto" else (law,)
    own = {n for name in laws for n in LAW_PARAMETERS[name]}
    if "table" in laws:
        own |= {f"table_mu_{i}" for i in range(MAX_TABLE_KNOTS)}
    for name, value in known.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ValueError(f"{name} = {value!r} held fixed must be a finite number")
        sign = _KNOWN_SIGN.get(name)
        if (sign == "positive" and not value > 0.0) or (sign == "non-negative" and value < 0.0):
            raise ValueError(f"{name} = {value!r} held fixed must be {sign}")
        shared = name in ("k", "c", "mu_s", "mu_k", "force_offset", "force_drift")
        if not shared and name not in own:
            owners = [n for n in LAWS if name in LAW_PARAMETERS[n]] or ["table"]
            raise ValueError(f"{name} held fixed does not belong to the {law} law (it is a "
                             f"parameter of the {' and '.join(owners)} law)")
    if "exponent" in known:
        low, high, why = STRIBECK_RANGES["exponent"]
        if not low <= known["exponent"] <= high:
            raise ValueError(f"exponent = {known['exponent']!r} held fixed must lie in [{low:g}, "
                             f"{high:g}] ({why})")
    if "mu_s" in known and "mu_k" in known and not known["mu_s"] > known["mu_k"]:
        raise ValueError(f"mu_s = {known['mu_s']!r} held fixed must exceed mu_k = {known['mu_k']!r}")


def _identify(record: MeasuredRecord, known: Mapping[str, float], law: str, *, mass: float, load: float,
              speed: float, bootstrap: int, seed: int, fit_offset: bool,
              knots: tuple[float, ...] | None, window: str = "",
              progress: Callable[[int, int], None] | None = None) -> IdentificationResult:
    """:func:`identify` after its arguments are checked: the Coulomb fit that starts the others,
    the law(s) asked for, the result."""
    est = estimate(record, mass=mass, load=load, speed=speed)
    if "mu_s" in known and "mu_k" not in known and not known["mu_s"] > est.mu_k:
        raise ValueError(f"mu_s = {known['mu_s']!r} held fixed must exceed the record's kinetic "
                         f"friction coefficient mu_k (about {est.mu_k:.3g} from its stick phases)")
    if "mu_k" in known and "mu_s" not in known and not known["mu_k"] < est.mu_s:
        raise ValueError(f"mu_k = {known['mu_k']!r} held fixed must be below the record's static "
                         f"friction coefficient mu_s (about {est.mu_s:.3g} from its breakaways)")
    laws = ("coulomb", "linear", "stribeck") if law == "auto" else (law,)
    try:
        fits = _fit_laws(record, est, known, law, laws, mass=mass, load=load, speed=speed,
                         fit_offset=fit_offset, knots=knots)
    except RecordError:
        raise
    except ValueError as exc:  # a parameter driven out of range: a wrong mass says so first
        note = mass_note(est, mass)
        if note:
            raise RecordError(f"{note}: check --mass (the fit stopped at: {exc})") from None
        raise
    return _result(record, est, fits, chosen=min(fits, key=lambda n: _bic(*fits[n])) if law == "auto"
                   else law, bootstrap=bootstrap, seed=seed, known=known, mass=mass, load=load,
                   speed=speed, fit_offset=fit_offset, window=window, progress=progress)


def _fit_laws(record: MeasuredRecord, est: RecordEstimates, known: Mapping[str, float], law: str,
              laws: tuple[str, ...], *, mass: float, load: float, speed: float, fit_offset: bool,
              knots: tuple[float, ...] | None) -> dict[str, tuple[FitProblem, Any]]:
    """The fits of ``laws``, each started from the Coulomb fit's optimum (fitted first)."""
    fits: dict[str, tuple[FitProblem, Any]] = {}
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
    return fits


def _n_params(problem: FitProblem) -> int:
    return problem.n_global + problem.seg_ref.size


def _criteria(problem: FitProblem, res: Any) -> tuple[float, float]:
    n = res.fun.size
    chi2 = max(2.0 * res.cost, 1e-300)
    p = _n_params(problem)
    base = n * math.log(chi2 / n)
    return base + 2.0 * p, base + p * math.log(n)


def _criteria_report(problem: FitProblem, res: Any) -> dict[str, float]:
    """``aic``, ``bic``, the weighted ``chi2`` and the parameter count ``n_params`` of one fit."""
    aic, bic = _criteria(problem, res)
    return {"aic": aic, "bic": bic, "chi2": 2.0 * float(res.cost), "n_params": _n_params(problem)}


def _bic(problem: FitProblem, res: Any) -> float:
    return _criteria(problem, res)[1]


def _result(record: MeasuredRecord, est: RecordEstimates, fits: Mapping[str, tuple[FitProblem, Any]],
            *, chosen: str, bootstrap: int, seed: int, known: Mapping[str, Any], mass: float,
            load: float, speed: float, fit_offset: bool, window: str = "",
            progress: Callable[[int, int], None] | None = None) -> IdentificationResult:
    problem, res = fits[chosen]
    values = problem.values(res.x)
    jac = two_sided_jacobian(problem, res)
    chi2 = 2.0 * res.cost
    reported, cov, singular, weak = parameter_covariance(problem, jac, chi2, res.fun.size)
    stderr = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        corr = cov / np.outer(stderr, stderr)
    intervals = bootstrap_intervals(problem, res, bootstrap, seed, progress) if bootstrap > 0 else {}
    model = problem.simulate_record(res.x)
    knot_names = [f"table_mu_{i}" for i in range(len(problem.table_v))]
    visited = visited_knots(problem.table_v, float(np.max(speed - model["v"]))) if knot_names else []
    outside = {n for n, seen in zip(knot_names, visited, strict=True) if not seen}
    at_limit = {n for n, z, lo, hi in zip(problem.names, res.x, problem.lower, problem.upper, strict=False)
                if n in SEARCH_LIMITED and min(z - lo, hi - z) <= LIMIT_TOLERANCE * max(abs(z), 1.0)}
    # with the force as the only position channel, a fitted offset is exactly a common shift
    # of the friction levels (it moves the kinetic equilibrium, adding the same constant to F):
    # the levels are undetermined whatever the rank test says (it does not see the degeneracy
    # of a noise-free record, whose optimum is sharp along every other direction)
    shifted: set[str] = set()
    if record.x is None and "force_offset" in problem.names:
        shifted = {"mu_s", "mu_k", "force_offset", *knot_names}
    params: dict[str, FitParameter] = {}
    order = ["k", "c", "mu_s", "mu_k", *LAW_PARAMETERS[chosen], "force_offset", "force_drift", *knot_names]
    for name in order:
        if chosen == "table" and name == "mu_k":
            params[name] = FitParameter(name, None, None, "", free=True)  # filled in below
        elif name in reported:
            i = reported.index(name)
            se = float(stderr[i])
            bad = (weak[i] or name in outside or name in at_limit or name in shifted
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
    warnings = judge(record, est, chi2, res.fun.size - _n_params(problem), mass=mass,
                      speed=speed)
    if not res.success:
        warnings += (f"the fit did not converge ({res.message}, {int(res.nfev)} evaluations): the "
                     "values and standard errors are where the optimiser stopped, not an "
                     "optimum; fix parameters you know (--fix) or try another --law",)
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
        warnings=warnings, window=window,
    )
