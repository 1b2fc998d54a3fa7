"""The worked example of docs/friction.md: a measured friction curve to a verdict and a map.

Run it from the repository root (it writes the figures next to this file, and prints every
number the page quotes):

    .venv/bin/python docs/friction_example.py [--out docs/figures] [--quick]

``--quick`` uses coarse maps (the test suite runs it that way).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from stickslip import (
    EngineOptions,
    PhysicalSystem,
    Slider,
    elastic_foundation,
    occurrence_map,
    optimal_foundation_fit,
    rigid_base,
    simulate,
)
from stickslip.analysis.design import stability_margin
from stickslip.analysis.stability import critical_weakening, steady_sliding_stability
from stickslip.analysis.stability_tuning import optimal_foundation_stability
from stickslip.model.friction import evaluate_bands
from stickslip.model.physical import foundation_to_physical, physical_friction_from_config

#: A friction curve as a tribometer gives it: sliding speed v [m/s] and friction coefficient.
#: It falls from the static value 0.5 at rest to 0.3 at 60 mm/s (the Stribeck effect) and
#: rises slowly beyond (lubricant viscosity).
CURVE = """# v [m/s], mu [-]: pin-on-belt, dry-lubricated steel on polymer (example data)
v,mu
0.000,0.480
0.005,0.452
0.010,0.427
0.020,0.387
0.030,0.356
0.045,0.327
0.060,0.310
0.080,0.302
0.120,0.300
0.200,0.305
0.400,0.318
"""

MACHINE = dict(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=150.0, speed=0.05)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "figures")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    curve = out / "measured_friction.csv"
    curve.write_text(CURVE)

    # 1. the measured curve as a friction law of the machine, in SI units
    friction = physical_friction_from_config({"law": "table", "table": str(curve)})
    system = PhysicalSystem(**MACHINE, friction=friction)
    slider = system.slider()
    zeta = system.zeta
    print(f"lambda = {slider.lam:.6g}, zeta = {zeta:.6g}, gamma = {slider.gamma:.6g}")
    print(f"law: {slider.friction.describe()}")

    # 2. verdicts at the operating point: rigid base and the recommended foundation
    fit = optimal_foundation_fit(zeta)
    stable = optimal_foundation_stability(zeta).foundation
    print(f"stability-optimal foundation: M = {stable.mass_ratio:.4g}, K = {stable.stiffness_ratio:.4g}, "
          f"zeta_a = {stable.damping_ratio:.4g}")
    structures = {"rigid": rigid_base(zeta), "foundation": elastic_foundation(zeta, fit),
                  "stability": elastic_foundation(zeta, stable)}
    runs = {}
    for name, structure in structures.items():
        horizon = 1500.0 if name == "stability" else 400.0  # the soft foundation loads up slowly
        runs[name] = simulate(structure, slider, options=EngineOptions(t_max=horizon),
                              run_to_t_max=True)  # for figures
        verdict = simulate(structure, slider, record=False)  # default horizon
        coulomb = simulate(structure, Slider(slider.lam, gamma=slider.gamma), record=False)
        stab = steady_sliding_stability(structure, slider)
        print(f"{name:10s} table law: {verdict.verdict.value:15s} Coulomb law: "
              f"{coulomb.verdict.value:15s} steady sliding {'stable' if stab.stable else 'UNSTABLE'} "
              f"(growth rate {stab.growth_rate:+.4f} per tau, delta_local {stab.delta_local:.4f}, "
              f"delta_crit {critical_weakening(structure):.4f})")
    margin = stability_margin(system, structures)
    for name in structures:
        m = margin[name]
        print(f"{name:10s} growth rate {m['growth_rate']:+.4g} 1/s, tolerated friction slope "
              f"-{m['sigma_crit']:.4g} s/m, the curve's slope at V: -{m['sigma_local']:.4g} s/m")
    for name, found in (("recommended (Eqs. 28-30)", fit), ("stability-optimal", stable)):
        phys = foundation_to_physical(found, system.mass, system.stiffness)
        print(f"{name} foundation: m_a = {phys.m_a:.4g} kg, k_a = {phys.k_a:.4g} N/m, "
              f"c_a = {phys.c_a:.4g} N s/m")

    # figure 1: the law as the engine uses it (exact piecewise-linear bands) and the points
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 3.8), layout="constrained")
    ax = fig.add_subplot()
    table = slider.friction.bands(slider.lam, slider.gamma)
    v = np.linspace(0.0, 0.4, 801)
    scale = (system.mu_s - system.mu_k) / slider.lam  # F -> mu: mu = F (mu_s - mu_k) / lambda
    ax.plot(v * 1e3, evaluate_bands(table, v / system.speed) * scale, color="black",
            label="law used by the engine (exact, piecewise linear)")
    data = np.loadtxt(curve, delimiter=",", skiprows=2)
    ax.plot(data[:, 0] * 1e3, data[:, 1], "o", color="tab:orange", label="measured points")
    ax.axhline(system.mu_s, color="0.5", ls=":", label=r"$\mu_s$ (stick)")
    ax.axvline(system.speed * 1e3, color="tab:blue", ls="--", label="belt speed V")
    ax.set_xlabel("sliding speed $v_r$ [mm/s]")
    ax.set_ylabel(r"friction coefficient $\mu$")
    ax.legend(fontsize=8)
    fig.savefig(out / "friction_law.png", dpi=130)

    # figure 2: the rigid base with the measured law, time history and phase portrait
    runs["rigid"].plot(t_start=300.0).savefig(out / "friction_rigid_run.png")
    runs["stability"].plot(t_start=0.0).savefig(out / "friction_stability_run.png")

    # figure 3: where does it stick-slip? the law fixed, lambda (the normal load) and zeta swept
    n_lam, n_zeta = (16, 8) if args.quick else (80, 40)
    lams = np.geomspace(0.1, 20.0, n_lam)
    zetas = np.linspace(0.005, 0.4, n_zeta)
    fig = Figure(figsize=(12.0, 4.6), layout="constrained")
    axes = fig.subplots(1, 2)
    for ax_i, (title, law) in zip(axes, [("Coulomb law (the paper)", None),
                                         ("measured curve", slider.friction)], strict=True):
        result = occurrence_map(lams, zetas, "optimal", slider.gamma, friction=law)
        result.plot(ax=ax_i, title=f"optimal foundation, {title}", legend=ax_i is axes[0],
                    analytic=law is None)  # the closed forms hold for the Coulomb law only
        print(f"map ({title}): {result.counts}")
    fig.savefig(out / "friction_map.png", dpi=130)
    print(f"figures written to {out}")


if __name__ == "__main__":
    main()
