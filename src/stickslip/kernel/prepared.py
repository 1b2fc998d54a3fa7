"""The tables a run needs, prepared from the structure and the parameter point.

:func:`prepared_tables` is :func:`~stickslip.kernel.system.prepare_bands` through its two
compiled steps (:func:`~stickslip.kernel.system.structure_data`, the structure's part, and
:func:`~stickslip.kernel.system.prepare_point`), with the structure's part kept between runs.
A plain Python function over compiled ones (see :func:`stickslip.kernel.engine.run`).
"""

from __future__ import annotations

import hashlib
import threading

import numpy as np

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel.system import prepare_point, structure_data

#: Structures whose :func:`structure_data` :func:`prepared_tables` keeps (the latest ones).
STRUCTURE_CACHE_SIZE = 4
_structure_cache: dict[bytes, tuple] = {}
#: Guards the cache: runs may come from several threads (the web app's sessions).
_cache_lock = threading.Lock()


def prepared_tables(mass, damping, stiffness, lam, gamma, edges, intercepts, slopes):
    """:func:`~stickslip.kernel.system.prepare_bands` through its two compiled steps.

    The structure's part (:func:`structure_data`: its matrices, both shared modes'
    exponentials and the Lyapunov solve) is kept for the last :data:`STRUCTURE_CACHE_SIZE`
    structures, keyed by a digest of the three matrices' bytes: the return map of a proof or
    a cycle search runs the engine dozens of times on one structure, and at 301 DOF this part
    took 0.73 s a run (118 s of a proof). :func:`prepare_point` only reads it (it copies what
    it keeps), so the tables are bit for bit those computed afresh.
    """
    digest = hashlib.blake2b(digest_size=20)
    for matrix in (mass, damping, stiffness):
        digest.update(np.ascontiguousarray(matrix, dtype=np.float64).tobytes())
    digest.update(np.asarray(mass.shape, dtype=np.int64).tobytes())
    key = digest.digest()
    with _cache_lock:
        structure = _structure_cache.get(key)
    if structure is None:
        structure = structure_data(mass, damping, stiffness)
        with _cache_lock:
            while len(_structure_cache) >= STRUCTURE_CACHE_SIZE:
                _structure_cache.pop(next(iter(_structure_cache)), None)
            _structure_cache[key] = structure
    return prepare_point(structure, mass, damping, stiffness, lam, gamma, edges, intercepts,
                         slopes)
