"""The web app takes the user's machine (issue 18 point 3): uploaded files or typed modes.

The uploaded files go through the command line's reader, so the machine is the one
``design --config`` builds from the same files (checked against it); typed modes become a
``[structure]`` ``modes`` table whose receptance at the contact is ``sum phi_i^2 / (w_i^2 - w^2
+ 2 i zeta_i w_i w)`` (:func:`stickslip.model.machine.modal_structure`): at ``w = 0`` the
static flexibility ``sum phi_i^2 / w_i^2``, written out here.
"""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Any

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


def _chain_upload(n: int, contact: int) -> dict[str, bytes]:
    """A fixed-free chain of ``n`` unit masses and 1e4 N/m springs, as uploaded .npy files."""
    stiffness = 2e4 * np.eye(n) - 1e4 * (np.eye(n, k=1) + np.eye(n, k=-1))
    stiffness[-1, -1] = 1e4
    files = {}
    for name, matrix in (("M.npy", np.eye(n)), ("K.npy", stiffness)):
        buffer = io.BytesIO()
        np.save(buffer, matrix)
        files[name] = buffer.getvalue()
    files["m.toml"] = (f'mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n[structure]\n'
                       f'mass = "M.npy"\nstiffness = "K.npy"\nmodal_damping = 0.02\n'
                       f'contact_dof = {contact}\n').encode()
    return files


def test_the_modes_of_a_reduced_model_are_drawn_over_the_files_dofs() -> None:
    """Issue 31: the contact is the file's DOF, ticks do not smear, the y axis is labelled.

    Reference for the shape: the lowest mode of the full chain (``scipy.linalg.eigh``); the
    reduction keeps the fixed-interface modes below its cut-off, so its lowest mode matches.
    """
    import scipy.linalg

    from stickslip.plot.operating import machine_modes_plot

    n, contact = 80, 50
    files = _chain_upload(n, contact)
    machine, _, reduction = machine_from_files(files)
    assert reduction is not None and machine.contact_dof == 0 and machine.n_dof < n
    result = machine_modes_plot(machine, reduction=reduction)
    title = result.figure.get_suptitle()
    assert f"contact on DOF {contact} ({n}-DOF model, reduced to {machine.n_dof})" in title
    first = result.axes[0]
    assert first.get_ylabel() == "mode shape (largest = 1)"
    assert len(first.get_xticks()) <= 8
    (span,) = first.patches
    assert span.get_x() == pytest.approx(contact - 0.4)
    full_k = np.load(io.BytesIO(files["K.npy"]))
    _, full_modes = scipy.linalg.eigh(full_k, np.eye(n))
    expected = full_modes[:, 0] / np.max(np.abs(full_modes[:, 0]))
    drawn = np.asarray(result.artists[0].get_ydata())
    assert drawn.shape == (n,)
    # the Ritz approximation's error (modes above the cut-off left out) is 6e-6 here; a shape
    # drawn over the wrong DOFs would be off by order 1
    np.testing.assert_allclose(drawn * np.sign(drawn[-1] * expected[-1]), expected, atol=1e-4)


def test_an_unforeseen_error_is_one_line_without_a_traceback(
        monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("streamlit", reason="the app extra (streamlit) is not installed")
    from streamlit.testing.v1 import AppTest

    from stickslip.app import machine_page
    from stickslip.cli import app_command

    def broken(files: object) -> None:
        raise RuntimeError("boom in /tmp/stickslip-x/K.csv")

    monkeypatch.setattr(machine_page, "machine_from_files", broken)
    at = AppTest.from_file(str(app_command.APP_SCRIPT), default_timeout=180.0)
    at.session_state["page"] = "your machine (matrices or modes)"
    at.run()
    assert not at.exception
    (error,) = [str(e.value).replace("\\", "") for e in at.error]
    assert "The design of this machine failed unexpectedly (RuntimeError: boom in <path>)" in error
    assert "/tmp" not in error


def test_the_modes_figure_is_drawn_once_per_machine(monkeypatch: pytest.MonkeyPatch) -> None:
    """Issue 31: a rerun of a machine drawn before draws nothing (the figure is cached on the
    digest of its files); a changed machine is drawn again."""
    pytest.importorskip("streamlit", reason="the app extra (streamlit) is not installed")
    from streamlit.testing.v1 import AppTest

    from stickslip.app import figures
    from stickslip.cli import app_command
    from stickslip.plot import operating

    drawn: list[int] = []
    real = operating.machine_modes_plot

    def counted(*args: Any, **kwargs: Any) -> Any:
        drawn.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(operating, "machine_modes_plot", counted)
    figures.cached_png.clear()
    at = AppTest.from_file(str(app_command.APP_SCRIPT), default_timeout=180.0)
    at.run()
    at.sidebar.radio(key="page").set_value("your machine (matrices or modes)").run()
    assert not at.exception and len(drawn) == 1 and len(at.get("image")) == 1
    at.text_input(key="machine_speed").set_value("0.6 mm/s").run()
    assert not at.exception and len(drawn) == 2
    at.text_input(key="machine_speed").set_value("0.5 mm/s").run()
    assert not at.exception and len(drawn) == 2  # the machine of the first run: not redrawn
