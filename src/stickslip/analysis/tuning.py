"""Deprecated: the former home of the foundation tuning, split by concept in 0.x (issue 17).

* :mod:`stickslip.analysis.optimise` - the shared Nelder-Mead search;
* :mod:`stickslip.analysis.peak_minimiser` - the H-infinity peak minimiser;
* :mod:`stickslip.analysis.absorber_tuning` - the absorber optimum (Figs. 3-6, 10);
* :mod:`stickslip.analysis.stick_slip_tuning` - the stick-slip objective;
* :mod:`stickslip.analysis.stability_tuning` - the stability objective.

Every public name is still importable from here for one release, with a ``DeprecationWarning``
that names its new module (or import it from ``stickslip``).
"""

from __future__ import annotations

import importlib
import warnings
from typing import Any

_MOVED: dict[str, str] = {
    **dict.fromkeys(("PeakMinimum", "minimise_peak"), "stickslip.analysis.peak_minimiser"),
    **dict.fromkeys(("DEFAULT_MASS_BOUNDS", "STIFFNESS_BOUNDS", "DAMPING_BOUNDS", "TuningResult",
                     "TuningCurve", "tune_foundation", "tuning_curve", "optimal_foundation_exact"),
                    "stickslip.analysis.absorber_tuning"),
    "MAX_TUNING_ZETA": "stickslip.analysis.theory",
    **dict.fromkeys(("StickSlipTuning", "optimal_foundation_stick_slip"),
                    "stickslip.analysis.stick_slip_tuning"),
    **dict.fromkeys(("StabilityTuning", "optimal_foundation_stability"),
                    "stickslip.analysis.stability_tuning"),
}


def __getattr__(name: str) -> Any:
    """A moved name from its new module, with a ``DeprecationWarning`` (PEP 562)."""
    try:
        module = _MOVED[name]
    except KeyError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    warnings.warn(f"stickslip.analysis.tuning.{name} moved to {module}.{name}",
                  DeprecationWarning, stacklevel=2)
    return getattr(importlib.import_module(module), name)


def __dir__() -> list[str]:
    return sorted(_MOVED)
