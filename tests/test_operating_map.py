"""The machine's map over belt speed and load (``map --config``) runs like the dimensionless map.

References: :func:`stickslip.analysis.simulation.simulate` of each cell's operating point (the
one-run answer the map must reproduce), and the serial backend (every backend must give its
arrays bit for bit: the cells are independent and the engine deterministic).
"""

from __future__ import annotations

import numpy as np
import pytest

from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.model.machine import Machine
from stickslip.sweep.execution import ExecutionOptions
from stickslip.sweep.grid import Axis
from stickslip.sweep.operating_map import operating_map
from stickslip.sweep.store import StoreMismatch

OPTIONS = EngineOptions()


def three_dof_machine() -> Machine:
    """Table, slider (the contact, DOF 1, in the middle) and saddle; SI, non-proportional damping."""
    mass = np.diag([4.0, 1.0, 6.0])
    k = np.array([[3.0e4 + 1.0e4, -1.0e4, 0.0], [-1.0e4, 1.0e4 + 2.0e4, -2.0e4],
                  [0.0, -2.0e4, 2.0e4 + 5.0e4]])
    c = np.array([[30.0, -6.0, 0.0], [-6.0, 14.0, -4.0], [0.0, -4.0, 40.0]])
    return Machine(mass, c, k, 1, 0.5, 0.3, 100.0, 0.05, name="3-DOF slideway")


def grid(machine: Machine, **execution: object) -> object:
    return operating_map(machine, Axis.parse("log:0.005:0.5:4", "speed"),
                         Axis.parse("20,200", "load"), options=OPTIONS,
                         execution=ExecutionOptions(**execution))  # type: ignore[arg-type]


def arrays(result: object) -> list[bytes]:
    return [np.asarray(getattr(result, name)).tobytes()
            for name in ("lam", "verdict", "period_s", "amplitude_m", "stick_ratio")]


def test_each_cell_is_simulate_at_its_operating_point() -> None:
    machine = three_dof_machine()
    res = grid(machine, backend="serial")
    assert set(res.verdict.reshape(-1)) >= {"stick-slip", "steady-sliding"}  # both kinds of cell
    for i, v in enumerate(res.speed):
        for j, w in enumerate(res.load):
            point = machine.with_operating_point(speed=float(v), load=float(w))
            one = simulate(point.structure(), point.slider(), options=OPTIONS, record=False)
            ref = point.reference_system()
            assert res.lam[i, j] == point.slider().lam
            assert res.verdict[i, j] == one.verdict.value
            if one.verdict.value == "stick-slip":
                assert res.period_s[i, j] == pytest.approx(one.period * ref.time_scale, rel=1e-12)
                assert res.amplitude_m[i, j] == pytest.approx(one.amplitude * ref.length_scale,
                                                              rel=1e-12)


def test_threads_and_chunks_give_the_serial_map_bit_for_bit() -> None:
    machine = three_dof_machine()
    serial = grid(machine, backend="serial")
    threads = grid(machine, backend="threads", workers=2, chunk_size=3)
    assert arrays(serial) == arrays(threads)


def test_resume_store_keeps_finished_chunks(tmp_path) -> None:  # type: ignore[no-untyped-def]
    machine = three_dof_machine()
    seen: list[tuple[int, int]] = []
    first = grid(machine, chunk_size=3, store=tmp_path / "parts")
    second = grid(machine, chunk_size=3, store=tmp_path / "parts",
                  progress=lambda done, total: seen.append((done, total)))
    assert seen == [(8, 8)]  # everything came from the store, nothing was run again
    assert arrays(first) == arrays(second)
    other = machine.with_operating_point(speed=0.05, load=100.0)
    other = Machine(2.0 * other.mass, other.damping, other.stiffness, 1, 0.5, 0.3, 100.0, 0.05)
    with pytest.raises(StoreMismatch):
        grid(other, chunk_size=3, store=tmp_path / "parts")


def test_map_config_backends_give_the_same_file(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    # the command takes the dimensionless map's execution flags; the resume store is removed
    # once the map is written
    import xarray as xr

    from tests.test_cli_machine import cli_json, write_structure_file

    path = write_structure_file(tmp_path / "m.toml")
    grid_args = ["--speed", "log:0.005:0.5:4", "--load", "20,200"]
    outs = []
    for k, flags in enumerate((["--backend", "serial"], ["--workers", "2", "--chunk-size", "3"])):
        out = tmp_path / f"vw{k}.nc"
        cli_json(["map", "--config", str(path), *grid_args, "--out", str(out), *flags], capsys)
        assert not (tmp_path / f"vw{k}.nc.parts").exists()
        with xr.open_dataset(out) as ds:
            outs.append({name: ds[name].values.tobytes() for name in ds.data_vars})
    assert outs[0] == outs[1]


@pytest.mark.parametrize("flags,word", [(["--workers", "0"], "workers"),
                                        (["--backend", "gpu"], "gpu"),
                                        (["--chunk-size", "0"], "--chunk-size"),
                                        (["--backend", "serial", "--workers", "2"], "serial")])
def test_map_config_bad_execution_flags_one_line(flags, word, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    from tests.cli_helpers import run_cli
    from tests.test_cli_machine import write_structure_file

    path = write_structure_file(tmp_path / "m.toml")
    code, out, err = run_cli(["map", "--config", str(path), "--speed", "0.1", "--load", "10",
                              "--out", str(tmp_path / "o.nc"), *flags], capsys)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and word in err
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.toml"]


def test_old_progress_keyword_still_reports_cells_done_with_a_warning() -> None:
    seen: list[int] = []
    with pytest.warns(DeprecationWarning, match="ExecutionOptions"):
        operating_map(three_dof_machine(), Axis.parse("0.05,0.1", "speed"), Axis.parse("50", "load"),
                      options=OPTIONS, progress=seen.append)
    assert seen[0] == 0 and seen[-1] == 2
