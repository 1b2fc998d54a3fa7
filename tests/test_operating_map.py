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


def test_file_gives_the_map_back_bit_for_bit_with_its_fingerprint(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # reference: the map as computed; netCDF-4 stores float64, so every array must come back
    # byte for byte, and the fingerprint is the hash of what determined the map
    from stickslip.io.netcdf import write_dataset
    from stickslip.sweep.operating_map import OperatingMap, operating_fingerprint

    machine = three_dof_machine()
    res = grid(machine, backend="serial")
    speeds = np.asarray(Axis.parse("log:0.005:0.5:4", "speed").values)
    assert res.fingerprint == operating_fingerprint(machine, speeds, np.array([20.0, 200.0]), OPTIONS)
    assert res.fingerprint != operating_fingerprint(machine, speeds, np.array([20.0, 201.0]), OPTIONS)
    assert res.fingerprint != operating_fingerprint(machine, speeds, np.array([20.0, 200.0]),
                                                    EngineOptions(t_max=OPTIONS.t_max / 2))
    path = write_dataset(res.to_xarray(), tmp_path / "vw.nc")
    back = OperatingMap.from_netcdf(path)
    assert arrays(back) == arrays(res)
    assert (back.speed.tobytes(), back.load.tobytes()) == (res.speed.tobytes(), res.load.tobytes())
    assert (back.machine, back.zeta, back.gamma, back.friction, back.fingerprint) == (
        res.machine, res.zeta, res.gamma, res.friction, res.fingerprint)
    assert back.summary() == res.summary()
    for name in ("status", "n_stick", "cycle_k"):
        assert np.array_equal(getattr(back, name), getattr(res, name))
    assert back.configuration == res.configuration


def test_the_file_describes_itself(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # an independent audit: the speed/load file held verdict strings without CF flags, no
    # certificate or stick phases, no version, date, t_max, start or law parameters; the
    # dimensionless map's file (sweep.map_data) is the model it must follow
    import json

    import xarray as xr

    from stickslip.analysis.verdict import RunStatus, Verdict
    from stickslip.io.netcdf import write_dataset

    machine = three_dof_machine()
    res = grid(machine, backend="serial")
    with xr.open_dataset(write_dataset(res.to_xarray(), tmp_path / "vw.nc")) as ds:
        flags = dict(zip(ds["verdict"].attrs["flag_values"].tolist(),
                         ds["verdict"].attrs["flag_meanings"].split(), strict=True))
        words = np.vectorize(flags.__getitem__)(ds["verdict"].values)
        assert np.array_equal(words, res.verdict)
        status = ds["certificate"].values
        assert all(RunStatus.from_code(int(c)).verdict.value == v
                   for c, v in zip(status.reshape(-1), res.verdict.reshape(-1), strict=True))
        stuck = res.verdict == Verdict.STICK_SLIP.value
        assert np.all(ds["cycle_k"].values[stuck] >= 1) and np.all(ds["n_stick"].values[stuck] > 1)
        attrs = ds.attrs
        assert attrs["Conventions"] == "CF-1.10" and attrs["stickslip_version"]
        assert attrs["date_created"] and attrs["t_max"] == OPTIONS.t_max
        assert "startup" in attrs["initial_condition"]
        assert json.loads(attrs["friction_json"])["law"] == "coulomb"
        assert json.loads(attrs["configuration"])["load_N"] == [20.0, 200.0]


def test_map_config_reuses_its_own_file_and_refuses_another(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    # like the dimensionless map: the same configuration is read back, not run again; another
    # one (or a file without a map's fingerprint) is refused in one line with the file untouched
    from tests.cli_helpers import run_cli
    from tests.test_cli_machine import cli_json, write_structure_file

    path = write_structure_file(tmp_path / "m.toml")
    out = tmp_path / "vw.nc"
    base = ["map", "--config", str(path), "--speed", "log:0.005:0.5:4", "--out", str(out)]
    first = cli_json([*base, "--load", "20,200"], capsys)
    stamp, data = out.stat().st_mtime_ns, out.read_bytes()
    again = cli_json([*base, "--load", "20,200", "--csv", str(tmp_path / "vw.csv")], capsys)
    assert (first["reused_output"], again["reused_output"]) == (False, True)
    assert again["fractions"] == first["fractions"] and again["machine"] == first["machine"]
    assert (out.stat().st_mtime_ns, out.read_bytes()) == (stamp, data)
    assert len((tmp_path / "vw.csv").read_text().splitlines()) == 1 + 8  # header and 4 x 2 cells
    code, stdout, err = run_cli([*base, "--load", "20,300"], capsys)
    assert code == 2 and stdout == "" and len(err.strip().splitlines()) == 1
    assert "another configuration" in err and "--overwrite" in err and "Traceback" not in err
    assert (out.stat().st_mtime_ns, out.read_bytes()) == (stamp, data)
    other = cli_json([*base, "--load", "20,300", "--overwrite"], capsys)
    assert other["reused_output"] is False and other["load_range_N"] == [20.0, 300.0]
    stranger = tmp_path / "notes.nc"
    stranger.write_text("not a map")
    code, stdout, err = run_cli([*base[:-1], str(stranger), "--load", "20,200"], capsys)
    assert code == 2 and "fingerprint" in err and stranger.read_text() == "not a map"
