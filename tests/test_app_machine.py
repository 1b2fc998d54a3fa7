"""The web app takes the user's machine (issue 18 point 3): uploaded files or typed modes.

The uploaded files go through the command line's reader, so the machine is the one
``design --config`` builds from the same files (checked against it); typed modes become a
``[structure]`` ``modes`` table whose receptance at the contact is ``sum phi_i^2 / (w_i^2 - w^2
+ 2 i zeta_i w_i w)`` (:func:`stickslip.model.machine.modal_structure`): at ``w = 0`` the
static flexibility ``sum phi_i^2 / w_i^2``, written out here.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from stickslip.app.machine_page import MODE_INPUTS, machine_from_files, modes_machine_toml

SLIDEWAY = Path(__file__).resolve().parents[1] / "examples" / "slideway"


def _slideway_uploads() -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in SLIDEWAY.iterdir() if p.suffix in (".toml", ".mtx")}


def test_uploaded_slideway_is_the_command_lines_machine() -> None:
    from stickslip.cli.machine_config import config_machine

    machine, absorber, reduction = machine_from_files(_slideway_uploads())
    reference, _ = config_machine(SLIDEWAY / "machine.toml")
    assert reduction is None and absorber is not None and absorber.attach_dof == 2
    assert machine.contact_dof == reference.contact_dof == 2
    for name in ("mass", "damping", "stiffness"):
        np.testing.assert_array_equal(getattr(machine, name), getattr(reference, name))
    assert (machine.speed, machine.load, machine.mu_s, machine.mu_k) == (
        reference.speed, reference.load, reference.mu_s, reference.mu_k)


def test_typed_modes_give_the_modal_static_flexibility() -> None:
    raw = {key: default for key, (_, default) in MODE_INPUTS.items()}
    machine, absorber, _ = machine_from_files({"m.toml": modes_machine_toml(raw).encode()})
    assert absorber is None and machine.contact_dof == 0
    w = [2 * math.pi * 55.0, 2 * math.pi * 150.0]
    phi = [0.07, 0.03]
    static = sum(p * p / (x * x) for p, x in zip(phi, w, strict=True))
    flex = np.linalg.inv(machine.stiffness)[0, 0]
    assert flex == pytest.approx(static, rel=1e-12)


@pytest.mark.parametrize("files,word", [
    ({}, "exactly one machine .toml"),
    ({"a.toml": b"mu_s = 0.5\n", "b.toml": b"mu_s = 0.5\n"}, "exactly one machine .toml"),
    ({"m.toml": b"mu_s = 0.5\nmu_k = 0.3\nload = 1\nspeed = 1\n[structure]\nmass = \"M.mtx\"\n"
      b"stiffness = \"M.mtx\"\ncontact_dof = 0\n"}, "M.mtx"),
    ({"m.toml": b"m = 1\nk = 1\nmu_s = 0.5\nmu_k = 0.3\nload = 1\nspeed = 1\n"}, "[structure]"),
])
def test_bad_uploads_are_one_line(files: dict[str, bytes], word: str) -> None:
    with pytest.raises(ValueError, match=None) as info:
        machine_from_files(files)
    message = str(info.value)
    assert word in message and len(message.splitlines()) == 1


def test_typed_modes_that_are_not_numbers_are_refused() -> None:
    raw = {key: default for key, (_, default) in MODE_INPUTS.items()}
    raw["shapes"] = "0.07, abc"
    with pytest.raises(ValueError, match="comma-separated list of numbers"):
        modes_machine_toml(raw)


def test_the_app_page_of_typed_modes_runs() -> None:
    pytest.importorskip("streamlit", reason="the app extra (streamlit) is not installed")
    from streamlit.testing.v1 import AppTest

    from stickslip.cli import app_command

    at = AppTest.from_file(str(app_command.APP_SCRIPT), default_timeout=180.0)
    at.run()
    at.sidebar.radio(key="page").set_value("your machine (matrices or modes)").run()
    assert not at.exception
    text = " ".join(str(t.value) for t in at.text)
    assert "modal model: 2 DOF, contact on DOF 0" in text and "stick-slip below V_c" in text
    at.text_input(key="machine_shapes").set_value("0.07, 0").run()
    assert not at.exception
    assert any("non\\-zero" in str(e.value) for e in at.error)  # escaped Markdown: read "non-zero"
