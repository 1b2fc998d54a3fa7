"""Where a result came from: package and library versions, git revision, date."""

from __future__ import annotations

import functools
import platform
import subprocess
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path

_LIBRARIES = ("numpy", "scipy", "numba", "xarray", "h5netcdf", "h5py", "dask", "distributed")


def package_version() -> str:
    """Version of the ``stickslip`` package."""
    from stickslip import __version__

    return __version__


@functools.cache
def git_revision() -> str:
    """``git describe``-like revision of the source tree, ``+dirty`` if modified; ``""`` if unknown.

    Only meaningful for a source checkout; an installed wheel has no repository.
    """
    here = Path(__file__).resolve().parent
    try:
        rev = subprocess.run(
            ["git", "-C", str(here), "rev-parse", "HEAD"],
            capture_output=True, text=True, timeout=10, check=True,
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "-C", str(here), "status", "--porcelain", "--untracked-files=no"],
            capture_output=True, text=True, timeout=10, check=True,
        ).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""
    return f"{rev}+dirty" if dirty else rev


@functools.cache
def library_versions() -> dict[str, str]:
    """Versions of Python and of the numerical libraries that produced a result."""
    versions = {"python": platform.python_version()}
    for name in _LIBRARIES:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            continue
    return versions


def utc_now() -> str:
    """Current date and time, ISO 8601 in UTC."""
    return datetime.now(UTC).isoformat(timespec="seconds")
