"""Reproduction of the paper: every figure and claim, with a report (``stickslip reproduce``).

Names load on first use (PEP 562); every name of ``__all__`` is public, the rest is private.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    "reproduce": "stickslip.reproduction.run",
}

__all__ = [
    "reproduce",
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from stickslip.reproduction.run import reproduce
