"""A tiny Sphinx extension: the claims of ``stickslip reproduce``, read from its source.

``.. reproduction-claims::`` parses ``src/stickslip/reproduction/steps_*.py`` with ``ast`` and
lists every ``Claim(key, source, statement, ...)`` it constructs: the key, where the paper
says it and what the paper claims. The measured values need a run (``stickslip reproduce``),
so the build stays independent of one.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective

import stickslip.reproduction


def _text(node: ast.expr) -> str:
    try:
        value = ast.literal_eval(node)
    except ValueError:  # an f-string or an expression: not a fixed text
        return ""
    return value if isinstance(value, str) else ""


def claims() -> list[tuple[str, str, str, str]]:
    """``(module, key, source, statement)`` of every claim, in file order."""
    found = []
    root = Path(next(iter(stickslip.reproduction.__path__)))
    for path in sorted(root.glob("steps_*.py")):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                    and node.func.id == "Claim" and len(node.args) >= 3):
                key, source, statement = (_text(a) for a in node.args[:3])
                found.append((path.stem, key, source, statement))
    return found


def _cell(text: str) -> str:
    return text.replace("*", r"\*").replace("|", r"\|") or "(computed)"


class ClaimsDirective(SphinxDirective):
    """``.. reproduction-claims::``: a table of the claims the report checks."""

    def run(self) -> list[nodes.Node]:
        lines = [".. list-table::", "   :header-rows: 1", "   :widths: 15 20 65", "",
                 "   * - key", "     - paper", "     - claim"]
        for _module, key, source, statement in claims():
            lines += [f"   * - ``{key}``", f"     - {_cell(source)}", f"     - {_cell(statement)}"]
        container = nodes.container()
        self.state.nested_parse(StringList(lines, source="reproduction-claims"), 0, container)
        return container.children


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("reproduction-claims", ClaimsDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
