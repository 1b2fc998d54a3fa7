"""Reading and writing results: netCDF (CF conventions, provenance) and CSV.

Names load on first use (PEP 562); every name of ``__all__`` is public, the rest is private.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    "read_dataset": "stickslip.io.netcdf",
    "read_fingerprint": "stickslip.io.netcdf",
    "write_dataset": "stickslip.io.netcdf",
    "write_map_csv": "stickslip.io.csv",
}

__all__ = [
    "read_dataset",
    "read_fingerprint",
    "write_dataset",
    "write_map_csv",
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from stickslip.io.csv import write_map_csv
    from stickslip.io.netcdf import read_dataset, read_fingerprint, write_dataset
