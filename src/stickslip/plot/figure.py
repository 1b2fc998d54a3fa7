"""The plotting contract: one return type and one axes helper for every ``*_plot`` function.

Modelled on python-control's ``ControlPlot``. Every plotting function of :mod:`stickslip.plot`

* is called ``<what>_plot(data, *, ax=None, ...)`` and draws into ``ax`` when given (a new
  figure otherwise, never ``pyplot`` state: the library never calls ``plt.show()`` and never
  changes ``rcParams``);
* rejects unknown keyword arguments with ``TypeError`` (Python does this for keyword-only
  signatures);
* returns a :class:`PlotResult`: the figure, its axes and the artists drawn.

Results plot by delegating: ``result.plot(**kwargs)`` calls the plotting function with the
result as ``data``.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


@dataclass
class PlotResult:
    """What every ``*_plot`` function returns.

    Unpacks as ``figure, axes, artists = result``.

    Attributes
    ----------
    figure : matplotlib.figure.Figure
        The figure drawn into (the one holding ``ax`` when an ``ax`` was given).
    axes : list of matplotlib.axes.Axes
        The axes drawn into, in the order the function documents.
    artists : list
        The artists drawn (lines, collections, images, texts), for restyling.
    """

    figure: Figure
    axes: list[Axes]
    artists: list[Any] = field(default_factory=list)

    def __iter__(self) -> Iterator[Any]:
        return iter((self.figure, self.axes, self.artists))

    @property
    def ax(self) -> Axes:
        """The first (for one-panel figures, the only) axes."""
        return self.axes[0]

    def savefig(self, path: str | os.PathLike[str], **kwargs: Any) -> Path:
        """Save the figure atomically (the format from the suffix; ``dpi`` etc. passed on)."""
        from stickslip.io.atomic import atomic_savefig

        kwargs.setdefault("dpi", 130)
        return atomic_savefig(self.figure, path, **kwargs)


def new_axes(ax: Axes | None = None, *, figsize: tuple[float, float] = (6.4, 4.4)) -> tuple[Figure, Axes]:
    """The figure and axes to draw into: ``ax`` and its figure, or a new one-panel figure.

    New figures are ``matplotlib.figure.Figure`` objects with constrained layout, not pyplot
    figures, so the library leaves no global state behind.
    """
    if ax is not None:
        return ax.get_figure(root=True), ax  # type: ignore[return-value]
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    return fig, fig.add_subplot()


def new_grid(
    nrows: int,
    ncols: int,
    *,
    axes: Sequence[Axes] | None = None,
    figsize: tuple[float, float] = (10.0, 4.4),
    **subplot_kw: Any,
) -> tuple[Figure, list[Axes]]:
    """A figure with ``nrows x ncols`` panels, or the ``axes`` given (checked for their count)."""
    if axes is not None:
        axes = list(axes)
        if len(axes) != nrows * ncols:
            raise ValueError(f"ax must hold {nrows * ncols} axes, got {len(axes)}")
        return axes[0].get_figure(root=True), axes  # type: ignore[return-value]
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    grid = fig.subplots(nrows, ncols, squeeze=False, **subplot_kw)
    return fig, [a for row in grid for a in row]
