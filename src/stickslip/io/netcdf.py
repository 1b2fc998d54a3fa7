"""netCDF-4 files of sweep results (h5netcdf engine, CF conventions, provenance attributes).

The datasets come with their provenance already in the attributes (package version, git
revision, library versions, date, the full resolved configuration as JSON, the initial
condition and the time horizon; see :func:`stickslip.sweep.occurrence.map_dataset`). This
module writes them atomically (a temporary file renamed over the target) and reads them
back fully into memory, so no file handle stays open.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any, Final

import numpy as np

from stickslip.io.atomic import atomic_output

if TYPE_CHECKING:
    import xarray as xr

ENGINE: Final = "h5netcdf"
#: Attribute holding the configuration fingerprint of a stickslip result.
FINGERPRINT_ATTR = "config_fingerprint"


def _encoding(dataset: xr.Dataset) -> dict[str, dict[str, Any]]:
    encoding: dict[str, dict[str, Any]] = {}
    for name, var in dataset.variables.items():
        if name in dataset.coords:
            encoding[str(name)] = {"_FillValue": None}
        elif np.issubdtype(var.dtype, np.floating):
            encoding[str(name)] = {"_FillValue": np.nan, "zlib": True, "complevel": 4}
        else:
            encoding[str(name)] = {"_FillValue": None, "zlib": True, "complevel": 4}
    return encoding


def write_dataset(dataset: xr.Dataset, path: str | os.PathLike[str], *, overwrite: bool = True) -> Path:
    """Write ``dataset`` to ``path`` as netCDF-4 with the h5netcdf engine, atomically.

    Float variables use NaN as ``_FillValue`` (a cell without a cycle has no period);
    integer codes and coordinates have no fill value: every cell has a code.

    Parameters
    ----------
    dataset : xarray.Dataset
    path : path-like
        Target file (its folder must exist).
    overwrite : bool
        Replace an existing file (default, like ``xarray``); with False an existing file
        raises ``FileExistsError``. The command line refuses to replace a result of another
        configuration before calling this.

    Returns
    -------
    pathlib.Path
        The written path.
    """
    target = Path(path)
    if target.exists() and not overwrite:
        raise FileExistsError(errno.EEXIST, "file exists; pass overwrite=True to replace it",
                              str(target))
    with atomic_output(target) as tmp:
        dataset.to_netcdf(tmp, engine=ENGINE, encoding=_encoding(dataset))
    return target


def read_dataset(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read a netCDF file written by :func:`write_dataset`, fully loaded into memory."""
    import xarray as xr

    with xr.open_dataset(Path(path), engine=ENGINE) as ds:
        return ds.load()


def read_fingerprint(path: str | os.PathLike[str]) -> str | None:
    """The configuration fingerprint stored in a result file, or None if it has none.

    A file that cannot be read as netCDF (or is not a stickslip result) gives None.
    """
    import xarray as xr

    try:
        with xr.open_dataset(Path(path), engine=ENGINE) as ds:
            value = ds.attrs.get(FINGERPRINT_ATTR)
    except (OSError, ValueError, TypeError):
        return None
    return None if value is None else str(value)
