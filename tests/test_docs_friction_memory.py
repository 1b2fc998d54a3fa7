"""docs/friction_memory.md quotes numbers that docs/friction_memory_example.py prints: run it and
check that every quoted number is still what the example computes (examples that cannot rot)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

QUOTED = [
    "stick-slip, period 6.36272 s, amplitude 0.19169 m",
    "trivial 1.00000001",
    "peak mu 0.62124",
    "mu_0 + a ln 10 = 0.62303",
    "final mu 0.60461 (mu_ss = 0.60461)",
    "V = 1.0e-03 m/s: k_c from the eigenvalues 10000 N/m, Rice-Ruina 10000 N/m",
    "LuGre periods at sigma0 = 1e5, 1e6, 1e7 N/m: 6.362720, 6.488955, 6.507337 s",
    "the limit law (exact engine): stick-slip, period 6.512319 s",
    "aging law, k = 0.8 k_c: stick-slip, period 282.668 s, nontrivial multipliers ['0.22'",
    "slip law, k = 0.8 k_c: slip-oscillation, period 236.711 s",
]


@pytest.mark.slow  # 8 s: out of the default run (kept under ten minutes)
def test_example_prints_the_numbers_the_page_quotes(tmp_path: Path) -> None:
    done = subprocess.run([sys.executable, str(ROOT / "docs" / "friction_memory_example.py"),
                           "--out", str(tmp_path)], capture_output=True, text=True, timeout=600,
                          check=False)
    assert done.returncode == 0, done.stderr
    page = (ROOT / "docs" / "friction_memory.md").read_text(encoding="utf-8")
    for text in QUOTED:
        assert text in done.stdout, text
    for number in ("6.36272", "0.19169", "1.00000001", "0.62124", "0.62303", "0.60461", "6.362720",
                   "6.488955", "6.507337", "6.512319", "282.668", "236.711"):
        assert number in page, number
    for name in ("memory_lugre_stick_slip.png", "memory_velocity_step.png", "memory_rice_ruina.png"):
        assert (tmp_path / name).stat().st_size > 10_000
