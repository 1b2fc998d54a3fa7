"""Occurrence maps (paper Figs. 8 and 11): backends, the rigid-base boundary, files, resume."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

from stickslip import RunStatus, Slider, Verdict, chain_structure, simulate
from stickslip.analysis.dva import resolve_dva
from stickslip.analysis.theory import critical_lambda_exact
from stickslip.model import STARTUP_DESCRIPTION
from stickslip.model.dva import DvaSpec
from stickslip.sweep import Axis, ChunkStore, OccurrenceMap, StoreMismatch, occurrence_map
from stickslip.sweep.execution import ExecutionOptions
from tests.sweep_helpers import LAMS, ZETAS, assert_same_map


@pytest.fixture(scope="module")
def optimal_serial() -> OccurrenceMap:
    return occurrence_map(LAMS, ZETAS, "optimal", execution=ExecutionOptions(backend="serial"))


def test_serial_and_threads_are_bit_identical(optimal_serial: OccurrenceMap) -> None:
    threads = occurrence_map(LAMS, ZETAS, DvaSpec("optimal"),
                             execution=ExecutionOptions(backend="threads", workers=2, chunk_size=4))
    assert_same_map(optimal_serial.dataset, threads.dataset)
    assert threads.chunks_total == 8 and threads.chunks_computed == 8


def test_cells_equal_single_simulations(optimal_serial: OccurrenceMap) -> None:
    # reference: the one-run API (stickslip.simulate) on the same cells
    ds = optimal_serial.dataset
    spec = DvaSpec("optimal")
    for i, j in [(0, 0), (3, 2), (5, 4), (4, 1)]:
        lam, zeta = float(ds["lambda"][i]), float(ds["zeta"][j])
        run = simulate(chain_structure(zeta, (resolve_dva(spec, zeta),)), Slider(lam, gamma=2.0),
                       record=False)
        assert optimal_serial.verdict_at(lam, zeta) is run.verdict
        assert int(ds["n_stick"][i, j]) == run.n_stick
        assert float(ds["t_end"][i, j]) == run.t_end
        np.testing.assert_array_equal(ds["period"][i, j], run.period)


def test_dataset_layout_and_cf_attributes(optimal_serial: OccurrenceMap) -> None:
    ds = optimal_serial.dataset
    assert ds["verdict"].dims == ("lambda", "zeta")
    assert ds["verdict"].dtype == np.int8
    # the codes of before the friction laws keep their meaning; slip-oscillation is added as 3
    assert list(ds["verdict"].attrs["flag_values"]) == [0, 1, 2, 3]
    assert ds["verdict"].attrs["flag_meanings"] == "steady-sliding stick-slip undetermined slip-oscillation"
    # every run status of the engine, in code order (RunStatus)
    meanings = ds["certificate"].attrs["flag_meanings"].split()
    assert meanings[:4] == ["certified-steady", "certified-cycle", "t-max", "max-events"]
    assert meanings == [s.label for s in sorted(RunStatus, key=lambda s: s.code)]
    assert list(ds["certificate"].attrs["flag_values"]) == sorted(s.code for s in RunStatus)
    for name in ("n_stick", "period", "amplitude", "stick_ratio", "max_velocity", "t_end"):
        assert ds[name].dims == ("lambda", "zeta")
    # NaN only where there is no cycle, and the attribute says so
    no_cycle = ds["verdict"].values != Verdict.STICK_SLIP.code
    assert np.all(np.isnan(ds["period"].values[no_cycle]))
    assert np.all(np.isfinite(ds["period"].values[~no_cycle]))
    assert "NaN" in ds["period"].attrs["comment"]
    assert ds.attrs["initial_condition"] == STARTUP_DESCRIPTION
    assert ds.attrs["Conventions"].startswith("CF-")
    for key in ("stickslip_version", "git_revision", "library_versions", "date_created", "t_max"):
        assert key in ds.attrs
    config = json.loads(ds.attrs["configuration"])
    assert config["dva"]["text"] == "optimal" and config["gamma"] == 2.0
    assert config["lambda"]["values"] == list(LAMS.values)
    assert ds["lambda"].attrs["spacing"] == "log"
    # Eq. (28) at zeta = 0.1: M_opt = 2.824
    assert float(ds["foundation_mass_ratio"].sel(zeta=0.1)) == pytest.approx(2.824)


def test_rigid_base_map_agrees_with_eq_36() -> None:
    # reference: Nakano's exact boundary, paper Eq. (36)
    zetas = [0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.45]
    result = occurrence_map("log:0.05:20:40", zetas, "none")
    lam, zeta, verdict = result
    critical = np.array([critical_lambda_exact(z) for z in zeta])
    above = lam[:, None] > 1.001 * critical[None, :]
    below = lam[:, None] < 0.999 * critical[None, :]
    assert np.all(verdict[above] == Verdict.STICK_SLIP.code)
    assert np.all(verdict[below] == Verdict.STEADY_SLIDING.code)
    assert above.sum() > 50 and below.sum() > 50


def test_undetermined_is_an_explicit_code_never_nan() -> None:
    # a horizon far too short to certify anything: every cell must say "undetermined"
    result = occurrence_map([5.0, 20.0], [0.1, 0.3], "optimal", t_max=0.5)
    assert np.all(result.verdict == Verdict.UNDETERMINED.code)
    assert np.all(result.dataset["certificate"].values == 3)  # t-max
    assert result.counts == {"steady-sliding": 0, "stick-slip": 0, "undetermined": 4, "slip-oscillation": 0}
    assert result.undetermined_fraction == 1.0


def test_progress_is_called_per_chunk() -> None:
    calls: list[tuple[int, int]] = []
    occurrence_map([0.5, 1.0, 2.0], [0.1, 0.2, 0.3], "none",
                   execution=ExecutionOptions(chunk_size=4, progress=lambda done,
                                              total: calls.append((done, total))))
    assert calls == [(0, 9), (4, 9), (8, 9), (9, 9)]


def test_netcdf_round_trip_and_csv(optimal_serial: OccurrenceMap, tmp_path: Path) -> None:
    path = optimal_serial.to_netcdf(tmp_path / "map.nc")
    back = OccurrenceMap.from_netcdf(path)
    xr.testing.assert_identical(back.dataset, optimal_serial.dataset)
    assert back.fingerprint == optimal_serial.fingerprint
    assert back.dva == DvaSpec("optimal")
    raw = xr.open_dataset(path, engine="h5netcdf", decode_cf=False)
    assert "_FillValue" not in raw["verdict"].attrs  # every cell has a code
    assert np.isnan(raw["period"].attrs["_FillValue"])
    raw.close()
    rows = list(csv.DictReader(open(optimal_serial.to_csv(tmp_path / "map.csv"))))
    assert len(rows) == 30
    ds = optimal_serial.dataset
    first = rows[0]
    assert float(first["lambda"]) == float(ds["lambda"][0])
    assert float(first["zeta"]) == float(ds["zeta"][0])
    assert first["verdict"] in ("steady-sliding", "stick-slip", "undetermined")
    assert int(first["verdict_code"]) == int(ds["verdict"][0, 0])
    last = rows[-1]  # lambda = 50: stick-slip with a period
    assert last["verdict"] == "stick-slip"
    assert float(last["period"]) == float(ds["period"][-1, -1])
    assert first["period"] == ""  # no cycle: empty, not "nan"


def test_resume_computes_only_missing_chunks(tmp_path: Path) -> None:
    store = tmp_path / "store"
    full = occurrence_map(LAMS, ZETAS, "none", execution=ExecutionOptions(chunk_size=4, store=store))
    assert full.chunks_computed == 8 and full.chunks_loaded == 0
    # lose three chunks, as if the run had been killed before writing them
    files = sorted(store.glob("chunk-*.npz"))
    for f in files[2:5]:
        f.unlink()
    calls: list[int] = []
    again = occurrence_map(LAMS, ZETAS, "none",
                           execution=ExecutionOptions(chunk_size=9, store=store, progress=lambda d,
                                                      n: calls.append(d)))
    assert (again.chunks_loaded, again.chunks_computed) == (5, 3)
    assert calls[0] == 30 - 12  # the loaded cells count as done from the start
    assert_same_map(full.dataset, again.dataset)
    log = ChunkStore(store, full.fingerprint, {}, 30, 4).runs
    assert [(r["chunks_loaded"], r["chunks_computed"]) for r in log] == [(0, 8), (5, 3)]


def test_store_of_another_configuration_is_never_mixed(tmp_path: Path) -> None:
    store = tmp_path / "store"
    occurrence_map([0.5, 1.0], [0.1, 0.2], "none", execution=ExecutionOptions(store=store))
    before = {p.name: p.read_bytes() for p in store.iterdir()}
    with pytest.raises(StoreMismatch, match="another configuration"):
        occurrence_map([0.5, 1.0], [0.1, 0.2], "none", gamma=1.0, execution=ExecutionOptions(store=store))
    assert {p.name: p.read_bytes() for p in store.iterdir()} == before
    replaced = occurrence_map([0.5, 1.0], [0.1, 0.2], "none", gamma=1.0,
                              execution=ExecutionOptions(store=store, overwrite=True))
    assert replaced.chunks_computed == 1


def test_fingerprint_tracks_every_input() -> None:
    from stickslip import EngineOptions
    from stickslip.sweep.occurrence import MapConfig

    lam, zeta = Axis.parse("1,2", "lambda"), Axis.parse("0.1", "zeta")
    base = MapConfig(lam, zeta, DvaSpec("optimal"))
    variants = [
        MapConfig(Axis.parse("1,2.0000001", "lambda"), zeta, DvaSpec("optimal")),
        MapConfig(lam, Axis.parse("0.2", "zeta"), DvaSpec("optimal")),
        MapConfig(lam, zeta, DvaSpec("optimal", k_scale=2.0)),
        MapConfig(lam, zeta, DvaSpec("optimal"), gamma=1.0),
        MapConfig(lam, zeta, DvaSpec("optimal"), options=EngineOptions(t_max=100.0)),
        MapConfig(lam, zeta, DvaSpec("optimal"), options=EngineOptions(max_period=3)),
    ]
    prints = {v.fingerprint() for v in variants}
    assert len(prints) == len(variants) and base.fingerprint() not in prints
    assert MapConfig(lam, zeta, DvaSpec("optimal")).fingerprint() == base.fingerprint()


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"lams": [0.0, 1.0]}, "lambda=0.0 must be positive"),
        ({"zetas": [-0.1]}, "zeta=-0.1 must not be negative"),
        ({"gamma": -1.0}, "gamma"),
        ({"t_max": -1.0}, "t_max"),
    ],
)
def test_bad_arguments_raise_value_error(kwargs: dict[str, object], needle: str) -> None:
    args: dict[str, object] = {"lams": [1.0], "zetas": [0.1], "dva": "none"}
    args.update(kwargs)
    with pytest.raises(ValueError, match=needle):
        occurrence_map(**args)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"backend": "gpu"}, "backend 'gpu'"),
        ({"backend": "serial", "workers": 2}, "serial backend"),
        ({"scheduler": "tcp://127.0.0.1:1"}, "needs the dask backend"),
        ({"chunk_size": 0}, "chunk_size=0"),
    ],
)
def test_bad_execution_options_raise_value_error(kwargs: dict[str, object], needle: str) -> None:
    # the options object refuses them at construction; the deprecated loose keywords still
    # reach the same check (and say they are deprecated first)
    with pytest.raises(ValueError, match=needle):
        ExecutionOptions(**kwargs)  # type: ignore[arg-type]
    with pytest.warns(DeprecationWarning, match="deprecated"), pytest.raises(ValueError, match=needle):
        occurrence_map(lams=[1.0], zetas=[0.1], dva="none", **kwargs)  # type: ignore[arg-type]


def test_plot_markers_image_and_contract(optimal_serial: OccurrenceMap) -> None:
    fig = Figure()
    ax = fig.add_subplot()
    artists = optimal_serial.plot(ax=ax).artists
    assert artists and ax.get_yscale() == "log"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "stick-slip" in labels and "steady-sliding" in labels
    assert any("Eq. (37)" in label for label in labels)
    filled = next(a for a in artists if getattr(a, "get_label", lambda: "")() == "stick-slip")
    assert filled.get_markerfacecolor() == "black"
    image_ax = Figure().add_subplot()
    from stickslip.plot.maps import occurrence_map_plot

    out = occurrence_map_plot(optimal_serial.dataset, ax=image_ax, style="image").artists
    assert out and image_ax.collections  # the categorical image
    with pytest.raises(TypeError):
        occurrence_map_plot(optimal_serial, ax=image_ax, colour="red")  # type: ignore[call-arg]
    with pytest.raises(ValueError, match="style"):
        occurrence_map_plot(optimal_serial, style="dots")  # type: ignore[arg-type]


def test_rigid_base_plot_has_eqs_36_and_39() -> None:
    result = occurrence_map("log:0.1:10:4", [0.05, 0.1], "none")
    ax = Figure().add_subplot()
    result.plot(ax=ax)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "Eq. (36), exact" in labels and "Eq. (39)" in labels
