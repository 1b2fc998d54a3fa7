"""The plotting contract of ``stickslip.plot.figure`` (issue 9 point 5), checked for every ``*_plot``.

Every public ``*_plot`` function takes its data first and keyword-only options with
``ax=None``, returns a ``PlotResult``, draws into the axes it is given, rejects unknown
keywords with ``TypeError``, leaves pyplot and rcParams alone; every result object that has
a figure plots by delegating. The Fig. 16 flowchart carries the worked example's numbers.
"""

from __future__ import annotations

import inspect
import math
import re
from collections.abc import Callable, Iterator
from types import ModuleType
from typing import Any

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.patches import FancyBboxPatch, Polygon

from stickslip.analysis.absorber_tuning import TuningCurve, tune_foundation, tuning_curve
from stickslip.analysis.design import DesignReport, design_foundation
from stickslip.analysis.frequency_response import response_curves
from stickslip.analysis.simulation import EngineOptions, SimulationResult, simulate
from stickslip.analysis.theory import optimal_foundation_fit
from stickslip.model import Slider, elastic_foundation, rigid_base
from stickslip.plot import absorber, basin, design, maps, simulation
from stickslip.plot.contact import maps as contact_map
from stickslip.plot.figure import PlotResult
from stickslip.reproduction.steps_design import EXAMPLE
from stickslip.sweep import stick_slip_boundary
from stickslip.sweep.basin import BasinResult, basin_stability, sample_box
from stickslip.sweep.basin_maps import BasinMap, basin_map
from stickslip.sweep.contact.maps import ContactMap
from stickslip.sweep.occurrence import OccurrenceMap, occurrence_map

PLOT_MODULES: tuple[ModuleType, ...] = (simulation, absorber, maps, design, basin, contact_map)
# arguments that select the data and may be given by position (everything else keyword-only)
DATA_ARGUMENTS = {"optimal_parameter_plot": 2, "analytic_curves_plot": 2}


@pytest.fixture(autouse=True)
def _no_global_state() -> Iterator[None]:
    """Each test leaves no pyplot figure and no rcParams change behind."""
    import matplotlib.pyplot as plt

    rc_before = dict(matplotlib.rcParams)
    assert plt.get_fignums() == []
    yield
    assert plt.get_fignums() == [], "a plotting function made a pyplot figure"
    assert dict(matplotlib.rcParams) == rc_before, "a plotting function changed rcParams"


@pytest.fixture(scope="module")
def run() -> SimulationResult:
    structure = elastic_foundation(0.05, optimal_foundation_fit(0.05).scaled(0.5))
    return simulate(structure, Slider(3.0), options=EngineOptions(t_max=60.0), run_to_t_max=True)


@pytest.fixture(scope="module")
def curve() -> TuningCurve:
    return tuning_curve([0.0, 0.1, 0.2])


@pytest.fixture(scope="module")
def occurrence() -> OccurrenceMap:
    return occurrence_map("log:0.1:10:4", [0.05, 0.1], "none")


@pytest.fixture(scope="module")
def boundary() -> Any:
    return stick_slip_boundary([0.05, 0.1], "none", lam_min=0.1, lam_max=10.0, n_scan=8, rtol=1e-3)


@pytest.fixture(scope="module")
def report() -> DesignReport:
    return design_foundation(EXAMPLE)


@pytest.fixture(scope="module")
def basin_result() -> BasinResult:
    structure, slider = rigid_base(0.1), Slider(2.5)
    states = sample_box(structure, slider, 200, {"xi": (-4.0, 4.0), "v": (-3.0, 1.5)}, seed=1)
    return basin_stability(structure, slider, states)


@pytest.fixture(scope="module")
def basin_grid() -> BasinMap:
    return basin_map("log:0.5:5:3", [0.05, 0.2], samples=40)


@pytest.fixture(scope="module")
def cases(run: SimulationResult, curve: TuningCurve, occurrence: OccurrenceMap, boundary: Any,
          report: DesignReport, basin_result: BasinResult,
          basin_grid: BasinMap) -> dict[str, tuple[Callable[..., PlotResult], tuple[Any, ...], int]]:
    """Every public ``*_plot``: (function, positional data, number of axes it draws into)."""
    curves = response_curves(0.1, optimal_foundation_fit(0.1))
    return {
        "time_history_plot": (simulation.time_history_plot, (run,), 1),
        "phase_portrait_plot": (simulation.phase_portrait_plot, (run,), 1),
        "simulation_plot": (simulation.simulation_plot, (run,), 3),
        "optimal_parameter_plot": (absorber.optimal_parameter_plot, (curve, "K"), 1),
        "optimal_tuning_plot": (absorber.optimal_tuning_plot, (curve,), 3),
        "frequency_response_plot": (absorber.frequency_response_plot, (curves,), 1),
        "peak_response_plot": (absorber.peak_response_plot, (curve,), 1),
        "equivalent_damping_plot": (absorber.equivalent_damping_plot, (curve,), 1),
        "analytic_curves_plot": (maps.analytic_curves_plot, (occurrence.dva, (0.05, 0.3)), 1),
        "occurrence_map_plot": (maps.occurrence_map_plot, (occurrence,), 1),
        "boundary_plot": (maps.boundary_plot, (boundary,), 1),
        "design_flowchart_plot": (design.design_flowchart_plot, (report,), 1),
        "basin_plot": (basin.basin_plot, (basin_result,), 1),
        "basin_map_plot": (basin.basin_map_plot, (basin_grid,), 1),
        "contact_map_plot": (contact_map.contact_map_plot, (_contact_grid(),), 1),
    }


def _contact_grid() -> ContactMap:
    """A 2 x 2 contact map (no run: the plot's data only)."""
    return ContactMap(np.array([0.01, 0.1]), np.array([1.0, 2.0]),
                      np.array([[1, 1], [0, 3]], dtype=np.int8), np.full((2, 2), np.nan),
                      np.full((2, 2), np.nan), np.array([[False, True], [False, True]]),
                      {"name": "probe"})


def _public_plot_functions() -> dict[str, Callable[..., Any]]:
    return {name: fn for module in PLOT_MODULES for name, fn in vars(module).items()
            if name.endswith("_plot") and inspect.isfunction(fn)
            and fn.__module__ == module.__name__}


def test_every_public_plot_function_is_covered(cases: dict[str, Any]) -> None:
    assert set(_public_plot_functions()) == set(cases)


@pytest.mark.parametrize("name", sorted(_public_plot_functions()))
def test_signature_is_data_first_then_keyword_only_with_ax(name: str) -> None:
    params = list(inspect.signature(_public_plot_functions()[name]).parameters.values())
    n_data = DATA_ARGUMENTS.get(name, 1)
    assert all(p.kind is p.POSITIONAL_OR_KEYWORD for p in params[:n_data])
    assert all(p.kind is p.KEYWORD_ONLY for p in params[n_data:]), name
    ax = next(p for p in params if p.name == "ax")
    assert ax.default is None


@pytest.mark.parametrize("name", sorted(_public_plot_functions()))
def test_new_figure_is_returned_as_a_plot_result(name: str, cases: dict[str, Any]) -> None:
    fn, args, n_axes = cases[name]
    out = fn(*args)
    assert isinstance(out, PlotResult)
    assert isinstance(out.figure, Figure) and len(out.axes) == n_axes and out.ax is out.axes[0]
    assert all(ax.get_figure(root=True) is out.figure for ax in out.axes)
    assert out.artists, "the artists drawn are returned for restyling"
    figure, axes, artists = out  # unpacks like python-control's ControlPlot
    assert (figure, axes, artists) == (out.figure, out.axes, out.artists)


@pytest.mark.parametrize("name", sorted(_public_plot_functions()))
def test_draws_into_the_axes_given(name: str, cases: dict[str, Any]) -> None:
    fn, args, n_axes = cases[name]
    fig = Figure()
    given = list(fig.subplots(1, n_axes, squeeze=False)[0])
    out = fn(*args, ax=given if n_axes > 1 else given[0])
    assert out.figure is fig and out.axes == given
    assert len(fig.axes) >= n_axes  # drawn into, not beside (twin/secondary axes may be added)
    assert all(ax.has_data() or ax.texts or ax.patches for ax in given)
    if n_axes > 1:
        with pytest.raises(ValueError, match=f"must hold {n_axes} axes"):
            fn(*args, ax=given[:-1])


@pytest.mark.parametrize("name", sorted(_public_plot_functions()))
def test_unknown_keyword_is_a_type_error(name: str, cases: dict[str, Any]) -> None:
    fn, args, _ = cases[name]
    with pytest.raises(TypeError):
        fn(*args, colour="red")


def test_results_plot_by_delegating(run: SimulationResult, curve: TuningCurve,
                                    occurrence: OccurrenceMap, boundary: Any,
                                    report: DesignReport, basin_result: BasinResult,
                                    basin_grid: BasinMap) -> None:
    results: list[tuple[Any, dict[str, Any], int]] = [
        (run, {}, 3),
        (occurrence, {}, 1),
        (boundary, {}, 1),
        (response_curves(0.1, optimal_foundation_fit(0.1)), {}, 1),
        (curve, {}, 3),
        (curve, {"kind": "parameters"}, 3),
        (curve, {"kind": "peak"}, 1),
        (curve, {"kind": "equivalent-damping"}, 1),
        (tune_foundation(0.1), {}, 1),
        (report, {}, 1),
        (basin_result, {}, 1),
        (basin_grid, {}, 1),
    ]
    for result, kwargs, n_axes in results:
        out = result.plot(**kwargs)
        assert isinstance(out, PlotResult) and len(out.axes) == n_axes, type(result).__name__
        ax = Figure().add_subplot()
        if n_axes == 1:
            assert result.plot(ax=ax, **kwargs).ax is ax
        with pytest.raises(TypeError):
            result.plot(colour="red", **kwargs)
    with pytest.raises(ValueError, match="kind"):
        curve.plot(kind="phase")


def test_tuning_result_plot_is_the_tuned_frequency_response() -> None:
    tuned = tune_foundation(0.1)
    labels = [line.get_label() for line in tuned.plot().ax.get_lines()]
    assert "rigid base" in labels and any(label.startswith("foundation M=") for label in labels)


def _numbers(texts: list[str]) -> list[float]:
    found = re.findall(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[+-]?\d+)?", " ".join(texts))
    return [float(x) for x in found]


def test_flowchart_shows_the_worked_example(report: DesignReport) -> None:
    out = design.design_flowchart_plot(report)
    ax = out.ax
    texts = [t.get_text() for t in ax.texts]
    numbers = _numbers(texts)
    d = report.to_dict()
    s, f = d["system"], d["foundation"]
    expected = {
        "m": s["m"], "k": s["k"], "c": s["c"], "mu_s": s["mu_s"], "mu_k": s["mu_k"],
        "W": s["load"], "V": s["speed"], "lambda": d["lambda"], "zeta": d["zeta"],
        "zeta_eq": d["zeta_eq"], "M_opt": f["M"], "K_opt": f["K"], "zeta_a_opt": f["zeta_a"],
        "m_a": f["m_a"], "k_a": f["k_a"], "c_a": f["c_a"],
        **{f"V_c {key}": v for key, v in d["critical_speed"].items() if key != "rigid_exact"},
        **{f"W_c {key}": v for key, v in d["critical_load"].items() if key != "rigid_exact"},
    }
    missing = [name for name, value in expected.items()
               if not any(math.isclose(n, value, rel_tol=6e-4) for n in numbers)]
    assert not missing, f"numbers not in the flowchart: {missing}\n{texts}"
    joined = "\n".join(texts)
    for needle in ("Eq. (33)", "Eq. (38)", "Eqs. (28)-(30)", "SI units", "yes", "no"):
        assert needle in joined
    # the worked example satisfies Eq. (38): (1 - zeta_eq)^5 lambda^2 / zeta_eq < 4 pi
    criterion = (1 - d["zeta_eq"]) ** 5 * d["lambda"] ** 2 / d["zeta_eq"]
    assert criterion < 4 * np.pi and any(math.isclose(n, criterion, rel_tol=6e-4) for n in numbers)
    boxes = [p for p in ax.patches if isinstance(p, FancyBboxPatch)]
    diamonds = [p for p in ax.patches if isinstance(p, Polygon) and len(p.get_xy()) == 5]
    assert len(boxes) >= 7 and len(diamonds) == 1  # seven steps and the decision of Eq. (38)


def test_flowchart_text_stays_inside_its_boxes(report: DesignReport) -> None:
    out = design.design_flowchart_plot(report)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(out.figure).get_renderer()
    out.figure.draw(renderer)
    boxes = [p.get_window_extent(renderer) for p in out.ax.patches]
    inside = 0
    for text in out.ax.texts:
        if not text.get_text():  # the arrows are empty annotations
            continue
        bbox = text.get_window_extent(renderer)
        holders = [b for b in boxes if b.x0 <= bbox.x0 and bbox.x1 <= b.x1
                   and b.y0 <= bbox.y0 and bbox.y1 <= b.y1]
        inside += bool(holders)
        if text.get_text() not in ("yes", "no"):
            assert holders, f"text outside every box: {text.get_text()!r}"
    assert inside >= 16
