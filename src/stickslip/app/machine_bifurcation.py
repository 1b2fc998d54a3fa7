"""The machine page's bifurcation diagram: the periodic motions of the user's machine in belt speed.

The command line's ``stickslip continue --config machine.toml --param speed --range A:B``
(:func:`stickslip.analysis.continuation.continue_cycles` on a
:class:`~stickslip.analysis.continuation.MachineSystem`): stick-slip branches with their
Floquet multipliers (stable solid, unstable dashed), steady sliding's stability along the
range, and the named events (folds, period doublings, tori, grazings, Hopf points). It runs
on demand in the worker process (:mod:`stickslip.app.workers`: a continuation takes seconds to
a few minutes), with the same bounds as the command's defaults.
"""

from __future__ import annotations

from typing import Any

#: Bounds of the continuation (those of ``stickslip continue``).
SEEDS = 12
MAX_PERIOD = 2
MAX_STEPS = 400
#: The default range: the operating speed divided and multiplied by this.
DEFAULT_SPAN = 5.0


def continuation_in_worker(machine: Any, lo: float, hi: float) -> Any:
    """:func:`continue_cycles` of ``machine`` in belt speed over ``[lo, hi]`` (m/s), in a worker."""
    from stickslip.analysis.continuation import MachineSystem, continue_cycles

    return continue_cycles(MachineSystem(machine), "speed", (lo, hi), max_period=MAX_PERIOD,
                           seeds=SEEDS, max_steps=MAX_STEPS)


def speed_range(low: str, high: str) -> tuple[float, float]:
    """The typed range of belt speeds (units allowed), checked: ``0 < lo < hi``.

    Parameters
    ----------
    low, high : str
        The two fields, e.g. ``"0.1 mm/s"``.

    Returns
    -------
    (float, float)
        The range, m/s.

    Raises
    ------
    ValueError
        One line naming the field and why.
    """
    from stickslip.model.units import to_si

    lo = to_si("speed", low, source="bifurcation diagram: from")
    hi = to_si("speed", high, source="bifurcation diagram: to")
    if not 0.0 < lo < hi:
        raise ValueError(f"bifurcation diagram: the range {lo:g} to {hi:g} m/s must be positive "
                         "and increasing")
    return lo, hi


def show_machine_bifurcation(machine: Any, digest: str) -> None:
    """The section of the machine page (Streamlit): range fields, a button, the diagram."""
    import streamlit as st

    from stickslip.app.figures import cached_png, fmt
    from stickslip.app.messages import show_error, show_failure
    from stickslip.app.workers import wait_for

    st.subheader("Bifurcation diagram in belt speed")
    st.caption("Every stick-slip cycle continued across a range of belt speeds, stable (solid) or "
               "not (dashed), with steady sliding's stability and the named events: what "
               "'stickslip continue --config' draws. Seconds to a few minutes.")
    col1, col2 = st.columns(2)
    low = col1.text_input("From belt speed", value=f"{fmt(machine.speed / DEFAULT_SPAN)} m/s",
                          key="bifurcation_from")
    high = col2.text_input("To belt speed", value=f"{fmt(machine.speed * DEFAULT_SPAN)} m/s",
                           key="bifurcation_to")
    try:
        lo, hi = speed_range(low, high)
    except ValueError as exc:
        show_error(str(exc))  # the typed text shown literally
        return
    key = ("bifurcation", digest, lo, hi)
    if st.session_state.get("machine_bifurcation") != key and not st.button(
            "Continue the periodic motions", key="machine_bifurcation_button"):
        return
    st.session_state["machine_bifurcation"] = key
    try:
        result = wait_for(key, continuation_in_worker, machine, lo, hi,
                          what="Continuing the periodic motions")
    except Exception as exc:
        show_failure(exc, "The continuation")
        return
    st.image(cached_png(key, lambda: result.plot().figure))  # drawn once per range
    st.text(result.summary())
