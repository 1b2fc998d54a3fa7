"""A quantitative claim of the paper next to what we measure."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal

ClaimVerdict = Literal["confirmed", "differs", "partly confirmed"]


@dataclass(frozen=True)
class Claim:
    """One line of the reproduction report.

    Attributes
    ----------
    key : str
        Short identifier, e.g. ``"narrowing"``.
    source : str
        Where the paper says it (figure, equation or section).
    statement : str
        What the paper claims.
    measured : str
        What we computed, with numbers.
    verdict : {"confirmed", "differs", "partly confirmed"}
    data : dict
        The numbers behind ``measured``, for the JSON version of the report.
    """

    key: str
    source: str
    statement: str
    measured: str
    verdict: ClaimVerdict
    data: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "key": self.key,
            "source": self.source,
            "statement": self.statement,
            "measured": self.measured,
            "verdict": self.verdict,
            "data": self.data,
        }
