"""Release hygiene (issue 11, point 5): CITATION.cff, CHANGELOG.md, CONTRIBUTING.md, pre-commit.

Sources of the expected values: the Citation File Format 1.2.0 schema (required keys of the
file and of a reference), Keep a Changelog 1.1.0 (an ``[Unreleased]`` section on top, the
section names), ``pyproject.toml`` (name, version, license) and the README (the paper's title).
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
PAPER = ("Discussion of Stick-Slip Dynamics of 2DOF Sliding Systems Based on Dynamic Vibration "
         "Absorbers Analysis")
CHANGE_TYPES = {"Added", "Changed", "Deprecated", "Removed", "Fixed", "Security"}


def _yaml(path: Path) -> Any:
    yaml = pytest.importorskip("yaml")
    return yaml.safe_load(path.read_text())


def _words(text: str) -> str:
    return " ".join(text.split())


def test_citation_cff_top_level_keys() -> None:
    """Without a YAML parser: the required keys, and the values pyproject.toml sets."""
    text = (ROOT / "CITATION.cff").read_text()
    for line in ("cff-version: 1.2.0", "type: software", f"title: {PROJECT['name']}",
                 f"version: {PROJECT['version']}", f"license: {PROJECT['license']}"):
        assert re.search(f"^{re.escape(line)}$", text, flags=re.MULTILINE), line
    for key in ("message", "authors", "references"):
        assert re.search(f"^{key}:", text, flags=re.MULTILINE), key


def test_citation_cff_is_valid_cff_1_2_0() -> None:
    cff = _yaml(ROOT / "CITATION.cff")
    for key in ("cff-version", "message", "title", "authors"):  # required by the schema
        assert cff[key], key
    assert cff["cff-version"] == "1.2.0"
    assert cff["type"] == "software"
    assert cff["title"] == PROJECT["name"]
    assert str(cff["version"]) == PROJECT["version"]
    assert cff["license"] == PROJECT["license"] == "MIT"
    for author in cff["authors"]:
        assert author.get("name") or author.get("family-names") or author.get("given-names")


def test_citation_cff_references_the_paper() -> None:
    cff = _yaml(ROOT / "CITATION.cff")
    for ref in cff["references"]:
        for key in ("type", "title", "authors"):  # required of a reference by the schema
            assert ref[key], key
    papers = [ref for ref in cff["references"] if _words(ref["title"]) == PAPER]
    assert len(papers) == 1 and papers[0]["type"] == "article"
    assert PAPER in _words((ROOT / "README.md").read_text())  # the title the README cites


def test_changelog_follows_keep_a_changelog() -> None:
    text = (ROOT / "CHANGELOG.md").read_text()
    assert text.startswith("# Changelog\n")
    releases = re.findall(r"^## \[([^\]]+)\](.*)$", text, flags=re.MULTILINE)
    assert releases[0] == ("Unreleased", "")
    for version, date in releases[1:]:
        assert re.fullmatch(r"\d+\.\d+\.\d+", version)
        assert re.fullmatch(r" - \d{4}-\d{2}-\d{2}", date), date
    assert PROJECT["version"] in [version for version, _ in releases]
    assert set(re.findall(r"^### (.+)$", text, flags=re.MULTILINE)) <= CHANGE_TYPES
    unreleased = text.split("## [Unreleased]")[1].split("\n## [")[0]
    assert "### Added" in unreleased and "\n- " in unreleased


def test_contributing_names_files_that_exist() -> None:
    text = (ROOT / "CONTRIBUTING.md").read_text()
    for target in ("make test", "make lint", "make bench", "-m slow", "tests/test_architecture.py",
                   "tests/test_coulomb_bit_identity.py"):
        assert target in text
    paths = set(re.findall(r"(?:tests|benchmarks|docs|src)/[\w./]+\.(?:py|md|json)", text))
    assert paths
    assert not [p for p in sorted(paths) if not (ROOT / p).exists()]


def test_pre_commit_runs_ruff_check_and_mypy() -> None:
    config = _yaml(ROOT / ".pre-commit-config.yaml")
    hooks = {hook["id"]: hook for repo in config["repos"] for hook in repo["hooks"]}
    assert hooks["ruff"]["entry"].split()[:2] == [".venv/bin/ruff", "check"]
    assert hooks["mypy"]["entry"].split()[0] == ".venv/bin/mypy"
