"""Resolving a foundation choice (:class:`stickslip.model.dva.DvaSpec`) at a primary damping.

The specification itself is plain data in the model layer; resolving ``optimal-exact`` needs the
H-infinity tuning (:func:`stickslip.analysis.absorber_tuning.optimal_foundation_exact`), so it
happens here, in the analysis layer.

``DvaSpec`` is still importable from this module for one release, with a
``DeprecationWarning``; import it from :mod:`stickslip.model.dva` (or ``stickslip``).
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from stickslip.analysis.theory import FITTED_ZETA_RANGE, check_fitted_zeta, optimal_foundation_fit
from stickslip.model.dva import DvaSpec as _DvaSpec
from stickslip.model.parameters import Foundation

if TYPE_CHECKING:  # the annotation; at run time the name is the deprecated attribute below
    from stickslip.model.dva import DvaSpec


def resolve_dva(spec: DvaSpec, zeta: float) -> Foundation | None:
    """The foundation that ``spec`` stands for at primary damping ratio ``zeta``.

    Parameters
    ----------
    spec : DvaSpec
        The foundation choice.
    zeta : float
        Primary damping ratio ``c / (2 sqrt(m k))``, dimensionless. For ``optimal`` (the fit of
        Eqs. 28-30) it must not exceed :data:`~stickslip.analysis.theory.MAX_DESIGN_ZETA`.

    Returns
    -------
    Foundation or None
        The dimensionless foundation with ``K`` scaled by ``spec.k_scale``; ``None`` for the
        rigid base (``kind="none"``).
    """
    if spec.kind == "none":
        return None
    if spec.kind == "optimal":
        base = optimal_foundation_fit(check_fitted_zeta(zeta))
    elif spec.kind == "optimal-exact":
        # on use: the tuning loads scipy, which the command line's start-up does not need
        from stickslip.analysis.absorber_tuning import optimal_foundation_exact

        base = optimal_foundation_exact(zeta)
    else:
        assert spec.foundation is not None
        base = spec.foundation
    return base.scaled(spec.k_scale) if spec.k_scale != 1.0 else base


def fitted_zeta_warning(spec: DvaSpec, zetas: Iterable[float]) -> str | None:
    """One line when the fitted optimum is used outside its fitted range.

    Parameters
    ----------
    spec : DvaSpec
        The foundation choice; only ``optimal`` (Eqs. 28-30) can warn.
    zetas : iterable of float
        Primary damping ratios at which it is used, dimensionless.

    Returns
    -------
    str or None
        The warning when some ``zeta`` exceeds
        :data:`~stickslip.analysis.theory.FITTED_ZETA_RANGE`, else ``None``.
    """
    if spec.kind != "optimal":
        return None
    above = [float(z) for z in zetas if float(z) > FITTED_ZETA_RANGE]
    if not above:
        return None
    return (
        f"zeta={max(above):.3g} is outside the range 0 <= zeta <= {FITTED_ZETA_RANGE} on which "
        "the optimal foundation (Eqs. 28-30) is fitted: it is extrapolated there"
    )


class _DeprecatedDvaSpec(_DvaSpec):
    """``DvaSpec`` with its former ``resolve`` method, for code importing the old path."""

    def resolve(self, zeta: float) -> Foundation | None:
        """Deprecated: use :func:`resolve_dva` (``resolve_dva(spec, zeta)``)."""
        warnings.warn("DvaSpec.resolve(zeta) is deprecated: use "
                      "stickslip.analysis.dva.resolve_dva(spec, zeta)", DeprecationWarning,
                      stacklevel=2)
        return resolve_dva(self, zeta)


def __getattr__(name: str) -> Any:
    """The old home of ``DvaSpec`` (PEP 562), kept for one release with a warning."""
    if name == "DvaSpec":
        warnings.warn("stickslip.analysis.dva.DvaSpec moved to stickslip.model.dva.DvaSpec "
                      "(also stickslip.DvaSpec); resolve it with stickslip.analysis.dva.resolve_dva",
                      DeprecationWarning, stacklevel=2)
        return _DeprecatedDvaSpec
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
