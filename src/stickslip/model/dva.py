"""Which elastic foundation (dynamic vibration absorber) a computation uses: plain data.

A map over ``zeta`` with the "optimal" foundation needs a different foundation in every
column (the optimum depends on ``zeta``), so the choice is kept as a specification. Parsing
the text ``none | optimal | optimal-exact | M,K,ZETA_A`` is model-level data parsing and
lives here; resolving a specification to a :class:`Foundation` at a given ``zeta`` needs the
tuning and is :func:`stickslip.analysis.dva.resolve_dva`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from stickslip.model._validate import at_most, positive
from stickslip.model.parameters import Foundation

DvaKind = Literal["none", "optimal", "optimal-exact", "explicit"]

DVA_SYNTAX = "'none', 'optimal', 'optimal-exact' or three numbers M,K,ZETA_A"
"""The text forms :meth:`DvaSpec.parse` accepts (for help and error messages)."""


@dataclass(frozen=True)
class DvaSpec:
    """A foundation choice: ``none``, ``optimal`` (Eqs. 28-30), ``optimal-exact`` or explicit.

    Parameters
    ----------
    kind : {"none", "optimal", "optimal-exact", "explicit"}
        ``none`` is the rigid base (1DOF system); ``optimal`` the paper's fitted optimum
        (Eqs. 28-30); ``optimal-exact`` the numerical H-infinity optimum.
    foundation : Foundation, optional
        The explicit foundation (``kind="explicit"`` only), dimensionless.
    k_scale : float
        Multiplies ``K`` after resolution (paper Figs. 11-15 use 1/2 and 2), dimensionless.
    """

    kind: DvaKind = "none"
    foundation: Foundation | None = None
    k_scale: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "k_scale", at_most("k_scale", positive("k_scale", self.k_scale)))
        if self.kind not in ("none", "optimal", "optimal-exact", "explicit"):
            raise ValueError(f"dva kind {self.kind!r} is not none, optimal, optimal-exact or explicit")
        if (self.kind == "explicit") != (self.foundation is not None):
            raise ValueError("an explicit foundation needs kind='explicit' and vice versa")
        if self.kind == "none" and self.k_scale != 1.0:
            raise ValueError(f"k_scale={self.k_scale!r} needs a foundation, but the dva is 'none'")

    @classmethod
    def parse(cls, text: str, k_scale: float = 1.0) -> DvaSpec:
        """Parse ``none``, ``optimal``, ``optimal-exact`` or ``M,K,ZETA_A``.

        Parameters
        ----------
        text : str
            The foundation choice; ``M,K,ZETA_A`` are the dimensionless mass, stiffness and
            damping ratios of an explicit foundation.
        k_scale : float
            Multiplier of ``K`` after resolution, dimensionless.

        Returns
        -------
        DvaSpec
            The specification; a ``ValueError`` names the text and why it is refused.
        """
        key = text.strip().lower()
        if key in ("none", "optimal", "optimal-exact"):
            return cls(key, None, k_scale)  # type: ignore[arg-type]
        parts = text.split(",")
        if len(parts) != 3:
            raise ValueError(f"foundation choice {text!r} is not {DVA_SYNTAX}")
        try:
            values = [float(p) for p in parts]
        except ValueError:
            raise ValueError(f"foundation choice {text!r}: M,K,ZETA_A must be numbers") from None
        return cls("explicit", Foundation(*values), k_scale)

    def describe(self) -> str:
        """Human-readable label, e.g. ``optimal (Eqs. 28-30), K x 0.5``."""
        if self.kind == "none":
            return "rigid base (no foundation)"
        if self.kind == "optimal":
            label = "optimal foundation (fitted Eqs. 28-30)"
        elif self.kind == "optimal-exact":
            label = "optimal foundation (exact numerical optimum)"
        else:
            assert self.foundation is not None
            f = self.foundation
            label = f"foundation M={f.mass_ratio:g}, K={f.stiffness_ratio:g}, zeta_a={f.damping_ratio:g}"
        if self.k_scale != 1.0:
            label += f", K x {self.k_scale:g}"
        return label

    def as_text(self) -> str:
        """The text that :meth:`parse` reads back to this specification (without ``k_scale``)."""
        if self.kind != "explicit":
            return self.kind
        assert self.foundation is not None
        f = self.foundation
        return f"{f.mass_ratio!r},{f.stiffness_ratio!r},{f.damping_ratio!r}"
