"""Grid axes of a parameter sweep, parsed from the command line's ``--lam`` / ``--zeta`` text.

An axis is written in one of three forms:

* ``start:stop:n`` -- ``n`` points from ``start`` to ``stop`` inclusive, linearly spaced
  unless the spacing is ``log`` (``--lam-spacing log`` on the command line, or the
  ``spacing`` argument);
* ``log:start:stop:n`` or ``lin:start:stop:n`` -- the same with the spacing in the text
  itself (it must agree with an explicitly requested spacing);
* ``v1,v2,...`` -- an explicit list (a single number is a one-point list). The values are
  sorted; duplicates are rejected because they would make two cells of a map share one
  coordinate.

Every malformed axis raises ``ValueError`` with one line naming the axis and the problem.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stickslip.model._validate import MAX_PARAMETER

Spacing = Literal["linear", "log", "list"]

#: Largest number of points accepted on one axis (a typo such as ``0.1:50:2e9`` would
#: otherwise allocate gigabytes before failing).
MAX_POINTS = 1_000_000

_SPACING_WORDS: dict[str, Spacing] = {"lin": "linear", "linear": "linear", "log": "log"}


@dataclass(frozen=True)
class Axis:
    """Sorted, finite, distinct values of one swept parameter and how they were spaced.

    Parameters
    ----------
    name : str
        Parameter name used in error messages and datasets (``lambda``, ``zeta``).
    values : array_like
        The grid values (dimensionless), strictly increasing after construction.
    spacing : {"linear", "log", "list"}
        ``linear`` and ``log`` for ``start:stop:n`` ranges, ``list`` for explicit values.
    spec : str
        The text the axis was parsed from (recorded in datasets), or ``""``.
    limit : float
        Largest magnitude accepted: :data:`~stickslip.model._validate.MAX_PARAMETER` for a
        dimensionless parameter; a quantity in SI units (a machine's speed or load) passes
        :data:`~stickslip.model.physical.MAX_SI`.
    """

    name: str
    values: NDArray[np.float64]
    spacing: Spacing = "list"
    spec: str = ""
    limit: float = MAX_PARAMETER

    def __post_init__(self) -> None:
        values = np.array(self.values, dtype=np.float64).reshape(-1)
        if values.size == 0:
            raise ValueError(f"{self.name} grid is empty")
        if not np.all(np.isfinite(values)):
            raise ValueError(f"{self.name} grid has NaN or infinite values")
        if np.abs(values).max() > self.limit:
            big = float(values[np.argmax(np.abs(values))])
            raise ValueError(
                f"{self.name} grid value {big!r} is beyond the supported range "
                f"|{self.name}| <= {self.limit:g} (larger values overflow the equations)"
            )
        values = np.sort(values)
        if np.any(np.diff(values) == 0.0):
            dup = float(values[1:][np.diff(values) == 0.0][0])
            raise ValueError(f"{self.name} grid repeats the value {dup!r}")
        if self.spacing == "log" and values[0] <= 0.0:
            raise ValueError(f"{self.name} grid with log spacing needs positive values")
        values.setflags(write=False)
        object.__setattr__(self, "values", values)

    def __len__(self) -> int:
        return int(self.values.size)

    @classmethod
    def parse(cls, text: str, name: str, spacing: str | None = None, *,
              limit: float = MAX_PARAMETER) -> Axis:
        """Parse ``start:stop:n``, ``log:start:stop:n`` or ``v1,v2,...``.

        Parameters
        ----------
        text : str
            The axis specification.
        name : str
            Parameter name for error messages (``lambda``, ``zeta``).
        spacing : {"lin", "linear", "log"}, optional
            Spacing of a ``start:stop:n`` range when the text has no prefix. Ignored for
            lists (an explicit list keeps its values whatever the spacing).
        limit : float, optional
            Largest magnitude accepted (see the class).

        Returns
        -------
        Axis
            The parsed axis.

        Raises
        ------
        ValueError
            Malformed text, ``n < 1``, ``stop < start``, ``n = 1`` with ``start != stop``,
            non-positive bounds with log spacing, NaN or infinite values, an empty grid.
        """
        raw = str(text).strip()
        label = f"{name} grid {raw!r}"
        if not raw:
            raise ValueError(f"{name} grid is empty")
        requested = _spacing_word(spacing, name) if spacing is not None else None
        if ":" not in raw:
            return cls(name, np.array(_numbers(raw.split(","), label)), "list", raw, limit)
        parts = raw.split(":")
        prefix: Spacing | None = None
        if parts[0].strip().lower() in _SPACING_WORDS:
            prefix = _SPACING_WORDS[parts[0].strip().lower()]
            parts = parts[1:]
        if len(parts) != 3:
            raise ValueError(f"{label} is not start:stop:n, log:start:stop:n or a comma list")
        if prefix is not None and requested is not None and prefix != requested:
            raise ValueError(f"{label} says {prefix} spacing but {requested} spacing was requested")
        kind: Spacing = prefix or requested or "linear"
        start, stop = _numbers(parts[:2], label)
        n = _count(parts[2], label)
        return cls(name, range_values(start, stop, n, kind, label), kind, raw, limit)

    def describe(self) -> str:
        """``n`` values from ``first`` to ``last`` and the spacing, for summaries."""
        return f"{len(self)} {self.spacing} values in [{self.values[0]:g}, {self.values[-1]:g}]"


def range_values(start: float, stop: float, n: int, spacing: Spacing, label: str) -> NDArray[np.float64]:
    """``n`` values from ``start`` to ``stop`` inclusive, linear or geometric."""
    if n < 1:
        raise ValueError(f"{label}: n={n} must be at least 1")
    if n > MAX_POINTS:
        raise ValueError(f"{label}: n={n} exceeds the limit of {MAX_POINTS} points per axis")
    if stop < start:
        raise ValueError(f"{label}: stop={stop!r} is below start={start!r}")
    if n == 1 and stop != start:
        raise ValueError(f"{label}: one point needs start == stop (or use a list)")
    if n > 1 and stop == start:
        raise ValueError(f"{label}: start == stop gives {n} equal points")
    if spacing == "log":
        if start <= 0.0:
            raise ValueError(f"{label}: log spacing needs positive bounds, got start={start!r}")
        values = np.geomspace(start, stop, n)
    else:
        values = np.linspace(start, stop, n)
    # geomspace/linspace can miss the end points by an ulp; the user wrote them exactly
    values[0], values[-1] = start, stop
    return values


def as_axis(values: Axis | ArrayLike, name: str) -> Axis:
    """Return ``values`` as an :class:`Axis` (an explicit list unless it is one already)."""
    if isinstance(values, Axis):
        return values
    if isinstance(values, str):
        return Axis.parse(values, name)
    return Axis(name, np.asarray(values, dtype=np.float64), "list")


def _spacing_word(word: str, name: str) -> Spacing:
    key = str(word).strip().lower()
    if key not in _SPACING_WORDS:
        raise ValueError(f"{name} spacing {word!r} is not 'lin' or 'log'")
    return _SPACING_WORDS[key]


def _numbers(parts: Sequence[str], label: str) -> list[float]:
    values = []
    for part in parts:
        token = part.strip()
        if not token:
            raise ValueError(f"{label} has an empty entry")
        try:
            x = float(token)
        except ValueError:
            raise ValueError(f"{label}: {token!r} is not a number") from None
        if not math.isfinite(x):
            raise ValueError(f"{label}: {token!r} must be finite")
        values.append(x)
    return values


def _count(token: str, label: str) -> int:
    token = token.strip()
    try:
        n = int(token)
    except ValueError:
        raise ValueError(f"{label}: n={token!r} must be a whole number of points") from None
    return n
