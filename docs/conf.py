"""Sphinx configuration of the stickslip documentation site.

Build it with ``make docs`` (``sphinx-build -W --keep-going -b html docs docs/_build/html``).
Generated at build time and not committed: ``api.rst`` (the API reference, one entry per name
of ``stickslip.__all__``), ``generated/`` (one page per public object), ``auto_examples/``
(the gallery, executed from ``examples/``).
"""

from __future__ import annotations

import os
import sys
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

import stickslip  # noqa: E402

project = "stickslip"
author = "stickslip developers"
copyright = "stickslip developers"
version = release = stickslip.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "typer_cli",
    "claims_table",
]
templates_path = ["_templates"]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_templates", "Thumbs.db", ".DS_Store", "figures/*.csv",
                    "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip",
                    "auto_examples/*.json", "auto_examples/*.md5", "sg_execution_times.rst",
                    "auto_examples/sg_execution_times.rst"]
suppress_warnings = ["myst.header"]

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3

# numpydoc renders the docstrings; it does not validate them
numpydoc_validation_checks: set[str] = set()
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

autosummary_generate = True
autosummary_imported_members = True
autodoc_typehints = "none"

intersphinx_mapping: dict[str, tuple[str, None]] = {}

html_theme = "pydata_sphinx_theme"
html_title = f"stickslip {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_static_path: list[str] = []

sphinx_gallery_conf = {
    "examples_dirs": "../examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": "/plot_",
    "ignore_pattern": r"__init__\.py|make_matrices\.py",
    "download_all_examples": True,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "plot_gallery": "True",
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "min_reported_time": 1,
    "matplotlib_animations": False,
    "write_computation_times": False,
}

# The API reference: one autosummary entry per public name, grouped by the layer that defines
# it (from ``stickslip._EXPORTS``), written before Sphinx reads the sources.
_GROUPS = {
    "model": "Model: parameters, structures, friction laws, initial states, physical units",
    "analysis": "Analysis: simulation, verdicts, closed forms, absorber, tuning, stability, design",
    "io": "Reading and writing datasets",
    "sweep": "Sweeps: occurrence maps, boundaries and basins",
    "plot": "Plotting",
    "reproduction": "Reproduction of the paper",
}


def _write_api_page() -> None:
    groups: dict[str, list[str]] = defaultdict(list)
    for name in stickslip.__all__:
        if name == "__version__":
            continue
        layer = stickslip._EXPORTS[name].split(".")[1]
        groups[layer].append(name)
    lines = [
        "API reference",
        "=============",
        "",
        "The public API is flat: every name below is imported from ``stickslip`` itself",
        "(``from stickslip import simulate``); this page lists ``stickslip.__all__``, one page per",
        "object. ``stickslip.__version__`` is the installed version.",
        "",
        ".. currentmodule:: stickslip",
        "",
    ]
    for layer, title in _GROUPS.items():
        names = groups.pop(layer, [])
        if not names:
            continue
        lines += [title, "-" * len(title), "", ".. autosummary::", "   :toctree: generated", ""]
        lines += [f"   {name}" for name in names]
        lines.append("")
    if groups:  # a layer not listed above still gets its names documented
        lines += ["Other", "-----", "", ".. autosummary::", "   :toctree: generated", ""]
        lines += [f"   {name}" for names in groups.values() for name in names]
        lines.append("")
    text = "\n".join(lines)
    target = HERE / "api.rst"
    if not target.exists() or target.read_text() != text:
        target.write_text(text)


_write_api_page()


def _copy_report(app, exception):  # type: ignore[no-untyped-def]
    """Put ``results/report.html`` next to the reproduction page when ``make run`` wrote one."""
    report = HERE.parent / "results" / "report.html"
    if exception is None and app.builder.format == "html" and report.is_file():
        import shutil

        shutil.copyfile(report, Path(app.outdir) / "report.html")


def setup(app):  # type: ignore[no-untyped-def]
    app.connect("build-finished", _copy_report)
