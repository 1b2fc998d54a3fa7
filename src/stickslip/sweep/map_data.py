"""The dataset of an occurrence map and how to read one back.

:func:`map_dataset` assembles the CF-described ``xarray.Dataset`` from the engine's per-cell
summaries; :func:`map_axes` and :func:`stored_foundations` read a stored map's grid and
foundations.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.verdict import status_flag_attributes, verdict_codes, verdict_flag_attributes
from stickslip.io.provenance import package_version, provenance_attributes
from stickslip.kernel import engine
from stickslip.model.friction import CoulombFriction
from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.model.parameters import Foundation
from stickslip.sweep.map_config import DELTA_LAW, MapConfig

if TYPE_CHECKING:
    import xarray as xr

_NAN_COMMENT = "NaN (the _FillValue) where no stick-slip cycle was certified (verdict is not stick-slip)"
_FLOAT_VARIABLES: dict[str, tuple[int, dict[str, str]]] = {
    "period": (engine.F_PERIOD, {
        "long_name": "period of the certified stick-slip cycle",
        "units": "1 (dimensionless time tau = omega_n t)",
        "comment": _NAN_COMMENT,
    }),
    "amplitude": (engine.F_AMPLITUDE, {
        "long_name": "half the peak-to-peak of xi over the certified cycle",
        "units": "1 (V / omega_n)",
        "comment": _NAN_COMMENT,
    }),
    "stick_ratio": (engine.F_STICK_RATIO, {
        "long_name": "fraction of the cycle period spent stuck",
        "units": "1",
        "comment": _NAN_COMMENT,
    }),
    "max_velocity": (engine.F_MAX_VELOCITY, {
        "long_name": "largest slider velocity xi' reached in the run",
        "units": "1 (belt speed V)",
    }),
    "t_end": (engine.F_T_END, {
        "long_name": "dimensionless time at which the run stopped (certificate or horizon)",
        "units": "1 (dimensionless time tau)",
    }),
}


def stored_foundations(dataset: xr.Dataset) -> list[Foundation | None]:
    """The foundation at each ``zeta`` of a map dataset (``None`` everywhere for the rigid base).

    A (lambda, delta) map has one ``zeta``, hence one foundation.
    """
    n_zeta = int(dataset.sizes["zeta"]) if "zeta" in dataset.dims else 1
    if "foundation_mass_ratio" not in dataset:
        return [None] * n_zeta
    return [
        Foundation(float(m), float(k), float(c))
        for m, k, c in zip(np.atleast_1d(dataset["foundation_mass_ratio"].values),
                           np.atleast_1d(dataset["foundation_stiffness_ratio"].values),
                           np.atleast_1d(dataset["foundation_damping_ratio"].values), strict=True)
    ]


def map_axes(dataset: xr.Dataset) -> tuple[str, str]:
    """``("lambda", "zeta")`` or ``("lambda", "delta")``: the dimensions of a map dataset."""
    return ("lambda", "delta") if "delta" in dataset.dims else ("lambda", "zeta")


def map_dataset(
    config: MapConfig, float_summary: NDArray[np.float64], int_summary: NDArray[np.int64], fingerprint: str
) -> xr.Dataset:
    """Assemble the occurrence-map dataset from the engine's per-cell summaries.

    Parameters
    ----------
    config : MapConfig
    float_summary, int_summary : ndarray, shapes ``(n_cells, N_FLOAT)`` and ``(n_cells, N_INT)``
        Summaries in flat lambda-major order (``c = i_lambda * n_zeta + j_zeta``).
    fingerprint : str
        :meth:`MapConfig.fingerprint`, stored in the attributes.
    """
    import xarray as xr

    shape = config.shape
    dims = ("lambda", config.second_axis_name)
    status = int_summary[:, engine.I_STATUS].reshape(shape)
    data_vars: dict[str, Any] = {
        "verdict": (dims, verdict_codes(status), {
            "long_name": "certified stick-slip verdict from the startup state",
            **verdict_flag_attributes(),
            "comment": "undetermined: no certificate before t_max or max_events (see certificate)",
        }),
        "certificate": (dims, status.astype(np.int8), {
            "long_name": "how the run ended: the certificate of the verdict, or why there is none",
            **status_flag_attributes(),
        }),
        "n_stick": (dims, int_summary[:, engine.I_N_STICK].reshape(shape).astype(np.int32), {
            "long_name": "number of stick phases in the run, the initial one included",
            "units": "1",
        }),
        "cycle_k": (dims, int_summary[:, engine.I_CYCLE_K].reshape(shape).astype(np.int16), {
            "long_name": "stick phases per certified cycle (period-k cycle); 0 without a cycle",
            "units": "1",
        }),
    }
    for name, (column, var_attrs) in _FLOAT_VARIABLES.items():
        data_vars[name] = (dims, float_summary[:, column].reshape(shape).astype(np.float64), var_attrs)
    foundations = config.structures.foundations
    if foundations and foundations[0] is not None:
        for name, attr, long_name in (
            ("foundation_mass_ratio", "mass_ratio", "foundation mass ratio M = m_a / m"),
            ("foundation_stiffness_ratio", "stiffness_ratio", "foundation stiffness ratio K = sqrt(k_a/k)"),
            ("foundation_damping_ratio", "damping_ratio", "foundation damping zeta_a = c_a / (2 sqrt(m k))"),
        ):
            values = np.array([getattr(f, attr) for f in foundations], dtype=np.float64)
            if config.delta is None:
                data_vars[name] = (("zeta",), values, {"long_name": long_name, "units": "1"})
            else:  # the one foundation of the fixed zeta
                data_vars[name] = ((), values[0], {"long_name": long_name, "units": "1"})
    coords = {
        "lambda": ("lambda", np.array(config.lam.values), {
            "long_name": "lambda = (mu_s - mu_k) W / (V sqrt(m k))",
            "units": "1",
            "spacing": config.lam.spacing,
        }),
    }
    if config.delta is None:
        coords["zeta"] = ("zeta", np.array(config.zeta.values), {
            "long_name": "damping ratio zeta = c / (2 sqrt(m k))",
            "units": "1",
            "spacing": config.zeta.spacing,
        })
    else:
        coords["delta"] = ("delta", np.array(config.delta.values), {
            "long_name": "friction slope delta = sigma W / (2 sqrt(m k)), > 0 velocity weakening",
            "units": "1",
            "spacing": config.delta.spacing,
        })
    law = "" if isinstance(config.friction, CoulombFriction) else f", friction {config.friction.describe()}"
    description = config.friction.describe()
    if config.delta is not None:
        zeta = float(config.zeta.values[0])
        law = f", over (lambda, delta) at zeta = {zeta:g}, friction {DELTA_LAW}"
        description = DELTA_LAW
    attrs: dict[str, Any] = provenance_attributes(
        f"stick-slip occurrence map, {config.dva.describe()}, gamma = {config.gamma:g}{law}",
        config.to_dict(),
    )
    attrs.update({
        "source": f"stickslip {package_version()}: exact piecewise-linear engine, certified verdicts",
        "references": "Discussion of Stick-Slip Dynamics of 2DOF Sliding Systems Based on Dynamic "
                      "Vibration Absorbers Analysis (Figs. 8 and 11)",
        "initial_condition": STARTUP_DESCRIPTION,
        "t_max": config.options.t_max,
        "gamma": config.gamma,
        "dva": config.dva.describe(),
        "friction": description,
        "config_fingerprint": fingerprint,
    })
    if config.delta is not None:
        attrs["zeta"] = float(config.zeta.values[0])
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)

