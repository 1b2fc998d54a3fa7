"""Issue 12, point 1: overflowing inputs end at once with one line, never spin forever.

Each case runs the real ``stickslip`` command as a subprocess under a short timeout (start-up
included): before the fix these spun at 100 % CPU inside the matrix exponential.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from stickslip.kernel.linalg import MAX_SQUARINGS_EXPM, expm

TIMEOUT_S = 60

OVERFLOW_CASES = [
    ["simulate", "--lam", "5e307", "--zeta", "0.1", "--t-max", "10"],
    ["simulate", "--lam", "5e307", "--zeta", "0.1", "--t-max", "10", "--initial", "0,1"],
    ["simulate", "--lam", "1", "--zeta", "0.1", "--gamma", "1e308"],
    ["simulate", "--lam", "1", "--zeta", "1e308"],
    ["simulate", "--lam", "1", "--zeta", "0.1", "--dva", "1,1e200,0.1"],
    ["simulate", "--lam", "1", "--zeta", "0.1", "--dva", "1,1,0.1", "--k-scale", "1e308"],
    ["map", "--lam", "1e308", "--zeta", "0.1", "--out", "{tmp}/m.nc"],
    ["map", "--lam", "1", "--zeta", "0.1", "--gamma", "1e308", "--out", "{tmp}/m.nc"],
    ["boundary", "--gamma", "1e308", "--zeta", "0.1"],
    ["boundary", "--lam-max", "1e308", "--zeta", "0.1"],
]


@pytest.mark.parametrize("args", OVERFLOW_CASES, ids=lambda a: " ".join(a[:3]))
def test_overflowing_input_is_refused_quickly(args: list[str], tmp_path: Path) -> None:
    argv = [a.format(tmp=tmp_path) for a in args]
    proc = subprocess.run(
        [sys.executable, "-c", "from stickslip.cli.main import run; run()", *argv],
        capture_output=True, text=True, timeout=TIMEOUT_S, cwd=tmp_path,
    )
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2, proc.stderr
    assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert "supported range" in lines[0] or "overflow" in lines[0]
    assert list(tmp_path.iterdir()) == []  # nothing written, no resume store


@pytest.mark.parametrize("value", [np.inf, -np.inf, np.nan, 1e308])
def test_expm_of_non_finite_matrix_ends_with_nan(value: float) -> None:
    # 3 x 1e308 sums to an infinite norm: before the fix `while norm > 0.5` never ended
    a = np.full((3, 3), value)
    assert np.all(np.isnan(expm(a)))


def test_expm_of_huge_finite_matrix_ends() -> None:
    # the largest finite norm needs about 1025 halvings, below the bound
    assert MAX_SQUARINGS_EXPM > 1025
    out = expm(np.array([[-1e300]]))
    assert out.shape == (1, 1) and np.isfinite(out).all()
