"""Lazy re-exports for package ``__init__`` modules (PEP 562), written once for every package."""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings
from collections.abc import Callable
from typing import Any


def lazy_exports(package: str, namespace: dict[str, Any], exports: dict[str, str]
                 ) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` that import ``exports[name]`` from its module on first use.

    Parameters
    ----------
    package : str
        Name of the package, for the error message.
    namespace : dict
        The package's ``globals()``: a loaded name is cached there, so it loads once.
    exports : dict
        Public name -> module that defines it.
    """

    def __getattr__(name: str) -> Any:
        try:
            module = exports[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        value = getattr(importlib.import_module(module), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(namespace.get("__all__", exports))

    return __getattr__, __dir__


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds a module under its former name and loads it from its new home, with a warning."""

    def __init__(self) -> None:
        self.moved: dict[str, str] = {}

    def find_spec(self, fullname: str, path: Any, target: Any = None) -> Any:
        if fullname not in self.moved:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec: Any) -> Any:
        new = self.moved[spec.name]
        warnings.warn(f"{spec.name} moved to {new}; the old name works for one release",
                      DeprecationWarning, stacklevel=2)
        return importlib.import_module(new)  # the module itself: one object under both names

    def exec_module(self, module: Any) -> None:
        """Nothing: :meth:`create_module` returned the loaded module."""


_MOVED = _MovedModules()


def alias_moved_modules(moved: dict[str, str]) -> None:
    """Let ``import OLD`` (and ``from PACKAGE import old``) load ``NEW`` for one release.

    Parameters
    ----------
    moved : dict
        Former full module name -> its new full name. Importing a former name warns
        (:class:`DeprecationWarning`) and gives the new module, the same object.
    """
    _MOVED.moved.update(moved)
    if _MOVED not in sys.meta_path:
        sys.meta_path.append(_MOVED)  # last: a real module of the old name would win
