"""Machine files with friction with memory shared by the tests (SI, as a user writes them).

``LUGRE``: the stick-slip example of Canudas de Wit et al. (1995): m = 1 kg, k = 2 N/m,
V = 0.1 m/s, sigma0 = 1e5 N/m, sigma1 = sqrt(1e5) N s/m, sigma2 = 0.4 N s/m, F_c = 1 N,
F_s = 1.5 N, v_s = 1 mm/s. ``RATE_STATE``: a 1-DOF rate-and-state slider below Rice and Ruina's
k_c (m 1 kg, k 8000 N/m, N 10 N, V 1 mm/s, a 0.01, b 0.015, d_c 10 um: k_c = 1e4 N/m).
"""

from __future__ import annotations

from pathlib import Path

LUGRE = """
[system]
m = "1 kg"
k = "2 N/m"
load = "1 N"
speed = "0.1 m/s"

[friction]
law = "lugre"
sigma0 = "1e5 N/m"
sigma1 = "316.22776601683796 N*s/m"
sigma2 = "0.4 N*s/m"
mu_c = 1.0
mu_s = 1.5
stribeck_velocity = "1 mm/s"
"""

RATE_STATE = """
load = "10 N"
speed = "1 mm/s"
m = "1 kg"
k = "8000 N/m"

[friction]
law = "rate-state"
a = 0.01
b = 0.015
d_c = "10 um"
mu_ref = 0.6
v_ref = "1 um/s"
"""


def machine_file(folder: Path, text: str) -> Path:
    """``text`` written to ``folder/machine.toml``."""
    path = folder / "machine.toml"
    path.write_text(text, encoding="utf-8")
    return path
