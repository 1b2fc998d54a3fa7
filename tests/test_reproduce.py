"""The reproduction of the paper (issue 5): report generator on a tiny configuration."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from stickslip.cli.main import run
from stickslip.reproduction.run import reproduce

FIGURES = {"fig04", "fig05", "fig06", "fig07", "fig08", "fig10", "fig11", "fig12", "fig13",
           "fig14", "fig15", "fig16"}
CLAIMS = {"fit-28-30", "fit-31", "definitions", "fig5", "fig7", "fig12-13", "phase", "narrowing",
          "inside-eq37", "rigid-map", "k-half-vs-double", "gamma", "undetermined", "eq34-35",
          "eq39-vs-36", "fig16", "beyond-absorber", "beyond-absorber-disturbed"}


def _check(out: Path, report_json: dict) -> None:
    assert {f["key"] for f in report_json["figures"]} == FIGURES
    for fig in report_json["figures"]:
        assert Path(fig["png"]).stat().st_size > 5_000
        assert Path(fig["pdf"]).stat().st_size > 1_000
        assert fig["data"] and all(Path(p).exists() for p in fig["data"])
    assert {c["key"] for c in report_json["claims"]} == CLAIMS
    assert all(c["verdict"] in ("confirmed", "partly confirmed", "differs")
               for c in report_json["claims"])
    html = (out / "report.html").read_text()
    assert html.count("data:image/png;base64,") == len(FIGURES)  # self-contained
    md = (out / "report.md").read_text()
    assert "| # | source | the paper says | we measure | verdict |" in md


def test_tiny_reproduction_writes_every_figure_claim_and_report(tmp_path: Path) -> None:
    out = tmp_path / "results"
    report = reproduce(out, "tiny")
    _check(out, json.loads((out / "report.json").read_text()))
    claims = {c.key: c for c in report.claims}
    # results that do not depend on the grid size (each named by its source in claims.py)
    assert claims["eq34-35"].verdict == "confirmed"  # Eqs. (34)-(35), exact
    assert claims["definitions"].verdict == "confirmed"  # Section 2.3 reproduces Eq. (31)
    assert claims["rigid-map"].data["wrong_eq36"] == 0  # the map follows Eq. (36) exactly


def test_reproduce_cli_rejects_bad_quality(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as err:
        run(["reproduce", "--out", str(tmp_path / "r"), "--quality", "fast"])
    assert err.value.code == 2
    assert "quality 'fast' is not one of tiny, default, high" in capsys.readouterr().err
    assert not (tmp_path / "r").exists()


@pytest.mark.slow
def test_default_reproduction(tmp_path: Path) -> None:
    out = tmp_path / "results"
    report = reproduce(out, "default")
    _check(out, json.loads((out / "report.json").read_text()))
    assert report.counts().get("confirmed", 0) >= 12


def test_reproduce_refuses_a_folder_it_did_not_write(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    # nothing lost: a folder with the user's own report.html is not written into without
    # --overwrite (an independent audit found it silently replaced)
    out = tmp_path / "mine"
    out.mkdir()
    (out / "report.html").write_text("my own report", encoding="utf-8")
    with pytest.raises(SystemExit) as err:
        run(["reproduce", "--out", str(out), "--quality", "tiny"])
    assert err.value.code == 2
    assert "non-empty folder that stickslip reproduce did not write" in capsys.readouterr().err
    assert (out / "report.html").read_text(encoding="utf-8") == "my own report"
    assert sorted(p.name for p in out.iterdir()) == ["report.html"]

    # a folder an earlier reproduce wrote (its marker) is refreshed, as make run does twice
    import stickslip.reproduction.run as reproduction_run

    class Reached(Exception):
        pass

    def reached(*_args: object) -> None:
        raise Reached

    monkeypatch.setattr(reproduction_run, "reproduce", reached)
    marked = tmp_path / "results"
    marked.mkdir()
    (marked / "report.html").write_text("an earlier run", encoding="utf-8")
    (marked / ".stickslip-reproduce").write_text("", encoding="utf-8")
    with pytest.raises(Reached):
        run(["reproduce", "--out", str(marked), "--quality", "tiny"])
    with pytest.raises(Reached):
        run(["reproduce", "--out", str(out), "--quality", "tiny", "--overwrite"])
    assert (out / ".stickslip-reproduce").exists()


def test_an_interrupted_reproduce_says_its_folder_is_incomplete(
        tmp_path, monkeypatch, capsys) -> None:  # type: ignore[no-untyped-def]
    """Ctrl-C part-way left nine figures beside an earlier report with only "aborted (Ctrl-C)"
    (an independent audit): one line says the folder is incomplete, and the folder says so."""
    import stickslip.reproduction.run as reproduction
    from tests.cli_helpers import run_cli

    def interrupted(out, quality, progress):  # type: ignore[no-untyped-def]
        (out / "figures").mkdir(parents=True, exist_ok=True)
        raise KeyboardInterrupt

    monkeypatch.setattr(reproduction, "reproduce", interrupted)
    out = tmp_path / "results"
    code, stdout, err = run_cli(["reproduce", "--out", str(out), "--quality", "tiny"], capsys)
    assert code == 130 and stdout == ""
    assert err.count("\n") == 1 and "aborted (Ctrl-C)" in err and "is incomplete" in err
    assert "again" in (out / "INCOMPLETE.txt").read_text()
