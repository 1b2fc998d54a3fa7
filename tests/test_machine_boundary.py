"""``boundary --config`` on a machine of a structure alone: every change of the start-up verdict.

The gallery's slideway (examples/slideway) was the case: ``design`` reports one onset, "stick-
slip below V_c = 0.7732 mm/s", from a scan that steps over changes narrower than 25 % in
lambda, and its start-up verdict changes five times between 0.5 and 2 mm/s. The search of
:func:`stickslip.analysis.contact.boundary.contact_boundary` (scan, then every change bisected)
runs it on the exact engine. References: direct runs of the exact engine at the brackets' ends
(the search's own claim), the onset of :class:`CriticalPoint` (the same first change), and an
independent event-driven integration (tests/oracle.py, DOP853, rtol 1e-10) inside and outside
the windows (slow).
"""

from __future__ import annotations

import itertools
import json
import re
from pathlib import Path

import numpy as np
import pytest

from stickslip import simulate
from stickslip.analysis.contact.boundary import EXACT_CRITERION
from stickslip.analysis.machine_absorber import ONSET_NOTE, CriticalPoint
from stickslip.cli.machine_config import config_machine
from tests.cli_helpers import run_cli

SLIDEWAY = Path(__file__).resolve().parents[1] / "examples" / "slideway"


@pytest.fixture(scope="module")
def crossings() -> dict:
    import subprocess
    import sys

    command = str(Path(sys.executable).parent / "stickslip")  # the installed console script
    out = subprocess.run([command, "boundary", "--config",
                          str(SLIDEWAY / "machine.toml"), "--range", "0.55 mm/s:1.2 mm/s",
                          "--scan", "25", "--json"], capture_output=True, text=True, timeout=600,
                         check=True)
    return json.loads(out.stdout)


def test_the_slideway_changes_verdict_beyond_its_onset(crossings: dict) -> None:
    assert crossings["criterion"] == EXACT_CRITERION
    assert crossings["machine"]["normal_dof"] is None
    assert "bare machine" in crossings["machine"]["contact"]  # the file has an [absorber] table
    found = [c for c in crossings["crossings"] if c["kind"] == "boundary"]
    assert all(c["converged"] for c in found)
    values = [c["value_SI"] for c in found]
    assert values == sorted(values)
    # consecutive boundaries alternate: the verdict above one is the verdict below the next
    for a, b in itertools.pairwise(found):
        assert a["above"] == b["below"]
    # the first stick-slip -> steady change is design's onset V_c (the same first change)
    machine = config_machine(SLIDEWAY / "machine.toml")[0]
    onset = CriticalPoint.of(machine)
    ends = [c for c in found if c["below"] == "stick-slip" and c["above"] == "steady-sliding"]
    assert any(c["bracket"][0] <= onset.speed * (1 + 1e-3) and onset.speed * (1 - 1e-3)
               <= c["bracket"][1] for c in ends)
    # and the verdict changes again above it: a stick-slip island the onset does not see
    island = [c for c in found if c["below"] == "steady-sliding" and c["above"] == "stick-slip"
              and c["value_SI"] > onset.speed]
    assert island, found
    # and steady sliding below it (a window of steady sliding below V_c)
    window = [c for c in found if c["below"] == "stick-slip" and c["above"] == "steady-sliding"
              and c["value_SI"] < onset.speed * (1 - 1e-3)]
    assert window, found


def test_every_bracket_end_has_the_verdict_it_claims(crossings: dict) -> None:
    machine = config_machine(SLIDEWAY / "machine.toml")[0]
    for c in crossings["crossings"]:
        for speed, verdict in zip(c["bracket"], (c["below"], c["above"]), strict=True):
            run = simulate(*machine.with_operating_point(speed=speed).to_dimensionless(),
                           record=False)
            assert run.verdict.value == verdict, (speed, verdict, run.certificate)


@pytest.mark.slow  # 28 s: out of the default run (kept under ten minutes)
def test_design_says_what_its_onset_is_and_lists_every_change(
        crossings: dict, capsys: pytest.CaptureFixture[str]) -> None:
    assert "25 % steps" in ONSET_NOTE and "stickslip boundary --config" in ONSET_NOTE
    code, out, err = run_cli(["design", "--config", str(SLIDEWAY / "machine.toml"),
                              "--no-stick-slip-optimum"], capsys)
    assert code == 0, err
    lines = out.splitlines()
    assert f"note: {ONSET_NOTE}" in lines
    assert CriticalPoint(0.5, 1e-3, 2e3).to_dict()["onset_search"] == ONSET_NOTE
    # design's own scan (a decade either side of 0.5 mm/s, 41 runs) finds every boundary of
    # the finer search of the fixture (0.55 to 1.2 mm/s, 25 runs): the same crossings, each
    # bisected to 1e-3 from different scan points
    head = [i for i, line in enumerate(lines) if line.startswith("start-up verdict along the speed")]
    assert len(head) == 1
    listed = [float(m.group(1)) for line in lines[head[0] + 1:]
              if (m := re.search(r"above, at ([0-9.e+-]+) m/s$", line))]
    for c in crossings["crossings"]:
        if c["kind"] == "boundary":
            assert any(abs(v / c["value_SI"] - 1.0) < 2e-3 for v in listed), (c, listed)


@pytest.mark.slow
@pytest.mark.parametrize(("speed", "sticks"), [(0.64e-3, False), (0.72e-3, True),
                                               (0.85e-3, False), (1.0e-3, True)])
def test_the_windows_are_those_of_an_independent_integration(speed: float, sticks: bool) -> None:
    # tests/oracle.py (event-driven DOP853, rtol 1e-10, atol 1e-12) from the start-up state over
    # tau = 1500: in the stick-slip windows the slider sticks again (the growing oscillation
    # reaches the belt speed after some hundred tau), in the steady windows it never does
    from tests.oracle import oracle_simulate_structure

    machine = config_machine(SLIDEWAY / "machine.toml")[0]
    structure, slider = machine.with_operating_point(speed=speed).to_dimensionless()
    oracle = oracle_simulate_structure(structure, slider, 1500.0, rtol=1e-10, atol=1e-12)
    stick_starts = np.flatnonzero(np.asarray(oracle.event_modes) == 2)
    engine = simulate(structure, slider, record=False)
    assert (stick_starts.size > 0) is sticks
    assert engine.verdict.value == ("stick-slip" if sticks else "steady-sliding")


def test_an_undetermined_load_onset_is_not_called_stick_slip() -> None:
    # under a law that moves with V and W the speed and load searches are separate: an audit's
    # 4-DOF Stribeck machine printed "stick-slip ... above W_c=3.147 N" where the run past the
    # load onset was undetermined (steady sliding, its own reference showed, up to the Hopf load
    # 5.83 N), because only the speed search's flag was carried
    both = CriticalPoint(0.5, 0.09666, 3.147, 0, False, False)
    assert both.describe() == "stick-slip below V_c=0.09666 m/s / above W_c=3.147 N"
    open_load = CriticalPoint(0.5, 0.09666, 3.147, 0, False, True)
    text = open_load.describe()
    assert text.startswith("stick-slip below V_c=0.09666 m/s / steady sliding proven at the runs "
                           "below W_c=3.147 N (the run just past it is undetermined")
    assert open_load.to_dict()["load_undetermined_past_onset"] is True
    assert open_load.to_dict()["undetermined_past_onset"] is False
    # the Coulomb law's one search serves both: the load follows the speed's flag, as before
    coulomb = CriticalPoint(0.5, 0.09666, 3.147, 0, True)
    assert coulomb.to_dict()["load_undetermined_past_onset"] is True
    assert coulomb.describe().startswith("steady sliding proven at the runs above V_c=0.09666 m/s "
                                         "/ below W_c=3.147 N")
