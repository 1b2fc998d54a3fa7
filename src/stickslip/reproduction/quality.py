"""Resolution presets of the reproduction: how dense the maps and curves are."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Quality:
    """Grid sizes used by ``stickslip reproduce``.

    Attributes
    ----------
    name : str
    map_lam, map_zeta : int
        Occurrence-map grid (lambda log-spaced in ``lam_range``, zeta linear in ``zeta_range``).
    tuning_zetas : int
        Number of zeta values at which the absorber optimum is computed (Figs. 4, 6, 10).
    gamma_lam, gamma_zeta : int
        Grid of the maps that test the effect of gamma.
    history_points : int
        Samples per time-history curve.
    """

    name: str
    map_lam: int
    map_zeta: int
    tuning_zetas: int
    gamma_lam: int
    gamma_zeta: int
    history_points: int
    lam_range: tuple[float, float] = (0.1, 50.0)
    zeta_range: tuple[float, float] = (0.005, 0.4)


QUALITIES = {
    "tiny": Quality("tiny", 8, 5, 2, 6, 4, 600),
    "default": Quality("default", 80, 40, 7, 40, 20, 3000),
    "high": Quality("high", 400, 200, 41, 120, 60, 8000),
}


def quality(name: str) -> Quality:
    """Look up a preset by name: ``tiny`` (tests), ``default`` or ``high`` (publication)."""
    try:
        return QUALITIES[name]
    except KeyError:
        raise ValueError(
            f"quality {name!r} is not one of {', '.join(QUALITIES)}"
        ) from None
