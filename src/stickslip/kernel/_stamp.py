"""The stamp of the compiled kernels: a hash of every kernel source (no numba imported here).

:mod:`stickslip.kernel._cache` stamps every cached kernel with it, and the command line reads
it to tell a cold cache from a warm one without importing numba
(:func:`stickslip.cli.main.engine_cache_is_cold`): the stamp depends on the sources'
names and contents only, so a checkout or reinstall that rewrites identical files (new
times, same bytes) leaves the cache warm, as numba itself finds it.
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

#: The kernel folder: every ``*.py`` here enters the stamp of every cached kernel.
KERNEL_DIR = Path(__file__).resolve().parent


def kernel_source_stamp(folder: Path | None = None) -> str:
    """SHA-256 (hex) of the names and contents of every ``*.py`` in ``folder`` (the kernels').

    The kernel folder's stamp is computed once per process (numba asks for it at every
    ``@njit(cache=True)`` and every cache load; 3 ms once): an edit is seen by the next process,
    which is when a stale cache would be loaded.
    """
    if folder is None:
        return _kernel_folder_stamp()
    digest = hashlib.sha256()
    for path in sorted(Path(folder).glob("*.py")):
        digest.update(path.name.encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


@functools.cache
def _kernel_folder_stamp() -> str:
    return kernel_source_stamp(KERNEL_DIR)
