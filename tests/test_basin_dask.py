"""Basin stability on the Dask backend, as for maps (issue 13, point 1), on a real LocalCluster.

Sources: every state is an independent, deterministic run of the engine, so the labels and
summaries cannot depend on the backend or the chunking (the contract of
:mod:`stickslip.sweep.executors`, bit-identical backends); a chunk read from the resume store
is the chunk written by an earlier run (:mod:`stickslip.sweep.store`). Bad input on the
command line is one line on stderr, exit code 2 and no file (DESIGN.md section 5).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from stickslip import Slider, elastic_foundation, optimal_foundation_fit, rigid_base
from stickslip.analysis.simulation import EngineOptions
from stickslip.model.structure import chain_structure
from stickslip.sweep.basin import basin_stability, sample_box
from stickslip.sweep.execution import ExecutionOptions

from .cli_helpers import run_cli

distributed = pytest.importorskip("distributed")


def _address(cluster: object) -> str:
    return str(cluster.scheduler_address)  # type: ignore[attr-defined]


SYSTEMS = [
    ("rigid", rigid_base(0.1), Slider(2.5), {"xi": (-4.0, 4.0), "v": (-3.0, 1.5)}),
    ("foundation", elastic_foundation(0.1, optimal_foundation_fit(0.1).scaled(0.5)), Slider(20.0),
     {"xi": (-4.0, 4.0), "v": (-3.0, 1.5), "xi_a": (-1.0, 1.0)}),
]


@pytest.mark.parametrize(("name", "structure", "slider", "box"), SYSTEMS, ids=[s[0] for s in SYSTEMS])
def test_dask_labels_are_identical_to_threads(name, structure, slider, box, cluster) -> None:  # type: ignore[no-untyped-def]
    states = sample_box(structure, slider, 400, box, seed=11)
    threads = basin_stability(structure, slider, states, execution=ExecutionOptions(workers=2))
    done: list[int] = []
    remote = basin_stability(structure, slider, states,
                             execution=ExecutionOptions(backend="dask", scheduler=_address(cluster),
                                                        chunk_size=48, progress=lambda d, n: done.append(d)))
    assert np.array_equal(remote.verdict, threads.verdict), name
    assert np.array_equal(remote.float_summary, threads.float_summary, equal_nan=True), name
    assert np.array_equal(remote.int_summary, threads.int_summary), name
    # ceil(400 / 48) = 9 tasks; progress starts at 0, grows with every chunk, ends at 400
    assert remote.backend == "dask" and remote.chunks_total == 9
    assert done[0] == 0 and done[-1] == 400 and sorted(done) == done and len(done) == 10
    # both outcomes occur, so equal labels are not trivially equal (measured: 0.86 of the states
    # end in stick-slip on the rigid base, 0.71 with the foundation at lambda = 20)
    assert 0 < remote.fractions["stick-slip"] < 1, name


class _Interrupt(Exception):
    pass


def test_an_interrupted_dask_run_resumes_from_its_store(tmp_path: Path, cluster: object) -> None:
    structure, slider = rigid_base(0.1), Slider(2.5)
    states = sample_box(structure, slider, 320, {"xi": (-4, 4), "v": (-3, 1.5)}, seed=4)
    reference = basin_stability(structure, slider, states)
    store = tmp_path / "basin.parts"
    calls: list[int] = []

    def stop_after_two_chunks(done: int, total: int) -> None:
        calls.append(done)
        if len(calls) == 3:  # the start, then two finished (and saved) chunks
            raise _Interrupt

    with pytest.raises(_Interrupt):
        basin_stability(structure, slider, states,
                        execution=ExecutionOptions(backend="dask", scheduler=_address(cluster),
                                                   chunk_size=32, progress=stop_after_two_chunks,
                                                   store=store))
    saved = sorted(store.glob("chunk-*.npz"))
    assert len(saved) == 2  # progress is reported after each chunk is saved
    resumed = basin_stability(structure, slider, states,
                              execution=ExecutionOptions(backend="dask", scheduler=_address(cluster),
                                                         store=store))
    assert resumed.chunks_total == 10 and resumed.chunks_loaded == len(saved)
    assert np.array_equal(resumed.verdict, reference.verdict)
    assert np.array_equal(resumed.float_summary, reference.float_summary, equal_nan=True)
    # a store finished on one backend serves the other: threads load every chunk
    again = basin_stability(structure, slider, states, execution=ExecutionOptions(store=store))
    assert again.chunks_loaded == again.chunks_total == 10
    assert np.array_equal(again.verdict, reference.verdict)


def test_cli_dask_backend_resumes_and_matches_threads(tmp_path: Path, cluster: object,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    args = ["basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "300", "--seed", "7",
            "--box", "xi=-4:4,v=-3:1.5", "--json"]
    code, out, err = run_cli([*args, "--out", str(tmp_path / "threads")], capsys)
    assert code == 0, err
    threads = json.loads(out)
    assert threads["backend"] == "threads"
    # the store an interrupted `basin --out DIR` leaves: the states and configuration the command
    # makes (chain_structure, EngineOptions(t_max=5000), sample_box with the seed), one chunk lost
    structure, slider = chain_structure(0.1, ()), Slider(2.5)
    states = sample_box(structure, slider, 300, {"xi": (-4.0, 4.0), "v": (-3.0, 1.5)}, seed=7)
    run = tmp_path / "dask"
    basin_stability(structure, slider, states, options=EngineOptions(t_max=5000.0),
                    execution=ExecutionOptions(chunk_size=64, store=run / "basin.parts"))
    (run / "basin.parts" / "chunk-000002.npz").unlink()
    code, out, err = run_cli([*args, "--out", str(run), "--backend", "dask",
                              "--scheduler", _address(cluster)], capsys)
    assert code == 0, err
    remote = json.loads(out)
    assert remote["backend"] == "dask"
    assert remote["chunks"] == {"total": 5, "loaded": 4, "computed": 1}  # ceil(300 / 64) = 5
    assert remote["fractions"] == threads["fractions"]
    assert (run / "labels.csv").read_text() == (tmp_path / "threads" / "labels.csv").read_text()
    assert not (run / "basin.parts").exists()  # removed when done, as for maps


def test_store_records_the_backends_that_used_it(tmp_path: Path, cluster: object) -> None:
    structure, slider = rigid_base(0.1), Slider(2.5)
    states = sample_box(structure, slider, 100, {"xi": (-4, 4), "v": (-3, 1.5)}, seed=1)
    store = tmp_path / "basin.parts"
    basin_stability(structure, slider, states,
                    execution=ExecutionOptions(backend="dask", scheduler=_address(cluster),
                                               chunk_size=50, store=store))
    basin_stability(structure, slider, states, execution=ExecutionOptions(store=store))
    manifest = json.loads((store / "manifest.json").read_text())
    assert [(r["backend"], r["chunks_loaded"], r["chunks_computed"]) for r in manifest["runs"]] == [
        ("dask", 0, 2), ("threads", 2, 0)]


@pytest.mark.parametrize("args", [
    ["--backend", "nope"],
    ["--backend", "dask", "--scheduler", "tcp://127.0.0.1:9"],  # port 9: nothing listens
    ["--backend", "dask", "--workers", "0"],
    ["--scheduler", "tcp://127.0.0.1:9", "--workers", "2"],
    ["--backend", "threads", "--scheduler", "tcp://127.0.0.1:9"],
    ["--backend", "serial", "--workers", "2"],
    ["--scheduler", "tcp://127.0.0.1:9", "--scheduler-timeout", "0"],
    ["--scheduler", "not an address"],
])
def test_basin_backend_bad_input_is_one_line_and_writes_nothing(
        args: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out_dir = tmp_path / "run"
    code, out, err = run_cli(["basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "50",
                              "--out", str(out_dir), "--plot", str(tmp_path / "b.png"), *args], capsys)
    assert code == 2 and out == "", err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert err.startswith("stickslip: error: ")
    assert list(tmp_path.iterdir()) == []
