"""Run the ``stickslip`` command in-process and capture what it prints."""

from __future__ import annotations

from pathlib import Path

import pytest

from stickslip.cli.main import run


def run_cli(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """Exit code, stdout and stderr of ``stickslip ARGS``."""
    try:
        run(args)
        code = 0
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


#: The one-DOF Stribeck slider of the Hopf closed forms: mu_s, mu_k, v_s [m/s], c [N s/m],
#: W [N], V [m/s]; m = 1 kg, k = 1e4 N/m.
STRIBECK_SLIDER = {"mu_s": 0.5, "mu_k": 0.3, "v_s": 0.05, "c": 20.0, "w": 100.0, "v": 0.1}


def stribeck_slider_file(path: Path) -> Path:
    """A machine file of one DOF (m = 1 kg, k = 1e4 N/m, c = 20 N s/m) with the exponential
    Stribeck law ``mu = mu_k + (mu_s - mu_k) exp(-v / v_s)`` (:data:`STRIBECK_SLIDER`).

    Its linearisation about steady sliding is ``m s^2 + (c + W mu'(V)) s + k`` with
    ``mu'(V) = -(mu_s - mu_k) / v_s exp(-V / v_s)``: the closed forms of the tests that use it.
    """
    p = STRIBECK_SLIDER
    path.write_text(f'mu_s = {p["mu_s"]}\nmu_k = {p["mu_k"]}\nload = "{p["w"]} N"\n'
                    f'speed = "{p["v"]} m/s"\n[structure]\nmass = [[1.0]]\nstiffness = [[1e4]]\n'
                    f'damping = [[{p["c"]}]]\ncontact_dof = 0\n[friction]\nlaw = "stribeck"\n'
                    f'stribeck_velocity = "{p["v_s"]} m/s"\nexponent = 1\n')
    return path
