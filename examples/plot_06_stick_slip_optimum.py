"""
The foundation that is best against stick-slip itself
=====================================================

The absorber optimum minimises a frequency-response peak; it is not the foundation that keeps
stick-slip away longest. :func:`stickslip.optimal_foundation_stick_slip` maximises the
stick-slip onset ``lambda`` directly. The full search takes tens of seconds; this example runs
a short one (few iterations, ``lambda`` up to 20) and checks the result by simulation.
"""

import matplotlib.pyplot as plt

from stickslip import Slider, elastic_foundation, optimal_foundation_stick_slip, simulate

zeta = 0.1
best = optimal_foundation_stick_slip(zeta, lam_max=20.0, rtol=1e-3, maxiter=6)
print("stick-slip optimum:", best.foundation, f"onset lambda {best.lambda_crit:.3g}")
print("absorber optimum:  ", best.reference, f"onset lambda {best.reference_lambda_crit:.3g}")
# an onset of ``inf`` means no stick-slip up to ``lam_max`` (here 20)

# %%
# The two foundations at ``lambda = 10``.
lam = 10.0
absorber = simulate(elastic_foundation(zeta, best.reference), Slider(lam))
stick_slip_optimum = simulate(elastic_foundation(zeta, best.foundation), Slider(lam))
print("absorber optimum:", absorber.verdict, "| stick-slip optimum:", stick_slip_optimum.verdict)
fig, axes = plt.subplots(2, 3, figsize=(11, 6), layout="constrained")
absorber.plot(ax=axes[0])
stick_slip_optimum.plot(ax=axes[1])
axes[0, 0].set_title("absorber optimum")
axes[1, 0].set_title("stick-slip optimum")
plt.show()
