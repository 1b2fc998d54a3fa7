"""Legends cover no data (issue 32.7): the simulate figure (run.png) and the paper's Figs. 7, 13, 15.

Their legends sat in a corner inside the axes, where the stick shading fills the whole panel and
the curves reach every corner: they covered the foundation's curve, the belt-speed line and
the bottom of the phase orbit. Each legend now lies outside every axes of its figure (one
legend below the eight panels of Fig. 7). Checked on the drawn figure: no legend's box
overlaps any axes' box.
"""

from __future__ import annotations

from typing import Any

import pytest

from stickslip import Slider, elastic_foundation, optimal_foundation_fit, simulate


def _legends_cover_no_axes(figure: Any) -> None:
    figure.canvas.draw()  # the constrained layout places the legends
    renderer = figure.canvas.get_renderer()
    legends = [ax.get_legend() for ax in figure.axes if ax.get_legend() is not None]
    legends += list(figure.legends)
    assert legends, "the figure has legends"
    for legend in legends:
        box = legend.get_window_extent(renderer)
        for ax in figure.axes:
            assert not box.overlaps(ax.get_window_extent(renderer)), (
                [t.get_text() for t in legend.get_texts()], ax.get_title())


def test_the_simulate_figure(tmp_path: Any) -> None:
    # `stickslip simulate --lam 15 --zeta 0.1 --dva optimal --plot run.png`
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    result = simulate(elastic_foundation(0.1, optimal_foundation_fit(0.1)), Slider(15.0))
    figure = result.plot().figure
    FigureCanvasAgg(figure)
    _legends_cover_no_axes(figure)


@pytest.mark.parametrize("figure_number", [7, 13, 15])
def test_the_paper_figures(figure_number: int) -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from stickslip.reproduction import histories

    if figure_number == 7:
        figure = histories.fig7_figure(histories.fig7_runs(), 1000)
    else:
        runs = histories.fig12_runs()
        draw = histories.fig12_figure if figure_number == 13 else histories.phase_figure
        figure = draw(runs, 10.0, 1000)
    FigureCanvasAgg(figure)
    _legends_cover_no_axes(figure)
