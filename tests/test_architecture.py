"""The layers import one way (DESIGN.md section 3, issues 9 and 17), read from the source with ``ast``.

    model -> kernel -> analysis -> io -> sweep -> plot -> reproduction -> cli | app

A module may import, at module level or inside a function, only from its own layer or from
layers below it; cli and app are siblings and never import each other. The one exception runs
back up lazily: a result class's ``plot`` method imports its plotting function inside the method
(python-control's pattern). ``from stickslip import X`` (or from a subpackage face) counts as an
import of the module that defines ``X``, read from the face's ``_EXPORTS`` table or its own
imports. No import cycle between files, counting imports inside functions and type-only imports
too (a result's ``plot`` method aside). The kernel imports no plotting, data or command-line
library. Each failure names the offending file, line and import.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable
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
    result_plot: bool = False  # inside a method named ``plot`` of a class

    def where(self) -> str:
        scope = f" (inside {self.function})" if self.function else ""
        return f"{self.source}:{self.line} imports {self.target}{scope}"


def _module_name(path: Path, package: Path = PACKAGE) -> str:
    parts = path.relative_to(package.parent).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _faces(package: Path) -> dict[str, dict[str, str]]:
    """Package -> {public name: defining module}, from each ``__init__``'s ``_EXPORTS`` and imports."""
    faces: dict[str, dict[str, str]] = {}
    for init in package.rglob("__init__.py"):
        name = _module_name(init, package)
        table: dict[str, str] = {}
        for node in ast.walk(ast.parse(init.read_text(encoding="utf-8"))):
            target = node.target if isinstance(node, ast.AnnAssign) else (
                node.targets[0] if isinstance(node, ast.Assign) and len(node.targets) == 1 else None)
            if (isinstance(target, ast.Name) and target.id == "_EXPORTS"
                    and isinstance(getattr(node, "value", None), ast.Dict)):
                table.update(ast.literal_eval(node.value))  # type: ignore[union-attr, arg-type]
            elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
                table.update({alias.asname or alias.name: node.module for alias in node.names})
        faces[name] = table
    return faces


class Scanner:
    """The imports of every file of a package tree (``PACKAGE`` or a scratch copy)."""

    def __init__(self, package: Path) -> None:
        self.package = package
        self.files = sorted(package.rglob("*.py"))
        self.modules = {_module_name(p, package) for p in self.files}
        self.faces = _faces(package)

    def resolve(self, node: ast.ImportFrom, source: str, is_package: bool) -> list[str]:
        if node.level:
            base = source.split(".")
            base = base if is_package else base[:-1]
            base = base[: len(base) - node.level + 1]
            module = ".".join(base + ([node.module] if node.module else []))
        else:
            module = node.module or ""
        targets = []
        for alias in node.names:
            if f"{module}.{alias.name}" in self.modules:  # ``from stickslip.plot import absorber``
                targets.append(f"{module}.{alias.name}")
            else:  # a name of a package face resolves to the module that defines it
                targets.append(self.faces.get(module, {}).get(alias.name, module))
        return targets

    def collect(self, path: Path) -> list[Import]:
        source = _module_name(path, self.package)
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        found: list[Import] = []
        is_package = path.name == "__init__.py"

        def visit(node: ast.AST, function: str | None, type_only: bool, in_class: bool,
                  result_plot: bool) -> None:
            for child in ast.iter_child_nodes(node):
                if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                    for grandchild in child.body:
                        visit(ast.Module(body=[grandchild], type_ignores=[]), function, True,
                              in_class, result_plot)
                    for grandchild in child.orelse:
                        visit(ast.Module(body=[grandchild], type_ignores=[]), function, type_only,
                              in_class, result_plot)
                    continue
                if isinstance(child, ast.Import):
                    for alias in child.names:
                        found.append(Import(source, alias.name, child.lineno, function, type_only,
                                            result_plot))
                elif isinstance(child, ast.ImportFrom):
                    for target in self.resolve(child, source, is_package):
                        found.append(Import(source, target, child.lineno, function, type_only,
                                            result_plot))
                elif isinstance(child, ast.ClassDef):
                    visit(child, function, type_only, True, result_plot)
                elif isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    plot_method = in_class and function is None and child.name == "plot"
                    visit(child, function or child.name, type_only, False, result_plot or plot_method)
                else:
                    visit(child, function, type_only, in_class, result_plot)

        visit(tree, None, False, False, False)
        return found

    def imports(self) -> list[Import]:
        return [imp for path in self.files for imp in self.collect(path)]


def _layer(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in RANK else None


def upward_imports(imports: Iterable[Import]) -> list[str]:
    """Every import that runs back up the layers, except a result class's lazy ``plot``."""
    bad = []
    for imp in imports:
        src, dst = _layer(imp.source), _layer(imp.target)
        if src is None or dst is None or (RANK[dst] <= RANK[src] and {src, dst} != {"cli", "app"}):
            continue
        if {src, dst} == {"cli", "app"} and src != dst:
            bad.append(f"{imp.where()}: cli and app are siblings")
            continue
        lazy_plot = imp.result_plot and dst == "plot" and imp.function is not None and not imp.type_only
        if not lazy_plot:
            bad.append(f"{imp.where()}: {src} may not import from {dst} (layers: {' -> '.join(LAYERS)})")
    return bad


def import_cycles(imports: Iterable[Import], modules: set[str]) -> list[list[str]]:
    """Cycles between files, counting function-level and type-only imports (not result ``plot``s)."""
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for imp in imports:
        if imp.target in graph and not imp.result_plot and imp.target != imp.source:
            graph[imp.source].add(imp.target)
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
    return cycles


SCAN = Scanner(PACKAGE)
ALL_MODULES = SCAN.modules
IMPORTS = SCAN.imports()
INTERNAL = [imp for imp in IMPORTS if imp.target.startswith("stickslip.")]
# package faces re-export their files (and ``stickslip`` lazily imports every layer): only the
# files' own imports form cycles
FILE_MODULES = {m for m in ALL_MODULES if m not in SCAN.faces}


def test_the_scan_sees_the_package() -> None:
    # guards against a vacuous pass: the scan must find the layers, many imports at both levels,
    # the lazy plot methods and the names imported from the package face
    assert {_layer(m) for m in ALL_MODULES} >= set(LAYERS)
    assert len(INTERNAL) > 100
    assert sum(imp.function is not None for imp in INTERNAL) > 50
    assert sum(imp.result_plot for imp in INTERNAL) >= 5
    assert SCAN.faces["stickslip"]["simulate"] == "stickslip.analysis.simulation"


def test_imports_go_down_the_layers() -> None:
    bad = upward_imports(INTERNAL)
    assert not bad, "imports that run back up the layers:\n" + "\n".join(bad)


def test_no_import_cycle_between_files() -> None:
    internal = [imp for imp in INTERNAL if imp.source in FILE_MODULES]
    cycles = import_cycles(internal, FILE_MODULES)
    assert not cycles, "import cycles:\n" + "\n".join(" -> ".join(c) for c in cycles)


@pytest.mark.parametrize("library", FORBIDDEN_IN_KERNEL)
def test_kernel_imports_arrays_only(library: str) -> None:
    bad = [imp.where() for imp in IMPORTS
           if _layer(imp.source) == "kernel" and imp.target.split(".")[0] == library]
    assert not bad, f"the kernel must not import {library}:\n" + "\n".join(bad)


def test_checker_catches_upward_imports_and_cycles(tmp_path: Path) -> None:
    # the checker itself on a scratch package: what it must report and what it must let pass
    root = tmp_path / "stickslip"
    for layer in ("model", "analysis", "sweep", "plot"):
        (root / layer).mkdir(parents=True)
        (root / layer / "__init__.py").write_text("", encoding="utf-8")
    (root / "__init__.py").write_text(
        '_EXPORTS: dict[str, str] = {"Axis": "stickslip.sweep.grid"}\n', encoding="utf-8")
    (root / "sweep" / "grid.py").write_text("class Axis: ...\n", encoding="utf-8")
    (root / "plot" / "drawing.py").write_text("def drawing_plot(r): ...\n", encoding="utf-8")
    (root / "model" / "probe.py").write_text(
        "from stickslip import Axis\n"  # 1: upward through the face
        "def helper():\n"
        "    from stickslip.sweep import grid\n"  # 3: upward inside a function
        "def plot():\n"
        "    from stickslip.plot.drawing import drawing_plot\n"  # 5: free function, not a method
        "class Result:\n"
        "    def plot(self):\n"
        "        from stickslip.plot.drawing import drawing_plot\n"  # 8: allowed, lazy result plot
        "    def table(self):\n"
        "        from stickslip.plot.drawing import drawing_plot\n",  # 10: other method: refused
        encoding="utf-8")
    (root / "analysis" / "one.py").write_text(
        "def f():\n    from stickslip.analysis.two import g\n", encoding="utf-8")
    (root / "analysis" / "two.py").write_text(
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n    from stickslip.analysis.one import f\n", encoding="utf-8")
    scan = Scanner(root)
    imports = [imp for imp in scan.imports() if imp.target.startswith("stickslip.")]
    bad = upward_imports(imports)
    reported = sorted(int(line.split(":")[1].split()[0]) for line in bad)
    assert reported == [1, 3, 5, 10], bad
    assert any("probe:1 imports stickslip.sweep.grid" in line for line in bad)
    files = {m for m in scan.modules if m not in scan.faces}
    cycles = import_cycles([imp for imp in imports if imp.source in files], files)
    assert [c[0] for c in cycles] == ["stickslip.analysis.one"], cycles
    # exempt only as a method named plot of a class: not the free function plot, not another method
    probe = {imp.line: imp for imp in imports if imp.source == "stickslip.model.probe"}
    assert probe[8].result_plot and not any(probe[n].result_plot for n in (1, 3, 5, 10))


def test_public_api_is_flat_and_complete() -> None:
    # every name of stickslip.__all__ resolves, and the lazy table and __all__ agree
    import stickslip

    assert set(stickslip.__all__) == set(stickslip._EXPORTS) | {"__version__"}
    for name in stickslip.__all__:
        assert getattr(stickslip, name) is not None, name
    from importlib import metadata

    assert stickslip.__version__ == metadata.version("stickslip")


FACES = ["stickslip.model", "stickslip.analysis", "stickslip.analysis.memory",
         "stickslip.analysis.contact", "stickslip.analysis.identification", "stickslip.io",
         "stickslip.sweep", "stickslip.plot", "stickslip.reproduction"]


@pytest.mark.parametrize("package", FACES)
def test_subpackage_faces_are_lazy_and_complete(package: str) -> None:
    # one style: a lazy ``_EXPORTS`` table that agrees with ``__all__``, each name being the object
    # its defining module holds; importing the face imports none of its modules
    import importlib
    import sys

    face = importlib.import_module(package)
    init = PACKAGE.joinpath(*package.split(".")[1:], "__init__.py")
    eager = [imp.where() for imp in SCAN.collect(init)
             if imp.target.startswith("stickslip.") and not imp.type_only
             and imp.target != "stickslip._lazy"]
    assert not eager, f"{package} imports eagerly:\n" + "\n".join(eager)
    assert set(face.__all__) == set(face._EXPORTS)
    for name, module in face._EXPORTS.items():
        assert getattr(face, name) is getattr(importlib.import_module(module), name), name
    assert package in sys.modules


def test_the_flat_api_offers_what_users_reach_for() -> None:
    # the names issue 17 found only in subpackages are now in ``stickslip`` itself
    import stickslip

    for name in ("CoulombFriction", "LinearFriction", "StribeckFriction", "TableFriction",
                 "parse_friction", "read_friction_table", "basin_stability", "basin_map",
                 "find_cycles", "read_dataset", "optimal_foundation_stability", "safe_disturbance",
                 "steady_sliding_stability", "resolve_dva", "DvaSpec"):
        assert name in stickslip.__all__, name


@pytest.mark.parametrize("layer", ["model", "analysis"])
def test_public_functions_document_parameters_and_returns(layer: str) -> None:
    # numpydoc sections on every public module-level function of the layer (issue 17, point 6);
    # a function without arguments needs no Parameters section
    bad = []
    for path in sorted((PACKAGE / layer).rglob("*.py")):  # the family sub-packages too
        if path.name.startswith("_") and path.name != "__init__.py":
            continue
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if not isinstance(node, ast.FunctionDef) or node.name.startswith("_"):
                continue
            doc = ast.get_docstring(node) or ""
            wanted = ["Returns"] + (["Parameters"] if node.args.args or node.args.kwonlyargs else [])
            missing = [s for s in wanted if f"{s}\n{'-' * len(s)}" not in doc]
            if missing:
                bad.append(f"{path.name}:{node.lineno} {node.name} lacks {', '.join(missing)}")
    assert not bad, "\n".join(bad)


def test_no_file_over_600_lines_and_no_long_function_without_a_reason() -> None:
    # one concept per module (issue 17, point 2), in every layer: a long function says why in a
    # comment above it or in its docstring
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        if text.count("\n") > 600:
            bad.append(f"{path.name}: {text.count(chr(10))} lines")
        lines = text.splitlines()
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.FunctionDef) and (node.end_lineno or 0) - node.lineno + 1 > 120:
                first = min([node.lineno, *(d.lineno for d in node.decorator_list)])
                before = lines[first - 2] if first >= 2 else ""
                why_in_doc = "longer than the house's 120 lines" in (ast.get_docstring(node) or "")
                if not (before.strip().startswith("#") or why_in_doc):
                    bad.append(f"{path.name}:{node.lineno} {node.name} is over 120 lines, no comment why")
    assert not bad, "\n".join(bad)


def test_modules_moved_into_family_subpackages_import_under_their_former_names() -> None:
    # memory, contact and identification became sub-packages; code written against the former
    # flat names (docs of the previous release) keeps working for one release, with a warning
    import importlib
    import sys

    import stickslip.analysis as analysis

    for old, new in analysis._MOVED_INTO_FAMILIES.items():
        sys.modules.pop(f"stickslip.analysis.{old}", None)
        with pytest.warns(DeprecationWarning, match=f"moved to stickslip.analysis.{new}"):
            module = importlib.import_module(f"stickslip.analysis.{old}")
        assert module is importlib.import_module(f"stickslip.analysis.{new}"), old
    assert not any(p.stem in analysis._MOVED_INTO_FAMILIES for p in (PACKAGE / "analysis").glob("*.py"))
