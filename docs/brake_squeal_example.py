"""The worked example of docs/brake_squeal.md: complex-eigenvalue analysis of a brake pad.

    .venv/bin/python docs/brake_squeal_example.py [--out docs/figures]

The minimal model of Hoffmann et al. (2002) of examples/brake_pad: its root locus over mu,
the damped critical coefficient against the amount of damping for equal and unequal damping
of the two directions (the destabilising effect of damping), and a stability map over
(mu, speed) with a falling Stribeck law. Prints the numbers the page quotes.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from stickslip.analysis.contact import (
    FrictionCoupledSystem,
    complex_eigenvalue_analysis,
    coupled_system,
    critical_friction,
    hoffmann_critical_mu,
    hoffmann_stiffness,
    root_locus,
    stability_map,
)
from stickslip.model.contact import Contact
from stickslip.model.machine import Machine
from stickslip.model.physical import PhysicalFriction

MASS, KN = 0.1, 5.0e7
K = hoffmann_stiffness(6.5e7, 1.0e7, 3.0e7, 3 * math.pi / 4)
CONTACT = Contact(normal_dof=1, normal_stiffness=KN)


def machine(friction: PhysicalFriction | None = None) -> Machine:
    """examples/brake_pad/machine.toml as a Machine (damping 40 and 4 N s/m)."""
    return Machine(MASS * np.eye(2), np.diag([40.0, 4.0]), K, 0, 0.5, 0.4, 1000.0, 5.0,
                   friction or PhysicalFriction(), name="brake pad")


def damping_figure(out: Path) -> None:
    """Damped critical mu against the damping scale, for C = c diag(1, r)."""
    fig = Figure(figsize=(6.4, 4.4), layout="constrained")
    ax = fig.add_subplot()
    undamped = hoffmann_critical_mu(MASS, K, KN)
    scales = np.geomspace(0.5, 500.0, 9)
    for ratio, label in ((1.0, "equal (C proportional to M)"), (0.1, "normal / tangential = 0.1"),
                         (10.0, "normal / tangential = 10"), (0.0, "tangential only")):
        found = [critical_friction(FrictionCoupledSystem(MASS * np.eye(2), c * np.diag([1.0, ratio]),
                                                         K, 0, 1, normal_stiffness=KN, load=1e3),
                                   n_scan=80).mu for c in scales]
        mus = [math.nan if m is None else m for m in found]  # None: stable up to mu = 2
        ax.semilogx(scales, mus, "o-", label=label)
        print(f"ratio {ratio:g}: critical mu {', '.join(f'{m:.5g}' for m in mus)} "
              f"at c = {', '.join(f'{c:.3g}' for c in scales)} N s/m")
    ax.axhline(undamped, color="k", ls="--", label=f"undamped (coalescence) {undamped:.5g}")
    ax.set_xlabel("tangential damping c [N s/m]")
    ax.set_ylabel("critical friction coefficient")
    ax.legend(fontsize="small")
    fig.savefig(out / "brake_squeal_damping.png", dpi=110)


def main() -> None:
    """Write the three figures and print the quoted numbers."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "figures")
    out = parser.parse_args().out
    out.mkdir(parents=True, exist_ok=True)
    result = complex_eigenvalue_analysis(machine(), CONTACT)
    print(f"verdict {result.verdict}; critical mu {result.critical.mu:.8g}; undamped "
          f"{result.critical_undamped.mu:.8g} (closed form {hoffmann_critical_mu(MASS, K, KN):.8g})")
    for mode in result.modes():
        print(f"mode {mode['frequency_hz']:.6g} Hz, damping ratio {mode['damping_ratio']:.4g}")
    locus = root_locus(result.system, np.linspace(0.0, 0.5, 251))
    locus.plot(title="brake pad: eigenvalues against mu").savefig(out / "brake_squeal_locus.png")
    damping_figure(out)
    stribeck = machine(PhysicalFriction("stribeck", mu_0=0.5, stribeck_velocity=1.0, exponent=1.0))
    speeds = np.geomspace(0.1, 10.0, 31)
    systems = [coupled_system(stribeck, CONTACT, speed=float(v))[0] for v in speeds]
    grid = stability_map(systems, speeds, np.linspace(0.0, 0.5, 101), "speed [m/s]")
    grid.plot(log_y=True, title="Stribeck law: growth rate over (mu, speed)").savefig(
        out / "brake_squeal_map.png")
    for v in (0.1, 1.0, 10.0):
        system = coupled_system(stribeck, CONTACT, speed=v)[0]
        print(f"Stribeck, V = {v:g} m/s: slope {system.slope:.4g} s/m, critical mu "
              f"{critical_friction(system, n_scan=100).mu}")


if __name__ == "__main__":
    main()
