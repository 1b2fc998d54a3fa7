"""
Tutorial: from a stick-slip verdict to a tuned foundation
==========================================================

A slider on a moving belt, held by a spring and damper (``zeta = 0.1``), stick-slips when the
friction drop ``lambda`` is above the boundary of Eq. (36). An elastic foundation tuned as a
dynamic vibration absorber moves that boundary. This tutorial is also a downloadable notebook.
"""

# %%
# The rigid base: certified stick-slip
# ------------------------------------
# :func:`stickslip.simulate` runs the exact engine from the start-up state and returns a
# certified verdict with what proves it.
import matplotlib.pyplot as plt

from stickslip import (
    Slider,
    critical_lambda_exact,
    elastic_foundation,
    optimal_foundation_fit,
    rigid_base,
    simulate,
)

zeta = 0.1
print(f"Eq. (36): stick-slip above lambda = {critical_lambda_exact(zeta):.4f}")
rigid = simulate(rigid_base(zeta), Slider(3.0))
print(rigid.verdict, "|", rigid.certificate)
print(f"period {rigid.period:.3f}, amplitude {rigid.amplitude:.3f}")

# %%
# Just below the boundary the slider slides steadily, and the verdict says so with a
# Lyapunov certificate.
below = simulate(rigid_base(zeta), Slider(0.99 * critical_lambda_exact(zeta)))
print(below.verdict, "|", below.certificate)

# %%
# The tuned foundation
# --------------------
# Eqs. (28)-(30) give the foundation (``M``, ``K``, ``zeta_a``) that minimises the peak of the
# slider's frequency response; on it the same slider slides steadily.
foundation = optimal_foundation_fit(zeta)
tuned = simulate(elastic_foundation(zeta, foundation), Slider(3.0))
print(foundation)
print(tuned.verdict, "|", tuned.certificate)

# %%
# Displacement, velocity and phase portrait of both runs: ``.plot()`` draws into the three
# axes given (one row per run).
fig, axes = plt.subplots(2, 3, figsize=(11, 6), layout="constrained")
rigid.plot(ax=axes[0])
tuned.plot(ax=axes[1])
axes[0, 0].set_title("rigid base, lambda = 3")
axes[1, 0].set_title("optimal foundation, lambda = 3")
plt.show()
