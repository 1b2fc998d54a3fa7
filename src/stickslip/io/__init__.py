"""Reading and writing results: netCDF (CF conventions, provenance) and CSV."""

from stickslip.io.csv import write_map_csv
from stickslip.io.netcdf import read_dataset, read_fingerprint, write_dataset

__all__ = ["read_dataset", "read_fingerprint", "write_dataset", "write_map_csv"]
