"""The web app's slider page with a friction law with memory (issue 33: the laws in the app).

The page must show what ``stickslip design --config`` gives for the same machine
(examples/friction_memory/*.toml): Canudas de Wit et al.'s (1995) LuGre slider, bistable at
0.1 m/s, and the 1-DOF rate-and-state slider whose critical load is Rice and Ruina's
``N_c = (k - m V^2 (b - a)/(a d_c^2)) d_c/(b - a) = 6 N``.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

pytest.importorskip("streamlit", reason="the app extra (streamlit) is not installed")

from streamlit.testing.v1 import AppTest

from stickslip.app.figures import fmt
from stickslip.cli import app_command
from tests.cli_helpers import run_cli

APP = Path(app_command.APP_SCRIPT)
ROOT = Path(__file__).resolve().parents[1]
TIMEOUT = 120.0


def _page(law: str, slider: dict[str, str], fields: dict[str, str] | None = None) -> AppTest:
    # the widgets' values set before the first run: the page computes only the memory report
    at = AppTest.from_file(str(APP), default_timeout=TIMEOUT)
    at.session_state["friction_law"] = law
    for key, text in {**slider, **(fields or {})}.items():
        at.session_state[key] = text
    at.run()
    return at


def _cli_design(name: str, capsys: pytest.CaptureFixture[str]) -> dict[str, object]:
    code, out, err = run_cli(["design", "--config", str(ROOT / "examples" / "friction_memory"
                                                        / name), "--json"], capsys)
    assert code == 0, err
    return dict(json.loads(out))


def _cells(at: AppTest) -> str:
    return " ".join(df.value.to_string() for df in at.dataframe) + " ".join(
        t.value.to_string() for t in at.table)


def test_lugre_slider_page_matches_design(capsys: pytest.CaptureFixture[str]) -> None:
    at = _page("lugre", {"m": "1 kg", "k": "2 N/m", "c": "0", "load": "1 N",
                         "speed": "0.1 m/s"})
    assert not at.exception and not at.error
    verdict = [m.value for m in at.metric if m.label == "Verdict"]
    assert verdict == ["stick-slip"]
    assert any("Bistable" in i.value for i in at.info)
    p = _cli_design("lugre.toml", capsys)
    startup = p["startup"]
    assert isinstance(startup, dict)
    assert fmt(startup["period_s"]) in _cells(at)  # 6.363 s, design's period to 4 digits
    assert len(at.get("image")) >= 1  # the start-up's time history


def test_rate_state_critical_load_on_the_page() -> None:
    at = _page("rate-state", {"m": "1 kg", "k": "8000 N/m", "c": "0", "load": "10 N",
                              "speed": "1 mm/s"})
    assert not at.exception and not at.error
    cells = _cells(at)
    assert re.search(r"\b6 N\b", cells), cells  # Rice and Ruina's N_c (module docstring)
    assert "10000 N/m" in cells or "1e+04 N/m" in cells  # k_c at N = 10 N


def test_bad_memory_field_is_one_line() -> None:
    at = _page("lugre", {"m": "1 kg", "k": "2 N/m", "c": "0", "load": "1 N",
                         "speed": "0.1 m/s"}, {"memory_sigma0": "3 kg"})
    assert not at.exception
    errors = [re.sub(r"\\(.)", r"\1", str(e.value)) for e in at.error]  # shown literally
    assert len(errors) == 1 and "σ0" in errors[0] and "N/m" in errors[0]
    assert not [m for m in at.metric if m.label == "Verdict"]


def test_memory_history_plot_axes_in_si() -> None:
    from stickslip.plot.memory.history import memory_history_plot

    history = {"t_s": [0.0, 1.0, 2.0], "x_m": [0.0, 0.1, 0.2],
               "slip_speed_m_s": [0.0, 0.05, 0.1], "mu": [1.5, 1.2, 1.0]}
    _, axes, artists = memory_history_plot(history, drive_speed=0.1, title="t")
    labels = [a.get_ylabel() for a in axes] + [axes[-1].get_xlabel()]
    assert labels[0].endswith("[m]") and labels[1].endswith("[m/s]") and labels[3].endswith("[s]")
    assert len(artists) == 4  # three curves and the drive speed


def test_machine_page_path_for_an_uploaded_memory_law_file(
        capsys: pytest.CaptureFixture[str]) -> None:
    # what the machine page runs in its worker for an uploaded LuGre file: design's report
    from stickslip.app.machine_page import uploaded_machine_file
    from stickslip.app.memory_page import memory_report

    text = (ROOT / "examples" / "friction_memory" / "lugre.toml").read_bytes()
    machine_file = uploaded_machine_file({"machine.toml": text})
    assert machine_file.has_memory_law and not machine_file.has_contact
    payload, image = memory_report(machine_file.memory_system())
    expected = _cli_design("lugre.toml", capsys)
    assert payload["verdict"] == expected["verdict"] == "stick-slip"
    assert payload["startup"]["period_s"] == pytest.approx(
        expected["startup"]["period_s"], rel=1e-12)  # type: ignore[index]
    assert image[:8] == b"\x89PNG\r\n\x1a\n"
