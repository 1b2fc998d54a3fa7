"""Sweeps over parameter space: grids, executors, occurrence maps, boundaries, basins, resume stores.

* :func:`occurrence_map` classifies a ``(lambda, zeta)`` grid by certified simulation
  (paper Figs. 8 and 11), serially, over numba threads or on a Dask cluster, with a
  progress callback and an optional resume store.
* :func:`stick_slip_boundary` finds every critical ``lambda`` at each ``zeta`` by scanning
  and bisecting on the verdict (non-monotone boundaries included, paper Fig. 11a).
* :func:`basin_stability` and :func:`basin_map` classify disturbed starts about steady sliding.
* :class:`Axis` parses ``start:stop:n``, ``log:start:stop:n`` and comma lists.

Names load on first use (PEP 562); every name of ``__all__`` is public, the rest is private.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    # sweep: maps, boundaries and basins over parameter or state space
    "Axis": "stickslip.sweep.grid",
    "occurrence_map": "stickslip.sweep.occurrence",
    "OccurrenceMap": "stickslip.sweep.occurrence",
    "MapConfig": "stickslip.sweep.occurrence",
    "stick_slip_boundary": "stickslip.sweep.boundary",
    "BoundaryResult": "stickslip.sweep.boundary",
    "basin_stability": "stickslip.sweep.basin",
    "BasinResult": "stickslip.sweep.basin",
    "basin_map": "stickslip.sweep.basin",
    "BasinMap": "stickslip.sweep.basin",
    "sample_box": "stickslip.sweep.basin",
    "equilibrium_state": "stickslip.sweep.basin",
    # execution and resume stores
    "BACKENDS": "stickslip.sweep.executors",
    "ChunkStore": "stickslip.sweep.store",
    "StoreMismatch": "stickslip.sweep.store",
    "Crossing": "stickslip.analysis.critical",
}

__all__ = [
    "BACKENDS",
    "Axis",
    "BasinMap",
    "BasinResult",
    "BoundaryResult",
    "ChunkStore",
    "Crossing",
    "MapConfig",
    "OccurrenceMap",
    "StoreMismatch",
    "basin_map",
    "basin_stability",
    "equilibrium_state",
    "occurrence_map",
    "sample_box",
    "stick_slip_boundary",
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from stickslip.analysis.critical import Crossing
    from stickslip.sweep.basin import (
        BasinMap,
        BasinResult,
        basin_map,
        basin_stability,
        equilibrium_state,
        sample_box,
    )
    from stickslip.sweep.boundary import BoundaryResult, stick_slip_boundary
    from stickslip.sweep.executors import BACKENDS
    from stickslip.sweep.grid import Axis
    from stickslip.sweep.occurrence import MapConfig, OccurrenceMap, occurrence_map
    from stickslip.sweep.store import ChunkStore, StoreMismatch
