"""
The rigid-base boundary against Eq. (36)
========================================

:func:`stickslip.stick_slip_boundary` finds, for each damping ratio, the lowest ``lambda`` at
which the simulated verdict turns to stick-slip (every verdict change bracketed and bisected).
On the rigid base it must fall on Nakano's exact boundary, Eq. (36)
(:func:`stickslip.critical_lambda_exact`).
"""

import matplotlib.pyplot as plt
import numpy as np

from stickslip import critical_lambda_exact, stick_slip_boundary

zetas = np.array([0.02, 0.05, 0.1, 0.2, 0.3])
boundary = stick_slip_boundary(zetas, "none", lam_min=0.05, lam_max=20.0, n_scan=16, rtol=1e-6)
exact = np.array([critical_lambda_exact(z) for z in zetas])
for z, simulated, eq36 in zip(zetas, boundary.critical_lambda, exact, strict=True):
    print(f"zeta = {z:4.2f}: simulated {simulated:.6f}, Eq. (36) {eq36:.6f}, "
          f"relative difference {abs(simulated / eq36 - 1):.1e}")

# %%
# The boundary plot draws the simulated crossings with the closed forms of the paper.
fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
boundary.plot(ax=ax)
plt.show()
