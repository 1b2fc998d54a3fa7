"""The CLI hardening audit: every user file read bounded, every extreme value refused by name.

The contract of ``tests/test_bad_input.py``: a bad value exits with code 2 and exactly one
``stickslip: error:`` line naming the value and why (no traceback, no warning), nothing written.
The bounds come from the code's stated limits: SI inputs in ``[1e-50, 1e50]``
(``stickslip.model.physical.MAX_SI``), dimensionless ratios in ``[1e-6, 1e6]``
(``stickslip.model._validate``), contact springs at most ``1e12`` times the structure's
stiffest (``stickslip.model.contact.MAX_CONTACT_STIFFNESS``). A FIFO nobody writes to blocks
a reader for ever, and ``/dev/zero`` never ends: both must be refused before they are opened.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.cli_helpers import run_cli

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SLIDER = ('mu_s = 0.3\nmu_k = 0.2\nload = "1 kN"\nspeed = "1 cm/s"\nm = "1 kg"\nk = "1 kN/m"\n'
          'c = "1 N*s/m"\n')
CHAIN = ('mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n[structure]\n'
         'mass = [[2.0, 0.0], [0.0, 1.0]]\nstiffness = [[3e4, -1e4], [-1e4, 2e4]]\ncontact_dof = 0\n')


def _one_error(args: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    code, out, err = run_cli(args, capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, (code, out, err)
    assert lines[0].startswith("stickslip: error:"), err
    assert "Traceback" not in err and "warning" not in err.lower()
    return lines[0]


def _special(kind: str, folder: Path, name: str) -> Path:
    """A FIFO nobody writes to, or ``/dev/zero``."""
    if kind == "fifo":
        path = folder / name
        os.mkfifo(path)
        return path
    return Path("/dev/zero")


# --- files that are not regular files ------------------------------------------------------

@pytest.mark.parametrize("kind", ["fifo", "device"])
def test_config_that_is_a_fifo_or_device_is_refused_unread(
        kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: a FIFO hung `simulate --config`; /dev/zero was read until memory ran out
    path = _special(kind, tmp_path, "machine.toml")
    line = _one_error(["simulate", "--config", str(path)], capsys)
    assert f"--config {str(path)!r} is not a regular file" in line


@pytest.mark.parametrize("kind", ["fifo", "device"])
def test_friction_tables_that_are_not_regular_files_are_refused(
        kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    table = _special(kind, tmp_path, "curve.csv")
    line = _one_error(["simulate", "--lam", "2", "--zeta", "0.1", "--friction", f"table:{table}"],
                      capsys)
    assert "friction table" in line and "is not a regular file" in line
    machine = tmp_path / "m.toml"
    machine.write_text(SLIDER + f'[friction]\nlaw = "table"\ntable = "{table}"\n')
    line = _one_error(["simulate", "--config", str(machine)], capsys)
    assert "[friction]: friction table" in line and "is not a regular file" in line
    assert line.count("--config") == 1


@pytest.mark.parametrize("kind", ["fifo", "device"])
def test_initial_states_that_are_not_regular_files_are_refused(
        kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    states = _special(kind, tmp_path, "states.csv")
    line = _one_error(["basin", "--lam", "2", "--zeta", "0.1", "--initial-states", str(states)],
                      capsys)
    assert f"--initial-states {str(states)!r} is not a regular file" in line


@pytest.mark.parametrize("law", ["rate-state", "lugre"])
def test_memory_law_records_that_are_not_regular_files_are_refused(
        law: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    record = _special("fifo", tmp_path, "record.csv")
    stiffness = ["--stiffness", "1e7 N/m"] if law == "rate-state" else []
    line = _one_error(["identify", str(record), "--law", law, *stiffness, "--load", "1 kN"], capsys)
    assert f"record {str(record)!r} is not a regular file" in line


def test_initial_states_not_utf8_name_the_option_and_file(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    states = tmp_path / "states.csv"
    states.write_bytes(b"xi,v\n\xff\xfe,1\n")
    line = _one_error(["basin", "--lam", "2", "--zeta", "0.1", "--initial-states", str(states)],
                      capsys)
    assert f"--initial-states {str(states)!r} is not UTF-8 text" in line


def test_initial_states_with_a_column_twice_are_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # csv.DictReader keeps the last of two equal names: the first column was silently dropped
    states = tmp_path / "states.csv"
    states.write_text("xi,v,v\n0,1,2\n")
    line = _one_error(["basin", "--lam", "2", "--zeta", "0.1", "--initial-states", str(states)],
                      capsys)
    assert "names the column(s) v more than once" in line


# --- values beyond the supported ranges -----------------------------------------------------

def test_absorber_mass_beyond_the_si_range_or_the_ratio_range_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN + '[absorber]\nmass = "1e300 kg"\nattach_dof = 1\n')
    line = _one_error(["design", "--config", str(machine)], capsys)
    assert "[absorber] mass=1e+300 is outside the supported range [1e-50, 1e+50]" in line
    # 1e40 kg is an SI value, but 5e39 times the contact DOF's 2 kg: the paper's M <= 1e6
    machine.write_text(CHAIN + '[absorber]\nmass = "1e40 kg"\nattach_dof = 1\n')
    line = _one_error(["design", "--config", str(machine)], capsys)
    assert "[absorber] mass = 1e+40 kg is 5e+39 times the contact DOF's mass (2 kg)" in line


@pytest.mark.parametrize(("key", "value"), [("stribeck_velocity", "1e-300 m/s"),
                                            ("stribeck_velocity", "1e300 m/s"),
                                            ("sigma0", "1e-60 N/m")])
def test_lugre_parameters_beyond_the_range_are_refused_by_name(
        key: str, value: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: v_s = 1e-300 m/s ended in "Array must not contain infs or NaNs"
    text = (EXAMPLES / "friction_memory" / "lugre.toml").read_text()
    lines = [f'{key} = "{value}"' if line.startswith(f"{key} =") else line
             for line in text.splitlines()]
    machine = tmp_path / "lugre.toml"
    machine.write_text("\n".join(lines) + "\n")
    line = _one_error(["simulate", "--config", str(machine)], capsys)
    assert f"[friction]: {key}=" in line and "outside the supported range [1e-50, 1e+50]" in line


@pytest.mark.parametrize(("extra", "named"), [
    ('tangential_stiffness = "1e8 N/m"\ntangential_damping = "1e300 N*s/m"\n', "tangential_damping"),
    ('tangential_stiffness = "1e-300 N/m"\n', "tangential_stiffness"),
])
@pytest.mark.parametrize("command", ["simulate", "stability"])
def test_contact_values_beyond_the_si_range_are_refused(
        extra: str, named: str, command: str, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    # before: tangential_damping 1e300 ran with exit 0; 1e-300 N/m warned of a cast
    machine = tmp_path / "pad.toml"
    machine.write_text(CHAIN + "[contact]\n" + extra)
    line = _one_error([command, "--config", str(machine)], capsys)
    assert f"[contact] {named} = " in line and "outside the supported range" in line


def test_stability_refuses_the_contact_spring_simulate_refuses(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # one rule for every engine: k_n beyond 1e12 times the stiffest structural spring (3e4 N/m)
    text = (EXAMPLES / "brake_pad" / "machine.toml").read_text()
    machine = tmp_path / "machine.toml"
    machine.write_text(text.replace('normal_stiffness = "5e7 N/m"', 'normal_stiffness = "1e40 N/m"'))
    for name in ("M.csv", "K.csv", "C.csv"):
        (tmp_path / name).write_bytes((EXAMPLES / "brake_pad" / name).read_bytes())
    for command in ("simulate", "stability"):
        line = _one_error([command, "--config", str(machine)], capsys)
        assert "normal_stiffness = 1e+40 N/m is beyond 1e+12 times the structure's stiffest" in line


def test_boundary_range_beyond_the_si_range_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN)
    line = _one_error(["boundary", "--config", str(machine), "--range", "1 cm/s:1e300 m/s"], capsys)
    assert "--range '1 cm/s:1e300 m/s' reaches beyond the supported speed range" in line


@pytest.mark.parametrize(("cutoff", "why"), [("abc", "is not a quantity"),
                                             ("-5 Hz", "must be a positive frequency"),
                                             ("0 Hz", "must be a positive frequency")])
def test_cutoff_is_checked_on_a_model_run_whole(
        cutoff: str, why: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: at <= 60 DOF any cutoff, even "abc", was silently ignored
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN + f'cutoff = "{cutoff}"\n')
    line = _one_error(["simulate", "--config", str(machine)], capsys)
    assert f"[structure] cutoff = {cutoff!r}" in line and why in line


@pytest.mark.parametrize(("law", "needs"), [("linear", "slope"), ("stribeck", "stribeck_velocity")])
def test_a_friction_law_without_its_defining_value_is_refused(
        law: str, needs: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: linear ran with slope 0 (Coulomb) and stribeck with v_s = 1 m/s, unsaid
    machine = tmp_path / "m.toml"
    machine.write_text(SLIDER + f'[friction]\nlaw = "{law}"\n')
    line = _one_error(["simulate", "--config", str(machine)], capsys)
    assert f"[friction]: law = {law!r} needs {needs}" in line


@pytest.mark.parametrize(("damping", "message"), [
    ("rayleigh = [1e300, 1e300]", "[structure] rayleigh: [alpha, beta] = [1e+300, 1e+300] gives "
                                  "damping entries of magnitude 3e+304"),
    ("modal_damping = 1e300", "modal damping ratio=1e+300 is outside the supported range [0, 1e+06]"),
    ('modal_damping = "abc"', "[structure] modal_damping = 'abc' must be a number"),
])
def test_damping_descriptions_out_of_range_are_named(
        damping: str, message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN + damping + "\n")
    line = _one_error(["simulate", "--config", str(machine)], capsys)
    assert message in line and line.count("--config") == 1


def test_a_malformed_npy_header_is_described_not_dumped(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: "malformed node or string on line 1: <ast.Name object at 0x...>"
    header = b"{'descr': foo, 'fortran_order': False, 'shape': (2, 2), }"
    header += b" " * (117 - len(header)) + b"\n"
    (tmp_path / "M.npy").write_bytes(b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little")
                                     + header + b"\0" * 32)
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN.replace("mass = [[2.0, 0.0], [0.0, 1.0]]", 'mass = "M.npy"'))
    line = _one_error(["simulate", "--config", str(machine)], capsys)
    assert "its .npy header is not valid" in line and "object at 0x" not in line


@pytest.mark.parametrize("friction", ['law = "stribeck"\nstribeck_velocity = "abc"',
                                      'law = "linear"\nslope = "1 kg"', "foo = 1",
                                      'law = "stribeck"\nstribeck_velocity = "-1 m/s"'])
def test_friction_errors_of_a_structure_file_name_the_file_once(
        friction: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: "--config 'X': --config 'X': [friction]: ..."
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN + "[friction]\n" + friction + "\n")
    line = _one_error(["simulate", "--config", str(machine)], capsys)
    assert line.count("--config") == 1 and "[friction]: " in line


# --- round 2: outputs over inputs, refusals by the user's names ------------------------------

@pytest.mark.slow  # 19 s: out of the default run (kept under ten minutes)
def test_an_output_never_replaces_an_input_of_the_same_command(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: `--csv machine.toml --overwrite` turned the machine file into a CSV table, and
    # `continue --out C.csv --overwrite` replaced the damping matrix the machine file names
    machine = tmp_path / "machine.toml"
    for name in ("machine.toml", "M.csv", "K.csv", "C.csv"):
        (tmp_path / name).write_bytes((EXAMPLES / "brake_pad" / name).read_bytes())
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    line = _one_error(["continue", "--config", str(machine), "--param", "speed", "--range",
                       "4 m/s:5 m/s", "--points", "2", "--out", str(tmp_path / "C.csv"),
                       "--overwrite"], capsys)
    assert "is an input file of this command" in line
    jenkins = tmp_path / "jenkins.toml"
    jenkins.write_bytes((EXAMPLES / "jenkins_slider" / "machine.toml").read_bytes())
    before[jenkins.name] = jenkins.read_bytes()
    line = _one_error(["map", "--config", str(jenkins), "--speed", "0.1,0.2", "--load", "1,2",
                       "--out", str(tmp_path / "t.nc"), "--csv", str(jenkins), "--overwrite"], capsys)
    assert f"{str(jenkins)!r} is an input file of this command" in line
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_basin_does_not_write_its_labels_over_its_initial_states(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    states = tmp_path / "labels.csv"
    states.write_text("xi,v\n0,1\n1,0\n")
    line = _one_error(["basin", "--lam", "2.5", "--zeta", "0.1", "--initial-states", str(states),
                       "--out", str(tmp_path), "--overwrite"], capsys)
    assert "is an input file of this command" in line
    assert states.read_text() == "xi,v\n0,1\n1,0\n"


def test_bare_stickslip_prints_its_help(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli([], capsys)
    assert code == 0 and out.startswith("Usage: stickslip") and "simulate" in out and err == ""


@pytest.mark.parametrize(("timeout", "message"), [
    ("1e300", "--scheduler-timeout 1e+300 is beyond 86400 s"),  # was an OverflowError traceback
    ("1e10", "--scheduler-timeout 10000000000.0 is beyond 86400 s")])
def test_scheduler_timeout_is_bounded(timeout: str, message: str, tmp_path: Path,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    line = _one_error(["map", "--lam", "1,2", "--zeta", "0.1,0.2", "--scheduler",
                       "tcp://127.0.0.1:1", "--scheduler-timeout", timeout, "--out",
                       str(tmp_path / "x.nc")], capsys)
    assert message in line


def test_an_empty_scheduler_address_is_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    line = _one_error(["map", "--lam", "1,2", "--zeta", "0.1,0.2", "--scheduler", "",
                       "--out", str(tmp_path / "x.nc")], capsys)
    assert "--scheduler '' is empty" in line


def test_map_config_grids_take_si_values_beyond_the_dimensionless_bound(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: "load grid value 3000000.0 is beyond |load| <= 1e+06", a bound of dimensionless
    # parameters, though simulate takes a 3 MN load (SI inputs up to 1e50)
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN)
    code, _, err = run_cli(["map", "--config", str(machine), "--speed", "0.01,0.02", "--load",
                            "2e6,3e6", "--out", str(tmp_path / "L.nc")], capsys)
    assert code == 0, err
    line = _one_error(["map", "--config", str(machine), "--speed", "0.01,0.02", "--load",
                       "2e6,3e60", "--out", str(tmp_path / "L2.nc")], capsys)
    assert "load grid value 3e+60 is beyond the supported range |load| <= 1e+50" in line


def test_a_grid_too_large_names_the_delta_axis(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    line = _one_error(["map", "--lam", "0.1:10:100000", "--delta", "-0.1:0.3:1000000", "--zeta",
                       "0.1", "--out", str(tmp_path / "big.nc")], capsys)
    assert "use fewer points (--lam/--delta)" in line


def test_basin_box_beyond_the_state_bound_is_said_in_the_users_columns(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    machine = tmp_path / "m.toml"
    machine.write_text(CHAIN)
    line = _one_error(["basin", "--config", str(machine), "--box", "x=-1e300:1e300"], capsys)
    assert "--box x=-1e+300:1e+300 reaches beyond the supported state magnitude" in line
    assert "np.float64" not in line


@pytest.mark.parametrize(("text", "message"), [
    ('system = 5\nm = "1 kg"\n', "system = 5 must be a table ([system])"),
    (CHAIN.replace("contact_dof = 0", "contact_dof = 0\nname = 5"),
     "[structure]: name = 5 must be a text in quotes")])
def test_machine_file_keys_of_the_wrong_type_are_named(
        text: str, message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    machine = tmp_path / "m.toml"
    machine.write_text(text)
    assert message in _one_error(["simulate", "--config", str(machine)], capsys)


def test_a_spacing_given_with_a_list_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    line = _one_error(["boundary", "--zeta", "0.05,0.1", "--zeta-spacing", "log"], capsys)
    assert "--zeta-spacing 'log' spaces a start:stop:n range" in line


def test_tune_lam_max_below_the_ratio_bound_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    # before: an "optimum" with lambda_crit_at_least 1e-300
    line = _one_error(["tune", "--zeta", "0.1", "--objective", "stick-slip", "--lam-max", "1e-300"],
                      capsys)
    assert "--lam-max=1e-300 is below the supported range" in line


@pytest.mark.parametrize(("text", "message"), [("xi,v\n1,2,3\n", "row 1: 3 values for the 2 columns"),
                                               ("xi,v,tag\n1,2\n", "row 1: 2 values for the 3 columns")])
def test_initial_state_rows_must_match_the_header(
        text: str, message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    states = tmp_path / "states.csv"
    states.write_text(text)
    line = _one_error(["basin", "--lam", "2", "--zeta", "0.1", "--initial-states", str(states)],
                      capsys)
    assert message in line


def _rig_record(tmp_path: Path, header: str | None = None, zero_x: bool = False) -> Path:
    lines = []
    for line in (EXAMPLES / "rig_record.csv").read_text().splitlines():
        if line.startswith("t ") and header is not None:
            line = header
        elif zero_x and not line.startswith(("#", "t ")):
            parts = line.split(",")
            line = ",".join([parts[0], "0", *parts[2:]])
        lines.append(line)
    path = tmp_path / "record.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


RIG = ["--mass", "1 kg", "--load", "100 N", "--speed", "5 cm/s"]


def test_identify_refuses_a_constant_displacement_and_a_doubled_channel(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: "warning: invalid value encountered in divide", then "SVD did not converge"
    line = _one_error(["identify", str(_rig_record(tmp_path, zero_x=True)), *RIG], capsys)
    assert "the displacement x does not change during the stick phase" in line
    line = _one_error(["identify", str(_rig_record(tmp_path, header="t [s],x [mm],x [mm]")), *RIG],
                      capsys)
    assert "two columns of the header (t [s], x [mm], x [mm]) are the x channel" in line


def test_identify_fixed_mu_s_below_the_records_mu_k_is_named(capsys: pytest.CaptureFixture[str]) -> None:
    # the example record's truth: mu_s 0.6, mu_k 0.4 (its header); before: "gamma=6.2e8 is beyond"
    line = _one_error(["identify", str(EXAMPLES / "rig_record.csv"), *RIG, "--fix", "mu_s=0.1"],
                      capsys)
    assert "mu_s = 0.1 held fixed must exceed the record's kinetic friction coefficient" in line


def test_a_foundation_ratio_out_of_range_names_the_inputs(capsys: pytest.CaptureFixture[str]) -> None:
    line = _one_error(["design", "--m", "2 kg", "--k", "50 kN/m", "--c", "20 N*s/m", "--mu-s", "0.5",
                       "--mu-k", "0.3", "--load", "500 N", "--speed", "5 cm/s", "--m-a", "1e-40 kg",
                       "--k-a", "1e40 N/m", "--c-a", "0"], capsys)
    assert "M = m_a/m = 5e-41 (m_a = 1e-40 kg, m = 2 kg) is outside the supported range" in line


def test_cycles_of_a_memory_law_refuse_seeding_options(capsys: pytest.CaptureFixture[str]) -> None:
    line = _one_error(["cycles", "--config", str(EXAMPLES / "friction_memory" / "lugre.toml"),
                       "--seeds", "10", "--seed", "5"], capsys)
    assert "--seeds, --seed: the cycles of a machine with a friction law with memory" in line


def test_a_script_may_rewrite_a_file_it_read_outside_a_command(tmp_path: Path) -> None:
    # the input registry guards a command's outputs; the Python API keeps plain file semantics
    import subprocess
    import sys

    table = tmp_path / "curve.csv"
    table.write_text("v,mu\n0,0.4\n2,0.3\n")
    code = ("from stickslip.model.friction_input import read_friction_csv_columns\n"
            "from stickslip.io.atomic import atomic_write_text\n"
            f"read_friction_csv_columns({str(table)!r})\n"
            f"atomic_write_text({str(table)!r}, 'v,mu\\n0,0.4\\n3,0.3\\n')\n")
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120)
    assert table.read_text() == "v,mu\n0,0.4\n3,0.3\n"


@pytest.mark.parametrize("out", ["", " "])
def test_basin_refuses_an_empty_output_folder(out: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    # an audit: `basin --out ""` wrote labels.csv and basin.nc into the current folder, and
    # `--out " "` made a folder named " "
    monkeypatch.chdir(tmp_path)
    line = _one_error(["basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "10", "--out", out],
                      capsys)
    assert f"--out {out!r} is empty" in line
    assert list(tmp_path.iterdir()) == []


def test_a_machine_files_table_in_the_dimensionless_form_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # an audit: a table with columns v, f was read as v [m/s] and mu, silently another law
    (tmp_path / "vf.csv").write_text("v,f\n0,0.3\n0.01,0.2\n")
    config = tmp_path / "machine.toml"
    config.write_text(SLIDER + '[friction]\nlaw = "table"\ntable = "vf.csv"\n')
    line = _one_error(["simulate", "--config", str(config)], capsys)
    assert "gives f, the dimensionless form" in line and "vf.csv" in line


@pytest.mark.parametrize("command", ["simulate", "design"])
def test_a_lambda_beyond_the_range_names_the_operating_point(
        command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # an audit: a belt speed of 10 nm/s gave "lambda=1e7 is beyond the supported range" with
    # neither the file nor the speed that made it (design: its own 1-DOF loading path)
    config = tmp_path / "machine.toml"
    config.write_text(SLIDER.replace('speed = "1 cm/s"', 'speed = "10 nm/s"'))
    line = _one_error([command, "--config", str(config)], capsys)
    assert str(config) in line and "at the belt speed 1e-08 m/s and load 1000 N" in line
    assert "lambda=" in line and "beyond the supported range" in line


def test_design_flags_name_the_operating_point_of_a_lambda_beyond_the_range(
        capsys: pytest.CaptureFixture[str]) -> None:
    line = _one_error(["design", "--m", "2 kg", "--k", "50 kN/m", "--c", "20 N*s/m", "--mu-s",
                       "0.5", "--mu-k", "0.3", "--load", "1e9 N", "--speed", "1e-9 m/s"], capsys)
    assert "at the belt speed 1e-09 m/s and load 1e+09 N, lambda=" in line
    assert "beyond the supported range" in line


@pytest.mark.parametrize(("table", "said", "prefix"), [
    # an audit: "[structure] modes: [structure] modes.shapes = ..." repeated its prefix
    ('damping_ratios = [0.02, 0.02], shapes = ["a", 1.0]',
     "modes.shapes = ['a', 1.0] must be a number or a list of numbers", "[structure]"),
    # an audit: "[structure] modes: modes: 2 frequencies, 1 damping ratios ..." said "modes" twice
    ("damping_ratios = [0.02], shapes = [1.0, 1.0]",
     "[structure] modes: 2 frequencies, 1 damping ratios and 2 mode shape values", "modes:"),
])
def test_a_modal_tables_fault_is_named_once(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                            table: str, said: str, prefix: str) -> None:
    config = tmp_path / "machine.toml"
    config.write_text('mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n[structure]\n'
                      f'modes = {{ frequencies = ["10 Hz", "30 Hz"], {table} }}\n')
    line = _one_error(["simulate", "--config", str(config)], capsys)
    assert said in line
    assert line.count(prefix) == 1


def test_a_speed_schedule_beyond_its_bound_is_refused_before_its_rows_are_read(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # an audit: a 40,000-row schedule (0.8 MB of TOML) took 15 s to parse and six minutes of
    # the app's one worker; a schedule holds at most MAX_SCHEDULE_STEPS steps
    from stickslip.model.state_friction import MAX_SCHEDULE_STEPS, SpeedSchedule

    rows = ", ".join(f'["{i} s", "{1 + i % 2} mm/s"]' for i in range(MAX_SCHEDULE_STEPS + 1))
    example = Path(__file__).resolve().parents[1] / "examples" / "friction_memory" / "rate_state.toml"
    config = tmp_path / "machine.toml"
    config.write_text(example.read_text().replace('speed = "1 mm/s"', f"speed = [{rows}]"))
    line = _one_error(["simulate", "--config", str(config)], capsys)
    assert f"has {MAX_SCHEDULE_STEPS + 1} rows, more than the {MAX_SCHEDULE_STEPS} steps" in line
    n = MAX_SCHEDULE_STEPS + 1
    with pytest.raises(ValueError, match=f"has {n} steps, more than the {MAX_SCHEDULE_STEPS}"):
        SpeedSchedule(tuple(float(i) for i in range(n)), (1e-3,) * n)


@pytest.mark.parametrize("rows, why", [
    ("0,0.3\n0.02,0.25\n0.01,0.2\n", "friction table speeds must increase strictly, got 0.02 m/s "
                                     "then 0.01 m/s"),
    ("0,0.3\n0.02,-0.25\n", "friction coefficient mu=-0.25 is negative"),
])
def test_a_bad_friction_table_is_blamed_not_the_operating_point(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], rows: str, why: str) -> None:
    # an independent audit: the table's own fault ended "the speed or the load is far outside
    # the machine's scales", which sent the user to the wrong input
    (tmp_path / "curve.csv").write_text("v,mu\n" + rows)
    machine = tmp_path / "m.toml"
    machine.write_text(SLIDER + '[friction]\nlaw = "table"\ntable = "curve.csv"\n')
    for command in ("design", "simulate"):
        line = _one_error([command, "--config", str(machine)], capsys)
        assert why in line and "outside the machine's scales" not in line, line
