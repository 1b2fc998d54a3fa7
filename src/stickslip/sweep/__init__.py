"""Sweeps over parameter space: grids, executors, occurrence maps, boundaries, basins, stores.

* :func:`occurrence_map` classifies a ``(lambda, zeta)`` grid by certified simulation
  (paper Figs. 8 and 11), serially, over numba threads or on a Dask cluster, with a
  progress callback and an optional resume store (how it runs: :class:`ExecutionOptions`).
* :func:`stick_slip_boundary` finds every critical ``lambda`` at each ``zeta`` by scanning
  and bisecting on the verdict (non-monotone boundaries included, paper Fig. 11a).
* :func:`basin_stability` labels many disturbed starts of one system; :func:`basin_map` does
  so on every cell of a grid.
* :class:`Axis` parses ``start:stop:n``, ``log:start:stop:n`` and comma lists.

Names load on first use (PEP 562), as in :mod:`stickslip.model`: importing one module of this
layer does not import the others.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

_EXPORTS: dict[str, str] = {
    "Axis": "stickslip.sweep.grid",
    "BACKENDS": "stickslip.sweep.executors",
    "ExecutionOptions": "stickslip.sweep.execution",
    "MapConfig": "stickslip.sweep.map_config",
    "OccurrenceMap": "stickslip.sweep.occurrence",
    "occurrence_map": "stickslip.sweep.occurrence",
    "BoundaryResult": "stickslip.sweep.boundary",
    "Crossing": "stickslip.analysis.critical",
    "stick_slip_boundary": "stickslip.sweep.boundary",
    "BasinResult": "stickslip.sweep.basin",
    "basin_stability": "stickslip.sweep.basin",
    "sample_box": "stickslip.sweep.basin",
    "equilibrium_state": "stickslip.sweep.basin",
    "states_from_physical": "stickslip.sweep.basin",
    "BasinMap": "stickslip.sweep.basin_maps",
    "basin_map": "stickslip.sweep.basin_maps",
    "ChunkStore": "stickslip.sweep.store",
    "StoreMismatch": "stickslip.sweep.store",
}

__all__ = [
    "BACKENDS",
    "Axis",
    "BasinMap",
    "BasinResult",
    "BoundaryResult",
    "ChunkStore",
    "Crossing",
    "ExecutionOptions",
    "MapConfig",
    "OccurrenceMap",
    "StoreMismatch",
    "basin_map",
    "basin_stability",
    "equilibrium_state",
    "occurrence_map",
    "sample_box",
    "states_from_physical",
    "stick_slip_boundary",
]


__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover
    from stickslip.analysis.critical import Crossing
    from stickslip.sweep.basin import (
        BasinResult,
        basin_stability,
        equilibrium_state,
        sample_box,
        states_from_physical,
    )
    from stickslip.sweep.basin_maps import BasinMap, basin_map
    from stickslip.sweep.boundary import BoundaryResult, stick_slip_boundary
    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.executors import BACKENDS
    from stickslip.sweep.grid import Axis
    from stickslip.sweep.map_config import MapConfig
    from stickslip.sweep.occurrence import OccurrenceMap, occurrence_map
    from stickslip.sweep.store import ChunkStore, StoreMismatch
