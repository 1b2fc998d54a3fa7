"""Write the two laboratory records the identification examples fit (seeded, reproducible).

    .venv/bin/python examples/friction_memory/make_records.py

* ``velocity_steps.csv``: a velocity-step test of rate-and-state friction (aging law,
  a = 0.01, b = 0.008, d_c = 10 um, mu_ref = 0.6 at v_ref = 1 um/s), machine stiffness
  1e7 N/m, normal load 1 kN, load point at 1, 10 and 1 um/s (steps at 10 s and 20 s),
  801 samples over 40 s, noise 1e-4 in mu.
* ``lugre_sine.csv``: a LuGre contact (sigma0 = 1e5 N/m, sigma1 = 316 N s/m, sigma2 = 0.4
  N s/m, F_c = 1 N, F_s = 1.5 N, v_s = 1 mm/s) driven at 1 cm/s amplitude, 1 Hz, for 2 s,
  4001 samples, noise 0.5 % of F_s in the force.

Both come from the package's own forward models (the ones the fits invert), so the fits must
return these values within their standard errors.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from stickslip.analysis.identification.lugre_fit import model_force
from stickslip.analysis.identification.rate_state_fit import model_mu
from stickslip.model.state_friction import RateStateFriction, SpeedSchedule

HERE = Path(__file__).resolve().parent


def main() -> None:
    rng = np.random.default_rng(2026)
    t = np.linspace(0.0, 40.0, 801)
    x = np.where(t < 10.0, 1e-6 * t, np.where(t < 20.0, 1e-5 + 1e-5 * (t - 10.0),
                                              1.1e-4 + 1e-6 * (t - 20.0)))
    law = RateStateFriction(a=0.01, b=0.008, d_c=10e-6, mu_ref=0.6, v_ref=1e-6, evolution="aging")
    mu = model_mu(t, SpeedSchedule((0.0, 10.0, 20.0), (1e-6, 1e-5, 1e-6)), 1e7, 1e3, law)
    mu = mu + 1e-4 * rng.normal(size=t.size)
    rows = "".join(f"{a:.6f},{b:.12e},{c:.8f}\n" for a, b, c in zip(t, x, mu, strict=True))
    (HERE / "velocity_steps.csv").write_text("t [s],x_lp [m],mu\n" + rows, encoding="utf-8")
    t = np.linspace(0.0, 2.0, 4001)
    v = 1e-2 * np.sin(2.0 * np.pi * t)
    force = model_force(t, v, 0.0, (1e5, 316.0, 0.4, 1.0, 1.5, 1e-3))
    force = force + 0.005 * 1.5 * rng.normal(size=t.size)
    rows = "".join(f"{a:.6f},{b:.10e},{c:.8f}\n" for a, b, c in zip(t, v, force, strict=True))
    (HERE / "lugre_sine.csv").write_text("t [s],v [m/s],F [N]\n" + rows, encoding="utf-8")


if __name__ == "__main__":
    main()
