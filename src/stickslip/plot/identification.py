"""Figure of an identification: measured against fitted signals, residuals, friction curve."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from stickslip.plot.figure import PlotResult, new_grid

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from stickslip.analysis.identification.result import IdentificationResult

_LABELS = {"F": ("force F", "N"), "x": ("displacement x", "m"), "v": ("velocity v", "m/s")}


def identification_plot(
    data: IdentificationResult,
    *,
    ax: Sequence[Axes] | None = None,
    channel: str | None = None,
    n_sigma: float = 2.0,
) -> PlotResult:
    """Draw a fit: signal measured and fitted, its residuals, and ``mu(v_r)`` with a band.

    Parameters
    ----------
    data : IdentificationResult
    ax : sequence of three matplotlib Axes, optional
        Drawn into (signal, residuals, friction curve); a new 3-panel figure otherwise.
    channel : {"F", "x", "v"}, optional
        The signal drawn (default: the force when measured, else the displacement).
    n_sigma : float
        Half-width of the friction curve's uncertainty band in standard errors (delta method
        from the fit's covariance).

    Returns
    -------
    PlotResult
        Axes: signal against time, residual against time, friction coefficient against
        sliding speed.
    """
    chosen = channel or ("F" if "F" in data.measured else "x")
    if chosen not in data.measured:
        raise ValueError(f"channel={chosen!r} is not in the record ({', '.join(data.measured)})")
    fig, axes = new_grid(1, 3, axes=ax, figsize=(13.0, 3.8))
    name, unit = _LABELS[chosen]
    t = data.t
    artists: list[Any] = []
    artists += axes[0].plot(t, data.measured[chosen], ".", ms=1.5, color="0.55", label="measured")
    artists += axes[0].plot(t, data.fitted[chosen], color="tab:blue", lw=1.0, label=f"fitted ({data.law})")
    axes[0].set_xlabel("time t [s]")
    axes[0].set_ylabel(f"{name} [{unit}]")
    axes[0].legend(loc="upper right", fontsize="small")
    resid = data.fitted[chosen] - data.measured[chosen]
    artists += axes[1].plot(t, resid, ".", ms=1.5, color="tab:red")
    artists.append(axes[1].axhline(0.0, color="k", lw=0.6))
    axes[1].set_xlabel("time t [s]")
    axes[1].set_ylabel(f"residual (fitted - measured) [{unit}]")
    axes[1].set_title(f"RMS {data.residual_rms[chosen]:.3g} {unit}", fontsize="small")
    v_max = max(2.0 * data.speed, float(np.max(np.abs(data.fitted["v"] - data.speed))))
    v_r = np.linspace(0.0, v_max, 300)[1:]
    mu, se = data.friction_curve(v_r)
    artists.append(axes[2].fill_between(v_r, mu - n_sigma * se, mu + n_sigma * se, color="tab:blue",
                                        alpha=0.25, lw=0, label=f"±{n_sigma:g} standard errors"))
    artists += axes[2].plot(v_r, mu, color="tab:blue", label=f"mu(v_r), {data.law}")
    mu_s = data.values()["mu_s"]
    artists.append(axes[2].axhline(mu_s, color="tab:orange", ls="--", lw=0.8, label="mu_s (stick)"))
    axes[2].set_xlabel("sliding speed v_r = V - x' [m/s]")
    axes[2].set_ylabel("friction coefficient")
    axes[2].legend(loc="upper right", fontsize="small")
    return PlotResult(fig, list(axes), artists)
