"""numba's on-disk cache of the kernels, stamped with every kernel source, not one file.

numba stamps a cached function with its own source file only (a content hash since 0.68, the
file's time and size before). A kernel compiles its callees from other kernel modules into
its own machine code, so after an edit of ``kernel/linalg.py`` the cached ``engine`` kernels
kept running the old ``linalg`` code until ``make clean-cache``: a stale cache once hid a
fixed bug for a session, and once made a test run segfault. Installed releases were safe
(every file of a new version is new), editable installs and development were not.

Importing this module (every kernel module does, before its first ``@njit(cache=True)``)
puts three locators in front of numba's own, for the functions of this folder only. They
keep numba's cache paths (``NUMBA_CACHE_DIR`` when set, else the source's ``__pycache__``,
else numba's user-wide folder) and change one thing: the stamp is
:func:`~stickslip.kernel._stamp.kernel_source_stamp`, the SHA-256 of every ``*.py`` of this
folder (names and contents, not times), so any kernel edit
makes numba recompile every kernel on its next call (and overwrite the stale entries). The
kernel layer imports nothing compiled from outside this folder (the layer rule), so the
folder is the whole call tree. Functions elsewhere keep numba's locators. numba's locator
classes are not public API: if they are not found, numba's default stays (and
``tests/test_kernel_cache.py`` fails, so the version that broke it is noticed).
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import Any

from stickslip.kernel._stamp import KERNEL_DIR, kernel_source_stamp


@functools.cache
def _in_kernel_dir(py_file: str) -> bool:
    try:
        return Path(py_file).resolve().parent == KERNEL_DIR
    except OSError:
        return False


def _register() -> tuple[type, ...]:
    """Put the kernel locators in front of numba's; the classes registered (empty if none)."""
    try:
        from numba.core import caching

        bases = (caching.UserProvidedCacheLocator, caching.InTreeCacheLocator,
                 caching.UserWideCacheLocator)
        impl: Any = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl")  # noqa: B009
        registry: list[type] = impl._locator_classes
    except (ImportError, AttributeError):  # numba's private names moved: keep its default
        return ()
    if any(getattr(cls, "_stickslip_kernel", False) for cls in registry):
        return tuple(cls for cls in registry if getattr(cls, "_stickslip_kernel", False))

    def make(base: type) -> type:
        def from_function(cls: type, py_func: Any, py_file: str) -> Any:
            if not _in_kernel_dir(py_file):
                return None
            parent: Any = super(locator, cls)
            return parent.from_function(py_func, py_file)

        def get_source_stamp(self: Any) -> str:
            return kernel_source_stamp()

        locator: type = type(f"Kernel{base.__name__}", (base,), {
            "_stickslip_kernel": True, "__module__": __name__,
            "from_function": classmethod(from_function), "get_source_stamp": get_source_stamp,
        })
        return locator

    ours = tuple(make(base) for base in bases)
    registry[:0] = ours
    return ours


#: The locators in front of numba's (empty when numba's private names could not be found).
LOCATORS = _register()

__all__ = ["KERNEL_DIR", "LOCATORS", "kernel_source_stamp"]

