"""Which elastic foundation (dynamic vibration absorber) a computation uses.

A map over ``zeta`` with the "optimal" foundation needs a different foundation in every
column (the optimum depends on ``zeta``), so the choice is kept as a specification that is
resolved per ``zeta``.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Literal

from stickslip.model._validate import at_most, positive
from stickslip.model.parameters import Foundation

DvaKind = Literal["none", "optimal", "optimal-exact", "explicit"]


@dataclass(frozen=True)
class DvaSpec:
    """A foundation choice: ``none``, ``optimal`` (Eqs. 28-30), ``optimal-exact`` or explicit.

    Parameters
    ----------
    kind : {"none", "optimal", "optimal-exact", "explicit"}
        ``none`` is the rigid base (1DOF system).
    foundation : Foundation, optional
        The explicit foundation (``kind="explicit"`` only).
    k_scale : float
        Multiplies ``K`` after resolution (paper Figs. 11-15 use 1/2 and 2).
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
        """Parse ``none``, ``optimal``, ``optimal-exact`` or ``M,K,ZETA_A`` (the ``--dva`` option)."""
        key = text.strip().lower()
        if key in ("none", "optimal", "optimal-exact"):
            return cls(key, None, k_scale)  # type: ignore[arg-type]
        parts = text.split(",")
        if len(parts) != 3:
            raise ValueError(
                f"--dva {text!r} is not 'none', 'optimal', 'optimal-exact' or three numbers M,K,ZETA_A"
            )
        try:
            values = [float(p) for p in parts]
        except ValueError:
            raise ValueError(f"--dva {text!r}: M,K,ZETA_A must be numbers") from None
        return cls("explicit", Foundation(*values), k_scale)

    def resolve(self, zeta: float) -> Foundation | None:
        """The foundation for primary damping ratio ``zeta`` (``None`` for the rigid base)."""
        if self.kind == "none":
            return None
        if self.kind == "optimal":
            from stickslip.analysis.theory import optimal_foundation_fit

            base = optimal_foundation_fit(check_fitted_zeta(zeta))
        elif self.kind == "optimal-exact":
            from stickslip.analysis.tuning import optimal_foundation_exact

            base = optimal_foundation_exact(zeta)
        else:
            assert self.foundation is not None
            base = self.foundation
        return base.scaled(self.k_scale) if self.k_scale != 1.0 else base

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
        """The ``--dva`` text that parses back to this specification (without ``k_scale``)."""
        if self.kind != "explicit":
            return self.kind
        assert self.foundation is not None
        f = self.foundation
        return f"{f.mass_ratio!r},{f.stiffness_ratio!r},{f.damping_ratio!r}"


def check_fitted_zeta(zeta: float) -> float:
    """Refuse ``zeta`` above ``MAX_DESIGN_ZETA`` for the fitted optimum (Eqs. 28-30).

    The fit is defined on ``0 <= zeta <= FITTED_ZETA_RANGE`` (0.4); between that and
    ``MAX_DESIGN_ZETA`` (0.9) it is extrapolated and callers warn
    (:func:`fitted_zeta_warning`), above it is refused, as ``tune`` and ``design`` do.
    """
    from stickslip.analysis.design import MAX_DESIGN_ZETA
    from stickslip.model._validate import non_negative

    z = non_negative("zeta", zeta)
    if z > MAX_DESIGN_ZETA:
        raise ValueError(
            f"zeta={zeta!r} is above {MAX_DESIGN_ZETA}: the fitted optimal foundation "
            "(--dva optimal, Eqs. 28-30, fitted for zeta <= 0.4) is not defined there"
        )
    return z


def fitted_zeta_warning(spec: DvaSpec, zetas: Iterable[float]) -> str | None:
    """One line when the fitted optimum is used outside its fitted range, else None."""
    from stickslip.analysis.design import FITTED_ZETA_RANGE

    if spec.kind != "optimal":
        return None
    above = [float(z) for z in zetas if float(z) > FITTED_ZETA_RANGE]
    if not above:
        return None
    return (
        f"zeta={max(above):.3g} is outside the range 0 <= zeta <= {FITTED_ZETA_RANGE} on which "
        "the optimal foundation (Eqs. 28-30) is fitted: it is extrapolated there"
    )
