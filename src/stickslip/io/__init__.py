"""Reading and writing results: netCDF (CF conventions, provenance) and CSV.

Names load on first use (PEP 562), as in :mod:`stickslip.model`: importing one module of this
layer does not import the others.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

_EXPORTS: dict[str, str] = {
    "read_dataset": "stickslip.io.netcdf",
    "read_fingerprint": "stickslip.io.netcdf",
    "write_dataset": "stickslip.io.netcdf",
    "write_map_csv": "stickslip.io.csv",
    "provenance_attributes": "stickslip.io.provenance",
}

__all__ = [
    "provenance_attributes",
    "read_dataset",
    "read_fingerprint",
    "write_dataset",
    "write_map_csv",
]


__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover
    from stickslip.io.csv import write_map_csv
    from stickslip.io.netcdf import read_dataset, read_fingerprint, write_dataset
    from stickslip.io.provenance import provenance_attributes
