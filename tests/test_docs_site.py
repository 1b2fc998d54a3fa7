"""The documentation site builds with warnings as errors and documents everything public.

Slow (the gallery executes every example of ``examples/``): ``.ci/run`` runs it. One build
into a temporary folder; the checks read its HTML and its Sphinx environment:

* every name of ``stickslip.__all__`` (except ``__version__``) has its own page;
* every page is reachable from the index, both through the toctree (the environment) and by
  following the links of the HTML from ``index.html``;
* every command that ``stickslip --help`` lists has a section in the CLI reference;
* every gallery script ran and produced a figure and a notebook (the tutorial's is linked).
"""

from __future__ import annotations

import os
import pickle
import re
import subprocess
import sys
import time
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urldefrag

import pytest

import stickslip

ROOT = Path(__file__).resolve().parents[1]
#: pages Sphinx writes that no toctree holds
SPECIAL = {"genindex.html", "search.html", "py-modindex.html"}


class _Links(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.links: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "a":
            href = dict(attrs).get("href")
            if href:
                self.links.append(href)


def _links(page: Path) -> list[str]:
    parser = _Links()
    parser.feed(page.read_text(encoding="utf-8"))
    return parser.links


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    out = tmp_path_factory.mktemp("docs")
    html, doctrees = out / "html", out / "doctrees"
    start = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", "-d", str(doctrees),
         # run every example even if an earlier build in docs/auto_examples has it cached
         "-D", "sphinx_gallery_conf.run_stale_examples=True", str(ROOT / "docs"), str(html)],
        capture_output=True, text=True, timeout=1800, cwd=ROOT,
    )
    elapsed = time.perf_counter() - start
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-5000:]
    print(f"documentation built in {elapsed:.0f} s")
    return {"html": html, "doctrees": doctrees}


@pytest.mark.slow
def test_every_public_object_has_a_page(site: dict[str, Path]) -> None:
    names = [n for n in stickslip.__all__ if n != "__version__"]
    missing = [n for n in names if not (site["html"] / "generated" / f"stickslip.{n}.html").is_file()]
    assert not missing
    api = (site["html"] / "api.html").read_text(encoding="utf-8")
    assert all(f"generated/stickslip.{n}.html" in api for n in names)


@pytest.mark.slow
def test_every_page_is_in_the_toctree_of_the_index(site: dict[str, Path]) -> None:
    with (site["doctrees"] / "environment.pickle").open("rb") as fh:
        env = pickle.load(fh)
    reachable, todo = set(), [env.config.root_doc]
    while todo:
        doc = todo.pop()
        if doc not in reachable:
            reachable.add(doc)
            todo.extend(env.toctree_includes.get(doc, []))
    orphans = sorted(set(env.found_docs) - reachable)
    assert not orphans


@pytest.mark.slow
def test_every_page_is_reachable_by_links_from_the_index(site: dict[str, Path]) -> None:
    html = site["html"]
    pages = {p.relative_to(html).as_posix() for p in html.rglob("*.html")
             if not p.relative_to(html).parts[0].startswith("_")} - SPECIAL
    seen, todo = set(), ["index.html"]
    while todo:
        page = todo.pop()
        if page in seen or not (html / page).is_file():
            continue
        seen.add(page)
        base = (html / page).parent
        for href in _links(html / page):
            target = unquote(urldefrag(href)[0])
            if not target or "://" in target or target.startswith(("mailto:", "#")):
                continue
            resolved = (base / target).resolve()
            if resolved.suffix == ".html" and resolved.is_relative_to(html.resolve()):
                todo.append(resolved.relative_to(html.resolve()).as_posix())
    assert not sorted(pages - seen)
    assert len(pages) > len(stickslip.__all__)


@pytest.mark.slow
def test_every_cli_command_is_in_the_cli_reference(site: dict[str, Path]) -> None:
    import typer.main

    from stickslip.cli.main import app

    help_text = subprocess.run([str(Path(sys.executable).parent / "stickslip"), "--help"],
                               capture_output=True, text=True, cwd=ROOT, check=True,
                               env={**os.environ, "COLUMNS": "200"}).stdout
    commands = list(typer.main.get_command(app).commands)  # type: ignore[attr-defined]
    assert len(commands) >= 10
    cli = (site["html"] / "cli.html").read_text(encoding="utf-8")
    for name in commands:
        assert re.search(rf"\b{name}\b", help_text), name
        assert f'id="stickslip-{name}"' in cli, name
        assert f"stickslip {name} [OPTIONS]" in cli, name


@pytest.mark.slow
def test_gallery_examples_ran_with_figures_and_notebooks(site: dict[str, Path]) -> None:
    html = site["html"]
    scripts = sorted((ROOT / "examples").glob("plot_*.py"))
    assert len(scripts) >= 8
    images = {p.name for p in (html / "_images").glob("sphx_glr_plot_*.png")}
    notebooks = {p.name for p in (html / "_downloads").rglob("*.ipynb")}
    for script in scripts:
        assert (html / "auto_examples" / f"{script.stem}.html").is_file(), script.name
        assert f"sphx_glr_{script.stem}_001.png" in images, script.name
        assert f"{script.stem}.ipynb" in notebooks, script.name
    tutorial = (html / "tutorial.html").read_text(encoding="utf-8")
    assert "plot_00_tutorial.ipynb" in tutorial
