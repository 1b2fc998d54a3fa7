"""Where a result came from: package and library versions, git revision, date.

:func:`provenance_attributes` gives the global attributes every stickslip dataset carries
(CF conventions, versions, revision, date, the full resolved configuration as JSON), so that
maps, boundaries and every later dataset describe their origin the same way.
"""

from __future__ import annotations

import functools
import json
import platform
import subprocess
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path
from typing import Any

_LIBRARIES = ("numpy", "scipy", "numba", "matplotlib", "xarray", "h5netcdf", "h5py", "dask", "distributed")


def package_version() -> str:
    """Version of the installed ``stickslip`` package (its metadata: the one source of truth).

    Read from :mod:`importlib.metadata` here rather than from ``stickslip.__version__``, so that
    this low layer does not import the package face (which loads ``sweep`` and ``io`` lazily and
    would loop back here). ``"0+unknown"`` when running from an uninstalled tree, as the face says.
    """
    try:
        return metadata.version("stickslip")
    except metadata.PackageNotFoundError:  # pragma: no cover - uninstalled source tree
        return "0+unknown"


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


def provenance_attributes(title: str, configuration: dict[str, Any]) -> dict[str, Any]:
    """Global attributes of a stickslip dataset (CF-1.10 and provenance).

    Parameters
    ----------
    title : str
        What the dataset is (the CF ``title``).
    configuration : dict
        The full resolved configuration, stored as sorted JSON (floats at full precision).
    """
    return {
        "title": title,
        "Conventions": "CF-1.10",
        "stickslip_version": package_version(),
        "git_revision": git_revision(),
        "library_versions": json.dumps(library_versions(), sort_keys=True),
        "date_created": utc_now(),
        "configuration": json.dumps(configuration, sort_keys=True, allow_nan=False),
    }
