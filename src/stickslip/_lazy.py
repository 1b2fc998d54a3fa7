"""Lazy re-exports for package ``__init__`` modules (PEP 562), written once for every package."""

from __future__ import annotations

import importlib
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
