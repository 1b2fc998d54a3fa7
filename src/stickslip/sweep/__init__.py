"""Sweeps over parameter space: grids, executors, occurrence maps, boundaries, resume stores.

* :func:`occurrence_map` classifies a ``(lambda, zeta)`` grid by certified simulation
  (paper Figs. 8 and 11), serially, over numba threads or on a Dask cluster, with a
  progress callback and an optional resume store.
* :func:`stick_slip_boundary` finds every critical ``lambda`` at each ``zeta`` by scanning
  and bisecting on the verdict (non-monotone boundaries included, paper Fig. 11a).
* :class:`Axis` parses ``start:stop:n``, ``log:start:stop:n`` and comma lists.
"""

from stickslip.sweep.boundary import BoundaryResult, Crossing, stick_slip_boundary
from stickslip.sweep.executors import BACKENDS
from stickslip.sweep.grid import Axis
from stickslip.sweep.occurrence import MapConfig, OccurrenceMap, occurrence_map
from stickslip.sweep.store import ChunkStore, StoreMismatch

__all__ = [
    "BACKENDS",
    "Axis",
    "BoundaryResult",
    "ChunkStore",
    "Crossing",
    "MapConfig",
    "OccurrenceMap",
    "StoreMismatch",
    "occurrence_map",
    "stick_slip_boundary",
]
