"""``boundary --config`` and ``map --config`` for a machine with a contact (Jenkins element, normal DOF).

Reference values and where they come from:

- the rigid critical speed: ``stickslip design --config`` on the same machine without its
  ``[contact]`` (``critical_speed.rigid_exact``: the paper's Eq. (36) with
  ``lambda = (mu_s - mu_k) W / (V sqrt(m k))``);
- the compliant-over-rigid speed ratios 0.99967 (``k_t / k = 1000``) and 0.79375
  (``k_t / k = 1``) at zeta = 0.1, contact damping ratio 0.3: the table of
  docs/brake_squeal.md ("How compliance moves the critical speed"), measured there by a
  30-halving bisection on lambda, independent of this search;
- a map cell: the same machine run by ``simulate --config`` at that cell's speed and load.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from stickslip.cli.main import run
from tests.cli_helpers import run_cli

#: The paper's 1 DOF slider (docs/brake_squeal.md's Jenkins example), zeta = 0.1, lambda = 0.5.
SLIDER = ('mu_s = 0.3\nmu_k = 0.2\nload = "{load}"\nspeed = "{speed}"\nm = "1 kg"\nk = "1 N/m"\n'
          'c = "0.2 N*s/m"\n')


def jenkins(ratio: float, speed: str = "0.2 m/s", load: str = "1 N") -> str:
    """The slider on a Jenkins element ``k_t = ratio k``, damping ratio 0.3: c_t = 0.6 sqrt(k_t m)."""
    kt = ratio * 1.0
    return (SLIDER.format(speed=speed, load=load) + f'\n[contact]\ntangential_stiffness = "{kt!r} N/m"\n'
            f'tangential_damping = "{0.6 * math.sqrt(kt)!r} N*s/m"\n')


def write(tmp_path: Path, text: str, name: str = "machine.toml") -> str:
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def one_error(err: str) -> str:
    """The single error line (a first-run compile notice may precede it), no traceback."""
    lines = [line for line in err.splitlines() if line.startswith("stickslip: error:")]
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


@pytest.fixture(scope="module")
def rigid_speed(tmp_path_factory: pytest.TempPathFactory) -> float:
    """``design --config``'s exact rigid critical speed (Eq. 36) of the slider without a contact."""
    path = tmp_path_factory.mktemp("rigid") / "rigid.toml"
    path.write_text(SLIDER.format(speed="0.2 m/s", load="1 N"))
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        with contextlib.suppress(SystemExit):
            run(["design", "--config", str(path), "--no-stick-slip-optimum", "--json"])
    speed = float(json.loads(buffer.getvalue())["critical_speed"]["rigid_exact"])
    # the same from Eq. (36) and the paper's lambda = (mu_s - mu_k) W / (V sqrt(m k))
    from stickslip.analysis.theory import critical_lambda_exact

    assert speed == pytest.approx(0.1 * 1.0 / (critical_lambda_exact(0.1) * 1.0), rel=1e-12)
    return speed


def boundary(tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str,
             *extra: str) -> dict[str, object]:
    code, out, err = run_cli(["boundary", "--config", write(tmp_path, text), "--param", "speed",
                              *extra, "--json"], capsys)
    assert code == 0, err
    payload: dict[str, object] = json.loads(out)
    return payload


def test_stiff_damped_contact_gives_eq36_critical_speed(tmp_path: Path, rigid_speed: float,
                                                        capsys: pytest.CaptureFixture[str]) -> None:
    # docs/brake_squeal.md: k_t / k = 1000 at zeta 0.1 moves the critical speed by the ratio
    # 0.99967 (5 digits); bisected here to rtol 1e-5. rigid_speed is design's Eq. (36).
    p = boundary(tmp_path, capsys, jenkins(1000.0), "--range", "2 cm/s:20 cm/s", "--rtol", "1e-5",
                 "--workers", "1")
    crossings = p["crossings"]
    assert isinstance(crossings, list) and len(crossings) == 1, crossings
    c = crossings[0]
    assert (c["kind"], c["below"], c["above"], c["converged"]) == (
        "boundary", "stick-slip", "steady-sliding", True)
    assert c["bracket"][0] < c["value_SI"] < c["bracket"][1]
    assert c["bracket"][1] / c["bracket"][0] - 1.0 <= 1e-5
    print(f"k_t/k = 1000: V_c = {c['value_SI']!r} m/s, rigid {rigid_speed!r}, "
          f"ratio {c['value_SI'] / rigid_speed!r} (docs 0.99967)")
    assert c["value_SI"] / rigid_speed == pytest.approx(0.99967, abs=1e-5)


def test_soft_contact_lowers_the_critical_speed_by_the_documented_ratio(
        tmp_path: Path, rigid_speed: float, capsys: pytest.CaptureFixture[str]) -> None:
    # docs/brake_squeal.md: k_t / k = 1 at zeta 0.1 gives 0.79375; the default --rtol 1e-3 and
    # the default pool of 2 worker processes
    p = boundary(tmp_path, capsys, jenkins(1.0))
    assert p["rtol"] == 1e-3 and p["n_scan"] == 12 and p["workers"] >= 1
    assert p["range_SI"] == pytest.approx([0.02, 2.0])  # a decade either side of 0.2 m/s
    (c,) = p["crossings"]  # type: ignore[misc]
    assert c["kind"] == "boundary" and c["bracket"][1] / c["bracket"][0] - 1.0 <= 1e-3
    print(f"k_t/k = 1: ratio {c['value_SI'] / rigid_speed!r} (docs 0.79375), {p['n_runs']} runs "
          f"in {p['elapsed_s']:.2f} s")
    assert c["value_SI"] / rigid_speed == pytest.approx(0.79375, rel=1e-3)


def test_an_undetermined_side_is_never_a_boundary(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    # a horizon of 20 natural times decides the stick-slip runs near 3-5 cm/s but not the slow
    # decay to steady sliding: every verdict change then has an undetermined side
    text = jenkins(1000.0)
    p = boundary(tmp_path, capsys, text, "--range", "0.01:1", "--t-max", "20", "--workers", "1")
    crossings = p["crossings"]
    assert isinstance(crossings, list) and crossings
    for c in crossings:
        assert c["kind"] == "undetermined" and c["value_SI"] is None, c
        assert "undetermined" in (c["below"], c["above"])
    code, out, err = run_cli(["boundary", "--config", write(tmp_path, text), "--range", "0.01:1",
                              "--t-max", "20", "--workers", "1"], capsys)
    assert code == 0, err
    assert out.count("(undetermined: not a boundary)") == len(crossings), out


def test_map_cells_agree_with_simulate(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # each map cell is the run simulate --config makes of the machine at that speed and load
    import xarray as xr

    config = write(tmp_path, jenkins(1000.0))
    out = tmp_path / "map.nc"
    code, stdout, err = run_cli(["map", "--config", config, "--speed", "0.03,0.2", "--load", "1,2",
                                 "--out", str(out), "--csv", str(tmp_path / "map.csv"), "--json"],
                                capsys)
    assert code == 0, err
    p = json.loads(stdout)
    assert p["n_cells"] == 4 and p["dataset"] == str(out)
    with xr.open_dataset(out, engine="h5netcdf") as data:
        verdict = data["verdict"].values
        period = data["period"].values
        meanings = str(data["verdict"].attrs["flag_meanings"]).split()
        codes = list(data["verdict"].attrs["flag_values"])
    rows = (tmp_path / "map.csv").read_text().splitlines()
    assert rows[0] == "speed_m_per_s,load_N,verdict,period_s,amplitude_m,separated" and len(rows) == 5
    seen = set()
    for i, j, speed, load in ((0, 0, "0.03 m/s", "1 N"), (1, 0, "0.2 m/s", "1 N"),
                              (0, 1, "0.03 m/s", "2 N")):
        one = write(tmp_path, jenkins(1000.0, speed=speed, load=load), f"cell{i}{j}.toml")
        code, stdout, err = run_cli(["simulate", "--config", one, "--json"], capsys)
        assert code == 0, err
        s = json.loads(stdout)
        name = meanings[codes.index(verdict[i, j])]
        seen.add(name)
        assert name == s["verdict"], (i, j)
        if s["period_s"] is None:
            assert math.isnan(period[i, j])
        else:
            assert period[i, j] == pytest.approx(s["period_s"], rel=1e-12)
    assert seen == {"stick-slip", "steady-sliding"}


@pytest.mark.slow
def test_brake_pad_map_cells_agree_with_simulate(tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    # the brake pad (examples/brake_pad) at 2 cm/s and 5 m/s: stick-slip with separation and a
    # slip-separation cycle, each as simulate --config finds it (about 7 s per run)
    example = Path(__file__).resolve().parents[1] / "examples" / "brake_pad"
    out = tmp_path / "pad.nc"
    code, stdout, err = run_cli(["map", "--config", str(example / "machine.toml"), "--speed",
                                 "0.02,5", "--load", "1000", "--out", str(out), "--json"], capsys)
    assert code == 0, err
    import xarray as xr

    with xr.open_dataset(out, engine="h5netcdf") as data:
        period, separated = data["period"].values[:, 0], data["separated"].values[:, 0]
    for i, name in enumerate(("slow_belt.toml", "machine.toml")):
        code, stdout, err = run_cli(["simulate", "--config", str(example / name), "--json"], capsys)
        assert code == 0, err
        s = json.loads(stdout)
        assert period[i] == pytest.approx(s["period_s"], rel=1e-12) and bool(separated[i]) is s["separated"]


@pytest.mark.parametrize(("args", "why"), [
    (["map", "--speed", "0.1", "--load", "1", "--out", "m.nc", "--backend", "dask"],
     "--backend cannot be given for a [contact] machine"),
    (["map", "--speed", "0.1", "--load", "1", "--out", "m.nc", "--chunk-size", "4"],
     "--chunk-size cannot be given for a [contact] machine"),
    (["map", "--speed", "0.1", "--load", "1", "--out", "m.nc", "--workers", "0"],
     "--workers 0 must be at least 1"),
    (["map", "--speed", "0.1", "--load", "-1", "--out", "m.nc"], "every value must be positive"),
    (["map", "--speed", "0.1", "--load", "1", "--out", "m.nc", "--zeta", "0.1"],
     "--zeta cannot be given with --config"),
    (["boundary", "--zeta", "0.1"], "--zeta cannot be given with --config"),
    (["boundary", "--gamma", "2"], "--gamma cannot be given with --config"),
    (["boundary", "--param", "temperature"], "--param 'temperature' must be speed or load"),
    (["boundary", "--range", "1 kg:2 kg"], "--range"),
    (["boundary", "--range", "0.2:0.1"], "with A < B"),
    (["boundary", "--range", "0.1"], "must be A:B"),
    (["boundary", "--rtol", "0"], "--rtol 0.0 must be between 0 and 1"),
    (["boundary", "--out", "b.nc"], "--out cannot be given with a [contact] machine"),
])
def test_bad_input_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                               monkeypatch: pytest.MonkeyPatch, args: list[str], why: str) -> None:
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli([args[0], "--config", write(tmp_path, jenkins(10.0)), *args[1:]],
                             capsys)
    assert code == 2 and out == ""
    assert why in one_error(err)
    assert not (tmp_path / "m.nc").exists()


def test_a_machine_without_contact_gets_eq_36(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    # the paper's slider as a machine file (no [contact]): the exact engine's start-up verdicts
    # change once, at lambda_c of Eq. (36) (theory.critical_lambda_exact, zeta = 0.1 here:
    # c = 0.2, m = k = 1), lambda = (mu_s - mu_k) W / (V sqrt(m k)) = 0.1 / V
    from stickslip.analysis.theory import critical_lambda_exact

    rigid = write(tmp_path, SLIDER.format(speed="0.2 m/s", load="1 N"), "rigid.toml")
    code, out, err = run_cli(["boundary", "--config", rigid, "--json"], capsys)
    assert code == 0, err
    found = json.loads(out)
    assert found["engine"] == "exact-engine"
    (crossing,) = found["crossings"]
    assert (crossing["below"], crossing["above"]) == ("stick-slip", "steady-sliding")
    v_c = 0.1 / critical_lambda_exact(0.1)
    assert crossing["bracket"][0] <= v_c <= crossing["bracket"][1]
    assert crossing["value_SI"] == pytest.approx(v_c, rel=1e-3)


@pytest.mark.parametrize(("args", "why"), [
    (["boundary", "--param", "speed"], "--param and --range search a machine file"),
    (["boundary"], "Missing option '--zeta'"),
])
def test_refusals_outside_a_contact_machine(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                            args: list[str], why: str) -> None:
    rigid = write(tmp_path, SLIDER.format(speed="0.2 m/s", load="1 N"), "rigid.toml")
    code, out, err = run_cli([rigid if a == "RIGID" else a for a in args], capsys)
    assert code == 2 and out == ""
    assert why in one_error(err)


def _children(pid: int) -> list[int]:
    found: list[int] = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        with contextlib.suppress(OSError):
            found += [int(x) for x in (task / "children").read_text().split()]
    return found


@pytest.mark.skipif(not Path("/proc/self/task").exists(), reason="needs /proc")
def test_ctrl_c_ends_the_workers_with_one_line(tmp_path: Path) -> None:
    # the brake pad's runs take seconds: interrupt while both workers run one
    example = Path(__file__).resolve().parents[1] / "examples" / "brake_pad" / "machine.toml"
    src = Path(__file__).resolve().parents[1] / "src"
    code = "import sys; from stickslip.cli.main import run; sys.argv[0] = 'stickslip'; run()"
    process = subprocess.Popen(
        [sys.executable, "-c", code, "map", "--config", str(example), "--speed", "0.02,0.03",
         "--load", "1000", "--out", "m.nc", "--json"], cwd=tmp_path,
        env=dict(os.environ, PYTHONPATH=str(src)), text=True, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120.0
    workers: list[int] = []
    while len(workers) < 2:
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "the workers did not start"
        workers = _children(process.pid)
        time.sleep(0.05)
    time.sleep(0.5)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    assert process.returncode == 130, err
    assert err.strip().splitlines() == ["stickslip: aborted (Ctrl-C)"], err
    assert out == "" and not (tmp_path / "m.nc").exists()
    time.sleep(0.2)
    alive = []
    for pid in workers:
        try:
            os.kill(pid, 0)
            alive.append(pid)
        except ProcessLookupError:
            pass
    assert not alive, f"workers still running: {alive}"


def test_contact_map_plot_draws_separation(tmp_path: Path) -> None:
    # the plot of a small map: one image, a legend with the verdicts present
    from stickslip.sweep.contact.maps import ContactMap

    data = ContactMap(np.array([0.01, 0.1]), np.array([1.0, 2.0]),
                      np.array([[1, 1], [0, 3]], dtype=np.int8), np.full((2, 2), np.nan),
                      np.full((2, 2), np.nan), np.array([[False, True], [False, True]]),
                      {"name": "probe"})
    result = data.plot()
    labels = [t.get_text() for t in result.ax.get_legend().get_texts()]
    assert labels == ["steady-sliding", "stick-slip", "slip-oscillation", "separated"]
    assert data.fractions()["stick-slip"] == 0.5
    assert result.savefig(tmp_path / "p.png").stat().st_size > 0


def test_bisection_splits_at_a_third_verdict_and_stops_at_an_undetermined_one(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # the search alone, on made-up verdict zones (no engine): stick-slip below 0.028 m/s,
    # slip-oscillation up to 0.029 (between two scan values: met by the first midpoint),
    # steady sliding up to 0.2, undetermined up to 0.3, stick-slip above
    from stickslip.analysis.contact import pool as contact_pool
    from stickslip.analysis.contact.boundary import contact_boundary
    from stickslip.analysis.contact.engine import ContactSystem
    from stickslip.analysis.verdict import Verdict

    def zones(system: object, speed: float, load: float, *_: object) -> contact_pool.ContactPoint:
        edges = [(0.028, Verdict.STICK_SLIP), (0.029, Verdict.SLIP_OSCILLATION),
                 (0.2, Verdict.STEADY_SLIDING), (0.3, Verdict.UNDETERMINED)]
        verdict = next((v for edge, v in edges if speed < edge), Verdict.STICK_SLIP)
        return contact_pool.ContactPoint(speed, load, verdict, math.nan, math.nan, False, "", 0)

    monkeypatch.setattr(contact_pool, "run_point", zones)
    system = ContactSystem(np.eye(1), np.array([[0.2]]), np.eye(1), 0, None, 1.0, 0.2, 0.3, 0.2)
    result = contact_boundary(system, "speed", 0.01, 1.0, n_scan=12, rtol=1e-4, workers=1)
    found = [(c.below.value, c.above.value, c.is_boundary) for c in result.crossings]
    assert found == [("stick-slip", "slip-oscillation", True),
                     ("slip-oscillation", "steady-sliding", True),
                     ("steady-sliding", "undetermined", False),
                     ("undetermined", "stick-slip", False)]
    assert result.crossings[0].value == pytest.approx(0.028, rel=1e-4)
    assert result.crossings[1].value == pytest.approx(0.029, rel=1e-4)
    assert [c.value for c in result.crossings[2:]] == [None, None]
    assert all(c.bracket[0] < 0.2 < c.bracket[1] or c.bracket[0] < 0.3 < c.bracket[1]
               for c in result.crossings[2:])
