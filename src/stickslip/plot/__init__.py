"""Figures: one ``*_plot(data, *, ax=None, ...)`` per result, each returning a :class:`PlotResult`.

A result's ``.plot()`` delegates here.

Names load on first use (PEP 562), as in :mod:`stickslip.model`: importing one module of this
layer does not import the others.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

_EXPORTS: dict[str, str] = {
    "PlotResult": "stickslip.plot.figure",
    "simulation_plot": "stickslip.plot.simulation",
    "time_history_plot": "stickslip.plot.simulation",
    "phase_portrait_plot": "stickslip.plot.simulation",
    "occurrence_map_plot": "stickslip.plot.maps",
    "boundary_plot": "stickslip.plot.maps",
    "analytic_curves_plot": "stickslip.plot.maps",
    "basin_plot": "stickslip.plot.basin",
    "basin_map_plot": "stickslip.plot.basin",
    "optimal_parameter_plot": "stickslip.plot.absorber",
    "optimal_tuning_plot": "stickslip.plot.absorber",
    "frequency_response_plot": "stickslip.plot.absorber",
    "peak_response_plot": "stickslip.plot.absorber",
    "equivalent_damping_plot": "stickslip.plot.absorber",
    "design_flowchart_plot": "stickslip.plot.design",
}

__all__ = [
    "PlotResult",
    "analytic_curves_plot",
    "basin_map_plot",
    "basin_plot",
    "boundary_plot",
    "design_flowchart_plot",
    "equivalent_damping_plot",
    "frequency_response_plot",
    "occurrence_map_plot",
    "optimal_parameter_plot",
    "optimal_tuning_plot",
    "peak_response_plot",
    "phase_portrait_plot",
    "simulation_plot",
    "time_history_plot",
]


__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover
    from stickslip.plot.absorber import (
        equivalent_damping_plot,
        frequency_response_plot,
        optimal_parameter_plot,
        optimal_tuning_plot,
        peak_response_plot,
    )
    from stickslip.plot.basin import basin_map_plot, basin_plot
    from stickslip.plot.design import design_flowchart_plot
    from stickslip.plot.figure import PlotResult
    from stickslip.plot.maps import analytic_curves_plot, boundary_plot, occurrence_map_plot
    from stickslip.plot.simulation import phase_portrait_plot, simulation_plot, time_history_plot
