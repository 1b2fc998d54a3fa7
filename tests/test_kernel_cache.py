"""Every cached kernel is stamped with the whole kernel folder (``stickslip.kernel._cache``).

Reference: numba's own index format (``numba.core.caching.IndexDataCacheFile``: a pickled
version, then a pickle of ``(source stamp, overloads)``), and the rule the stamp must keep:
an edit of any kernel module, not only the function's own file, must make every cached kernel
stale (a callee's edit left the engine running the callee's old code before).
"""

from __future__ import annotations

import pickle
import shutil
import sys
from pathlib import Path

import numba
import numpy as np

from stickslip.kernel import _cache, dense_output, engine, linalg


def test_the_kernel_locators_are_registered_in_front_of_numbas() -> None:
    from numba.core import caching

    assert _cache.LOCATORS, f"numba {numba.__version__}: its cache locator classes moved"
    impl = getattr(caching, "CacheImpl", None) or caching._CacheImpl
    assert impl._locator_classes[: len(_cache.LOCATORS)] == list(_cache.LOCATORS)
    for dispatcher in (engine.run_prepared, linalg.expm, dense_output.evaluate_prepared):
        locator = dispatcher._cache._impl.locator
        assert type(locator) in _cache.LOCATORS
        assert locator.get_source_stamp() == _cache.kernel_source_stamp()


def test_the_stamp_changes_with_any_file_of_the_folder(tmp_path: Path) -> None:
    folder = tmp_path / "kernel"
    shutil.copytree(_cache.KERNEL_DIR, folder, ignore=shutil.ignore_patterns("__pycache__"))
    before = _cache.kernel_source_stamp(folder)
    assert before == _cache.kernel_source_stamp(_cache.KERNEL_DIR)  # names and contents only
    callee = folder / "linalg.py"
    callee.write_text(callee.read_text() + "\n# an edit of a callee's module\n")
    edited = _cache.kernel_source_stamp(folder)
    assert edited != before
    (folder / "new_kernel.py").write_text("")
    assert _cache.kernel_source_stamp(folder) not in (before, edited)


def test_numba_writes_the_folder_stamp_into_the_engine_index() -> None:
    # a run compiles or loads the engine; its index on disk must carry the folder's stamp
    # (numba compares it at each load and recompiles when it differs)
    from stickslip import Slider, rigid_base, simulate

    simulate(rigid_base(0.1), Slider(3.0), record=False)
    impl = engine.run_prepared._cache._impl
    index = Path(impl.locator.get_cache_path()) / f"{impl.filename_base}.nbi"
    with index.open("rb") as f:
        pickle.load(f)  # numba's version
        stamp, overloads = pickle.loads(f.read())
    assert stamp == _cache.kernel_source_stamp() and overloads


def test_functions_outside_the_kernel_folder_keep_numbas_locators(tmp_path: Path) -> None:
    module = tmp_path / "user_kernel.py"
    module.write_text("from numba import njit\n\n@njit(cache=True)\ndef twice(x):\n    return 2 * x\n")
    sys.path.insert(0, str(tmp_path))
    try:
        import user_kernel  # type: ignore[import-not-found]

        assert user_kernel.twice(np.float64(2.0)) == 4.0
        assert type(user_kernel.twice._cache._impl.locator) not in _cache.LOCATORS
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop("user_kernel", None)
