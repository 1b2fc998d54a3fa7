"""LuGre parameters from a record of sliding velocity and friction force.

The record holds, at times ``t`` (s), the sliding velocity ``v`` (m/s) of the contact over the
surface and the friction force ``F`` (N): a friction test rig with imposed motion, a
pre-sliding test (small reversing displacements) or the sliding phases of a stick-slip record.
The model is LuGre (Canudas de Wit et al. 1995) driven by that velocity,

    z' = v - sigma0 |v| z / g(v),   g(v) = F_c + (F_s - F_c) exp(-(v / v_s)^2),
    F  = sigma0 z + sigma1 z' + sigma2 v,

integrated exactly on each sample interval with the velocity held at the interval's mean
(:func:`stickslip.kernel.lugre_response.lugre_force`). The bristle state at the first sample
is the one that gives its measured force.

The fit. The unknowns are ``sigma0`` (N/m), ``sigma1``, ``sigma2`` (N s/m), ``F_c``, ``F_s``
(N, ``F_s >= F_c``) and ``v_s`` (m/s), fitted as logarithms (``F_s - F_c`` too) by
``scipy.optimize.least_squares`` from :data:`SIGMA0_STARTS` first guesses of ``sigma0``, the
best kept. Standard errors are those of the linearised problem (as for the rate-and-state
fit, :mod:`stickslip.analysis.identification.rate_state_fit`); a parameter whose standard error exceeds its
value is *undetermined*, and so are ``sigma0`` and ``sigma1`` whenever the velocity never
reverses (no pre-sliding): the standard errors are local, and without a reversal other
bristle parameters fit the record to its noise while their local errors look small. With the
normal load the coefficients are ``mu_c = F_c / N`` and ``mu_s = F_s / N``, the machine file's
``[friction] law = "lugre"``.
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
from stickslip.kernel.lugre_response import lugre_force

FloatArray = NDArray[np.float64]

NAMES = ("sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s")
UNITS = {"sigma0": "N/m", "sigma1": "N s/m", "sigma2": "N s/m", "F_c": "N", "F_s": "N",
         "v_s": "m/s"}
#: First guesses of ``sigma0``: the force scale over these bristle deflections (m).
SIGMA0_STARTS = (1e-4, 1e-5, 1e-6)
MAX_EVALUATIONS = 2000


def _unpack(p: FloatArray) -> tuple[float, float, float, float, float, float]:
    sigma0, sigma1, sigma2, f_c, excess, v_s = (math.exp(float(x)) for x in p)
    return sigma0, sigma1, sigma2, f_c, f_c + excess, v_s


def model_force(t: FloatArray, v: FloatArray, f0: float, params: tuple[float, ...]) -> FloatArray:
    """The LuGre force along the record's velocity, from the first sample's force ``f0`` (N).

    Parameters
    ----------
    t, v : ndarray
        Times (s) and sliding velocities (m/s).
    f0 : float
        The force at ``t[0]``, N: it fixes the bristle state there.
    params : tuple
        ``(sigma0, sigma1, sigma2, F_c, F_s, v_s)`` in SI.

    Returns
    -------
    ndarray
        The force at every sample, N.
    """
    sigma0, sigma1, sigma2, f_c, f_s, v_s = params
    g = f_c + (f_s - f_c) * math.exp(-(float(v[0]) / v_s) ** 2)
    a0 = sigma0 * abs(float(v[0])) / g
    denominator = sigma0 - sigma1 * a0
    z0 = (f0 - (sigma1 + sigma2) * float(v[0])) / denominator if denominator != 0.0 else 0.0
    force, _ = lugre_force(t, v, sigma0, sigma1, sigma2, f_c, f_s, v_s, z0)
    return np.asarray(force)


@dataclass
class LuGreFit:
    """A LuGre fit (see module notes); ``mu_c``, ``mu_s`` with the load when given."""

    values: dict[str, float]
    errors: dict[str, float]
    undetermined: list[str]
    rms: float
    n: int
    load: float | None = None
    t: FloatArray = field(default_factory=lambda: np.zeros(0), repr=False)
    force: FloatArray = field(default_factory=lambda: np.zeros(0), repr=False)
    force_fit: FloatArray = field(default_factory=lambda: np.zeros(0), repr=False)
    #: False when the optimiser stopped at its budget (the values are where it stopped)
    converged: bool = True
    #: Warnings on the fit (residuals beyond the record's noise:
    #: :func:`~stickslip.analysis.identification.estimates.mismatch_warnings`)
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI); ``friction_table``: the machine file's ``[friction]`` with a load."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None
        out: dict[str, Any] = {
            "law": "lugre",
            # an undetermined parameter is null, as in the main fit; the optimiser's numbers
            # are kept under "estimates"
            "parameters": {k: None if k in self.undetermined else num(v) for k, v in self.values.items()},
            "estimates": {k: num(v) for k, v in self.values.items()},
            "standard_errors": {k: num(v) for k, v in self.errors.items()},
            "units": UNITS, "undetermined": self.undetermined, "rms_residual_N": self.rms,
            "n_samples": self.n, "load_N": self.load, "converged": self.converged,
            "warnings": list(self.warnings),
            "model": "LuGre driven by the record's sliding velocity (Canudas de Wit et al. 1995)"}
        if self.load is not None:
            out["friction_table"] = {
                "law": "lugre", "sigma0": f"{self.values['sigma0']:.8g} N/m",
                "sigma1": f"{self.values['sigma1']:.8g} N*s/m",
                "sigma2": f"{self.values['sigma2']:.8g} N*s/m",
                "mu_c": self.values["F_c"] / self.load, "mu_s": self.values["F_s"] / self.load,
                "stribeck_velocity": f"{self.values['v_s']:.8g} m/s"}
        return out

    def summary(self) -> str:
        """A few lines for the terminal."""
        lines = [f"identify    LuGre from {self.n} samples of sliding velocity and force"]
        for name in NAMES:
            flag = "  UNDETERMINED" if name in self.undetermined else ""
            lines.append(f"{name:<11} {self.values[name]:.6g} {UNITS[name]} +- "
                         f"{self.errors[name]:.2g}{flag}")
        if self.load is not None:
            lines.append(f"mu_c, mu_s  {self.values['F_c'] / self.load:.6g}, "
                         f"{self.values['F_s'] / self.load:.6g} (load {self.load:g} N)")
        lines.append(f"residual    rms {self.rms:.3g} N")
        if not self.converged:
            lines.append(NOT_CONVERGED)
        lines += [f"warning     {w}" for w in self.warnings]
        return "\n".join(lines)


def fit_lugre(t: FloatArray, v: FloatArray, force: FloatArray, *, load: float | None = None
              ) -> LuGreFit:
    """Fit the six LuGre parameters to a record of sliding velocity and force (module notes).

    Parameters
    ----------
    t, v, force : ndarray
        Times (s, strictly increasing), sliding velocity (m/s) and friction force (N).
    load : float, optional
        Normal load, N: also reports ``mu_c`` and ``mu_s``.

    Returns
    -------
    LuGreFit
        Values, standard errors, the undetermined parameters and the fitted force.
    """
    from scipy.optimize import least_squares

    t, v, force = checked_record((t, v, force), 12, "t, v and F")
    v_max = float(np.max(np.abs(v)))
    if not v_max > 0.0:
        raise ValueError("the velocity is zero throughout: nothing slides, nothing to fit")
    if load is not None and not (load > 0.0 and math.isfinite(load)):
        raise ValueError(f"load {load!r} N must be positive")
    fast = np.abs(v) > 0.5 * v_max
    against = float(np.mean(force[fast] * v[fast] < 0.0))
    if against > 0.5:  # sliding fast, friction acts with the motion's sign (F ~ g(v) sgn v)
        raise ValueError(f"the force has the opposite sign of the sliding velocity in "
                         f"{against:.0%} of the fast sliding samples: the friction force is "
                         "positive when the body slides forward (v > 0); is the force column's "
                         "sign reversed?")
    f_c0 = max(float(np.median(np.abs(force[fast]))), 1e-12)
    f_s0 = max(float(np.max(np.abs(force))), 1.05 * f_c0)
    f0 = float(force[0])
    # sigma0 from the pre-sliding slope: just after a reversal z' ~ v, so dF/dt ~ sigma0 v
    slow = (np.abs(v[:-1]) > 1e-3 * v_max) & (np.abs(v[:-1]) < 0.05 * v_max)
    rates = np.abs(np.diff(force) / np.diff(t))[slow] / np.abs(v[:-1][slow])
    sigma0_est = float(np.median(rates)) if rates.size else f_c0 / SIGMA0_STARTS[1]

    def residuals(p: FloatArray) -> FloatArray:
        # p[6]: the force at t[0], fitted (it fixes the bristle state; taking the first noisy
        # sample for it put sigma1, F_s and v_s 5-8 standard errors off on a 2 % record)
        r = model_force(t, v, float(p[6]), _unpack(p[:6])) - force
        return np.where(np.isfinite(r), r, 1e6 * f_c0)

    best = None
    starts = [sigma0_est * f for f in (1.0, 0.3, 3.0)] + [f_c0 / d for d in SIGMA0_STARTS]
    for sigma0 in starts:
        p0 = np.append(np.log([sigma0, math.sqrt(sigma0), 1e-3 * f_c0 / v_max, f_c0, f_s0 - f_c0,
                               0.1 * v_max]), f0)
        sol = least_squares(residuals, p0, method="trf", max_nfev=MAX_EVALUATIONS)
        if best is None or sol.cost < best.cost:
            best = sol
    assert best is not None
    values = dict(zip(NAMES, _unpack(best.x[:6]), strict=True))
    # the Jacobian in the parameters themselves: d/dx = (d/d ln x) / x; F_s = F_c + excess
    jac_log = best.jac
    excess = values["F_s"] - values["F_c"]
    jac = np.empty_like(jac_log)
    for i, name in enumerate(("sigma0", "sigma1", "sigma2")):
        jac[:, i] = jac_log[:, i] / values[name]
    # columns 3, 4 in (F_c, F_s): d/dF_s = d/d excess; d/dF_c = d/d F_c|excess - d/d excess
    d_excess = jac_log[:, 4] / excess
    jac[:, 3] = jac_log[:, 3] / values["F_c"] - d_excess
    jac[:, 4] = d_excess
    jac[:, 5] = jac_log[:, 5] / values["v_s"]
    jac[:, 6] = jac_log[:, 6]  # the initial force, in N already: a nuisance parameter
    errors = linearised_errors(jac, float(best.cost), (*NAMES, "F_0"))
    errors.pop("F_0")
    undetermined = [name for name in NAMES if not errors[name] <= abs(values[name])]
    moving = np.sign(v[v != 0.0])  # a reversal sampled at v = 0 exactly is one too
    if not np.any(moving[:-1] * moving[1:] < 0.0):
        # no reversal, no pre-sliding: the bristles act only through the lag of sliding, and
        # other sigma0, sigma1 fit such a record to its noise (seen: sigma1 97 instead of 316
        # N s/m with a local standard error of 1): undetermined, whatever the local errors say
        undetermined += [name for name in ("sigma0", "sigma1") if name not in undetermined]
    fitted = model_force(t, v, float(best.x[6]), _unpack(best.x[:6]))
    rms = float(np.sqrt(np.mean((fitted - force) ** 2)))
    return LuGreFit(values, errors, undetermined, rms, int(t.size), load, t, force, fitted,
                    converged=best.status > 0,
                    warnings=mismatch_warnings(force, fitted, "is it LuGre friction of the stated "
                                                "sliding velocity, in its units?"))




__all__ = ["LuGreFit", "fit_lugre", "model_force"]
