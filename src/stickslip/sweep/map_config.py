"""The configuration of an occurrence map: grid axes, foundation, friction and engine limits.

:class:`MapConfig` holds everything that determines a map (its fingerprint is a hash of it) and
cuts the grid into the engine's cell batches; :func:`stickslip.sweep.occurrence.occurrence_map`
runs it and :func:`stickslip.sweep.map_data.map_dataset` turns the summaries into a dataset.
"""

from __future__ import annotations

import functools
import hashlib
import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from stickslip.analysis.simulation import EngineOptions
from stickslip.io.provenance import package_version
from stickslip.model._validate import non_negative, positive
from stickslip.model.dva import DvaSpec
from stickslip.model.friction import CoulombFriction, FrictionLaw, LinearFriction
from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.sweep.executors import CellBatch, Chunk, StructureSet
from stickslip.sweep.grid import Axis, as_axis
from stickslip.sweep.renamed import warn_renamed


@dataclass(frozen=True)
class MapConfig:
    """Everything that determines an occurrence map (its fingerprint is a hash of it).

    Parameters
    ----------
    lam, zeta : Axis
        Grid axes, dimensionless (``lambda > 0``, ``zeta >= 0``).
    dva : DvaSpec
        The foundation, resolved at each ``zeta`` (``none`` is the rigid base).
    gamma : float
        ``mu_k / (mu_s - mu_k)``, dimensionless (the paper uses 2).
    options : EngineOptions
        Engine limits of every cell.
    friction : FrictionLaw
        The friction law of every cell (default: the paper's Coulomb law).
    delta : Axis, optional
        Slopes ``delta`` of the linear friction law (dimensionless, finite): the grid is then
        ``(lambda, delta)`` at the one value of ``zeta``, cell ``(i, j)`` has the law
        ``LinearFriction(delta[j])`` and ``friction`` stays the Coulomb default.
    """

    lam: Axis
    zeta: Axis
    dva: DvaSpec = field(default_factory=DvaSpec)
    gamma: float = 2.0
    options: EngineOptions = field(default_factory=EngineOptions)
    friction: FrictionLaw = field(default_factory=CoulombFriction)
    delta: Axis | None = None

    def __post_init__(self) -> None:
        for value in self.lam.values.tolist():
            positive("lambda", value)
        for value in self.zeta.values.tolist():
            non_negative("zeta", value)
        object.__setattr__(self, "gamma", non_negative("gamma", self.gamma))
        if self.delta is not None:
            if len(self.zeta) != 1:
                raise ValueError(f"a (lambda, delta) map is at one fixed zeta; got {len(self.zeta)} "
                                 "zeta values")
            if not isinstance(self.friction, CoulombFriction):
                raise ValueError("a (lambda, delta) map sets the linear law LinearFriction(delta) "
                                 f"in every cell; it cannot also take the friction law "
                                 f"{self.friction.describe()!r}")
            for value in self.delta.values.tolist():
                LinearFriction(value)  # finite, or a one-line ValueError

    @classmethod
    def create(
        cls,
        lams: Axis | ArrayLike,
        zetas: Axis | ArrayLike,
        dva: DvaSpec | str = "none",
        gamma: float = 2.0,
        *,
        options: EngineOptions | None = None,
        t_max: float | None = None,
        friction: FrictionLaw | None = None,
        deltas: Axis | ArrayLike | None = None,
    ) -> MapConfig:
        """The configuration of :func:`occurrence_map` for these arguments (same parsing rules).

        Lets a caller know the map's :meth:`fingerprint` before computing it (the command line
        uses it to recognise an output file that already holds this map).
        """
        spec = DvaSpec.parse(dva) if isinstance(dva, str) else dva
        engine_options = (options or EngineOptions()).with_t_max(t_max)
        if deltas is not None and friction is not None:
            raise ValueError("deltas and friction exclude each other: a (lambda, delta) map has "
                             "the linear law LinearFriction(delta) in every cell")
        return cls(as_axis(lams, "lambda"), as_axis(zetas, "zeta"), spec, gamma, engine_options,
                   friction or CoulombFriction(),
                   None if deltas is None else as_axis(deltas, "delta"))

    @property
    def second_axis_name(self) -> str:
        """Name of the grid's second axis: ``"zeta"``, or ``"delta"`` for a (lambda, delta) map."""
        return "zeta" if self.delta is None else "delta"

    @property
    def second(self) -> str:
        """Deprecated name of :attr:`second_axis_name` (removed in the next release)."""
        warn_renamed("MapConfig.second", "MapConfig.second_axis_name")
        return self.second_axis_name

    @property
    def second_axis(self) -> Axis:
        """The grid's second axis (:attr:`zeta` or :attr:`delta`)."""
        return self.zeta if self.delta is None else self.delta

    @functools.cached_property
    def structures(self) -> StructureSet:
        """The structure at every ``zeta`` of the grid."""
        return StructureSet.resolve(self.dva, self.zeta.values)

    @property
    def shape(self) -> tuple[int, int]:
        """``(n_lambda, n_zeta)``, or ``(n_lambda, n_delta)``."""
        return len(self.lam), len(self.second_axis)

    @property
    def n_cells(self) -> int:
        """Number of grid cells."""
        return len(self.lam) * len(self.second_axis)

    def to_dict(self) -> dict[str, Any]:
        """The full resolved configuration, JSON-ready (floats kept to full precision).

        The friction law appears only when it is not the paper's Coulomb law, and the
        ``delta`` axis only for a (lambda, delta) map, so that the configuration (and
        fingerprint) of a Coulomb map is what it was before friction laws.
        """
        friction: dict[str, Any] = {} if isinstance(self.friction, CoulombFriction) else {
            "friction": {**self.friction.to_dict(), "description": self.friction.describe()}}
        if self.delta is not None:
            friction = {
                "friction": {"law": "linear", "delta": "per cell: the delta axis",
                             "description": DELTA_LAW},
                "delta": axis_dict(self.delta),
                "axes": ["lambda", "delta"],
            }
        return {
            **friction,
            "lambda": axis_dict(self.lam),
            "zeta": axis_dict(self.zeta),
            "dva": {
                "text": self.dva.as_text(),
                "kind": self.dva.kind,
                "k_scale": self.dva.k_scale,
                "description": self.dva.describe(),
            },
            "foundations": [
                None if f is None else [f.mass_ratio, f.stiffness_ratio, f.damping_ratio]
                for f in self.structures.foundations
            ],
            "gamma": self.gamma,
            "engine": self.options.to_dict(),
            "initial_condition": STARTUP_DESCRIPTION,
            "package_version": package_version(),
        }

    def fingerprint(self) -> str:
        """SHA-256 of the resolved configuration: grids, foundations, gamma, engine, version."""
        text = json.dumps(self.to_dict(), sort_keys=True, allow_nan=False)
        return hashlib.sha256(text.encode()).hexdigest()

    def batch(self, chunk: Chunk) -> CellBatch:
        """The cells of ``chunk``: flat index ``c = i_lambda * n_second + j``.

        A (lambda, zeta) map indexes the structure of ``zeta_j``; a (lambda, delta) map has
        one structure and the law ``LinearFriction(delta_j)`` per cell.
        """
        cells = np.arange(chunk.start, chunk.stop, dtype=np.int64)
        n_second = self.shape[1]
        lams = np.array(self.lam.values[cells // n_second])
        if self.delta is None:
            return CellBatch(structure_index=cells % n_second, lams=lams, gamma=self.gamma,
                             friction=self.friction)
        deltas = self.delta.values[cells % n_second]
        return CellBatch(structure_index=np.zeros(cells.size, dtype=np.int64), lams=lams,
                         gamma=self.gamma, laws=tuple(LinearFriction(float(d)) for d in deltas))


#: How the cells of a (lambda, delta) map are computed (``describe()`` of their laws).
DELTA_LAW = "linear, delta per cell (the delta axis), exact (floored at zero)"


def axis_dict(axis: Axis) -> dict[str, Any]:
    """An axis as JSON-ready data: its spec, spacing and values (full float precision)."""
    return {"spec": axis.spec, "spacing": axis.spacing, "values": [float(v) for v in axis.values]}


def dva_from_config(configuration: dict[str, Any]) -> DvaSpec:
    """The :class:`DvaSpec` recorded in a map's configuration (``MapConfig.to_dict``)."""
    dva = configuration["dva"]
    return DvaSpec.parse(str(dva["text"]), float(dva["k_scale"]))
