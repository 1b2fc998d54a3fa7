"""A measured stick-slip record and the starting values read from it (issue 19).

The 1DOF rig of the paper's Fig. 1 (rigid base), in SI units: a slider of mass ``m`` [kg] on
a belt (or drive) moving at ``V`` [m/s] under the normal load ``W`` [N], held by a spring ``k``
[N/m] and a dashpot ``c`` [N s/m]. ``x`` [m] is the slider's displacement from where the spring
is relaxed, positive along the belt's motion; the load cell between the spring-damper and the
slider reads ``F = k x + c x'`` [N] (tension positive).

Everything that is exact about a stick phase is used to start the fit:

* during stick the slider moves with the belt, ``x' = V``, so ``F`` rises linearly with the
  slope ``k V`` (``k`` from the force record, or from the displacement record through the
  slip-phase frequency below);
* stick ends at the breakaway force ``F = mu_s W`` (a peak of the force record);
* for the paper's Coulomb law without damping the slip phase is half an ellipse about the
  kinetic equilibrium ``k x_eq = mu_k W``: it starts at ``x_eq + D`` with ``x' = V`` and ends
  (stick onset) at ``x_eq - D`` with ``x' = V``, after ``omega T_slip = pi + 2 atan(V / (omega D))``
  (paper Section 3.1, Eqs. 34-35 in the dimensionless form). So the midpoint of the breakaway
  and stick-onset forces is ``mu_k W`` and the slip duration gives ``omega = sqrt(k / m)``.

These are starting values, not answers: the least-squares fit of
:mod:`stickslip.analysis.identification.record_fit` refines them against the exact engine.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq
from scipy.signal import find_peaks, savgol_filter

FloatArray = NDArray[np.float64]
#: Largest magnitude of a record's displacement or velocity, SI (m, m/s): far beyond any rig,
#: and far below where the fit's squares overflow (a force is checked against the load).
MAX_RECORD_VALUE = 1e12
#: Most samples of a record: 100 s at 10 kHz. The fit's engine runs span the record, so a
#: longer one takes minutes; 10 to 20 stick-slip periods determine the parameters.
MAX_RECORD_SAMPLES = 1_000_000


def check_record_length(name: str, samples: int) -> None:
    """Refuse a record of more than :data:`MAX_RECORD_SAMPLES` samples, in one line.

    Parameters
    ----------
    name : str
        How the message names the record.
    samples : int
        Its number of samples (data rows).

    Returns
    -------
    None
        Returns when the record is short enough; raises :class:`RecordError` otherwise.
    """
    if samples > MAX_RECORD_SAMPLES:
        raise RecordError(f"record {name} has {samples:,} samples, more than "
                          f"{MAX_RECORD_SAMPLES:,}: cut it to 10-20 stick-slip periods or "
                          "decimate it (keep 40 or more samples per period)")

#: Fewest breakaways (stick phases ending in a peak of the force) a record must show.
MIN_STICK_PHASES = 2
#: Fewest samples per stick-slip period the estimates need.
MIN_SAMPLES_PER_PERIOD = 40
#: In a stick phase the slider moves with the belt: a displacement record's rising phases must
#: move at the drive speed ``V`` within this fraction (the median over the stick phases), or
#: they are not stick phases (a smooth oscillation, a wrong ``--speed``, a wrong sign of x).
STICK_SPEED_RTOL = 0.1
#: Within that, a median stick speed beyond this fraction of ``V`` (and beyond five standard
#: errors of the per-phase speeds' mean) is said in the fit's warnings: the fit takes ``V`` as
#: stated, and a 5 % error in it moved the fitted ``k`` by 2 % at 33 standard errors with only
#: a reduced chi-square of 1.4 to show for it.
STICK_SPEED_NOTE = 0.01


class RecordError(ValueError):
    """The record cannot support an identification (too short, no stick phases, ...)."""


@dataclass(frozen=True)
class MeasuredRecord:
    """A sampled stick-slip record in SI units and the rig's sign conventions.

    Parameters
    ----------
    t : array_like
        Sample times, s, strictly increasing (shifted so that the record starts at 0).
    F : array_like, optional
        Load-cell force ``F = k x + c x'``, N (tension positive).
    x : array_like, optional
        Slider displacement from where the spring is relaxed, m, positive along the belt.
    v : array_like, optional
        Slider velocity, m/s.
    source : str
        Where the record came from (file name), for reports.

    At least one of ``F`` and ``x`` is needed (``v`` alone does not show the stick force).
    """

    t: FloatArray
    F: FloatArray | None = None
    x: FloatArray | None = None
    v: FloatArray | None = None
    source: str = "(array)"

    def __post_init__(self) -> None:
        t = np.asarray(self.t, dtype=np.float64).reshape(-1)
        if t.size < 3:
            raise RecordError(f"record {self.source} has {t.size} samples; it needs many stick-slip periods")
        check_record_length(self.source, t.size)
        if not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0.0):
            raise RecordError(f"record {self.source}: the times t must be finite and strictly increasing")
        object.__setattr__(self, "t", t - t[0])
        for name in ("F", "x", "v"):
            value = getattr(self, name)
            if value is None:
                continue
            arr = np.asarray(value, dtype=np.float64).reshape(-1)
            if arr.size != t.size:
                raise RecordError(f"record {self.source}: column {name} has {arr.size} samples, "
                                  f"t has {t.size}")
            if not np.all(np.isfinite(arr)):
                raise RecordError(f"record {self.source}: column {name} has NaN or infinite values")
            # (a force has its own check against the normal load, which names the unit)
            limit = math.inf if name == "F" else MAX_RECORD_VALUE
            beyond = np.flatnonzero(np.abs(arr) > limit)
            if beyond.size:
                i = int(beyond[0])
                raise RecordError(f"record {self.source}: column {name} = {arr[i]:.6g} at sample "
                                  f"{i + 1} (t = {t[i] - t[0]:.6g} s) is beyond {MAX_RECORD_VALUE:g} "
                                  "in SI units: a corrupt cell, or a wrong unit")
            object.__setattr__(self, name, arr)
        if self.F is None and self.x is None:
            raise RecordError(f"record {self.source} needs a force column F or a displacement column x")

    @property
    def channels(self) -> tuple[str, ...]:
        """The measured signals present, in the order ``F``, ``x``, ``v``."""
        return tuple(n for n in ("F", "x", "v") if getattr(self, n) is not None)

    @property
    def sample_rate(self) -> float:
        """Mean sampling rate, Hz."""
        return float((self.t.size - 1) / self.t[-1])

    def subset(self, index: NDArray[np.intp]) -> MeasuredRecord:
        """The samples at ``index`` (sorted), as a record of its own."""
        pick = {n: getattr(self, n)[index] for n in self.channels}
        return MeasuredRecord(self.t[index], source=self.source, **pick)


#: The residuals are judged against the record's own noise (the weights are one over each
#: channel's white-noise level, :func:`noise_level`), so a model that describes the record has
#: a reduced chi-square near 1. Above this one (the residuals twice the noise) the result
#: carries a warning that the model does not describe the record.
MISMATCH_CHI2 = 4.0
#: A record's noise counts as measurable above this fraction of its range; below it (a
#: noise-free record) the residuals are judged against this fraction instead.
NOISE_FLOOR = 1e-5


def mismatch_warnings(measured: FloatArray, fitted: FloatArray, advice: str) -> tuple[str, ...]:
    """A warning when a fit's residuals exceed ``sqrt(MISMATCH_CHI2)`` times the record's noise.

    The yardstick is :func:`noise_level` of ``measured``, at least :data:`NOISE_FLOOR` of its
    range (a noise-free record). Used by the fits of one measured signal (rate-and-state,
    LuGre); the stick-slip fit judges its weighted chi-square by the same rule.

    Parameters
    ----------
    measured, fitted : ndarray
        The measured signal and the fitted model's, same unit.
    advice : str
        What to check, appended to the message.

    Returns
    -------
    tuple of str
        The warning, or nothing when the residuals are within the rule.
    """
    rms = float(np.sqrt(np.mean((fitted - measured) ** 2)))
    noise = max(noise_level(measured), NOISE_FLOOR * float(np.ptp(measured)))
    ratio = rms / noise if noise > 0.0 else math.inf
    if ratio <= math.sqrt(MISMATCH_CHI2):
        return ()
    return (f"the model does not describe the record: its residuals are {ratio:.3g} times the "
            f"record's own noise, above {math.sqrt(MISMATCH_CHI2):g} times: {advice}",)


def noise_level(signal: FloatArray) -> float:
    """Standard deviation of white noise on a smooth signal, from its second differences.

    ``d2 = y[i+1] - 2 y[i] + y[i-1]`` removes a smooth signal sampled finely and multiplies
    white noise's variance by 6; the median absolute deviation (/0.6745) ignores the few
    kinks at mode switches. Floored at ``1e-6`` of the signal's range.

    Parameters
    ----------
    signal : ndarray
        A finely sampled signal (any unit).

    Returns
    -------
    float
        The noise standard deviation, in the signal's unit.
    """
    d2 = np.diff(signal, 2)
    mad = float(np.median(np.abs(d2 - np.median(d2)))) / 0.6745
    return max(mad / math.sqrt(6.0), 1e-6 * float(np.ptp(signal)) + 1e-300)


@dataclass(frozen=True)
class StickPhase:
    """One stick phase read from the record: sample indices of its start, a point inside it
    (where a fit segment starts), and its end (the breakaway, a peak of the force)."""

    start: int
    anchor: int
    breakaway: int
    onset_value: float
    peak_value: float


@dataclass(frozen=True)
class RecordEstimates:
    """Starting values read from the record (SI) and the stick phases found in it."""

    period: float
    k: float
    c: float
    mu_s: float
    mu_k: float
    force_offset: float
    max_sliding_speed: float
    stick_phases: tuple[StickPhase, ...]
    noise: dict[str, float] = field(default_factory=dict)
    starts_in_stick: bool = False
    implied_mass: float = math.nan  # k / omega^2 of the slip phases' duration (undamped Coulomb)
    stick_speed: float = math.nan  # median speed of x over the stick phases, m/s (x recorded)
    stick_speed_error: float = math.nan  # standard error of the per-phase speeds' mean, m/s

    @property
    def breakaway_times_index(self) -> list[int]:
        """Sample indices of the breakaways."""
        return [p.breakaway for p in self.stick_phases]


#: Time steps that spread by more than this fraction of their median are flagged: the
#: estimates (autocorrelation, filters, the noise from second differences) take even steps.
UNEVEN_STEPS = 0.1


def uneven_steps_note(t: FloatArray) -> str | None:
    """A warning when the record's time steps are not even (:data:`UNEVEN_STEPS`), else None.

    Parameters
    ----------
    t : ndarray
        The record's times, s.

    Returns
    -------
    str or None
        The warning's text.
    """
    steps = np.diff(t)
    if not float(np.ptp(steps)) > UNEVEN_STEPS * float(np.median(steps)):
        return None
    return (f"the record's time steps range from {float(steps.min()):.4g} to "
            f"{float(steps.max()):.4g} s: the period, the stick phases and the noise levels are "
            "read as from even steps, so stick phases may go unused and the noise (and the "
            "standard errors) come out larger; the fit itself uses the record's own times")


def _dominant_period(t: FloatArray, y: FloatArray) -> float:
    """The stick-slip period from the first peak of the autocorrelation, s."""
    z = y - np.linspace(y[0], y[-1], y.size)
    z = z - z.mean()
    n = z.size
    spec = np.fft.rfft(z, 2 * n)
    ac = np.fft.irfft(spec * np.conj(spec))[:n]
    if ac[0] <= 0.0:
        raise RecordError("the record is constant: no stick-slip to identify")
    ac = ac / ac[0]
    neg = np.nonzero(ac < 0.0)[0]
    if neg.size == 0:
        raise RecordError("the record shows no oscillation: no stick phases to identify from "
                          f"(identification needs at least {MIN_STICK_PHASES} stick-slip cycles)")
    lag = int(np.argmax(ac[neg[0]:])) + neg[0]
    if ac[lag] < 0.2:
        raise RecordError("the record shows no repeating stick-slip cycle (autocorrelation "
                          f"{ac[lag]:.2f} at its best lag): identification needs at least "
                          f"{MIN_STICK_PHASES} stick phases; record more stick-slip periods")
    return float(lag * (t[-1] / (n - 1)))


def _slip_omega(t_slip: float, d: float, speed: float) -> float:
    """``omega`` solving ``omega T_slip = pi + 2 atan(V / (omega D))`` (undamped Coulomb slip)."""
    def g(w: float) -> float:
        return w * t_slip - math.pi - 2.0 * math.atan(speed / (w * max(d, 1e-300)))

    lo, hi = math.pi / t_slip, 2.0 * math.pi / t_slip
    return float(brentq(g, lo, hi)) if g(lo) < 0.0 < g(hi) else 1.5 * math.pi / t_slip


def _stick_phases(t: FloatArray, main: FloatArray, peaks: NDArray[np.int64], period: float,
                  dt: float, wide: int, slope: FloatArray, smooth: FloatArray,
                  sigma_smooth: float) -> list[StickPhase]:
    """The stick phases before the force peaks: a linear rise, found from the smoothed slope.

    For each peak, the steepest stretch of the preceding ``0.9`` period (the slope above 75 %
    of its 90th percentile) is fitted by a line, extended while the smoothed signal stays
    within ``3 sigma`` of it; its end is the breakaway.
    """
    span = int(0.9 * period / dt)
    stick: list[StickPhase] = []
    for p in peaks:
        lo = max(0, p - span)
        if p - lo < 2 * wide:
            continue
        region = slope[lo:p]
        rate = float(np.percentile(region, 90))
        if rate <= 0.0:
            continue
        top = lo + int(np.argmax(region))
        a = top
        while a > lo and region[a - 1 - lo] > 0.75 * rate:
            a -= 1
        b = top
        while b < p - 1 and region[b + 1 - lo] > 0.75 * rate:
            b += 1
        fa, fb = (a + wide // 2, b - wide // 2) if a > 0 else (0, b - wide // 2)
        if fb - fa < 4:
            continue
        line = np.polyfit(t[fa:fb], main[fa:fb], 1)
        dev = np.abs(smooth - np.polyval(line, t))
        end = fb
        while end < p and dev[end + 1] < 3.0 * sigma_smooth:
            end += 1
        start = fa
        while start > 0 and dev[start - 1] < 3.0 * sigma_smooth and start > lo:
            start -= 1
        start_value = float(np.polyval(line, t[start]))
        stick.append(StickPhase(start=start, anchor=(fa + fb) // 2, breakaway=end,
                                onset_value=start_value, peak_value=float(np.polyval(line, t[end]))))
    return stick


def _stick_at_period(t: FloatArray, main: FloatArray, dt: float,
                     period: float) -> tuple[list[StickPhase], int]:
    """The stick phases of the record for a stick-slip period ``period`` (s), and the
    half-width (samples) of the smoothing window they were found with."""
    if period / dt < MIN_SAMPLES_PER_PERIOD:
        raise RecordError(f"the record has {period / dt:.0f} samples per stick-slip period; "
                          f"at least {MIN_SAMPLES_PER_PERIOD} are needed")
    half = max(2, round(period / dt / 60.0))
    wide = max(half, round(period / dt / 10.0))
    smooth = savgol_filter(main, 2 * half + 1, 2)
    slope = savgol_filter(main, 2 * wide + 1, 2, deriv=1, delta=dt)
    sigma_smooth = noise_level(main) * math.sqrt(3.0 / (2 * half + 1))
    peaks, _ = find_peaks(smooth, distance=max(1, int(0.6 * period / dt)),
                          prominence=0.3 * float(np.ptp(smooth)))
    return _stick_phases(t, main, peaks, period, dt, wide, slope, smooth, sigma_smooth), half


def _periodic_stick(t: FloatArray, main: FloatArray,
                    dt: float) -> tuple[float, list[StickPhase], int]:
    """The stick-slip period (s), the stick phases and their smoothing half-width.

    The period is the first autocorrelation peak of the whole record, and also of its later
    half: a start-up from a preloaded spring (a long first stick phase, a slow transient)
    can dominate the whole record's autocorrelation with a lag two or three periods long, so
    that most stick phases are missed. The candidate that finds more stick phases is taken
    (the whole record's on a tie); the later half's only when the whole record has none.
    """
    tried: list[tuple[float, list[StickPhase], int]] = []
    first_error: RecordError | None = None
    h = t.size // 2
    for times, signal in ((t, main), (t[h:] - t[h], main[h:])):
        try:
            period = _dominant_period(times, signal)
            tried.append((period, *_stick_at_period(t, main, dt, period)))
        except RecordError as exc:
            first_error = first_error or exc
    if not tried:
        assert first_error is not None
        raise first_error
    return max(tried, key=lambda c: len(c[1]))  # the first of equals: the whole record's


def estimate(record: MeasuredRecord, *, mass: float, load: float, speed: float) -> RecordEstimates:
    """Read starting values from the record: period, stick phases, ``k``, ``mu_s``, ``mu_k``.

    Raises :class:`RecordError` with a sentence saying what is missing when the record shows
    fewer than :data:`MIN_STICK_PHASES` stick phases or is sampled too coarsely.

    Parameters
    ----------
    record : MeasuredRecord
        The measured record (SI units).
    mass : float
        Slider mass, kg.
    load : float
        Normal load W, N.
    speed : float
        Drive (belt) speed V, m/s.

    Returns
    -------
    RecordEstimates
        The period (s), the stick phases found and starting values of ``k`` (N/m), ``mu_s`` and ``mu_k``.
    """
    t = record.t
    main = record.F if record.F is not None else record.x
    assert main is not None
    dt = t[-1] / (t.size - 1)
    period, stick, half = _periodic_stick(t, main, dt)
    if len(stick) < MIN_STICK_PHASES:
        raise RecordError(
            f"the record shows {len(stick)} complete stick phase(s) (a linear rise of the force "
            f"ending in a breakaway); identification needs at least {MIN_STICK_PHASES}: record "
            "more stick-slip periods, or check that the drive speed is low enough to stick-slip"
        )
    noise = {name: noise_level(getattr(record, name)) for name in record.channels}
    # stick-phase regressions: slope of the main signal, and F against x when both exist
    rates, f_vs_x = [], []
    for ph in stick:
        sl = slice(ph.start + half, ph.breakaway - half)
        if sl.stop - sl.start < 3:
            sl = slice(ph.start, ph.breakaway + 1)
        rates.append(np.polyfit(t[sl], main[sl], 1)[0])
        if record.F is not None and record.x is not None:
            if not float(np.ptp(record.x[sl])) > 0.0:  # a fit of F against a constant x
                raise RecordError(
                    f"the displacement x does not change during the stick phase from t = "
                    f"{float(t[ph.start]):.6g} s, where the slider moves with the drive: check "
                    "the x column (constant in the record?)")
            f_vs_x.append(np.polyfit(record.x[sl], record.F[sl], 1))
    rate = float(np.median(rates))
    if record.x is not None:
        spans = [slice(ph.start, ph.breakaway + 1) for ph in stick]
        x_rates = np.array([np.polyfit(t[sl], record.x[sl], 1)[0] for sl in spans])
        x_rate = float(np.median(x_rates))
        x_rate_error = float(np.std(x_rates, ddof=1) / math.sqrt(x_rates.size))
        if not abs(x_rate / speed - 1.0) <= STICK_SPEED_RTOL:
            # the rising phases are those of F when it is recorded: a flipped F shows its
            # slips as rises, and x moves backwards there (an audit: the hint named x alone)
            signs = ("the signs of x and F (--columns F=-NAME or x=-NAME flips a column)"
                     if record.F is not None else "the sign of x (--columns x=-NAME flips it)")
            raise RecordError(
                f"the record has no stick phase: its rising phases move at {x_rate:.4g} m/s, "
                f"{x_rate / speed:.3g} times the drive speed V = {speed:.4g} m/s (a sticking slider "
                f"moves with the belt, within {STICK_SPEED_RTOL:.0%}); check --speed and "
                f"{signs}, or that the record shows stick-slip")
    peak = float(np.median([ph.peak_value for ph in stick]))
    onset = float(np.median([ph.onset_value for ph in stick if ph.start > 0] or [stick[-1].onset_value]))
    # slip duration: from a breakaway to the next stick onset
    slips = [(b.start - a.breakaway) * dt for a, b in itertools.pairwise(stick)
             if b.start > a.breakaway]
    t_slip = float(np.median(slips)) if slips else 0.5 * period
    offset = 0.0
    c0 = 0.0
    if record.F is not None:
        k0 = rate / speed
        if f_vs_x:
            k0 = float(np.median([s for s, _ in f_vs_x]))
            offset = float(np.median([b for _, b in f_vs_x]))  # = c V + offset; c starts at 0
        force_peak, force_onset = peak - offset, onset - offset
    else:
        d_x = 0.5 * (peak - onset)
        omega = _slip_omega(t_slip, d_x, speed)
        k0 = mass * omega**2
        force_peak, force_onset = k0 * peak, k0 * onset
    mu_s0 = force_peak / load
    mu_k0 = 0.5 * (force_peak + force_onset) / load
    if record.F is not None and not force_peak > 0.0:
        raise RecordError(
            f"the force at breakaway is {force_peak:.4g} N, not positive: the belt drags the "
            "slider, so the friction force it holds is positive; check the sign of F "
            "(--columns F=-NAME flips a column)")
    if not (0.0 < mu_k0 < mu_s0):
        mu_k0 = 0.5 * mu_s0
    omega0 = math.sqrt(k0 / mass)
    d0 = (mu_s0 - mu_k0) * load / k0
    u_max = speed + math.hypot(d0 * omega0, speed)
    if k0 <= 0.0 or not math.isfinite(k0):
        raise RecordError("the stick phases of the record do not rise: cannot read the stiffness")
    implied_mass = k0 / _slip_omega(t_slip, d0, speed) ** 2 if slips else math.nan
    return RecordEstimates(
        period=period, k=k0, c=c0, mu_s=mu_s0, mu_k=mu_k0, force_offset=offset,
        max_sliding_speed=u_max, stick_phases=tuple(stick), noise=noise,
        starts_in_stick=stick[0].start == 0, implied_mass=implied_mass,
        stick_speed=x_rate if record.x is not None else math.nan,
        stick_speed_error=x_rate_error if record.x is not None else math.nan,
    )
