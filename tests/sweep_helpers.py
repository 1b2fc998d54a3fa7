"""Shared pieces of the sweep tests: a small grid and a bit-for-bit map comparison."""

from __future__ import annotations

import xarray as xr

from stickslip.sweep import Axis

LAMS = Axis.parse("log:0.1:50:6", "lambda")
ZETAS = Axis.parse("0.01,0.05,0.1,0.2,0.4", "zeta")


def assert_same_map(a: xr.Dataset, b: xr.Dataset) -> None:
    """Bit-identical coordinates and variables, same configuration (dates may differ)."""
    assert set(a.variables) == set(b.variables)
    for name in a.variables:
        va, vb = a[name].values, b[name].values
        assert va.dtype == vb.dtype and va.shape == vb.shape, name
        assert va.tobytes() == vb.tobytes(), f"{name} differs"
    for key in ("configuration", "config_fingerprint", "t_max", "initial_condition"):
        assert a.attrs[key] == b.attrs[key]
