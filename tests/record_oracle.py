"""Independent event-driven simulator of the 1DOF stick-slip rig in SI units (tests only).

Writes the rig's equations directly in physical units and integrates them with
``scipy.integrate.solve_ivp`` (DOP853, tight tolerances, bounded step) with terminal events;
it uses no code of the ``stickslip`` package (not the engine, not the dimensionless mapping),
so identification tests built on it check the mapping too.

The rig: a slider of mass ``m`` [kg] on a belt moving at ``V`` [m/s], held by a spring ``k``
[N/m] and a dashpot ``c`` [N s/m] to a rigid wall; ``x`` [m] is measured from where the spring
is relaxed, positive along the belt's motion, and the load cell reads ``F = k x + c x'`` [N].

* slip (``x' != V``): ``m x'' = -k x - c x' + W mu(|V - x'|) sign(V - x')``;
* stick (``x' = V``): holds while ``|k x + c V| <= mu_s W``; breakaway when ``k x + c V``
  reaches ``+mu_s W`` (into forward slip, ``x' < V``) or ``-mu_s W``.

``mu_s_per_stick`` lets the static coefficient change from one stick phase to the next
(cycles that are not quite equal, as on a real rig).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

FloatArray = NDArray[np.float64]


def coulomb(mu_k: float) -> Callable[[float], float]:
    """``mu(v_r) = mu_k``."""
    return lambda vr: mu_k


def linear(mu_k: float, slope: float) -> Callable[[float], float]:
    """``mu(v_r) = max(mu_k - slope v_r, 0)``, ``slope`` in s/m."""
    return lambda vr: max(mu_k - slope * vr, 0.0)


def stribeck(mu_k: float, mu_0: float, v_s: float, n: float = 1.0, viscous: float = 0.0
             ) -> Callable[[float], float]:
    """``mu(v_r) = mu_k + (mu_0 - mu_k) exp(-(v_r/v_s)^n) + viscous v_r`` (floored at 0)."""
    return lambda vr: max(mu_k + (mu_0 - mu_k) * np.exp(-((vr / v_s) ** n)) + viscous * vr, 0.0)


@dataclass(frozen=True)
class RigRecord:
    """Sampled truth: times [s], displacement [m], velocity [m/s], load-cell force [N]."""

    t: FloatArray
    x: FloatArray
    v: FloatArray
    F: FloatArray
    breakaways: FloatArray


def simulate_rig(*, m: float, k: float, c: float, mu_s: float, mu: Callable[[float], float],
                 load: float, speed: float, t_end: float, fs: float, t_start: float = 0.0,
                 mu_s_per_stick: Sequence[float] | None = None, max_events: int = 5000,
                 x0: float = 0.0) -> RigRecord:
    """Start-up run (slider stuck, the spring at ``x0``: relaxed by default, compressed for
    ``x0 < 0``, a preload that makes the first stick phase longer) sampled at ``fs`` Hz on
    ``[t_start, t_end]``.

    The samples' times are shifted so that the record starts at ``t = 0``.
    """
    w, vb = load, speed
    omega = np.sqrt(k / m)
    max_step = 0.02 / omega

    def mu_s_at(i_stick: int) -> float:
        if mu_s_per_stick is None:
            return mu_s
        return float(mu_s_per_stick[i_stick % len(mu_s_per_stick)])

    def slip_rhs(t: float, y: FloatArray) -> FloatArray:
        vr = vb - y[1]
        fr = w * mu(abs(vr)) * np.sign(vr)
        return np.array([y[1], (-k * y[0] - c * y[1] + fr) / m])

    def cross(t: float, y: FloatArray) -> float:
        return y[1] - vb

    pieces: list[tuple[float, float, str, object, float]] = []
    breakaways: list[float] = []
    t, _x, mode, n_stick = 0.0, 0.0, "stick", 0
    y = np.array([x0, vb])
    for _ in range(max_events):
        if t >= t_end:
            break
        if mode == "stick":
            ms = mu_s_at(n_stick)
            # x(t) = x0 + V (t - t0): force k x + c V reaches +-mu_s W at a closed-form time
            f0 = k * y[0] + c * vb
            t_up = t + (ms * w - f0) / (k * vb)
            t_hi = min(t_up, t_end)
            pieces.append((t, t_hi, "stick", (y[0], t), 0.0))
            if t_up >= t_end:
                break
            breakaways.append(t_up)
            y = np.array([y[0] + vb * (t_up - t), vb])
            t, mode, n_stick = t_up, "slip", n_stick + 1
            # leave v = V downwards: the slider slows because spring force exceeds friction
            continue
        cross.terminal = True  # type: ignore[attr-defined]
        cross.direction = 1  # type: ignore[attr-defined]
        sol = solve_ivp(slip_rhs, (t, t_end), y, method="DOP853", events=cross, dense_output=True,
                        max_step=max_step, rtol=1e-12, atol=1e-14 * max(1.0, vb / omega))
        if sol.status == 0:
            pieces.append((t, t_end, "slip", sol.sol, 0.0))
            break
        t_e = float(sol.t_events[0][0])
        y_e = np.array(sol.y_events[0][0])
        pieces.append((t, t_e, "slip", sol.sol, 0.0))
        y_e[1] = vb
        ms = mu_s_at(n_stick)
        if abs(k * y_e[0] + c * vb) <= ms * w:
            mode = "stick"
        else:  # pragma: no cover - the rigs in the tests always re-stick
            raise RuntimeError("slider overtakes the belt: not covered by this oracle")
        t, y = t_e, y_e
    else:  # pragma: no cover
        raise RuntimeError("event budget exhausted")

    ts = np.arange(t_start, t_end, 1.0 / fs)
    xs = np.empty_like(ts)
    vs = np.empty_like(ts)
    starts = np.array([p[0] for p in pieces])
    for i, tt in enumerate(ts):
        j = int(np.searchsorted(starts, tt, side="right") - 1)
        _a, _b, kind, data, _ = pieces[j]
        if kind == "stick":
            x0, t0 = data  # type: ignore[misc]
            xs[i], vs[i] = x0 + vb * (tt - t0), vb
        else:
            xs[i], vs[i] = data(tt)  # type: ignore[operator]
    return RigRecord(ts - t_start, xs, vs, k * xs + c * vs,
                     np.array(breakaways) - t_start)


def noisy(signal: FloatArray, fraction: float, rng: np.random.Generator) -> FloatArray:
    """``signal`` plus white Gaussian noise of standard deviation ``fraction`` times its
    peak-to-peak range."""
    return signal + fraction * float(np.ptp(signal)) * rng.standard_normal(signal.size)
