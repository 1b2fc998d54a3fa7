"""``stickslip design --config`` for a machine with its contact (issue 34, point 4).

References: the paper's Eq. (36) critical speed of the rigid slider (``design --config`` on the
same file without its ``[contact]``, ``critical_speed.rigid_exact``), and the ratio of
critical speeds measured for a damped Jenkins element in docs/brake_squeal.md (k_t/k = 100,
zeta = 0.1, contact damping ratio 0.3: 0.99681); the recommended foundation is Eqs. 28-30's,
as ``design`` gives it for the rigid contact.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.cli_helpers import run_cli

ROOT = Path(__file__).resolve().parents[1]
JENKINS = ROOT / "examples" / "jenkins_boundary" / "machine.toml"


def _design(path: Path, capsys: pytest.CaptureFixture[str]) -> dict[str, object]:
    code, out, err = run_cli(["design", "--config", str(path), "--json"], capsys)
    assert code == 0, err
    return dict(json.loads(out))


@pytest.mark.slow  # 11 s: out of the default run (kept under ten minutes)
def test_jenkins_slider_design_against_eq36_and_the_rigid_design(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rigid_file = tmp_path / "rigid.toml"
    rigid_file.write_text(JENKINS.read_text().split("[contact]")[0])
    rigid = _design(rigid_file, capsys)
    eq36 = rigid["critical_speed"]["rigid_exact"]  # type: ignore[index]
    p = _design(JENKINS, capsys)
    rows = {r["name"]: r for r in p["rows"]}  # type: ignore[attr-defined]
    (v_c,) = rows["rigid base"]["critical_speeds_m_per_s"]
    assert v_c == pytest.approx(0.99681 * eq36, rel=1.5e-3)  # the docs' ratio, rtol 1e-3 each
    (w_c,) = rows["rigid base"]["critical_loads_N"]
    assert w_c > rigid["critical_load"]["rigid_exact"]  # type: ignore[index]
    assert rows["rigid base"]["verdict"] == "steady-sliding"  # 0.2 m/s is above V_c
    # the foundation is the one design recommends for the rigid contact (Eqs. 28-30)
    recommended = rigid["recommended_foundation"]
    foundation = p["foundation"]
    for key in ("m_a", "k_a", "c_a"):
        assert foundation[key] == pytest.approx(recommended[key], rel=1e-12)  # type: ignore[index]
    assert "recommended foundation" in rows
    assert p["stability"]["note"].startswith("no normal DOF")  # type: ignore[index]


def test_design_with_contact_refuses_flags(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["design", "--config", str(JENKINS), "--speed", "1 m/s"], capsys)
    lines = [line for line in err.splitlines() if line.startswith("stickslip: error:")]
    assert code != 0 and out == "" and len(lines) == 1 and "--speed" in lines[0]
    assert "[contact]" in lines[0] and "Traceback" not in err
