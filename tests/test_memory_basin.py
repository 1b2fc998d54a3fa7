"""``basin --config`` with friction with memory (sweep.memory.basin, issue 33).

Reference: each start ``(x, v)`` is the state ``simulate_memory`` builds for a kick ``F``
(``x`` the steady deflection, ``v = -F V``: analysis.memory.simulation.initial_state), so a
basin of such starts must label each as ``simulate --initial-kick F`` does; for Canudas de
Wit's bistable slider (tests/test_memory_cycle_search.py) kicks -1 and 2 end in stick-slip and
0.25 in steady sliding.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from stickslip.analysis.memory.simulation import initial_state, simulate_memory
from stickslip.io.machine_file import read_machine_file
from stickslip.sweep.memory.basin import memory_basin, sample_memory_box
from tests.cli_helpers import run_cli
from tests.memory_machines import LUGRE


def _file(tmp_path: Path) -> Path:
    path = tmp_path / "machine.toml"
    path.write_text(LUGRE, encoding="utf-8")
    return path



def test_starts_labelled_as_kicked_runs(tmp_path: Path) -> None:
    system = read_machine_file(_file(tmp_path)).memory_system()
    kicks = (-1.0, 0.25, 2.0)
    starts = np.array([[initial_state(system, f)[0][0], initial_state(system, f)[0][1]] for f in kicks])
    result = memory_basin(system, starts)
    expected = [simulate_memory(system, kick=f).verdict.code for f in kicks]
    assert result.verdict.tolist() == expected
    assert [result.fractions["stick-slip"], result.fractions["steady-sliding"]] == [2 / 3, 1 / 3]


def test_sampling_box_and_refusals(tmp_path: Path) -> None:
    system = read_machine_file(_file(tmp_path)).memory_system()
    states = sample_memory_box(system, 5, {"v": (-0.05, 0.05)}, seed=3)
    assert states.shape == (5, 2) and np.all(np.abs(states[:, 1]) <= 0.05)
    assert np.all(states[:, 0] == initial_state(system)[0][0])  # x keeps its steady value
    with pytest.raises(ValueError, match="not among x, v"):
        sample_memory_box(system, 5, {"xi": (0.0, 1.0)})


def test_cli_contract(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _file(tmp_path)
    starts = tmp_path / "starts.csv"
    x = float(initial_state(read_machine_file(path).memory_system())[0][0])
    starts.write_text(f"x,v\n{x!r},0.1\n{x!r},-0.025\n", encoding="utf-8")
    code, out, err = run_cli(["basin", "--config", str(path), "--initial-states", str(starts),
                           "--out", str(tmp_path / "b"), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["n"] == 2
    labels = (tmp_path / "b" / "labels.csv").read_text().splitlines()
    # v = V: stuck to the drive (the kick -1 start), stick-slip; a small kick: steady sliding
    assert labels[1].endswith("stick-slip") and labels[2].endswith("steady-sliding")


@pytest.mark.parametrize(("extra", "needle"), [
    (["--t-max", "100"], "dimensionless horizon"),
    (["--plot", "b.png"], "labels.csv"),
    (["--box", "xi=0:1"], "not among x, v"),
])
def test_cli_refusals(tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: list[str],
                      needle: str) -> None:
    code, out, err = run_cli(["basin", "--config", str(_file(tmp_path)), "--samples", "2", *extra],
                          capsys)
    assert code == 2 and out == "" and needle in err and len(err.strip().splitlines()) == 1
