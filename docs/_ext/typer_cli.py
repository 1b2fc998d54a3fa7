"""A tiny Sphinx extension: the CLI reference generated from the Typer app.

``sphinx-click`` checks ``isinstance(obj, click.Command)``, but Typer >= 0.25 builds its
commands on its own bundled copy of click (``typer._click``), so it cannot document them.
This extension walks the command tree of ``typer.main.get_command(app)`` itself and emits,
for each command, a section with its usage line, its help text and its options::

    .. typer-cli:: stickslip.cli.main:app
       :prog: stickslip
"""

from __future__ import annotations

import importlib
from typing import Any

from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles


def _load(spec: str) -> Any:
    module_name, _, attr = spec.partition(":")
    obj = getattr(importlib.import_module(module_name), attr)
    import typer.main

    return typer.main.get_command(obj) if hasattr(obj, "registered_commands") else obj


def _param_lines(ctx: Any, param: Any) -> list[str]:
    record = param.get_help_record(ctx)
    if record is None:  # hidden option
        return []
    names, help_text = record
    lines = [f"``{names}``", ""]
    for line in (help_text or "").splitlines() or [""]:
        lines.append(f"   {line}" if line else "")
    lines.append("")
    return lines


def _command_lines(cmd: Any, ctx: Any, path: str, level: str) -> list[str]:
    title = f"``{path}``"
    lines = [title, level * len(title), ""]
    usage = " ".join(cmd.collect_usage_pieces(ctx))
    lines += [".. code-block:: text", "", f"   Usage: {path} {usage}", ""]
    help_text = (cmd.help or "").strip()
    if help_text:
        lines += [".. code-block:: text", ""]
        lines += [f"   {line}" if line else "" for line in help_text.splitlines()]
        lines.append("")
    params = [p for p in cmd.get_params(ctx) if getattr(p, "param_type_name", "") != "argument"]
    args = [p for p in cmd.params if getattr(p, "param_type_name", "") == "argument"]
    if args:
        lines += ["**Arguments**", ""]
        for p in args:
            # click's Argument has human_readable_name; typer's own copy of click may not
            name = getattr(p, "human_readable_name", None) or (p.metavar or p.name or "").upper()
            lines += [f"``{name}``", ""]
            arg_help = (getattr(p, "help", None) or "").strip()
            if arg_help:
                lines += [f"   {line}" if line else "" for line in arg_help.splitlines()] + [""]
    if params:
        lines += ["**Options**", ""]
        for p in params:
            lines += _param_lines(ctx, p)
    return lines


class TyperCliDirective(SphinxDirective):
    """``.. typer-cli:: module:app`` with ``:prog: NAME``."""

    required_arguments = 1
    option_spec = {"prog": directives.unchanged}  # noqa: RUF012

    def run(self) -> list[nodes.Node]:
        root = _load(self.arguments[0])
        prog = self.options.get("prog", root.name or "cli")
        ctx_cls = root.context_class
        root_ctx = ctx_cls(root, info_name=prog)
        lines = _command_lines(root, root_ctx, prog, "-")
        for name in root.list_commands(root_ctx):
            sub = root.get_command(root_ctx, name)
            if sub is None or getattr(sub, "hidden", False):
                continue
            sub_ctx = ctx_cls(sub, info_name=name, parent=root_ctx)
            lines += _command_lines(sub, sub_ctx, f"{prog} {name}", "-")
        container = nodes.section()
        container.document = self.state.document
        nested_parse_with_titles(self.state, StringList(lines, source="typer-cli"), container)
        return container.children


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("typer-cli", TyperCliDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
