"""``stickslip basin-map`` (issue 13, point 2), and the backend options ``basin`` shares with ``map``.

Sources: the command is a thin layer over :func:`stickslip.sweep.basin.basin_map` (same grid,
same fixed sample: identical fractions); the command-line contract of DESIGN.md section 5 (one
line on stderr, exit code 2, no file for bad input; an example in every ``--help``).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import typer

from stickslip.cli.main import app
from stickslip.sweep.basin_maps import basin_map

from .cli_helpers import run_cli

COMMANDS = typer.main.get_command(app).commands  # type: ignore[attr-defined]


def test_basin_map_is_registered_with_an_example(capsys: pytest.CaptureFixture[str]) -> None:
    assert {"basin", "basin-map"} <= set(COMMANDS)
    code, out, _ = run_cli(["basin-map", "--help"], capsys)
    text = " ".join(out.split())
    assert code == 0
    assert "Example: stickslip basin-map --lam" in text and "--delta" in text
    code, out, _ = run_cli(["--help"], capsys)
    assert code == 0 and "basin-map" in out


def _help(command: str, option: str) -> str:
    [param] = [p for p in COMMANDS[command].params if option in p.opts]
    return str(param.help)


@pytest.mark.parametrize("option", ["--backend", "--workers", "--scheduler", "--scheduler-timeout"])
def test_basin_backend_options_are_those_of_map(option: str) -> None:
    assert _help("basin", option) == _help("map", option)


def test_basin_map_command_over_lambda_and_delta(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import xarray as xr

    out, plot = tmp_path / "maps" / "d.nc", tmp_path / "d.png"
    code, stdout, err = run_cli(["basin-map", "--lam", "0.4,3.5", "--delta", "0,0.05", "--zeta", "0.1",
                                 "--samples", "60", "--seed", "2", "--out", str(out), "--plot", str(plot),
                                 "--json"], capsys)
    assert code == 0, err
    payload = json.loads(stdout)
    assert payload["axes"] == ["lambda", "delta"] and payload["n_delta"] == 2 and payload["zeta"] == 0.1
    assert payload["n_cells"] == 4 and payload["samples"] == 60 and payload["out"] == str(out)
    assert payload["plot"] == str(plot) and plot.stat().st_size > 0
    api = basin_map([0.4, 3.5], [0.1], "none", samples=60, seed=2, deltas=[0.0, 0.05])
    with xr.open_dataset(out) as ds:
        assert ds["stick_slip_fraction"].dims == ("lambda", "delta")
        assert np.array_equal(ds["stick_slip_fraction"].values, api.dataset["stick_slip_fraction"].values)
        assert np.array_equal(ds["startup_verdict"].values, api.dataset["startup_verdict"].values)
    # Eq. (36) at zeta - delta: lambda_c = 1.470 (delta 0) and 0.911 (delta 0.05), so the
    # first row slides steadily from every start and the second row stick-slips from start-up
    assert payload["startup_counts"]["stick-slip"] == 2 and payload["disturbable_cells"] == 0
    # the same map again: refused without --overwrite, replaced with it
    code, _, err = run_cli(["basin-map", "--lam", "0.4,3.5", "--delta", "0,0.05", "--zeta", "0.1",
                            "--samples", "60", "--out", str(out)], capsys)
    assert code == 2 and "--overwrite" in err


def test_basin_map_command_text_summary(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, stdout, err = run_cli(["basin-map", "--lam", "0.5,3", "--zeta", "0.05,0.2", "--samples", "40",
                                 "--box", "v=-1:0.5"], capsys)
    assert code == 0, err
    lines = stdout.splitlines()
    assert lines[0].startswith("basin-map   2 lambda x 2 zeta = 4 cells")
    assert "v=-1:0.5" in lines[1]
    assert not any(line.startswith("output") for line in lines)


@pytest.mark.parametrize("args", [
    ["--delta", "0:0.1:3", "--zeta", "0.05,0.1"],
    ["--delta", "0:0.1:3", "--zeta", "0.1", "--friction", "linear:0.1"],
    ["--delta", "abc", "--zeta", "0.1"],
    ["--zeta", "0.1", "--samples", "0"],
    ["--zeta", "0.1", "--box", "q=1:2"],
    ["--zeta", "0.1", "--box", "xi=1"],
    ["--zeta", "0.1", "--box", "xi=2:1"],
    ["--zeta", "0.1", "--box", "xi=-inf:1"],
    ["--zeta", "0.1", "--dva", "none", "--box", "xi_a=-1:1"],
    ["--zeta", "0.1", "--workers", "0"],
    ["--zeta", "0.1", "--out", "OUT/x.csv"],
    ["--zeta", "0.1", "--plot", "OUT/x.txt"],
    ["--zeta", "-0.1"],
    ["--zeta", "0.1", "--gamma", "-1"],
    ["--zeta", "0.1", "--dva", "bogus"],
    ["--zeta", "0.1", "--friction", "nope"],
])
def test_basin_map_bad_input_is_one_line_and_writes_nothing(
        args: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    args = [a.replace("OUT", str(tmp_path / "out")) for a in args]
    if not any(a in ("--out", "--plot") for a in args):
        args += ["--out", str(tmp_path / "out" / "m.nc"), "--plot", str(tmp_path / "out" / "m.png")]
    code, out, err = run_cli(["basin-map", "--lam", "0.5,2", "--samples", "10", *args], capsys)
    assert code == 2 and out == "", err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert err.startswith("stickslip: error: ")
    assert list(tmp_path.iterdir()) == []
