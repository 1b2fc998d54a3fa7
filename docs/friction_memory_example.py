"""The worked examples of docs/friction_memory.md: LuGre stick-slip, a velocity step, Rice-Ruina, a map.

Run it from the repository root (it writes the figures next to this file and prints every
number the page quotes):

    .venv/bin/python docs/friction_memory_example.py [--out docs/figures]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from stickslip.analysis.memory import hopf_stiffness, rice_ruina_critical_stiffness, simulate_memory
from stickslip.model.state_friction import (
    LuGreFriction,
    MemorySystem,
    RateStateFriction,
    SpeedSchedule,
)


def canudas_de_wit(out: Path) -> None:
    """Canudas de Wit et al. (1995): m = 1 kg, k = 2 N/m, V = 0.1 m/s, the slider starting stuck."""
    law = LuGreFriction(sigma0=1e5, sigma1=math.sqrt(1e5), sigma2=0.4, mu_c=1.0, mu_s=1.5,
                        stribeck_velocity=1e-3)
    system = MemorySystem(np.array([[1.0]]), np.array([[0.0]]), np.array([[2.0]]), 0, 1.0, law,
                          SpeedSchedule.constant(0.1))
    times = np.linspace(0.0, 30.0, 3001)
    result = simulate_memory(system, kick=-1.0, t_max=60.0, history_times=times)
    assert result.orbit is not None and result.history is not None
    print(f"LuGre (Canudas de Wit 1995): {result.verdict.value}, period {result.period:.5f} s, "
          f"amplitude {result.amplitude:.5f} m, shooting residual {result.orbit.residual:.1e}, "
          f"Floquet multipliers {[f'{abs(m):.1e}' for m in result.orbit.multipliers]}, "
          f"trivial {result.orbit.trivial_multiplier.real:.8f}")
    h = result.history
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    ax1.plot(h["t_s"], h["v_m_s"])
    ax1.axhline(0.1, color="0.6", lw=0.8, ls="--")
    ax1.set_ylabel("slider velocity (m/s)")
    ax2.plot(h["t_s"], np.asarray(h["mu"]) * 1.0)
    ax2.set_ylabel("friction force (N)")
    ax2.set_xlabel("time (s)")
    fig.suptitle("LuGre stick-slip, Canudas de Wit et al. (1995)")
    fig.savefig(out / "memory_lugre_stick_slip.png", dpi=120)
    plt.close(fig)


def lugre_limit() -> None:
    """LuGre's periods as sigma0 grows (sigma1 = sqrt(sigma0)) and the limit law with a true stick.

    The limit runs on the exact engine: the Stribeck law ``F_c + (F_s - F_c) exp(-(v/v_s)^2) +
    sigma2 v`` (n = 2, viscous 0.4 s/m with W = 1 N), interpolated to 1e-6.
    """
    from stickslip import PhysicalSystem, simulate
    from stickslip.model.physical import PhysicalFriction

    periods = []
    for sigma0 in (1e5, 1e6, 1e7):
        law = LuGreFriction(sigma0=sigma0, sigma1=math.sqrt(sigma0), sigma2=0.4, mu_c=1.0, mu_s=1.5,
                            stribeck_velocity=1e-3)
        system = MemorySystem(np.array([[1.0]]), np.array([[0.0]]), np.array([[2.0]]), 0, 1.0, law,
                              SpeedSchedule.constant(0.1))
        periods.append(f"{simulate_memory(system, kick=-1.0, t_max=60.0).period:.6f}")
    limit = PhysicalSystem(mass=1.0, stiffness=2.0, damping=0.0, mu_s=1.5, mu_k=1.0, load=1.0,
                           speed=0.1, friction=PhysicalFriction("stribeck", stribeck_velocity=1e-3,
                                                                exponent=2.0, viscous=0.4,
                                                                tolerance=1e-6))
    run = simulate(limit.structure(), limit.slider())
    print(f"LuGre periods at sigma0 = 1e5, 1e6, 1e7 N/m: {', '.join(periods)} s; the limit law "
          f"(exact engine): {run.verdict.value}, period {run.period * limit.time_scale:.6f} s")


def gu_rice_ruina() -> None:
    """Gu, Rice, Ruina and Tse (1984): the spring-slider with inertia at k = 0.8 k_c, both laws."""
    a, b, d_c, load, speed = 0.01, 0.015, 1e-5, 1.0, 1e-6
    k = 0.8 * rice_ruina_critical_stiffness(load, a, b, d_c, 1.0, speed)
    for evolution in ("aging", "slip"):
        law = RateStateFriction(a=a, b=b, d_c=d_c, mu_ref=0.6, v_ref=1e-6, evolution=evolution)
        system = MemorySystem(np.array([[1.0]]), np.array([[0.0]]), np.array([[k]]), 0, load, law,
                              SpeedSchedule.constant(speed))
        result = simulate_memory(system, kick=0.5)
        multipliers = [] if result.orbit is None else [f"{abs(m):.2g}" for m in result.orbit.multipliers]
        print(f"Gu-Rice-Ruina, {evolution} law, k = 0.8 k_c: {result.verdict.value}, period "
              f"{result.period:.3f} s, nontrivial multipliers {multipliers}")


def velocity_step(out: Path) -> None:
    """The quasi-static slider through a tenfold load-point velocity step (aging law)."""
    a, b, d_c = 0.01, 0.008, 10e-6
    law = RateStateFriction(a=a, b=b, d_c=d_c, mu_ref=0.6, v_ref=1e-6)
    system = MemorySystem(np.zeros((1, 1)), np.zeros((1, 1)), np.array([[1e7]]), 0, 1e3, law,
                          SpeedSchedule((0.0, 10.0), (1e-6, 1e-5)))
    times = np.linspace(0.0, 20.0, 2001)
    result = simulate_memory(system, t_max=20.0, history_times=times)
    assert result.history is not None
    h = result.history
    mu = np.asarray(h["mu"])
    slip = 1e-6 * 10.0 + (np.asarray(h["t_s"]) - 10.0) * 1e-5  # load-point displacement (m)
    print(f"velocity step 1 -> 10 um/s: peak mu {mu.max():.5f} (mu_0 + a ln 10 = "
          f"{0.6 + a * math.log(10):.5f} for an infinitely stiff machine), final mu "
          f"{mu[-1]:.5f} (mu_ss = {0.6 + (a - b) * math.log(10):.5f})")
    fig, ax = plt.subplots(figsize=(7, 3.5))
    after = np.asarray(h["t_s"]) >= 9.0
    ax.plot((slip[after] - 1e-5) * 1e6, mu[after])
    ax.axhline(0.6 + a * math.log(10), color="0.6", lw=0.8, ls="--", label="mu_0 + a ln 10")
    ax.axhline(0.6 + (a - b) * math.log(10), color="0.3", lw=0.8, ls=":",
               label="mu_0 + (a - b) ln 10")
    ax.set_xlabel("load-point displacement after the step (um)")
    ax.set_ylabel("mu")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "memory_velocity_step.png", dpi=120)
    plt.close(fig)


def rice_ruina(out: Path) -> None:
    """The Hopf stiffness from the eigenvalues against Rice and Ruina's closed form."""
    a, b, d_c, load = 0.01, 0.015, 1e-5, 10.0
    law = RateStateFriction(a=a, b=b, d_c=d_c, mu_ref=0.6, v_ref=1e-6)
    speeds = np.geomspace(1e-6, 1e-2, 9)
    found, closed = [], []
    for v in speeds:
        k_c = rice_ruina_critical_stiffness(load, a, b, d_c, 1.0, v)
        system = MemorySystem(np.array([[1.0]]), np.array([[0.0]]), np.array([[k_c / 3.0]]), 0,
                              load, law, SpeedSchedule.constant(float(v)))
        found.append(hopf_stiffness(system) * k_c / 3.0)
        closed.append(k_c)
        print(f"V = {v:.1e} m/s: k_c from the eigenvalues {found[-1]:.10g} N/m, "
              f"Rice-Ruina {k_c:.10g} N/m")
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.loglog(speeds, closed, "-", label="Rice & Ruina (1983)")
    ax.loglog(speeds, found, "o", label="eigenvalues of the linearisation")
    ax.set_xlabel("load-point speed V (m/s)")
    ax.set_ylabel("critical stiffness k_c (N/m)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "memory_rice_ruina.png", dpi=120)
    plt.close(fig)


def stability_map(out: Path) -> None:
    """The growth-rate map of the rate-and-state slider of the stability section, its critical speed."""
    from stickslip.analysis.memory import memory_stability, rice_ruina_critical_speed
    from stickslip.sweep.memory.maps import memory_stability_map

    law = RateStateFriction(a=0.01, b=0.015, d_c=1e-5, mu_ref=0.6, v_ref=1e-6)
    system = MemorySystem(np.array([[1.0]]), np.array([[0.0]]), np.array([[8000.0]]), 0, 10.0,
                          law, SpeedSchedule.constant(1e-3))
    result = memory_stability(system)
    print(f"stability map slider: {result.verdict}, critical speeds {result.critical_speeds} m/s, "
          f"closed form {rice_ruina_critical_speed(system)!r} m/s")
    data = memory_stability_map(system, 1e-3 * np.logspace(-1.0, 1.0, 61),
                                10.0 * np.logspace(-1.0, 1.0, 41))
    data.plot().savefig(out / "memory_stability_map.png")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "figures")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    canudas_de_wit(args.out)
    lugre_limit()
    velocity_step(args.out)
    rice_ruina(args.out)
    gu_rice_ruina()
    stability_map(args.out)


if __name__ == "__main__":
    main()
