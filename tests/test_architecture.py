"""The layers import one way (DESIGN.md section 3, issue 9), read from the source with ``ast``.

    model -> kernel -> analysis -> io -> sweep -> plot -> reproduction -> cli | app

A module may import, at module level, only from its own layer or from layers below it; cli and
app are siblings and never import each other. The one exception runs back up lazily: a result
object's ``plot`` method imports its plotting function inside the method (python-control's
pattern). No import cycle between files at module level. The kernel imports no plotting, data
or command-line library. Each failure names the offending file, line and import.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "stickslip"
LAYERS = ["model", "kernel", "analysis", "io", "sweep", "plot", "reproduction", "cli", "app"]
RANK = {name: i for i, name in enumerate(LAYERS)}
RANK["app"] = RANK["cli"]  # siblings
FORBIDDEN_IN_KERNEL = ("matplotlib", "xarray", "typer", "rich", "pint", "scipy", "pandas")


@dataclass(frozen=True)
class Import:
    source: str  # importing module, e.g. stickslip.sweep.occurrence
    target: str  # imported module, e.g. stickslip.io.netcdf
    line: int
    function: str | None  # enclosing function name when not at module level
    type_only: bool  # inside ``if TYPE_CHECKING:``

    def where(self) -> str:
        scope = f" (inside {self.function})" if self.function else ""
        return f"{self.source}:{self.line} imports {self.target}{scope}"


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _resolve(node: ast.ImportFrom, source: str, is_package: bool) -> list[str]:
    if node.level:
        base = source.split(".")
        base = base if is_package else base[:-1]
        base = base[: len(base) - node.level + 1]
        module = ".".join(base + ([node.module] if node.module else []))
    else:
        module = node.module or ""
    if node.module is None or module == "stickslip" or module.count(".") == 1:
        # ``from stickslip.reproduction import steps_maps`` imports a module
        return [f"{module}.{a.name}" if f"{module}.{a.name}" in ALL_MODULES else module
                for a in node.names]
    return [module]


def _collect(path: Path) -> list[Import]:
    source = _module_name(path)
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: list[Import] = []

    def visit(node: ast.AST, function: str | None, type_only: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                for grandchild in child.body:
                    visit(ast.Module(body=[grandchild], type_ignores=[]), function, True)
                for grandchild in child.orelse:
                    visit(ast.Module(body=[grandchild], type_ignores=[]), function, type_only)
                continue
            if isinstance(child, ast.Import):
                for alias in child.names:
                    found.append(Import(source, alias.name, child.lineno, function, type_only))
            elif isinstance(child, ast.ImportFrom):
                for target in _resolve(child, source, path.name == "__init__.py"):
                    found.append(Import(source, target, child.lineno, function, type_only))
            elif isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                visit(child, function or child.name, type_only)
            else:
                visit(child, function, type_only)

    visit(tree, None, False)
    return found


FILES = sorted(PACKAGE.rglob("*.py"))
ALL_MODULES = {_module_name(p) for p in FILES}
IMPORTS = [imp for path in FILES for imp in _collect(path)]
INTERNAL = [imp for imp in IMPORTS if imp.target.startswith("stickslip.")]


def _layer(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in RANK else None


def test_the_scan_sees_the_package() -> None:
    # guards against a vacuous pass: the scan must find the layers and many imports
    assert {_layer(m) for m in ALL_MODULES} >= set(LAYERS)
    assert len(INTERNAL) > 100


def test_imports_go_down_the_layers() -> None:
    bad = []
    for imp in INTERNAL:
        src, dst = _layer(imp.source), _layer(imp.target)
        if src is None or dst is None or (RANK[dst] <= RANK[src] and {src, dst} != {"cli", "app"}):
            continue
        if {src, dst} == {"cli", "app"} and src != dst:
            bad.append(f"{imp.where()}: cli and app are siblings")
            continue
        lazy_plot = imp.function == "plot" and dst == "plot" and not imp.type_only
        if not lazy_plot:
            bad.append(f"{imp.where()}: {src} may not import from {dst} (layers: {' -> '.join(LAYERS)})")
    assert not bad, "imports that run back up the layers:\n" + "\n".join(bad)


def test_no_import_cycle_between_files_at_module_level() -> None:
    graph: dict[str, set[str]] = {m: set() for m in ALL_MODULES}
    for imp in INTERNAL:
        if imp.function is None and not imp.type_only and imp.target in graph:
            graph[imp.source].add(imp.target)
    # packages import their submodules (and vice versa through re-exports): only files count
    state: dict[str, int] = {}
    stack: list[str] = []
    cycles: list[list[str]] = []

    def dfs(node: str) -> None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycles.append([*stack[stack.index(nxt):], nxt])
            elif nxt not in state:
                dfs(nxt)
        stack.pop()
        state[node] = 2

    for module in sorted(graph):
        if module not in state:
            dfs(module)
    assert not cycles, "module-level import cycles:\n" + "\n".join(" -> ".join(c) for c in cycles)


@pytest.mark.parametrize("library", FORBIDDEN_IN_KERNEL)
def test_kernel_imports_arrays_only(library: str) -> None:
    bad = [imp.where() for imp in IMPORTS
           if _layer(imp.source) == "kernel" and imp.target.split(".")[0] == library]
    assert not bad, f"the kernel must not import {library}:\n" + "\n".join(bad)


def test_checker_catches_an_upward_import(tmp_path: Path) -> None:
    # the checker itself: an upward import in a scratch file is reported with its line
    fake = PACKAGE / "model" / "zz_probe_upward.py"
    fake.write_text("from stickslip.sweep.grid import Axis\n", encoding="utf-8")
    try:
        imports = _collect(fake)
    finally:
        fake.unlink()
    [imp] = imports
    assert imp.source == "stickslip.model.zz_probe_upward" and imp.target == "stickslip.sweep.grid"
    assert RANK[_layer(imp.target) or ""] > RANK[_layer(imp.source) or ""]
    assert "zz_probe_upward:1 imports stickslip.sweep.grid" in imp.where()


def test_public_api_is_flat_and_complete() -> None:
    # every name of stickslip.__all__ resolves, and the lazy table and __all__ agree
    import stickslip

    assert set(stickslip.__all__) == set(stickslip._EXPORTS) | {"__version__"}
    for name in stickslip.__all__:
        assert getattr(stickslip, name) is not None, name
    from importlib import metadata

    assert stickslip.__version__ == metadata.version("stickslip")
