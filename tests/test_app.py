"""The web app (``stickslip app``) under Streamlit's AppTest, and the command that starts it.

AppTest runs the real script in-process: every widget, table and figure is built, and any
uncaught exception is recorded in ``at.exception``. The operating points below come from
``design_foundation`` for the defaults (m = 2 kg, k = 50 kN/m, c = 20 N s/m, mu_s = 0.5,
mu_k = 0.3, W = 500 N): lambda = 0.2 * 500 / (V sqrt(2 * 5e4)), so lambda = 6.32 at
5 cm/s; the simulated critical speeds are 0.459 m/s on the rigid base and 0.0619 m/s with
the recommended foundation (Eqs. 28-30).
"""

from __future__ import annotations

import csv
import importlib.util
import io
import itertools
import json
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("streamlit", reason="the app extra (streamlit) is not installed")

from streamlit.testing.v1 import AppTest

from stickslip.cli import app_command
from tests.cli_helpers import run_cli as _run

APP = Path(app_command.APP_SCRIPT)


def _errors(at: AppTest) -> list[str]:
    """The red boxes' texts as the user reads them (the page escapes Markdown, issue 31)."""
    return [re.sub(r"\\(.)", r"\1", str(e.value)) for e in at.error]

#: A page run's time limit; the engine is compiled before the first page run (fixture below),
#: so this bounds the app's own work, not numba's first compile.
TIMEOUT = 120.0


@pytest.fixture(scope="module", autouse=True)
def _compiled_engine() -> None:
    """Compile (or load from numba's cache) the kernels the page runs, before any page run.

    On a fresh clone the cache is cold and numba compiles every kernel on first use, which on
    a loaded 2-core machine took longer than a page run's time limit; the page itself is what
    these tests time. The calls are tiny: one run, one map cell, one basin state.
    """
    import numpy as np

    from stickslip import ExecutionOptions, Slider, basin_stability, occurrence_map, rigid_base, simulate

    simulate(rigid_base(0.1), Slider(3.0), record=False)
    occurrence_map([3.0], [0.1], "none", execution=ExecutionOptions(backend="serial"))
    basin_stability(rigid_base(0.1), Slider(3.0), np.array([[0.0, 0.5]]))


def _started() -> AppTest:
    at = AppTest.from_file(str(APP), default_timeout=TIMEOUT)
    at.run()
    return at


def _metric(at: AppTest, label: str) -> str:
    values = [m.value for m in at.metric if m.label == label]
    assert len(values) == 1, f"no single metric {label!r} on the page"
    return str(values[0])


def _verdicts(at: AppTest) -> tuple[str, str]:
    return _metric(at, "Verdict on the rigid base"), _metric(at, "Verdict with foundation")


@pytest.mark.slow  # 14 s: out of the default run (kept under ten minutes)
def test_default_inputs_render_and_show_the_verdicts() -> None:
    at = _started()
    assert not at.exception
    assert not at.error
    assert _verdicts(at) == ("stick-slip", "stick-slip")
    assert float(_metric(at, "λ")) == pytest.approx(0.2 * 500 / (0.05 * math.sqrt(2 * 5e4)),
                                                    rel=1e-3)
    assert float(_metric(at, "γ")) == pytest.approx(1.5)
    # verdict table, critical speed/load table, foundation table, stability table
    assert len(at.table) == 4
    critical = at.table[1].value
    assert critical.loc["with foundation, simulation", "critical speed V_c [m/s]"] == "0.06188"
    assert critical.loc["rigid base, exact (Eq. 36)", "critical speed V_c [m/s]"] == "0.4588"
    # a time history and a phase portrait per machine, and the two occurrence maps
    assert len(at.get("vega_lite_chart")) == 6
    assert len(at.get("download_button")) == 2


def test_the_cycles_period_and_amplitude_are_shown_in_seconds_and_metres() -> None:
    """Issue 31: the rigid base's certified cycle at the defaults, in s and m.

    Reference: ``simulate`` of the public API on the defaults' dimensionless groups
    (lambda = (mu_s - mu_k) W / (V sqrt(m k)), zeta = c / (2 sqrt(m k)), gamma = mu_k /
    (mu_s - mu_k), paper Eq. 22), scaled by 1/omega_n and V/omega_n (omega_n = sqrt(k/m)).
    """
    from stickslip import Slider, rigid_base, simulate

    m, k, c, w, v = 2.0, 5e4, 20.0, 500.0, 0.05
    root_mk, omega = math.sqrt(m * k), math.sqrt(k / m)
    run = simulate(rigid_base(c / (2 * root_mk)), Slider(0.2 * w / (v * root_mk), gamma=1.5))
    assert run.cycle_length > 0
    at = _started()
    assert not at.exception
    assert _metric(at, "rigid base: period T") == f"{run.period / omega:.4g} s"
    assert _metric(at, "rigid base: amplitude") == f"{run.amplitude * v / omega:.4g} m"


def _dataset(spec: dict[str, Any], name: str) -> Any:
    """A chart's dataset as a DataFrame (the charts carry Arrow tables)."""
    return spec["datasets"][name].to_pandas()


def test_the_time_plots_are_in_si() -> None:
    """The charts' samples are the run's exact trajectory scaled by (1/omega_n, V/omega_n, V)
    (Eqs. 15-16), and the stick shading is the run's stick phases in seconds."""
    from stickslip import Slider, rigid_base, simulate
    from stickslip.app.charts import PLOT_POINTS, phase_portrait_chart, time_history_chart

    run = simulate(rigid_base(0.1), Slider(3.0), record=True)
    scales = (0.01, 0.002, 0.5)  # s, m, m/s
    hist = run.time_history(n_points=PLOT_POINTS)
    history = _dataset(time_history_chart(run, scales), "history")
    at = np.searchsorted(hist.t * scales[0], history["t"].to_numpy())
    np.testing.assert_allclose(history["t"], hist.t[at] * scales[0], rtol=1e-15)
    np.testing.assert_allclose(history["x"], hist.position[at, 0] * scales[1], rtol=1e-15)
    stick = _dataset(time_history_chart(run, scales), "stick")
    np.testing.assert_allclose(stick[["start", "end"]].to_numpy(),
                               run.stick_intervals() * scales[0], rtol=1e-15)
    orbit = _dataset(phase_portrait_chart(run, scales), "history")
    x, v = hist.position[:, 0] * scales[1], hist.velocity[:, 0] * scales[2]
    kept = orbit["i"].to_numpy()
    assert np.all(np.diff(kept) > 0) and kept[0] == 0 and kept[-1] == x.size - 1
    np.testing.assert_array_equal(orbit["x"], x[kept])
    np.testing.assert_array_equal(orbit["v"], v[kept])
    belt = _dataset(phase_portrait_chart(run, scales), "belt")
    assert belt["v"].tolist() == [scales[2]]


def test_a_simplified_line_stays_within_its_tolerance() -> None:
    """Every dropped sample lies within the tolerance (a fraction of the axes' ranges) of the
    segment between the kept samples around it: the chart draws the same line."""
    from stickslip.app.charts import simplified

    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 10.0, 1500)
    for y in (np.sin(3.0 * t), np.where(t % 2.0 < 1.2, t % 2.0, 3.0 * np.cos(5.0 * t)),
              np.cumsum(rng.normal(size=t.size))):
        tolerance = 5e-4
        kept = simplified(t, y, tolerance)
        assert kept[0] == 0 and kept[-1] == t.size - 1 and np.all(np.diff(kept) > 0)
        px, py = (t - t[0]) / np.ptp(t), (y - y[0]) / np.ptp(y)
        worst = 0.0
        for a, b in itertools.pairwise(kept):
            dx, dy = px[b] - px[a], py[b] - py[a]
            inner = slice(a + 1, b)
            d = np.abs((px[inner] - px[a]) * dy - (py[inner] - py[a]) * dx) / np.hypot(dx, dy)
            worst = max(worst, float(d.max(initial=0.0)))
        assert worst <= tolerance
    line = np.linspace(0.0, 1.0, 1500)  # a straight line keeps its two ends only
    assert simplified(t, line).tolist() == [0, t.size - 1]


def test_the_occurrence_map_axes_read_the_operating_point_in_si() -> None:
    """The top axis is c = 2 zeta sqrt(m k) and the right one V = lambda_op V_op / lambda at the
    same load (Eq. 22), over the map's edges; the star is the operating point."""
    from stickslip.app import charts
    from stickslip.app.computations import occurrence_maps
    from stickslip.app.inputs import system_from_key

    lam, zeta, gamma, foundation, law, key = _default_occurrence_args()
    system = system_from_key(key)
    maps = occurrence_maps(lam, zeta, gamma, foundation, law)
    for name, result in maps.items():
        spec = charts.occurrence_chart(result, name, system, lam, zeta)
        cells, frame = _dataset(spec, "cells"), _dataset(spec, "frame")
        root_mk = math.sqrt(2.0 * 5e4)  # m = 2 kg, k = 50 kN/m
        np.testing.assert_allclose(frame["c"], [2 * root_mk * cells["z0"].min(),
                                                2 * root_mk * cells["z1"].max()], rtol=1e-12)
        np.testing.assert_allclose(frame["V"], [lam * 0.05 / cells["l1"].max(),
                                                lam * 0.05 / cells["l0"].min()], rtol=1e-12)
        point = _dataset(spec, "point")
        assert (point["zeta"][0], point["lambda"][0]) == (zeta, lam)
        # every cell of the map once: the runs of a column cover its lambda edges
        verdicts = result.dataset["verdict"]
        assert len(cells) <= verdicts.size and cells.groupby("zeta").size().size == 12
        curves = _dataset(spec, "curves")
        assert curves["lambda"].between(cells["l0"].min() * (1 - 1e-12),
                                        cells["l1"].max() * (1 + 1e-12)).all()


def test_charts_are_built_once_per_input_and_their_layout_holds_no_data(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Issue 31: a rerun of inputs charted before builds nothing (the charts are cached), and
    a new operating point changes the charts' data only, which the browser updates in place."""
    from stickslip.app import charts, figures

    built: list[int] = []
    real = charts.time_history_chart

    def counted(result: Any, si: Any) -> Any:
        built.append(1)
        return real(result, si)

    monkeypatch.setattr(figures, "time_history_chart", counted)
    figures.run_charts.clear()
    figures.occurrence_map_charts.clear()
    at = _started()
    assert not at.exception and len(built) == 2
    layouts = [_layout(c.proto.spec) for c in at.get("vega_lite_chart")]
    at.text_input(key="speed").set_value("10 cm/s").run()
    assert not at.exception and len(built) == 4
    assert [_layout(c.proto.spec) for c in at.get("vega_lite_chart")] == layouts
    at.text_input(key="speed").set_value("5 cm/s").run()
    assert not at.exception and len(built) == 4  # back to the defaults: nothing rebuilt


def _layout(spec: str) -> str:
    """A chart's specification without its datasets (which Streamlit sends apart)."""
    return json.dumps({k: v for k, v in json.loads(spec).items() if k != "datasets"},
                      sort_keys=True)


def _default_occurrence_args() -> tuple[Any, ...]:
    from stickslip.app import streamlit_app as web
    from stickslip.model.friction import CoulombFriction

    system, errors = web.parse_inputs(dict(web.DEFAULTS))
    assert system is not None and not errors
    report = web.design_report(web.si_key(system))
    return (report["lambda"], report["zeta"], report["gamma"], None, CoulombFriction(),
            web.si_key(system))


@pytest.mark.slow  # heavy (10-30 s cold); the default run keeps the cheaper app tests
def test_changing_the_speed_changes_the_verdict() -> None:
    at = _started()
    for speed, verdicts in (
        ("10 cm/s", ("stick-slip", "steady-sliding")),  # between the two critical speeds
        ("2 m/s", ("steady-sliding", "steady-sliding")),  # above both
        ("1 cm/s", ("stick-slip", "stick-slip")),  # lambda = 31.6: below both
    ):
        at.text_input(key="speed").set_value(speed).run()
        assert not at.exception and not at.error
        assert _verdicts(at) == verdicts, speed


def test_bad_input_replaces_the_results_and_a_fix_restores_them() -> None:
    at = _started()
    at.text_input(key="k").set_value("5 kg").run()
    assert not at.exception
    assert _errors(at) == [
        "Spring stiffness k: '5 kg' has the wrong unit for the slider stiffness: expected N/m "
        "(dimension [force] / [length]), got kg"
    ]
    assert not at.metric and not at.table and not at.get("image") and not at.get("vega_lite_chart")
    at.text_input(key="k").set_value("50000").run()  # a bare number is SI
    assert not at.exception and not at.error
    assert _verdicts(at) == ("stick-slip", "stick-slip")


@pytest.mark.parametrize(
    ("key", "text", "expected"),
    [
        ("k", "5 kg", "wrong unit"),
        ("speed", "3 N", "wrong unit"),
        ("mu_s", "0.5 m", "must be dimensionless"),
        ("m", "-2 kg", "must be positive"),
        ("m", "0 kg", "must be positive"),
        ("load", "-500 N", "must be positive"),
        ("speed", "0 m/s", "must be positive"),
        ("c", "-1 N*s/m", "must not be negative"),
        ("mu_k", "0.5", "must be smaller than mu_s"),
        ("mu_k", "0.7", "must be smaller than mu_s"),
        ("speed", "fast", "not a quantity"),
        ("load", "", "is empty"),
        ("m_a", "3 kg", "needs all of m_a, k_a and c_a"),
    ],
)
def test_bad_input_is_one_clear_line_and_nothing_is_computed(key: str, text: str,
                                                             expected: str) -> None:
    at = AppTest.from_file(str(APP), default_timeout=TIMEOUT)
    at.session_state[key] = text  # as if typed before the first run: nothing to compute
    at.run()
    assert not at.exception
    messages = _errors(at)
    assert len(messages) == 1
    assert expected in messages[0] and "\n" not in messages[0]
    assert not at.metric and not at.table and not at.get("image") and not at.get("vega_lite_chart")


def test_inputs_outside_the_model_range_are_one_line() -> None:
    at = AppTest.from_file(str(APP), default_timeout=TIMEOUT)
    # valid units, but zeta = c / (2 sqrt(mk)) = 20 / (2 sqrt(1e-10 * 5e4)) = 4472: the design
    # procedure refuses it
    at.session_state["m"] = "1e-10 kg"
    at.run()
    assert not at.exception
    (message,) = _errors(at)
    assert message.startswith("Cannot analyse these inputs:") and "is above 0.9" in message
    # beyond the SI range of a physical input (its products would overflow): refused by name
    at.session_state["m"] = "1e-300 kg"
    at.run()
    assert not at.exception
    (message,) = _errors(at)
    assert "m=1e-300 is outside the supported range [1e-50, 1e+50]" in message


def test_existing_foundation_is_assessed() -> None:
    at = _started()
    for key, text in (("m_a", "3.81 kg"), ("k_a", "47.9 kN/m"), ("c_a", "766 N*s/m")):
        at.text_input(key=key).set_value(text)
    at.run()
    assert not at.exception and not at.error
    # close to the recommended foundation: same verdicts as the default
    assert _verdicts(at) == ("stick-slip", "stick-slip")
    assert "given (assessed above)" in list(at.table[2].value.index)


@pytest.mark.slow  # heavy (10-30 s cold); the default run keeps the cheaper app tests
def test_stick_slip_optimal_foundation_on_demand() -> None:
    at = _started()
    assert not any("Stick-slip-optimal foundation:" in m.value for m in at.markdown)
    at.button(key="find_stick_slip_optimum").click().run()
    assert not at.exception
    found = [m.value for m in at.markdown if "Stick-slip-optimal foundation:" in m.value]
    assert len(found) == 1
    assert "m_a =" in found[0] and "kg" in found[0]
    # it depends on zeta: a result for another damping is never shown
    at.text_input(key="c").set_value("30 N*s/m").run()
    assert not any("Stick-slip-optimal foundation:" in m.value for m in at.markdown)


@pytest.mark.slow  # heavy (10-30 s cold); the default run keeps the cheaper app tests
def test_disturbed_starts_on_demand() -> None:
    # issue 13: basin stability of the machine without and with its foundation, on demand
    from stickslip import Slider, rigid_base
    from stickslip.app.streamlit_app import BASIN_SAMPLES, BASIN_V, BASIN_XI
    from stickslip.sweep.basin import basin_stability, sample_box

    at = _started()
    images = len(at.get("image"))
    at.button(key="sample_basin").click().run()
    assert not at.exception and not at.error
    table = at.table[-1].value
    assert list(table.index) == ["rigid base", "with foundation"]
    assert len(at.get("image")) == images + 2  # one basin figure per machine
    # reference: basin_stability on the same knocks of the default machine's rigid base
    # (lambda = (mu_s - mu_k) W / (V sqrt(m k)), zeta = c / (2 sqrt(m k)), gamma = mu_k /
    # (mu_s - mu_k), Eqs. 19-22; Coulomb law, steady sliding at xi = 0)
    lam = 0.2 * 500 / (0.05 * math.sqrt(2 * 5e4))
    structure, slider = rigid_base(20.0 / (2 * math.sqrt(2 * 5e4))), Slider(lam, gamma=1.5)
    states = sample_box(structure, slider, BASIN_SAMPLES, {"xi": (-BASIN_XI, BASIN_XI), "v": BASIN_V},
                        seed=1)
    reference = basin_stability(structure, slider, states)
    assert table.loc["rigid base", "ends in stick-slip"] == (
        f"{reference.fractions['stick-slip']:.3f} ± {reference.standard_errors['stick-slip']:.3f}")
    assert 0.0 < reference.fractions["stick-slip"] < 1.0  # the default machine is bistable
    # another damping is another machine: its basin is not shown until asked for
    at.text_input(key="c").set_value("30 N*s/m").run()
    assert len(at.get("image")) == images


@pytest.mark.slow  # heavy (10-30 s cold); the default run keeps the cheaper app tests
def test_bifurcation_diagram_on_demand(tmp_path: Path) -> None:
    # issue 20, point 5: the bifurcation diagram of the design point's machine in lambda
    import csv as csv_module

    from stickslip import Foundation
    from stickslip.analysis.continuation import ContinuationSystem, continue_cycles
    from stickslip.analysis.design import design_foundation
    from stickslip.app.computations import (
        BIFURCATION_MAX_PERIOD,
        BIFURCATION_MAX_STEPS,
        BIFURCATION_SEEDS,
        bifurcation_range,
    )
    from stickslip.app.exports import bifurcation_csv
    from stickslip.app.streamlit_app import _fmt
    from stickslip.model.physical import PhysicalSystem

    at = _started()
    images, downloads = len(at.get("image")), len(at.get("download_button"))
    assert not [d for d in at.dataframe if "event" in d.value.columns]
    at.button(key="continue_cycles").click().run()
    assert not at.exception and not at.error
    assert len(at.get("image")) == images + 1  # the two diagrams, one figure
    assert len(at.get("download_button")) == downloads + 2  # CSV and netCDF
    (shown,) = [d.value for d in at.dataframe if "event" in d.value.columns]

    # reference: continue_cycles on the same inputs (Eq. 22: lambda = (mu_s - mu_k) W /
    # (V sqrt(m k)); zeta = c / (2 sqrt(m k)); gamma = mu_k / (mu_s - mu_k); the foundation the
    # design report assesses), over the range the page states
    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05)
    report = design_foundation(system).to_dict()
    root_mk = math.sqrt(2.0 * 5e4)
    lam, zeta = 0.2 * 500.0 / (0.05 * root_mk), 20.0 / (2.0 * root_mk)
    crit = report["critical_lambda"]
    lo, hi = bifurcation_range(lam, [crit["rigid_exact"], crit["rigid_simulation"],
                                     crit["foundation_simulation"]])
    assert lo < crit["rigid_exact"] < lam < hi  # the birth of the rigid-base cycle is inside
    assert any(f"for λ from {_fmt(lo)} to {_fmt(hi)}" in m.value for m in at.markdown)
    f = report["foundation"]
    results = {name: continue_cycles(ContinuationSystem(lam, zeta, 1.5, found), "lam", (lo, hi),
                                     max_period=BIFURCATION_MAX_PERIOD, seeds=BIFURCATION_SEEDS,
                                     max_steps=BIFURCATION_MAX_STEPS)
               for name, found in (("rigid base", None),
                                   ("with foundation", Foundation(f["M"], f["K"], f["zeta_a"])))}
    expected = [(name, e) for name, r in results.items() for e in r.events]
    assert len(shown) == len(expected) > 0
    for (_, row), (name, e) in zip(shown.iterrows(), expected, strict=True):
        assert (row["machine"], row["event"], row["λ"]) == (name, e.type, f"{e.param:.8g}")
        # the belt speed of that lambda at the same load (Eq. 22 solved for V)
        assert row["belt speed V [m/s]"] == _fmt(0.2 * 500.0 / (e.param * root_mk))
        assert row["amplitude (V/ω_n)"] == _fmt(e.amplitude)
    # physics: on the rigid base with the Coulomb law the stick-slip cycle is born at the
    # exact boundary of Eq. (36), which the design report gives
    (graze,) = [e for e in results["rigid base"].events if e.type == "grazing"]
    assert graze.param == pytest.approx(crit["rigid_exact"], rel=1e-6)

    # the download: every branch point, in SI by Eqs. (15)-(16) and (22)
    rows = list(csv_module.DictReader(io.StringIO(bifurcation_csv(results, system, "speed"))))
    points = [(name, p) for name, r in results.items() for b in r.branches for p in b.points]
    assert len(rows) == len(points) > 0
    for row, (name, p) in zip(rows, points, strict=True):
        speed = 0.2 * 500.0 / (p.param * root_mk)
        assert row["structure"] == name and float(row["lam"]) == p.param
        assert float(row["speed_m_s"]) == pytest.approx(speed, rel=1e-12)
        assert float(row["amplitude_m"]) == pytest.approx(p.amplitude * speed / math.sqrt(5e4 / 2.0),
                                                          rel=1e-12)
        assert float(row["period_s"]) == pytest.approx(p.period / math.sqrt(5e4 / 2.0), rel=1e-12)
        assert int(row["stable"]) == int(p.stable)
    # the netCDF: each machine's to_xarray under its prefix, read back as written
    from stickslip.app.exports import bifurcation_netcdf
    from stickslip.io.netcdf import read_dataset

    path = tmp_path / "bifurcation.nc"
    path.write_bytes(bifurcation_netcdf(results))
    ds = read_dataset(path)
    for name, result in results.items():
        prefix = name.replace(" ", "_") + "_"
        ref = result.to_xarray()
        for var in ("lam", "amplitude", "period", "stable", "steady_growth_rate", "event_lam"):
            assert list(ds[prefix + var].values) == list(ref[var].values), (name, var)
        assert list(ds[prefix + "event_type"].values) == [e.type for e in result.events]
    assert ds.attrs["Conventions"] == "CF-1.10"
    # another damping is another machine: its diagram is not shown until asked for
    at.text_input(key="c").set_value("30 N*s/m").run()
    assert len(at.get("image")) == images
    assert not [d for d in at.dataframe if "event" in d.value.columns]


@pytest.mark.slow
def test_bifurcation_diagram_of_a_stribeck_law_reads_lambda_as_the_load() -> None:
    # a Stribeck curve is given in m/s (u_s = v_s / V): lambda is the load at the same speed
    from stickslip.app.streamlit_app import _fmt

    at = _started()
    at.selectbox(key="friction_law").set_value("stribeck").run()
    at.button(key="continue_cycles").click().run()
    assert not at.exception and not at.error
    (shown,) = [d.value for d in at.dataframe if "event" in d.value.columns]
    assert "load W [N]" in shown.columns and "belt speed V [m/s]" not in shown.columns
    root_mk = math.sqrt(2.0 * 5e4)
    for _, row in shown.iterrows():  # Eq. 22 solved for W at V = 5 cm/s
        assert row["load W [N]"] == _fmt(float(row["λ"]) * 0.05 * root_mk / 0.2)
    # on the rigid base steady sliding loses stability where the law's weakening outgrows the
    # damping: xi'' + (2 zeta + F'(1)) xi' + xi = 0 with F(u) = lam (gamma + r0 exp(-u/u_s)),
    # u_s = v_s / V = 10, r0 = 1 (mu_0 = mu_s), so the Hopf point is lam = 2 zeta u_s e^(1/u_s)
    zeta = 20.0 / (2.0 * root_mk)
    rigid = shown[shown["machine"] == "rigid base"]
    (hopf,) = [float(x) for x in rigid.loc[rigid["event"] == "hopf", "λ"]]
    assert hopf == pytest.approx(2.0 * zeta * 10.0 * math.exp(0.1), rel=1e-6)
    # and the slip oscillation born there is continued
    assert any("slip-oscillation branch" in c.value for c in at.caption)


@pytest.mark.parametrize(
    ("fields", "axis"),
    [
        # PhysicalFriction.dimensionless: Coulomb has no parameter; linear delta = sigma W /
        # (2 sqrt(m k)) holds at any V; table u_i = v_i / V and Stribeck u_s = v_s / V hold at
        # any W (f_i, r0 need no W); a viscous slope d_v = sigma_v W / (2 sqrt(m k)) needs both
        ({"law": "coulomb"}, "speed"),
        ({"law": "linear", "slope": 0.02}, "speed"),
        ({"law": "table", "table_v": (0.0, 0.5), "table_mu": (0.45, 0.3)}, "load"),
        ({"law": "stribeck", "stribeck_velocity": 0.5}, "load"),
        ({"law": "stribeck", "stribeck_velocity": 0.5, "viscous": 0.01}, None),
    ],
)
def test_lambda_stands_for_the_speed_or_the_load_the_law_does_not_depend_on(
        fields: dict[str, Any], axis: str | None) -> None:
    from stickslip.app.computations import lambda_axis
    from stickslip.model.physical import PhysicalFriction, PhysicalSystem

    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05, friction=PhysicalFriction(**fields))
    assert lambda_axis(system) == axis


# ---- the friction law (issue 10, point 5) -------------------------------------------------

def _design_stability(friction: Any) -> dict[str, Any]:
    """Reference: the stability section of ``design_foundation`` for the default inputs."""
    from stickslip import PhysicalSystem
    from stickslip.analysis.design import design_foundation

    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0, speed=0.05,
                            friction=friction)
    return dict(design_foundation(system).to_dict()["stability"])


def test_linear_law_shows_the_stability_table_of_the_design_report() -> None:
    from stickslip.app.streamlit_app import _fmt
    from stickslip.model.physical import PhysicalFriction

    at = _started()
    at.selectbox(key="friction_law").set_value("linear").run()
    assert at.text_input(key="slope").value == "0.02 s/m"
    assert not at.exception and not at.error
    # delta = sigma W / (2 sqrt(m k)) = 0.02 * 500 / (2 sqrt(1e5)) = 0.0158114
    assert any(c.value.startswith("Friction law: linear, delta = 0.0158114") for c in at.caption)
    (table,) = [t.value for t in at.table if "δ_crit" in t.value.columns]
    expected = _design_stability(PhysicalFriction("linear", slope=0.02))
    for row, key in (("rigid base", "rigid"), ("with foundation", "foundation")):
        ref = expected[key]
        assert table.loc[row, "stable"] == ("yes" if ref["stable"] else "no")
        assert table.loc[row, "growth rate [1/s]"] == _fmt(ref["growth_rate"])
        assert table.loc[row, "δ_crit"] == _fmt(ref["delta_crit"])
        assert table.loc[row, "δ_local"] == _fmt(ref["delta_local"])
        assert table.loc[row, "margin"] == _fmt(ref["margin"])
        assert table.loc[row, "σ_crit [s/m]"] == _fmt(ref["sigma_crit"])
    assert expected["rigid"]["delta_local"] == pytest.approx(0.02 * 500 / (2 * math.sqrt(1e5)))
    (reading,) = [m.value for m in at.markdown if "stays stable" in m.value]
    assert f"down to −{_fmt(expected['foundation']['sigma_crit'], 's/m')}" in reading
    assert "\n" not in reading
    # the certified safe disturbance margin of the design report, one line per structure
    margins = [m.value for m in at.markdown if m.value.startswith("Disturbances, ")]
    assert margins == [f"Disturbances, {row}: {expected[key]['safe_disturbance']['sentence']}."
                       for row, key in (("rigid base", "rigid"), ("with foundation", "foundation"))]
    # and the linear stability boundary along the speed and the load, as design gives it
    hopf = [m.value for m in at.markdown if "linear stability boundary (Hopf)" in m.value]
    assert hopf == [f"{row}: {expected[key]['boundaries']['sentence']}."
                    for row, key in (("Rigid base", "rigid"), ("With foundation", "foundation"))]


@pytest.mark.slow  # 14 s: out of the default run (kept under ten minutes)
def test_linear_law_shows_the_design_commands_warning_and_stability_optimal_foundation(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 31: what 'stickslip design' prints for a non-Coulomb law, on the page too.

    Reference: the JSON of ``stickslip design --config`` on the same machine, the app's
    defaults with ``[friction] law = "linear", slope = "0.02 s/m"``.
    """
    from stickslip.app.streamlit_app import _fmt

    config = tmp_path / "machine.toml"
    config.write_text('m = "2 kg"\nk = "50 kN/m"\nc = "20 N*s/m"\nmu_s = 0.5\nmu_k = 0.3\n'
                      'load = "500 N"\nspeed = "5 cm/s"\n[friction]\nlaw = "linear"\n'
                      'slope = "0.02 s/m"\n')
    code, out, _ = _run(["design", "--config", str(config), "--json"], capsys)
    assert code == 0
    cli = json.loads(out)
    (procedure,) = [w for w in cli["warnings"] if "paper's procedure" in w]
    stable = cli["stability_optimal_foundation"]

    at = _started()
    at.selectbox(key="friction_law").set_value("linear").run()
    assert not at.exception and not at.error
    shown = [re.sub(r"\\(.)", r"\1", str(w.value)) for w in at.warning]
    assert procedure in shown
    foundation = [t.value for t in at.table if "m_a [kg]" in t.value.columns]
    (table,) = foundation
    assert list(table.loc["stability-optimal"]) == [_fmt(stable["m_a"]), _fmt(stable["k_a"]),
                                                   _fmt(stable["c_a"])]
    critical = [t.value for t in at.table if "friction law" in t.value.columns]
    assert len(critical) == 1
    assert critical[0].loc["rigid base, simulation", "friction law"] == cli["friction"]


def test_bad_friction_slope_is_one_line_and_nothing_is_computed() -> None:
    at = AppTest.from_file(str(APP), default_timeout=TIMEOUT)
    at.session_state["friction_law"] = "linear"
    at.session_state["slope"] = "2 kg"
    at.run()
    assert not at.exception
    (message,) = _errors(at)
    assert message.startswith("Friction slope σ") and "wrong unit" in message and "s/m" in message
    assert "\n" not in message
    assert not at.metric and not at.table and not at.dataframe
    assert not at.get("image") and not at.get("vega_lite_chart")


@pytest.mark.parametrize(
    ("fields", "expected"),
    [
        ({"friction_law": "stribeck", "stribeck_velocity": "3 kg"}, "wrong unit"),
        ({"friction_law": "stribeck", "mu_0": "0.6"}, "above μs"),
        ({"friction_law": "stribeck", "exponent": ""}, "is empty"),
        ({"friction_law": "table"}, "upload a CSV"),
        ({"friction_law": "table", "friction_table": "v,f\n0,0.1\n"}, "takes v [m/s] and mu"),
        # an audit: only comment lines escaped as StopIteration, a 200,000-digit field as a
        # bare _csv.Error (the page showed Streamlit's redacted error)
        ({"friction_law": "table", "friction_table": "# measured on rig 3\n"},
         "needs a header row and at least one data row"),
        ({"friction_law": "table", "friction_table": "v,mu\n0," + "1" * 200_000 + "\n"},
         "row 2: not a readable CSV row"),
        ({"friction_law": "table", "friction_table": "v [mm/s],mu\n0,0.4\n"},
         "column v is given in 'mm/s'; it takes v in m/s"),
        ({"friction_law": "table", "friction_table": "v,mu\n0,x\n"}, "not two numbers"),
        ({"friction_law": "table", "friction_table": "v,mu\n0,0.4\n0.1,-0.2\n"}, "negative"),
    ],
)
def test_bad_friction_inputs_are_one_line(fields: dict[str, str], expected: str) -> None:
    from stickslip.app import streamlit_app as web

    raw = dict(web.DEFAULTS) | {k: d for k, (_, d) in web.FRICTION_INPUTS.items()} | fields
    system, errors = web.parse_inputs(raw)
    assert system is None and len(errors) == 1
    assert expected in errors[0] and "\n" not in errors[0]


def test_stribeck_and_table_inputs_convert_in_si() -> None:
    from stickslip.app import streamlit_app as web
    from stickslip.model.friction import StribeckFriction, TableFriction

    base = dict(web.DEFAULTS) | {k: d for k, (_, d) in web.FRICTION_INPUTS.items()}
    system, errors = web.parse_inputs(base | {"friction_law": "stribeck", "mu_0": "0.45"})
    assert system is not None and not errors
    law = system.slider().friction
    # u_s = v_s / V = 0.5 / 0.05; r0 = (mu_0 - mu_k) / (mu_s - mu_k) = 0.15 / 0.2
    assert isinstance(law, StribeckFriction)
    assert law.velocity_ratio == pytest.approx(10.0) and law.mu0_ratio == pytest.approx(0.75)
    curve = "v [m/s],mu\n0.0,0.45\n0.05,0.35\n0.5,0.3\n"  # the uploader's own header
    system, errors = web.parse_inputs(base | {"friction_law": "table", "friction_table": curve,
                                              "friction_table_name": "tribometer.csv"})
    assert system is not None and not errors
    law = system.slider().friction
    # u_i = v_i / V, f_i = (mu_i - mu_k) / (mu_s - mu_k)
    assert isinstance(law, TableFriction)
    assert law.u == pytest.approx((0.0, 1.0, 10.0)) and law.f == pytest.approx((0.75, 0.25, 0.0))
    assert web.system_from_key(web.si_key(system)) == system


# ---- the download contents (pure functions of the script) ---------------------------------

@pytest.fixture(scope="module")
def computed() -> dict[str, Any]:
    from stickslip.app import streamlit_app as web

    raw = dict(web.DEFAULTS)
    system, errors = web.parse_inputs(raw)
    assert system is not None and not errors
    report = web.design_report(web.si_key(system))
    f = report["foundation"]
    runs = web.operating_point_runs(report["lambda"], report["zeta"], report["gamma"],
                                    (f["M"], f["K"], f["zeta_a"]))
    return {"web": web, "raw": raw, "system": system, "report": report, "runs": runs}


def test_report_json_has_the_design_report_and_the_initial_condition(computed: dict[str, Any]) -> None:
    web = computed["web"]
    payload = json.loads(web.report_json(computed["raw"], computed["report"], computed["runs"], None))
    assert payload["inputs"]["speed"] == "5 cm/s"
    assert payload["initial_condition"].startswith("startup")
    design = payload["design"]
    assert design["verdict"]["foundation"]["simulation"] == "stick-slip"
    assert design["critical_speed"]["foundation_simulation"] == pytest.approx(0.06188, rel=1e-3)
    assert set(design["recommended_foundation"]) >= {"m_a", "k_a", "c_a"}
    assert set(payload["operating_point"]) == {"rigid base", "with foundation"}
    assert payload["operating_point"]["with foundation"]["verdict"] == "stick-slip"


def test_history_csv_is_in_si_and_dimensionless(computed: dict[str, Any]) -> None:
    web, system = computed["web"], computed["system"]
    rows = list(csv.DictReader(io.StringIO(web.history_csv(computed["runs"], system, n_points=50))))
    assert {r["structure"] for r in rows} == {"rigid base", "with foundation"}
    first = rows[0]
    assert float(first["t_s"]) == pytest.approx(float(first["tau"]) * system.time_scale)
    assert float(first["v_m_s"]) == pytest.approx(float(first["xi_dot"]) * system.speed)
    assert first["xi_a"] == "" and first["mode"] == "stick"  # rigid base, startup state
    assert next(r for r in rows if r["structure"] == "with foundation")["xi_a"] != ""


# ---- the command ------------------------------------------------------------------------



def test_app_command_without_streamlit_is_one_line(monkeypatch: pytest.MonkeyPatch,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "streamlit" else real(name, *a))
    code, out, err = _run(["app"], capsys)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "pip install stickslip[app]" in err


def _started_commands(monkeypatch: pytest.MonkeyPatch) -> list[list[str]]:
    """The command lines ``stickslip app`` starts (recorded, not run)."""
    calls: list[list[str]] = []

    class FakeProcess:
        def __init__(self, command: list[str]) -> None:
            calls.append(command)

        def wait(self, timeout: float | None = None) -> int:
            return 0

    monkeypatch.setattr(app_command.subprocess, "Popen", FakeProcess)
    monkeypatch.setattr(app_command.signal, "signal", lambda *a: None)
    return calls


def test_app_command_runs_streamlit_on_the_script(monkeypatch: pytest.MonkeyPatch,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    calls = _started_commands(monkeypatch)
    code, _, err = _run(["app", "--port", "8600", "--headless"], capsys)
    assert code == 0 and err == ""
    (command,) = calls
    assert command[1:4] == ["-m", "streamlit", "run"]
    assert Path(command[4]) == APP and APP.is_file()
    assert command[command.index("--server.port") + 1] == "8600"
    assert command[command.index("--server.headless") + 1] == "true"
    # issue 31: this computer only by default, no tracebacks sent to the browser, upload limit
    assert command[command.index("--server.address") + 1] == "127.0.0.1"
    assert command[command.index("--client.showErrorDetails") + 1] == "none"
    from stickslip.io.machine_file import UPLOAD_MAX_MB

    assert command[command.index("--server.maxUploadSize") + 1] == str(UPLOAD_MAX_MB)


@pytest.mark.parametrize("address,warned", [
    ("0.0.0.0", True), ("::", True), ("192.0.2.7", True), ("myhost.example", True), ("0", True),
    ("127.0.0.1", False), ("127.0.1.1", False), ("::1", False), ("localhost", False),
    # an independent audit: these bind the loopback alone but were warned about
    ("127.1", False), ("::ffff:127.0.0.1", False), ("[::1]", False),
])
def test_app_command_warns_when_opened_to_the_network(
        address: str, warned: bool, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    calls = _started_commands(monkeypatch)
    # the warning alone (whether this computer can serve on the address: the test below)
    monkeypatch.setattr("stickslip.cli.app_command.check_can_serve", lambda *_: None)
    code, out, err = _run(["app", "--address", address, "--headless"], capsys)
    assert code == 0 and out == ""
    (command,) = calls
    # an IPv6 literal's brackets are not passed on (Streamlit failed on "[::1]" with a traceback)
    assert command[command.index("--server.address") + 1] == address.strip("[]")
    if warned:
        assert err.count("\n") == 1 and err.startswith("stickslip: warning: --address")
        assert "no login" in err
    else:
        assert err == ""


def test_app_command_refuses_an_empty_address(monkeypatch: pytest.MonkeyPatch,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    calls = _started_commands(monkeypatch)
    code, _, err = _run(["app", "--address", " "], capsys)
    assert code == 2 and err.count("\n") == 1 and "--address" in err and not calls


@pytest.mark.parametrize("address, message", [
    ("bogus.invalid", "--address 'bogus.invalid' cannot be resolved"),  # RFC 2606: never resolves
    ("192.0.2.7", "--address '192.0.2.7' cannot be served on by this computer"),  # RFC 5737
])
def test_app_command_refuses_an_address_it_cannot_serve_on(
        address: str, message: str, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit: Streamlit's 53-line traceback was all such an address got
    calls = _started_commands(monkeypatch)
    code, _, err = _run(["app", "--address", address, "--headless"], capsys)
    assert code == 2 and err.count("\n") == 1 and message in err and not calls


def test_app_command_refuses_a_port_in_use(monkeypatch: pytest.MonkeyPatch,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    import socket

    calls = _started_commands(monkeypatch)
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        code, _, err = _run(["app", "--port", str(port), "--headless"], capsys)
    assert code == 2
    assert err == f"stickslip: error: --port {port} is in use on 127.0.0.1: choose another port\n"
    assert not calls


def test_app_command_rejects_a_bad_port(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = _run(["app", "--port", "0"], capsys)
    assert code == 2 and err.count("\n") == 1


def test_an_unexpected_error_shows_no_traceback_or_server_path(monkeypatch: pytest.MonkeyPatch) -> None:
    """Security (the app serves people over a network): a bug's traceback names the server's
    files. The script itself hides the details, so ``streamlit run`` on it directly does too
    (``stickslip app`` also passes ``--client.showErrorDetails none``)."""
    from stickslip.app import computations

    secret = "/srv/secret/stickslip-internal.py"

    def broken(*args: Any, **kwargs: Any) -> Any:
        raise RuntimeError(f"an internal failure in {secret}")

    monkeypatch.setattr(computations, "design_report", broken)
    at = _started()
    assert len(at.exception) == 1
    shown = f"{at.exception[0].message} {' '.join(at.exception[0].stack_trace)}"
    assert secret not in shown and "Traceback" not in shown and "computations" not in shown
