"""The ``frf`` and ``tune`` commands: JSON contract, figure, one-line errors with exit code 2.

The commands are tested on a fresh Typer app built with their own ``register``; the
bad-input contract (one stderr line, exit code 2, no file written) also goes through the
real entry point ``stickslip.cli.main.run``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from stickslip.analysis.frequency_response import response_peak
from stickslip.analysis.theory import (
    equivalent_damping_fit,
    optimal_foundation_fit,
    peak_response_fit,
)
from stickslip.cli.absorber_commands import register
from stickslip.model import elastic_foundation
from tests.cli_helpers import run_cli as _run_main

FRF_KEYS = {"H_max", "Omega_peak", "zeta_eq", "foundation", "local_maxima", "rigid_base"}
TUNE_KEYS = {"M", "K", "zeta_a", "H_max", "Omega_peak", "zeta_eq", "fitted", "at_bound"}


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    app = typer.Typer(add_completion=False, pretty_exceptions_enable=False)
    register(app)
    return app


def _invoke(app: typer.Typer, args: list[str]) -> tuple[int, str]:
    result = CliRunner().invoke(app, args)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout


def test_frf_json_rigid_base(app: typer.Typer) -> None:
    code, out = _invoke(app, ["frf", "--zeta", "0.1", "--dva", "none", "--json"])
    assert code == 0
    payload = json.loads(out)  # exactly one JSON document on stdout
    assert FRF_KEYS <= payload.keys() and payload["foundation"] is None
    # closed form of the damped 1DOF oscillator
    assert payload["H_max"] == pytest.approx(1 / (2 * 0.1 * math.sqrt(1 - 0.01)), rel=1e-13)
    assert payload["Omega_peak"] == pytest.approx(math.sqrt(1 - 2 * 0.01), rel=1e-13)


def test_frf_json_fitted_optimum(app: typer.Typer) -> None:
    code, out = _invoke(app, ["frf", "--zeta", "0.1", "--dva", "optimal", "--json"])
    payload = json.loads(out)
    assert code == 0
    fit = optimal_foundation_fit(0.1)  # Eqs. (28)-(30)
    assert payload["foundation"]["M"] == fit.mass_ratio
    expected = response_peak(elastic_foundation(0.1, fit)).h_max
    assert payload["H_max"] == pytest.approx(expected, rel=1e-14)
    assert payload["H_max"] == pytest.approx(peak_response_fit(0.1), rel=0.01)  # Eq. (31)
    assert payload["zeta_eq"] == pytest.approx(1 / (2 * payload["H_max"]))  # Eq. (32)
    assert len(payload["local_maxima"]) == 2
    assert payload["rigid_base"]["H_max"] > 2 * payload["H_max"]


def test_frf_k_scale_equals_explicit_foundation(app: typer.Typer) -> None:
    _, a = _invoke(app, ["frf", "--zeta", "0.1", "--dva", "2,1,1", "--k-scale", "2", "--json"])
    _, b = _invoke(app, ["frf", "--zeta", "0.1", "--dva", "2,2,1", "--json"])
    assert json.loads(a)["H_max"] == json.loads(b)["H_max"]


def test_frf_plot_is_written(app: typer.Typer, tmp_path: Path) -> None:
    target = tmp_path / "sub" / "frf.png"
    code, out = _invoke(app, ["frf", "--zeta", "0.1", "--plot", str(target)])
    assert code == 0 and target.stat().st_size > 10_000
    assert "H_max" in out and str(target) in out


def test_tune_json_exact_and_fitted(app: typer.Typer) -> None:
    code, out = _invoke(app, ["tune", "--zeta", "0", "--json"])
    assert code == 0
    payload = json.loads(out)
    assert TUNE_KEYS <= payload.keys()
    # zeta = 0 optimum (closed form confirmed in tests/test_absorber.py): H_max = sqrt 5
    assert payload["H_max"] == pytest.approx(math.sqrt(5), rel=1e-13)
    assert payload["M"] == pytest.approx(25 / 16, rel=1e-7)
    fitted = payload["fitted"]
    assert fitted["M"] == optimal_foundation_fit(0.0).mass_ratio  # Eq. (28)
    assert fitted["H_max"] == peak_response_fit(0.0)  # Eq. (31)
    assert fitted["zeta_eq"] == equivalent_damping_fit(0.0)  # Eq. (33)


def test_tune_with_fixed_mass_ratio_text(app: typer.Typer) -> None:
    code, out = _invoke(app, ["tune", "--zeta", "0", "--mass-ratio", "1.5625"])
    assert code == 0
    assert "M fixed" in out and "Eq. (31)" in out and "2.23607" in out




@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["frf", "--zeta", "-0.1"], "--zeta"),
        (["frf", "--zeta", "nan"], "--zeta"),
        (["frf", "--zeta", "0.1", "--dva", "1,2"], "--dva"),
        (["frf", "--zeta", "0.1", "--dva", "1,0,1"], "K"),
        (["frf", "--zeta", "0.1", "--dva", "none", "--k-scale", "2"], "k_scale"),
        (["frf", "--zeta", "0.1", "--k-scale", "-1"], "k_scale"),
        (["tune", "--zeta", "-1"], "--zeta"),
        (["tune", "--zeta", "0.95"], "0.95"),
        (["tune", "--zeta", "0.1", "--mass-ratio", "0"], "--mass-ratio"),
        (["tune", "--zeta", "abc"], "--zeta"),
    ],
)
def test_bad_input_is_one_line_and_exit_code_2(
    args: list[str], expected: str, capsys: pytest.CaptureFixture[str]
) -> None:
    pytest.importorskip("stickslip.cli.main")
    code, out, err = _run_main(args, capsys)
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and expected in lines[0] and "Traceback" not in err


def test_bad_input_writes_no_figure(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    target = tmp_path / "frf.png"
    code, _, err = _run_main(["frf", "--zeta", "-1", "--plot", str(target)], capsys)
    assert code == 2 and not target.exists()
    code, _, err = _run_main(["frf", "--zeta", "0.1", "--plot", str(tmp_path / "a.txt")], capsys)
    assert code == 2 and "figure" in err and not (tmp_path / "a.txt").exists()


def test_commands_are_registered_in_the_real_app(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run_main(["frf", "--zeta", "0.2", "--dva", "none", "--json"], capsys)
    assert code == 0 and json.loads(out)["Omega_peak"] == pytest.approx(math.sqrt(1 - 0.08))


def test_an_undamped_resonance_is_said_unbounded(app: typer.Typer) -> None:
    # |H| = 1 / |1 - Omega^2| has no maximum at zeta = 0 (a bad-input audit saw "H_max inf")
    code, out = _invoke(app, ["frf", "--zeta", "0", "--dva", "none"])
    assert code == 0, out
    assert "H_max       unbounded (undamped resonance) at Omega = 1" in out and " inf" not in out


def test_every_undamped_resonance_is_listed(app: typer.Typer) -> None:
    # an independent audit: the undamped slider on an undamped foundation (M = 0.1, K = 1) has
    # two infinite peaks and only one was listed. Closed form: det([[1 - w^2, -1], [-1,
    # 1 + K^2 - M w^2]]) = 0, i.e. 0.1 w^4 - 2.1 w^2 + 1 = 0, w^2 = (2.1 -+ sqrt(4.01)) / 0.2
    lows = [math.sqrt((2.1 - sign * math.sqrt(4.01)) / 0.2) for sign in (1.0, -1.0)]
    code, out = _invoke(app, ["frf", "--zeta", "0", "--dva", "0.1,1,0", "--json"])
    assert code == 0, out
    payload = json.loads(out)
    assert payload["H_max"] is None and "unbounded" in payload["H_max_note"]
    omegas = [peak["Omega"] for peak in payload["local_maxima"]]
    assert omegas == pytest.approx(lows, rel=1e-9)
    assert payload["Omega_peak"] == pytest.approx(lows[0], rel=1e-9)
