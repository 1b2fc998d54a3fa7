"""The verdict vocabulary: friction modes, verdicts, run statuses and their dataset codes.

One home for every name and integer code a result can carry: the :class:`Verdict` of a run
(``stick-slip``, ``steady-sliding``, ``undetermined``), the :class:`RunStatus` that certifies
it (or says why there is no certificate), the friction :class:`Mode` of each phase, and the
CF ``flag_values``/``flag_meanings`` attributes with which datasets store them. Codes never
change meaning; new members get new codes.
"""

from __future__ import annotations

from enum import Enum, IntEnum, StrEnum
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.kernel import engine


class Mode(IntEnum):
    """Friction state of the slider (paper Eq. 2)."""

    SLIP_I = engine.SLIP_I  # slower than the belt, xi' < 1
    SLIP_II = engine.SLIP_II  # faster than the belt, xi' > 1
    STICK = engine.STICK  # moving with the belt, xi' = 1

    @property
    def label(self) -> str:
        """Name used in the paper: ``slip-I``, ``slip-II`` or ``stick``."""
        return {0: "slip-I", 1: "slip-II", 2: "stick"}[int(self)]


class Verdict(StrEnum):
    """Certified answer to "does this system stick-slip?"."""

    STICK_SLIP = "stick-slip"
    STEADY_SLIDING = "steady-sliding"
    UNDETERMINED = "undetermined"
    SLIP_OSCILLATION = "slip-oscillation"

    @property
    def code(self) -> int:
        """Integer code used in datasets (``flag_values``); codes never change meaning."""
        return {"steady-sliding": 0, "stick-slip": 1, "undetermined": 2, "slip-oscillation": 3}[
            self.value
        ]


class RunStatus(Enum):
    """How a run ended, with an actionable message."""

    CERTIFIED_STEADY = (engine.STATUS_STEADY, "steady sliding certified by a Lyapunov bound")
    CERTIFIED_CYCLE = (engine.STATUS_CYCLE, "stick-slip cycle certified by a repeating breakaway")
    T_MAX = (
        engine.STATUS_T_MAX,
        "time horizon reached before a verdict could be certified; increase t_max",
    )
    MAX_EVENTS = (
        engine.STATUS_MAX_EVENTS,
        "maximum number of events reached before a verdict; increase max_events",
    )
    MAX_STEPS = (
        engine.STATUS_MAX_STEPS,
        f"step budget ({engine.MAX_STEPS} sub-steps) used up before a verdict: the run is "
        "long for its time steps (a long t_max with a motion that does not settle, e.g. an "
        "undamped one, or a structure so stiff or so heavily damped that its steps are tiny)",
    )
    CERTIFIED_OSCILLATION = (
        engine.STATUS_OSCILLATION,
        "slip oscillation (never sticking) certified by a repeating Poincare-section state",
    )
    UNPROVEN_CYCLE = (
        8,
        "a breakaway state repeated but no divisor of its period could be proven a contracting "
        "fixed point of the return map; increase t_max to run on",
    )
    INTERPOLANT_OSCILLATION = (
        10,
        "slip oscillation certified for the friction law's piecewise-linear interpolant only: "
        "the law's own steady sliding is linearly stable and the interpolant's is not (near "
        "its stability limit the band's secant slope and the law's tangent fall on either "
        "side), so the oscillation may be the interpolant's; lower the law's tolerance",
    )
    INTERPOLANT_STEADY = (
        9,
        "steady sliding certified for the friction law's piecewise-linear interpolant only: the "
        "law's own steady sliding is not linearly stable (near its stability limit the band's "
        "secant slope and the law's tangent fall on either side); lower the law's tolerance",
    )

    def __init__(self, code: int, message: str) -> None:
        self.code = code
        self.message = message

    @classmethod
    def from_code(cls, code: int) -> RunStatus:
        for status in cls:
            if status.code == code:
                return status
        raise ValueError(f"unknown run status code {code}")

    @property
    def label(self) -> str:
        """Short machine-readable name, e.g. ``t-max``."""
        return self.name.lower().replace("_", "-")

    @property
    def verdict(self) -> Verdict:
        """The verdict this status certifies; ``undetermined`` for a status that is no certificate.

        The one mapping from run status to verdict (:data:`CERTIFIED_VERDICTS`): a time horizon,
        an event budget or a step budget is never rounded to a verdict.
        """
        return CERTIFIED_VERDICTS.get(self, Verdict.UNDETERMINED)


#: The certificates and the verdict each one proves; every other status is ``undetermined``.
CERTIFIED_VERDICTS: dict[RunStatus, Verdict] = {
    RunStatus.CERTIFIED_STEADY: Verdict.STEADY_SLIDING,
    RunStatus.CERTIFIED_CYCLE: Verdict.STICK_SLIP,
    RunStatus.CERTIFIED_OSCILLATION: Verdict.SLIP_OSCILLATION,
}


#: Verdicts in the order of their integer codes (``Verdict.code``).
VERDICTS: tuple[Verdict, ...] = tuple(sorted(Verdict, key=lambda v: v.code))
#: Run statuses (the certificate of a run) in the order of their integer codes.
STATUSES: tuple[RunStatus, ...] = tuple(sorted(RunStatus, key=lambda s: s.code))


def verdict_flag_attributes() -> dict[str, Any]:
    """CF ``flag_values`` and ``flag_meanings`` of an integer verdict variable.

    Returns
    -------
    dict
        ``flag_values`` (int8 array) and ``flag_meanings``.
    """
    return {
        "flag_values": np.array([v.code for v in VERDICTS], dtype=np.int8),
        "flag_meanings": " ".join(v.value for v in VERDICTS),
    }


def status_flag_attributes() -> dict[str, Any]:
    """CF flag attributes of an integer run-status (certificate) variable, with the messages.

    Returns
    -------
    dict
        ``flag_values``, ``flag_meanings`` and ``comment`` (the messages).
    """
    return {
        "flag_values": np.array([s.code for s in STATUSES], dtype=np.int8),
        "flag_meanings": " ".join(s.label for s in STATUSES),
        "comment": "; ".join(f"{s.label}: {s.message}" for s in STATUSES),
    }


def verdict_codes(status: NDArray[np.integer[Any]]) -> NDArray[np.int8]:
    """Verdict code of each run status: steady 0, stick-slip cycle 1, slip oscillation 3, else 2.

    Anything that is not a certificate (time horizon, event budget, an unknown status) is
    ``undetermined``: never rounded to a verdict. The array form of :attr:`RunStatus.verdict`.

    Parameters
    ----------
    status : ndarray of int
        Run-status codes (:attr:`RunStatus.code`), any shape.

    Returns
    -------
    ndarray of int8
        Verdict codes (:attr:`Verdict.code`), same shape.
    """
    codes = np.full(np.shape(status), Verdict.UNDETERMINED.code, dtype=np.int8)
    for certificate, verdict in CERTIFIED_VERDICTS.items():
        codes[status == certificate.code] = verdict.code
    return codes
