"""The web app's "frequency response and absorber tuning" page: ``stickslip tune`` and
``stickslip frf`` in a browser (issue 31).

The foundation as a vibration absorber (paper Figs. 3-6, Eqs. 28-33): for the slider's
damping ratio ``zeta`` (and, optionally, a fixed mass ratio ``M``) the exact optimum of
:func:`~stickslip.analysis.absorber_tuning.tune_foundation` beside the paper's fitted
Eqs. (28)-(31) and (33), and the frequency response ``H = k|X|/f`` of
:func:`~stickslip.analysis.frequency_response.response_curves` on the rigid base and with the
foundation (paper Fig. 5). Everything is dimensionless, as in the commands.
"""

from __future__ import annotations

from typing import Any

#: Widget key -> (label, default) of the page's inputs.
TUNING_INPUTS: dict[str, tuple[str, str]] = {
    "tuning_zeta": ("Slider damping ratio ζ = c / (2 √(mk))", "0.05"),
    "tuning_mass_ratio": ("Mass ratio M = m_a / m (empty: optimised too)", ""),
}


def tuning(zeta_text: str, mass_ratio_text: str) -> tuple[Any, Any]:
    """``(tune_foundation result, response curves)`` of the typed inputs, or one-line ``ValueError``.

    The checks of ``stickslip tune``: ``0 <= zeta <= MAX_TUNING_ZETA``, ``M`` a ratio.
    """
    from stickslip.analysis.absorber_tuning import tune_foundation
    from stickslip.analysis.frequency_response import response_curves
    from stickslip.analysis.theory import MAX_TUNING_ZETA
    from stickslip.model._validate import non_negative, ratio

    label = TUNING_INPUTS["tuning_zeta"][0]
    try:
        zeta = non_negative("ζ", float(zeta_text))
    except ValueError as exc:
        raise ValueError(f"{label}: {zeta_text!r}: {exc}") from None
    if zeta > MAX_TUNING_ZETA:
        raise ValueError(f"{label}: {zeta_text!r} is above {MAX_TUNING_ZETA}: no tuning is "
                         "defined there")
    mass_ratio = None
    if mass_ratio_text.strip():
        try:
            mass_ratio = ratio("M", float(mass_ratio_text))
        except ValueError as exc:
            raise ValueError(f"{TUNING_INPUTS['tuning_mass_ratio'][0]}: {mass_ratio_text!r}: "
                             f"{exc}") from None
    result = tune_foundation(zeta, mass_ratio=mass_ratio)
    return result, response_curves(zeta, result.foundation)


def show_tuning_page() -> None:
    """Lay out the "frequency response and absorber tuning" page (Streamlit)."""
    import pandas as pd
    import streamlit as st

    from stickslip.app.figures import cached_png, fmt
    from stickslip.app.messages import show_error

    st.title("The foundation as a vibration absorber")
    st.caption("The exact optimum of the foundation (M, K, ζ_a minimising the peak of the "
               "frequency response H = k|X|/f, paper Figs. 3-6) beside the paper's fitted "
               "Eqs. (28)-(31) and (33): 'stickslip tune' and 'stickslip frf'. Dimensionless.")
    raw = {key: st.text_input(label, value=default, key=key)
           for key, (label, default) in TUNING_INPUTS.items()}
    try:
        result, curves = tuning(raw["tuning_zeta"], raw["tuning_mass_ratio"])
    except ValueError as exc:
        show_error(str(exc))
        return
    payload = result.to_dict()
    fit, rel = payload["fitted"], payload["relative_difference"]
    rows = [("M", "Eq. (28)"), ("K", "Eq. (29)"), ("zeta_a", "Eq. (30)"), ("H_max", "Eq. (31)"),
            ("zeta_eq", "Eq. (33)")]
    st.dataframe(pd.DataFrame({
        "exact": [fmt(payload[name]) for name, _ in rows],
        "paper fit": [fmt(fit[name]) for name, _ in rows],
        "fit / exact − 1": [f"{rel[name]:+.2%}" for name, _ in rows],
        "paper": [eq for _, eq in rows],
    }, index=["M", "K", "ζ_a", "H_max", "ζ_eq"]), key="tuning_table")
    st.caption(f"Exact optimum: H_max = {fmt(payload['H_max'])} at Ω = "
               f"{fmt(payload['Omega_peak'])}; the paper's fitted parameters give H_max = "
               f"{fmt(fit['H_max_exact_at_fitted'])} (exact response)."
               + (" The optimum lies on a search bound." if any(result.at_bound) else ""))
    st.image(cached_png(("tuning", raw["tuning_zeta"], raw["tuning_mass_ratio"]),
                        lambda: curves.plot().figure))
