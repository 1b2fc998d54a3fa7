"""Examples that cannot rot (pysindy's habit): the documented scripts run in the test suite.

``docs/friction_example.py --quick`` is the worked example of docs/friction.md; the check
here is that it runs and that the verdicts the page states come out (source: the page).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow  # 18 s: out of the default run (kept under ten minutes)
def test_friction_worked_example_runs_and_states_the_documented_verdicts(tmp_path: Path) -> None:
    proc = subprocess.run(
        [sys.executable, str(ROOT / "docs" / "friction_example.py"), "--out", str(tmp_path), "--quick"],
        capture_output=True, text=True, timeout=600, check=True,
    )
    lines = {line.split()[0]: line for line in proc.stdout.splitlines() if "table law:" in line}
    assert "table law: stick-slip" in lines["rigid"]
    assert "table law: stick-slip" in lines["foundation"]
    assert "Coulomb law: steady-sliding" in lines["foundation"]
    assert "table law: steady-sliding" in lines["stability"] and "stable (growth" in lines["stability"]
    for name in ("friction_law.png", "friction_map.png", "friction_rigid_run.png",
                 "friction_stability_run.png"):
        assert (tmp_path / name).stat().st_size > 10_000


@pytest.mark.slow  # 9 s: out of the default run (kept under ten minutes)
def test_disturbance_worked_example_states_the_documented_numbers(tmp_path: Path) -> None:
    proc = subprocess.run(
        [sys.executable, str(ROOT / "docs" / "disturbances_example.py"), "--out", str(tmp_path),
         "--samples", "4000"],
        capture_output=True, text=True, timeout=600, check=True,
    )
    assert "from start-up: stick-slip" in proc.stdout
    assert "a velocity kick below 20 mm/s" in proc.stdout
    assert (tmp_path / "basin_rigid.png").stat().st_size > 10_000
    # the (lambda, delta) map: friction that weakens faster lets more knocks start stick-slip
    # (docs/disturbances.md; at delta > zeta steady sliding is unstable, every knock sticks)
    prefix = "stick-slip fraction at lambda = 10 by delta"
    line = next(x for x in proc.stdout.splitlines() if x.startswith(prefix))
    fractions = [float(pair.split(": ")[1]) for pair in line.split("delta: ")[1].split(", ")]
    assert fractions == sorted(fractions) and fractions[-1] == 1.0 and fractions[0] < 0.5
    assert (tmp_path / "basin_map_delta.png").stat().st_size > 10_000


@pytest.mark.slow  # the docs-site build (slow, in .ci/run) executes the gallery too
def test_slideway_gallery_example_goes_from_matrices_to_the_absorber(tmp_path: Path) -> None:
    """examples/plot_10_slideway.py (issue 18): the lines its text quotes come out."""
    proc = subprocess.run([sys.executable, str(ROOT / "examples" / "plot_10_slideway.py")],
                          capture_output=True, text=True, timeout=600, check=True, cwd=tmp_path,
                          env={**__import__("os").environ, "MPLBACKEND": "Agg"})
    out = proc.stdout
    assert "slideway: 6 DOF, contact on DOF 2" in out
    assert out.count("stick-slip |") == 1  # the certified run at the feed speed
    bare = next(x for x in out.splitlines() if x.startswith("bare machine:"))
    tuned = next(x for x in out.splitlines() if x.startswith("with absorber:"))
    v_bare = float(bare.split("V_c = ")[1].split()[0])
    v_tuned = float(tuned.split("V_c = ")[1].split()[0])
    assert v_tuned < v_bare  # stick-slip only below V_c: the tuned absorber widens the safe range
    assert "operating points" in out
