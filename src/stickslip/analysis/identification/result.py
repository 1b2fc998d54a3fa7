"""The result of an identification: values, uncertainties, the fit report and the machine file.

Parameters carry the names of the machine file: ``k`` [N/m],
``c`` [N s/m], ``mu_s``, ``mu_k`` and the ``[friction]`` keys ``slope`` [s/m],
``stribeck_velocity`` [m/s], ``exponent``, ``viscous`` [s/m]; the nuisance parameters of the
force zero are ``force_offset`` [N] and ``force_drift`` [N/s].
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    import xarray as xr

FloatArray = NDArray[np.float64]

#: Unit of every parameter the fit may report (SI; "" is dimensionless).
PARAMETER_UNITS: dict[str, str] = {
    "k": "N/m", "c": "N s/m", "mu_s": "", "mu_k": "", "slope": "s/m", "stribeck_velocity": "m/s",
    "exponent": "", "viscous": "s/m", "force_offset": "N", "force_drift": "N/s",
    **{f"table_mu_{i}": "" for i in range(16)},
}

#: Relative standard error above which a Stribeck shape parameter (``stribeck_velocity``,
#: ``exponent``) is undetermined: its two-standard-error band then spans a factor of three
#: (``0.5 |value|`` either side: ``v_s`` and ``0.5 v_s`` or ``n = 2`` and ``n = 1`` are one
#: record), so the record does not say which curve it saw.
SHAPE_RELATIVE_STDERR = 0.5

def _toml_string(text: str) -> str:
    """``text`` as a TOML basic string: quoted, every control character escaped.

    JSON's escapes (``\\"``, ``\\\\``, ``\\n``, ``\\uXXXX``) are TOML's; DEL, which JSON leaves
    raw and TOML forbids, is escaped too. A record named ``"a\\n[friction]"`` stays one line.
    """
    import json

    return json.dumps(text, ensure_ascii=True).replace("\x7f", "\\u007f")


UNDETERMINED_RULE = (
    "a fitted parameter is undetermined (value null) when it lies along a numerically null "
    "direction of the column-scaled Jacobian at the optimum (singular value below 1e-8 of the "
    "largest, the parameter's weight in that direction above 0.1), or when its standard error "
    "exceeds its scale: |value| for k and mu_s; mu_s for mu_k and the table values; 10 % of "
    "critical damping 2 sqrt(m k) for c; 10 % of (mu_s - mu_k) / V for slope and viscous (a "
    "slope that would change friction by a tenth of the static-kinetic gap across the drive "
    "speed); half of |value| for the Stribeck shape parameters stribeck_velocity and exponent, "
    "which are also undetermined when the optimum rests on a limit of their search range "
    "(the record then does not bracket them); a table value is undetermined when the record's "
    "sliding speeds do not reach the midpoint between its knot and the one below; the force "
    "offset and drift are nuisance parameters and are always reported with their standard errors, "
    "but for a fitted offset of a record without x: it is then exactly a common shift of the "
    "friction levels, and the offset, mu_s, mu_k and the table values are undetermined"
)


def undetermined(name: str, value: float, stderr: float, values: Mapping[str, float], *,
                 mass: float, speed: float) -> bool:
    """Apply :data:`UNDETERMINED_RULE`'s standard-error part to one parameter.

    Parameters
    ----------
    name : str
        Machine-file name of the parameter (``k``, ``c``, ``mu_s``, ...).
    value, stderr : float
        The fitted value and its standard error (the parameter's unit).
    values : mapping
        Every fitted value by name (gives the scales of ``mu_k``, ``c``, ``slope``, ``viscous``).
    mass : float
        Slider mass, kg.
    speed : float
        Drive speed, m/s.

    Returns
    -------
    bool
        True when the standard error exceeds the parameter's scale (the record cannot determine it).
    """
    if not math.isfinite(stderr):
        return True
    if name in ("force_offset", "force_drift"):
        return False
    if name == "mu_k" or name.startswith("table_mu_"):
        scale = abs(values["mu_s"])
    elif name in ("stribeck_velocity", "exponent"):
        scale = SHAPE_RELATIVE_STDERR * abs(value)
    elif name == "c":
        scale = 0.1 * 2.0 * math.sqrt(mass * values["k"])
    elif name in ("slope", "viscous"):
        scale = 0.1 * abs(values["mu_s"] - values["mu_k"]) / speed
    else:
        scale = abs(value)
    return stderr > scale


@dataclass(frozen=True)
class FitParameter:
    """One parameter of the fit.

    ``value`` and ``stderr`` are ``None`` when the record cannot determine it
    (:data:`UNDETERMINED_RULE`); ``estimate`` is the optimiser's number all the same (used for
    the fitted curves, never reported as a value). ``free`` is False for a parameter held
    fixed; ``interval`` is the bootstrap 95 % interval over cycles, when asked for.
    """

    name: str
    value: float | None
    stderr: float | None
    unit: str
    free: bool = True
    estimate: float = math.nan
    interval: tuple[float, float] | None = None

    def to_dict(self) -> dict[str, Any]:
        """``{"value", "stderr", "unit", "fixed"[, "interval"]}`` (JSON-ready)."""
        out: dict[str, Any] = {"value": self.value, "stderr": self.stderr, "unit": self.unit,
                               "fixed": not self.free}
        if self.interval is not None:
            out["interval"] = list(self.interval)
        return out


@dataclass(frozen=True)
class IdentificationResult:
    """Outcome of :func:`stickslip.analysis.identification.record_fit.identify`.

    Attributes
    ----------
    law : str
        The friction law fitted (or chosen by ``auto``).
    parameters : dict of str to FitParameter
        Machine-file names to values, standard errors and units.
    correlations : dict of (str, str) to float
        Correlation coefficients between the free parameters (from the covariance).
    residual_rms : dict of str to float
        Root-mean-square residual of each channel in its SI unit (``F`` N, ``x`` m, ``v`` m/s).
    noise : dict of str to float
        White-noise level of each channel estimated from the record (the weights).
    cycles_used : int
        Stick phases (breakaways) found in the record and fitted.
    criteria : dict of str to dict
        ``{"aic", "bic"}`` of each law fitted (Gaussian, from the weighted chi-square).
    t, measured, fitted
        The record's times [s], its channels and the fitted model at the same samples.
    engine_calls, engine_seconds
        Calls of the exact engine (one per segment and evaluation) and their wall time, s.
    """

    law: str
    parameters: dict[str, FitParameter]
    correlations: dict[tuple[str, str], float]
    residual_rms: dict[str, float]
    noise: dict[str, float]
    cycles_used: int
    segments: int
    stick_segments: int
    n_samples: int
    n_free: int
    chi2: float
    criteria: dict[str, dict[str, float]]
    mass: float
    load: float
    speed: float
    table_v: tuple[float, ...]
    t: FloatArray = field(repr=False)
    measured: dict[str, FloatArray] = field(repr=False)
    fitted: dict[str, FloatArray] = field(repr=False)
    engine_calls: int = 0
    engine_seconds: float = 0.0
    n_evaluations: int = 0
    success: bool = True
    message: str = ""
    source: str = ""
    fit_offset: bool = True
    condition: float = math.nan
    covariance: FloatArray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)
    covariance_names: tuple[str, ...] = ()
    bootstrap: int = 0
    table_visited: tuple[bool, ...] = ()
    warnings: tuple[str, ...] = ()
    window: str = ""  # the part of a long record fitted (analysis.identification.record_fit.fit_window)

    # ------------------------------------------------------------------ values
    def values(self) -> dict[str, float]:
        """Every parameter's number, determined or not (the optimiser's estimates)."""
        return {n: p.estimate for n, p in self.parameters.items()}

    @property
    def undetermined(self) -> list[str]:
        """Names of the free parameters the record cannot determine."""
        return [n for n, p in self.parameters.items() if p.free and p.value is None]

    def friction_curve(self, v_r: Any) -> tuple[FloatArray, FloatArray]:
        """``mu(v_r)`` of the fitted law and its standard error (delta method) at ``v_r`` [m/s]."""
        v = np.asarray(v_r, dtype=np.float64)
        base = self.values()
        mu = friction_coefficient(self.law, base, v, self.table_v)
        names = [n for n in self.covariance_names if n in base]
        grads = []
        for n in names:
            h = 1e-6 * max(abs(base[n]), 1e-3)
            shifted = dict(base)
            shifted[n] = base[n] + h
            grads.append((friction_coefficient(self.law, shifted, v, self.table_v) - mu) / h)
        if not grads:
            return mu, np.zeros_like(mu)
        g = np.array(grads)
        idx = [self.covariance_names.index(n) for n in names]
        cov = self.covariance[np.ix_(idx, idx)]
        var = np.einsum("iv,ij,jv->v", g, cov, g)
        return mu, np.sqrt(np.clip(var, 0.0, None))

    # ------------------------------------------------------------------ exports
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``law``, ``parameters`` (``{"value", "stderr", "unit"}`` each), residual
        RMS, cycles used, correlations, information criteria, fit diagnostics."""
        return {
            "law": self.law,
            "parameters": {n: p.to_dict() for n, p in self.parameters.items()},
            "undetermined": self.undetermined,
            "undetermined_rule": _rule(),
            "residual_rms": {n: v for n, v in self.residual_rms.items()},
            "residual_rms_units": {n: _CHANNEL_UNITS[n] for n in self.residual_rms},
            "noise": dict(self.noise),
            "cycles_used": self.cycles_used,
            "segments": self.segments,
            "n_samples": self.n_samples,
            "n_free": self.n_free,
            "reduced_chi2": self.chi2 / max(self.n_samples * len(self.measured) - self.n_free, 1),
            "warnings": list(self.warnings),
            "window": self.window or None,
            "correlations": {f"{a},{b}": v for (a, b), v in self.correlations.items()},
            "information_criteria": self.criteria,
            "known": {"m": self.mass, "load": self.load, "speed": self.speed},
            "table_v": list(self.table_v) if self.table_v else None,
            "table_visited": list(self.table_visited) if self.table_visited else None,
            "engine_calls": self.engine_calls,
            "engine_seconds": self.engine_seconds,
            "evaluations": self.n_evaluations,
            "success": self.success,
            "message": self.message,
            "source": self.source,
            "fit_offset": self.fit_offset,
            "bootstrap": self.bootstrap,
        }

    def to_config(self, *, table_file: str = "friction_table.csv") -> str:
        """The machine file (TOML) that ``stickslip design --config`` and ``simulate --config``
        read: ``[system]`` with ``m``, ``k``, ``c``, ``mu_s``, ``mu_k``, ``load``, ``speed``
        and a ``[friction]`` table. Raises ``ValueError`` when a parameter the file needs is
        undetermined (the file would carry a number the record does not support).
        """
        needed = ["k", "c", "mu_s", "mu_k", *_FRICTION_KEYS[self.law],
                  *[f"table_mu_{i}" for i in self._table_rows()]]
        missing = [n for n in needed if n in self.parameters and self.parameters[n].value is None
                   and self.parameters[n].free]
        if missing:
            raise ValueError(f"cannot write a machine file: the record does not determine "
                             f"{', '.join(missing)} (fix them with known values and fit again)")
        v = {n: (p.value if p.value is not None else p.estimate) for n, p in self.parameters.items()}
        lines = [
            f"# identified by stickslip identify from {_toml_string(self.source)} (law {self.law})",
            "# residual RMS: " + ", ".join(f"{n} {r:.4g} {_CHANNEL_UNITS[n]}"
                                           for n, r in self.residual_rms.items()),
            *(["# warning: the fit did not converge; these values are where the optimiser "
               "stopped"] if not self.success else []),
            "[system]",
            f'm = "{self.mass!r} kg"',
            f'k = "{v["k"]!r} N/m"',
            f'c = "{max(v["c"], 0.0)!r} N*s/m"',
            f"mu_s = {v['mu_s']!r}",
            f"mu_k = {v['mu_k']!r}",
            f'load = "{self.load!r} N"',
            f'speed = "{self.speed!r} m/s"',
            "",
            "[friction]",
            f'law = "{self.law}"',
        ]
        if self.law == "linear":
            lines.append(f'slope = "{v["slope"]!r} s/m"')
        elif self.law == "stribeck":
            lines += [f"mu_0 = {v['mu_s']!r}", f'stribeck_velocity = "{v["stribeck_velocity"]!r} m/s"',
                      f"exponent = {v['exponent']!r}", f'viscous = "{v["viscous"]!r} s/m"']
        elif self.law == "table":
            lines.append(f"table = {_toml_string(table_file)}")
        return "\n".join(lines) + "\n"

    def _table_rows(self) -> list[int]:
        """Indices of the table's knots that the record reaches (all when not recorded)."""
        flags = self.table_visited or (True,) * len(self.table_v)
        return [i for i, seen in enumerate(flags) if seen]

    def table_csv(self) -> str:
        """The fitted ``table`` law as the CSV the machine file points to (columns v, mu).

        Knots beyond the sliding speeds the record reaches are left out (undetermined): the
        engine's table law holds its last value beyond the last knot.
        """
        v = self.values()
        rows = ["v,mu"] + [f"{self.table_v[i]!r},{min(v[f'table_mu_{i}'], v['mu_s'])!r}"
                           for i in self._table_rows()]
        return "\n".join(rows) + "\n"

    def to_xarray(self) -> xr.Dataset:
        """Measured and fitted signals against time, parameters as attributes."""
        import json

        import xarray as xr

        data = {}
        for n, arr in self.measured.items():
            unit = _CHANNEL_UNITS[n]
            data[f"{n}_measured"] = ("t", arr, {"units": unit})
            data[f"{n}_fitted"] = ("t", self.fitted[n], {"units": unit})
            data[f"{n}_residual"] = ("t", self.fitted[n] - arr, {"units": unit})
        return xr.Dataset(data, coords={"t": ("t", self.t, {"units": "s"})},
                          attrs={"law": self.law, "identification": json.dumps(self.to_dict())})

    def to_csv(self) -> str:
        """Measured, fitted and residual signals as CSV text (SI units in the header)."""
        cols = ["t [s]"]
        arrays = [self.t]
        for n, arr in self.measured.items():
            unit = _CHANNEL_UNITS[n]
            cols += [f"{n}_measured [{unit}]", f"{n}_fitted [{unit}]"]
            arrays += [arr, self.fitted[n]]
        table = np.column_stack(arrays)
        body = "\n".join(",".join(f"{x:.10g}" for x in row) for row in table)
        return ",".join(cols) + "\n" + body + "\n"

    # ------------------------------------------------------------------ report
    def summary(self) -> str:
        """A fit report in the manner of lmfit's ``fit_report``."""
        lines = ["[[Fit Statistics]]",
                 f"    friction law       = {self.law}",
                 f"    record             = {self.source}",
                 f"    # data points      = {self.n_samples} x {len(self.measured)} channel(s)",
                 *([f"    window             = {self.window}"] if self.window else []),
                 f"    # variables        = {self.n_free} ({self.segments} segment states)",
                 f"    stick phases used  = {self.cycles_used}",
                 f"    reduced chi-square = {self.to_dict()['reduced_chi2']:.4g}",
                 f"    engine calls       = {self.engine_calls} ({self.engine_seconds:.2f} s)"]
        for n, r in self.residual_rms.items():
            lines.append(f"    residual RMS {n:<5} = {r:.4g} {_CHANNEL_UNITS[n]} (noise {self.noise[n]:.3g})")
        for law, ic in self.criteria.items():
            mark = "  <- chosen" if law == self.law and len(self.criteria) > 1 else ""
            lines.append(f"    {law:<9} AIC = {ic['aic']:.6g}, BIC = {ic['bic']:.6g}{mark}")
        if self.warnings:
            lines.append("[[Warnings]]")
            lines += [f"    {w}" for w in self.warnings]
        lines.append("[[Variables]]")
        for n, p in self.parameters.items():
            unit = f" {p.unit}" if p.unit else ""
            if not p.free:
                lines.append(f"    {n + ':':<19} {p.estimate:.8g}{unit} (fixed)")
            elif p.value is None:
                lines.append(f"    {n + ':':<19} undetermined (optimiser's number {p.estimate:.4g}{unit})")
            else:
                rel = f" ({100 * p.stderr / abs(p.value):.2f}%)" if p.stderr is not None and p.value else ""
                ci = (f"  95% bootstrap [{p.interval[0]:.6g}, {p.interval[1]:.6g}]"
                      if p.interval is not None else "")
                lines.append(f"    {n + ':':<19} {p.value:.8g} +/- {p.stderr:.3g}{unit}{rel}{ci}")
        if self.table_v:
            flags = self.table_visited or (True,) * len(self.table_v)
            knots = [f"{v:.4g}{'' if seen else ' (not reached)'}"
                     for v, seen in zip(self.table_v, flags, strict=True)]
            lines.append(f"[[Table knots]] table_mu_i is mu at v_r = {', '.join(knots)} m/s")
        strong = sorted(((abs(v), a, b, v) for (a, b), v in self.correlations.items()
                         if math.isfinite(v) and abs(v) > 0.1), reverse=True)
        if strong:
            lines.append("[[Correlations]] (unreported correlations are < 0.100)")
            lines += [f"    C({a}, {b}) = {v:+.3f}" for _, a, b, v in strong]
        if self.undetermined:
            lines.append(f"[[Undetermined]] {', '.join(self.undetermined)}: {UNDETERMINED_RULE}")
        return "\n".join(lines)

    def plot(self, **kwargs: Any) -> Any:
        """Measured against fitted signals, residuals and the fitted friction curve with its
        uncertainty band (:func:`stickslip.plot.identification.identification_plot`)."""
        from stickslip.plot.identification import identification_plot

        return identification_plot(self, **kwargs)


_CHANNEL_UNITS = {"F": "N", "x": "m", "v": "m/s"}
_FRICTION_KEYS: dict[str, tuple[str, ...]] = {
    "coulomb": (), "linear": ("slope",), "stribeck": ("stribeck_velocity", "exponent", "viscous"),
    "table": (),
}


def _rule() -> str:
    return UNDETERMINED_RULE


def friction_coefficient(law: str, values: Mapping[str, float], v_r: Sequence[float] | FloatArray,
                         table_v: Sequence[float] = ()) -> FloatArray:
    """The fitted friction coefficient ``mu(v_r)`` at sliding speeds ``v_r`` [m/s] (SI law,
    the law's definition, floored at zero as the engine does).

    Parameters
    ----------
    law : str
        ``coulomb``, ``linear``, ``stribeck`` or ``table``.
    values : mapping
        Fitted values by machine-file name (``mu_s``, ``mu_k``, ``slope`` s/m,
        ``stribeck_velocity`` m/s, ...).
    v_r : array_like
        Sliding speeds, m/s.
    table_v : sequence of float
        Speeds of the table law's nodes, m/s.

    Returns
    -------
    ndarray
        ``mu(v_r)``, dimensionless.
    """
    v = np.abs(np.asarray(v_r, dtype=np.float64))
    mu_k = values["mu_k"]
    if law == "linear":
        mu = mu_k - values["slope"] * v
    elif law == "stribeck":
        decay = np.exp(-((v / values["stribeck_velocity"]) ** values["exponent"]))
        mu = mu_k + (values["mu_s"] - mu_k) * decay + values["viscous"] * v
    elif law == "table":
        mus = [min(values[f"table_mu_{i}"], values["mu_s"]) for i in range(len(table_v))]
        mu = np.interp(v, table_v, mus)
    else:
        mu = np.full_like(v, mu_k)
    return np.maximum(mu, 0.0)
