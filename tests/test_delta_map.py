"""Occurrence maps over (lambda, delta) at a fixed zeta (issue 10, point 5).

``delta = sigma W / (2 sqrt(m k))`` is the dimensionless slope of the linear friction law
(``LinearFriction(delta)``, > 0 velocity weakening); each cell of a delta map has the law of
its ``delta``. References used below:

* the one-run API ``stickslip.simulate`` on the same cell (the map must be that run, bit for
  bit, whatever the backend or chunking);
* the exact boundary of the rigid base with the linear law, ``critical_lambda_linear(zeta,
  delta)`` = Eq. (36) at ``zeta - delta`` (derived in its docstring, checked to 1e-6 in
  tests/test_friction_interfaces.py against bisection);
* the linear-stability threshold of steady sliding, ``critical_weakening(structure)``, which on
  the rigid base is ``zeta`` (Routh-Hurwitz of ``s^2 + 2 (zeta - delta) s + 1``).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.lines import Line2D

from stickslip import Slider, Verdict, elastic_foundation, rigid_base, simulate
from stickslip.analysis.stability import critical_weakening
from stickslip.analysis.theory import critical_lambda_linear, optimal_foundation_fit
from stickslip.model.friction import LinearFriction, StribeckFriction
from stickslip.plot.figure import PlotResult
from stickslip.sweep import Axis, occurrence_map
from stickslip.sweep.execution import ExecutionOptions
from stickslip.sweep.occurrence import MapConfig, OccurrenceMap
from tests.cli_helpers import run_cli
from tests.sweep_helpers import assert_same_map

ZETA = 0.1
LAMS = Axis.parse("log:0.2:20:6", "lambda")
DELTAS = Axis.parse("-0.1:0.3:5", "delta")  # strengthening, Coulomb, weakening up to 3 zeta


@pytest.fixture(scope="module")
def rigid() -> OccurrenceMap:
    return occurrence_map(LAMS, [ZETA], "none", deltas=DELTAS,
                          execution=ExecutionOptions(backend="serial"))


def test_dataset_layout(rigid: OccurrenceMap) -> None:
    ds = rigid.dataset
    assert ds["verdict"].dims == ("lambda", "delta")
    assert ds["delta"].attrs["long_name"] == (
        "friction slope delta = sigma W / (2 sqrt(m k)), > 0 velocity weakening")
    assert ds["delta"].attrs["units"] == "1"
    np.testing.assert_array_equal(ds["delta"].values, DELTAS.values)
    assert "zeta" not in ds.dims and ds.attrs["zeta"] == ZETA
    config = rigid.configuration
    assert config["zeta"]["values"] == [ZETA]
    assert config["delta"]["values"] == [float(d) for d in DELTAS.values]
    assert config["axes"] == ["lambda", "delta"]
    assert "linear" in ds.attrs["friction"]
    _, delta, verdict = rigid
    assert verdict.shape == (6, 5) and rigid.second_axis_name == "delta"
    np.testing.assert_array_equal(delta, rigid.delta)
    np.testing.assert_array_equal(rigid.zeta, [ZETA])
    summary = rigid.to_dict()
    assert summary["axes"] == ["lambda", "delta"]
    assert (summary["n_lambda"], summary["n_delta"], summary["zeta"]) == (6, 5, ZETA)
    assert sum(rigid.counts.values()) == 30


def test_cells_equal_single_simulations(rigid: OccurrenceMap) -> None:
    # reference: stickslip.simulate on the same cell, rigid base, LinearFriction(delta)
    ds = rigid.dataset
    for i, lam in enumerate(LAMS.values):
        for j, delta in enumerate(DELTAS.values):
            run = simulate(rigid_base(ZETA), Slider(float(lam), friction=LinearFriction(float(delta))),
                           record=False)
            assert int(ds["verdict"][i, j]) == run.verdict.code, (lam, delta)
            assert rigid.verdict_at(float(lam), delta=float(delta)) is run.verdict
            assert int(ds["n_stick"][i, j]) == run.n_stick
            assert float(ds["t_end"][i, j]) == run.t_end
            np.testing.assert_array_equal(ds["period"][i, j], run.period)


def test_cells_with_a_foundation_equal_single_simulations() -> None:
    # reference: stickslip.simulate with the fitted optimum of Eqs. 28-30 at the map's zeta
    zeta, lams, deltas = 0.2, [0.5, 3.0], [-0.05, 0.1]
    result = occurrence_map(lams, [zeta], "optimal", deltas=deltas,
                            execution=ExecutionOptions(backend="serial"))
    assert "foundation_mass_ratio" in result.dataset and result.dataset["foundation_mass_ratio"].dims == ()
    structure = elastic_foundation(zeta, optimal_foundation_fit(zeta))
    for i, lam in enumerate(lams):
        for j, delta in enumerate(deltas):
            run = simulate(structure, Slider(lam, friction=LinearFriction(delta)), record=False)
            assert int(result.verdict[i, j]) == run.verdict.code
            assert float(result.dataset["t_end"][i, j]) == run.t_end


def test_boundary_of_each_delta_column_meets_the_closed_form() -> None:
    # reference: critical_lambda_linear (Eq. 36 at zeta - delta); every (zeta, delta) below
    # satisfies its validity conditions (startup stick lasts, the floor of the law is not reached)
    zeta = 0.2
    deltas = [-0.1, -0.05, 0.0, 0.05, 0.1, 0.15]
    result = occurrence_map("log:0.5:8:160", [zeta], "none", deltas=deltas)
    lam = result.lam
    for j, delta in enumerate(deltas):
        expected = critical_lambda_linear(zeta, delta)
        column = result.verdict[:, j]
        stick = column == Verdict.STICK_SLIP.code
        assert stick.any() and not stick.all()
        k = int(np.argmax(stick))  # first stick-slip lambda
        assert np.all(column[:k] == Verdict.STEADY_SLIDING.code), delta
        assert np.all(stick[k:]), delta
        assert lam[k - 1] < expected <= lam[k], (delta, expected, lam[k - 1], lam[k])


def test_weakening_beyond_zeta_always_sticks_on_the_rigid_base(rigid: OccurrenceMap) -> None:
    # reference: critical_lambda_linear = 0 for delta > zeta (slip-I does not decay); from
    # lambda = 0.5 on (below it the floor of the weakening law is reached, outside the closed form)
    lam, delta, verdict = rigid
    rows = lam >= 0.5
    cols = delta > ZETA
    assert np.all(verdict[np.ix_(rows, cols)] == Verdict.STICK_SLIP.code)


def test_serial_and_threads_are_bit_identical(rigid: OccurrenceMap) -> None:
    threads = occurrence_map(LAMS, [ZETA], "none", deltas=DELTAS,
                             execution=ExecutionOptions(backend="threads", workers=2, chunk_size=7))
    assert_same_map(rigid.dataset, threads.dataset)
    assert threads.chunks_total == 5


def test_dask_is_bit_identical(rigid: OccurrenceMap) -> None:
    pytest.importorskip("distributed")
    remote = occurrence_map(LAMS, [ZETA], "none", deltas=DELTAS,
                            execution=ExecutionOptions(backend="dask", workers=1, chunk_size=10))
    assert_same_map(rigid.dataset, remote.dataset)
    assert remote.backend == "dask" and remote.chunks_computed == 3


def test_resume_from_a_store(rigid: OccurrenceMap, tmp_path: Path) -> None:
    store = tmp_path / "store"
    full = occurrence_map(LAMS, [ZETA], "none", deltas=DELTAS,
                          execution=ExecutionOptions(chunk_size=4, store=store))
    assert full.chunks_computed == 8
    for f in sorted(store.glob("chunk-*.npz"))[1:4]:
        f.unlink()
    again = occurrence_map(LAMS, [ZETA], "none", deltas=DELTAS,
                           execution=ExecutionOptions(chunk_size=4, store=store))
    assert (again.chunks_loaded, again.chunks_computed) == (5, 3)
    assert_same_map(rigid.dataset, again.dataset)
    # the zeta map of the same lambdas is another configuration, never mixed in
    from stickslip.sweep.store import StoreMismatch

    with pytest.raises(StoreMismatch):
        occurrence_map(LAMS, [ZETA], "none", execution=ExecutionOptions(chunk_size=4, store=store))


def test_netcdf_and_csv(rigid: OccurrenceMap, tmp_path: Path) -> None:
    back = OccurrenceMap.from_netcdf(rigid.to_netcdf(tmp_path / "d.nc"))
    xr.testing.assert_identical(back.dataset, rigid.dataset)
    assert back.second_axis_name == "delta" and back.zeta.tolist() == [ZETA]
    rows = list(csv.DictReader(open(rigid.to_csv(tmp_path / "d.csv"))))
    assert len(rows) == 30
    assert list(rows[0])[:2] == ["lambda", "delta"] and rows[0]["zeta"] == repr(ZETA)
    assert float(rows[1]["delta"]) == float(DELTAS.values[1])


def test_fingerprint_tracks_delta_and_zeta_maps_are_unchanged() -> None:
    base = MapConfig.create([1.0], [0.1], "none", deltas=[0.0, 0.05])
    assert base.fingerprint() != MapConfig.create([1.0], [0.1], "none", deltas=[0.0, 0.06]).fingerprint()
    assert base.fingerprint() != MapConfig.create([1.0], [0.2], "none", deltas=[0.0, 0.05]).fingerprint()
    coulomb = MapConfig.create([1.0], [0.1, 0.2], "none").to_dict()
    assert "delta" not in coulomb and "axes" not in coulomb and "friction" not in coulomb


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"zetas": [0.1, 0.2], "deltas": [0.0]}, "one fixed zeta"),
        ({"zetas": [0.1], "deltas": [0.0], "friction": StribeckFriction(0.5)}, "exclude each other"),
        ({"zetas": [0.1], "deltas": [0.0], "friction": LinearFriction(0.1)}, "exclude each other"),
        ({"zetas": [0.1], "deltas": "0:x:3"}, "not a number"),
        ({"zetas": [0.1], "deltas": [float("nan")]}, "delta"),
    ],
)
def test_bad_arguments_raise_value_error(kwargs: dict[str, object], needle: str) -> None:
    with pytest.raises(ValueError, match=needle):
        occurrence_map([1.0], **kwargs)  # type: ignore[arg-type]


def test_verdict_at_needs_the_map_axis(rigid: OccurrenceMap) -> None:
    assert rigid.verdict_at(20.0, delta=0.3) is Verdict.STICK_SLIP
    assert rigid.verdict_at(20.0, ZETA, delta=0.3) is Verdict.STICK_SLIP
    with pytest.raises(ValueError, match="delta="):
        rigid.verdict_at(20.0, ZETA)
    with pytest.raises(ValueError, match=r"not 0\.2"):
        rigid.verdict_at(20.0, 0.2, delta=0.3)


# ---- the figure -------------------------------------------------------------------------

def _lines(result: PlotResult) -> list[Line2D]:
    return [a for a in result.artists if isinstance(a, Line2D)]


def test_plot_has_the_threshold_line_and_the_closed_form(rigid: OccurrenceMap) -> None:
    out = rigid.plot()
    assert isinstance(out, PlotResult)
    assert "delta" in out.ax.get_ylabel()
    # reference: critical_weakening(rigid_base(zeta)) = zeta (Routh-Hurwitz)
    d_crit = critical_weakening(rigid_base(ZETA))
    assert d_crit == pytest.approx(ZETA, rel=1e-8)
    (threshold,) = [ln for ln in _lines(out) if "delta_{crit}" in str(ln.get_label())]
    np.testing.assert_allclose(np.asarray(threshold.get_ydata(), dtype=float), [d_crit, d_crit])
    (curve,) = [ln for ln in _lines(out) if "Eq. (36)" in str(ln.get_label())]
    x, y = np.asarray(curve.get_xdata()), np.asarray(curve.get_ydata())
    assert y.max() < ZETA  # lambda_c = 0 at delta >= zeta: not drawn
    np.testing.assert_allclose(x, [critical_lambda_linear(ZETA, d) for d in y])


def test_plot_with_a_foundation_has_the_threshold_only() -> None:
    zeta = 0.1
    result = occurrence_map([0.5, 3.0], [zeta], "optimal", deltas=[0.0, 0.2],
                            execution=ExecutionOptions(backend="serial"))
    out = result.plot(style="image")
    labels = [str(ln.get_label()) for ln in _lines(out)]
    assert len(labels) == 1 and "delta_{crit}" in labels[0]
    d_crit = critical_weakening(elastic_foundation(zeta, optimal_foundation_fit(zeta)))
    np.testing.assert_allclose(np.asarray(_lines(out)[0].get_ydata(), dtype=float), [d_crit, d_crit])


@pytest.mark.parametrize("style", ["markers", "image"])
def test_plot_shows_slip_oscillation_cells(rigid: OccurrenceMap, style: str) -> None:
    ds = rigid.dataset.copy(deep=True)
    ds["verdict"][0, 0] = Verdict.SLIP_OSCILLATION.code  # a cell of code 3, as the engine writes it
    out = OccurrenceMap(ds).plot(style=style)
    legend = out.ax.get_legend()
    assert Verdict.SLIP_OSCILLATION.value in [t.get_text() for t in legend.get_texts()]


# ---- the command line -------------------------------------------------------------------

def test_cli_delta_map_json(rigid: OccurrenceMap, tmp_path: Path,
                            capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "d.nc"
    code, stdout, _ = run_cli(["map", "--lam", "log:0.2:20:6", "--delta", "-0.1:0.3:5",
                               "--zeta", "0.1", "--out", str(out), "--json"], capsys)
    assert code == 0
    payload = json.loads(stdout)
    assert payload["axes"] == ["lambda", "delta"] and payload["n_delta"] == 5
    assert payload["zeta"] == 0.1
    back = OccurrenceMap.from_netcdf(out).dataset  # the cells of the Python API's map
    for name in rigid.dataset.variables:
        assert back[name].values.tobytes() == rigid.dataset[name].values.tobytes(), name
    code, stdout, _ = run_cli(["map", "--lam", "log:0.2:20:6", "--delta", "-0.1:0.3:5",
                               "--zeta", "0.1", "--out", str(out)], capsys)
    assert code == 0 and "6 lambda x 5 delta at zeta=0.1" in stdout
    assert "nothing: the output already holds this map" in stdout


@pytest.mark.parametrize(
    ("extra", "needle"),
    [
        (["--zeta", "0.1,0.2"], "exactly one --zeta"),
        (["--zeta", "0.05:0.2:4"], "exactly one --zeta"),
        (["--zeta", "0.1", "--friction", "stribeck:vs=0.5"], "cannot be combined with --friction"),
        (["--zeta", "0.1", "--friction", "linear:0.05"], "cannot be combined with --friction"),
    ],
)
def test_cli_bad_delta_input_is_one_line_exit_2(extra: list[str], needle: str, tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "bad.nc"
    code, stdout, stderr = run_cli(["map", "--lam", "1,2", "--delta", "0,0.1", "--out", str(out),
                                    *extra], capsys)
    assert code == 2 and stdout == ""
    assert stderr.count("\n") == 1 and needle in stderr
    assert not out.exists() and not list(tmp_path.iterdir())
