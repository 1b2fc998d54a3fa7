"""The package as a user gets it (issue 11, point 4): a wheel and an sdist, installed elsewhere.

``python -m build`` writes the sdist and then builds the wheel from it (so the sdist is known
to be complete); ``twine check`` must accept both. The wheel holds the package alone (with
``py.typed``), the sdist also the tests and the docs sources. The slow test installs the wheel
into a fresh virtual environment (its dependencies from the package index, as ``pip install
stickslip`` would), and runs the command and the import from an empty directory, never from
the editable checkout. It takes about two minutes, most of it the dependencies' download and
numba compiling the engine on first use; ``.ci/run`` runs it after ``make test``.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tarfile
import tomllib
import zipfile
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
VERSION = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]


def _run(cmd: list[str | Path], *, cwd: Path, timeout: float, env: dict[str, str] | None = None
         ) -> subprocess.CompletedProcess[str]:
    """Run ``cmd``; on failure, the assertion shows its output."""
    proc = subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=timeout)
    assert proc.returncode == 0, f"{cmd} exited {proc.returncode}\n{proc.stdout}\n{proc.stderr}"
    return proc


@pytest.fixture(scope="module")
def dist(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Build the sdist, and the wheel from it, into a temporary folder (about 2 s)."""
    out = tmp_path_factory.mktemp("dist")
    # --no-isolation: the build backend (hatchling) comes from the test extra, so the build
    # needs no network; build still checks that the backend version satisfies pyproject.toml
    _run([sys.executable, "-m", "build", "--no-isolation", "--outdir", out, ROOT], cwd=out, timeout=300)
    wheels = sorted(out.glob("*.whl"))
    sdists = sorted(out.glob("*.tar.gz"))
    assert [w.name for w in wheels] == [f"stickslip-{VERSION}-py3-none-any.whl"]
    assert [s.name for s in sdists] == [f"stickslip-{VERSION}.tar.gz"]
    return {"wheel": wheels[0], "sdist": sdists[0]}


def test_twine_accepts_wheel_and_sdist(dist: dict[str, Path]) -> None:
    proc = _run([sys.executable, "-m", "twine", "check", "--strict", dist["wheel"], dist["sdist"]],
                cwd=dist["wheel"].parent, timeout=120)
    assert proc.stdout.count("PASSED") == 2, proc.stdout


def test_wheel_holds_the_package_only(dist: dict[str, Path]) -> None:
    names = zipfile.ZipFile(dist["wheel"]).namelist()
    info = f"stickslip-{VERSION}.dist-info/"
    assert {n.split("/")[0] + "/" for n in names} == {"stickslip/", info}
    for required in ("stickslip/__init__.py", "stickslip/py.typed", "stickslip/cli/main.py",
                     "stickslip/kernel/__init__.py", f"{info}METADATA", f"{info}entry_points.txt"):
        assert required in names
    assert not [n for n in names if "/tests/" in n or "/docs/" in n or n.endswith((".pyc", ".nbi", ".nbc"))]
    entry_points = zipfile.ZipFile(dist["wheel"]).read(f"{info}entry_points.txt").decode()
    assert "stickslip = stickslip.cli.main:run" in entry_points
    metadata = zipfile.ZipFile(dist["wheel"]).read(f"{info}METADATA").decode()
    assert f"Version: {VERSION}\n" in metadata


def test_sdist_holds_tests_and_docs(dist: dict[str, Path]) -> None:
    top = f"stickslip-{VERSION}/"
    with tarfile.open(dist["sdist"]) as archive:
        names = {n.removeprefix(top) for n in archive.getnames()}
    for required in ("pyproject.toml", "README.md", "LICENSE", "CHANGELOG.md", "CITATION.cff",
                     "CONTRIBUTING.md", "src/stickslip/__init__.py", "src/stickslip/py.typed",
                     "tests/test_packaging.py", "tests/conftest.py", "tests/data/coulomb_reference.json",
                     "docs/friction.md"):
        assert required in names
    tracked = subprocess.run(["git", "ls-files", "tests", "docs"], cwd=ROOT, capture_output=True,
                             text=True)
    if tracked.returncode == 0:  # a git checkout: every committed test and docs source is there
        assert not set(tracked.stdout.split()) - names
    assert not [n for n in names if n.startswith((".venv/", "results/", "dist/"))
                or "__pycache__" in n or n.endswith((".pyc", ".nbi", ".nbc"))]


@pytest.fixture
def venv(tmp_path: Path) -> Iterator[Path]:
    """A folder for a fresh virtual environment, removed afterwards (it holds about 700 MB)."""
    path = tmp_path / "venv"
    yield path
    shutil.rmtree(path, ignore_errors=True)


@pytest.mark.slow
def test_wheel_installs_and_runs_in_a_fresh_venv(dist: dict[str, Path], venv: Path, tmp_path: Path
                                                 ) -> None:
    from stickslip import critical_lambda_exact

    clean = tmp_path / "clean"  # an empty working directory: no checkout on sys.path
    clean.mkdir()
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV", "PYTHONSTARTUP")}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    # a clean environment without the project's site-packages, from the base interpreter
    _run([sys.executable, "-m", "venv", venv], cwd=clean, timeout=300, env=env)
    bindir = venv / ("Scripts" if os.name == "nt" else "bin")
    python = bindir / "python"
    _run([python, "-m", "pip", "install", "--quiet", dist["wheel"]], cwd=clean, timeout=900, env=env)

    site = Path(_run([python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                     cwd=clean, timeout=60, env=env).stdout.strip())
    proc = _run([python, "-c", "import stickslip; print(stickslip.__version__); print(stickslip.__file__)"],
                cwd=clean, timeout=120, env=env)
    version, location = proc.stdout.split()
    assert version == VERSION
    assert Path(location).resolve().is_relative_to(site.resolve())
    assert not Path(location).resolve().is_relative_to(ROOT)
    assert (Path(location).parent / "py.typed").is_file()

    stickslip = bindir / "stickslip"
    assert _run([stickslip, "--version"], cwd=clean, timeout=120, env=env).stdout == f"stickslip {VERSION}\n"

    # rigid base (the default --dva none) at zeta 0.1: Eq. (36) puts the onset at lambda 1.4701,
    # so lambda 3 stick-slips; the first call compiles the engine (about a minute)
    assert critical_lambda_exact(0.1) == pytest.approx(1.4701, abs=1e-4)
    proc = _run([stickslip, "simulate", "--lam", "3", "--zeta", "0.1", "--json"], cwd=clean,
                timeout=900, env=env)
    result = json.loads(proc.stdout)
    assert result["verdict"] == "stick-slip"
    assert result["structure"] == "rigid base"
    assert result["lambda"] == 3.0 and result["zeta"] == 0.1
    assert list(clean.iterdir()) == []  # nothing written where the user stands
