"""
Tuning the foundation as a vibration absorber
=============================================

:func:`stickslip.tune_foundation` finds the exact foundation (``M``, ``K``, ``zeta_a``) that
minimises the peak of the slider's frequency response, next to the fitted Eqs. (28)-(31).
"""

import matplotlib.pyplot as plt

from stickslip import optimal_foundation_fit, peak_response_fit, tune_foundation

zeta = 0.1
tuning = tune_foundation(zeta)
fit = optimal_foundation_fit(zeta)
print("exact optimum:", tuning.foundation)
print("Eqs. (28)-(30):", fit)
print(f"H_max exact {tuning.h_max:.4f}, Eq. (31) {peak_response_fit(zeta):.4f}")

# %%
# The frequency response of the slider on the rigid base and on the tuned foundation.
fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
tuning.plot(ax=ax)
plt.show()
