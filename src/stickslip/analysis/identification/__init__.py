"""Identification: a machine's stiffness, damping and friction law from a measured record.

Stick-slip records (Coulomb, Stribeck, linear or table laws, with uncertainties), velocity-step
records (rate-and-state), and imposed-motion records (LuGre). Names load on first use (PEP 562).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    "identify": "stickslip.analysis.identification.record_fit",
    "IdentificationResult": "stickslip.analysis.identification.result",
    "MeasuredRecord": "stickslip.analysis.identification.estimates",
    "RecordError": "stickslip.analysis.identification.estimates",
    "RecordEstimates": "stickslip.analysis.identification.estimates",
    "estimate": "stickslip.analysis.identification.estimates",
    "LuGreFit": "stickslip.analysis.identification.lugre_fit",
    "fit_lugre": "stickslip.analysis.identification.lugre_fit",
    "RateStateFit": "stickslip.analysis.identification.rate_state_fit",
    "fit_rate_state": "stickslip.analysis.identification.rate_state_fit",
}

__all__ = [
    "IdentificationResult",
    "LuGreFit",
    "MeasuredRecord",
    "RateStateFit",
    "RecordError",
    "RecordEstimates",
    "estimate",
    "fit_lugre",
    "fit_rate_state",
    "identify",
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from stickslip.analysis.identification.estimates import (
        MeasuredRecord,
        RecordError,
        RecordEstimates,
        estimate,
    )
    from stickslip.analysis.identification.lugre_fit import (
        LuGreFit,
        fit_lugre,
    )
    from stickslip.analysis.identification.rate_state_fit import (
        RateStateFit,
        fit_rate_state,
    )
    from stickslip.analysis.identification.record_fit import (
        identify,
    )
    from stickslip.analysis.identification.result import (
        IdentificationResult,
    )
