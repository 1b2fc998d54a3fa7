"""The machine page's bifurcation diagram (issue 30, point 3): the user's machine in belt speed.

Reference: ``continue_cycles`` on the same machine and range (the command line's
``stickslip continue --config``): the page's summary is that result's, and a typed range that
is not increasing, or not a speed, gets one line and no computation.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from streamlit.testing.v1 import AppTest

APP = Path(__file__).resolve().parents[1] / "src" / "stickslip" / "app" / "streamlit_app.py"


def _machine_page() -> AppTest:
    at = AppTest.from_file(str(APP), default_timeout=600)
    at.run()
    at.sidebar.radio(key="page").set_value("your machine (matrices or modes)").run()
    return at


@pytest.mark.slow  # 16 s: out of the default run (kept under ten minutes)
def test_the_diagram_is_the_command_lines() -> None:
    from stickslip.analysis.continuation import MachineSystem, continue_cycles
    from stickslip.app.machine_bifurcation import MAX_PERIOD, MAX_STEPS, SEEDS
    from stickslip.app.machine_page import MODE_INPUTS, machine_from_files, modes_machine_toml

    at = _machine_page()
    at.text_input(key="bifurcation_from").set_value("1.3 mm/s")
    at.text_input(key="bifurcation_to").set_value("2.5 mm/s").run()
    at.button(key="machine_bifurcation_button").click().run()
    assert not at.exception
    shown = [t.value for t in at.text if t.value.startswith("continuation in speed")]
    raw = {key: default for key, (_, default) in MODE_INPUTS.items()}
    machine, _, _ = machine_from_files({"m.toml": modes_machine_toml(raw).encode()})
    reference = continue_cycles(MachineSystem(machine), "speed", (1.3e-3, 2.5e-3),
                                max_period=MAX_PERIOD, seeds=SEEDS, max_steps=MAX_STEPS)
    assert shown == [reference.summary()]


@pytest.mark.parametrize(("low", "high", "needle"), [
    ("2 mm/s", "1 mm/s", "positive and increasing"),
    ("1 kg", "2 mm/s", "from"),
])
def test_a_bad_range_is_one_line(low: str, high: str, needle: str) -> None:
    at = _machine_page()
    at.text_input(key="bifurcation_from").set_value(low)
    at.text_input(key="bifurcation_to").set_value(high).run()
    errors = [e.value for e in at.error]
    assert len(errors) == 1 and needle in errors[0]
    assert not [t for t in at.text if t.value.startswith("continuation in speed")]
