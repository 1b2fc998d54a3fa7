"""
Reading a saved map with xarray
===============================

An :class:`stickslip.OccurrenceMap` is an :class:`xarray.Dataset` underneath;
:meth:`~stickslip.OccurrenceMap.to_netcdf` writes it (CF conventions, provenance attributes)
and any netCDF reader opens it again. Here a small rigid-base map round-trips through a
temporary file and is analysed with plain xarray.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from stickslip import critical_lambda_exact, occurrence_map

result = occurrence_map(np.geomspace(0.3, 10.0, 20), np.linspace(0.05, 0.4, 8), "none")
with tempfile.TemporaryDirectory() as tmp:
    path = result.to_netcdf(Path(tmp) / "rigid_map.nc")
    with xr.open_dataset(path) as saved:
        saved = saved.load()
print(saved)

# %%
# The lowest stick-slip ``lambda`` of each column, read from the saved verdicts, against
# Eq. (36). The verdict variable's attributes say how it is coded.
verdict = saved["verdict"]
print(verdict.attrs["flag_values"], verdict.attrs["flag_meanings"])
stick_slip = verdict == 1
onset = saved["lambda"].where(stick_slip).min("lambda")
exact = xr.DataArray([critical_lambda_exact(float(z)) for z in saved["zeta"]], coords=[saved["zeta"]])

fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
ax.plot(saved["zeta"], onset, "o", label="lowest stick-slip lambda on the grid")
ax.plot(saved["zeta"], exact, "-", label="Eq. (36)")
ax.set(xlabel="zeta", ylabel="lambda", yscale="log", title="rigid base, read back with xarray")
ax.legend()
plt.show()
