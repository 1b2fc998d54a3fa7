"""
Basin stability of a bistable slider
====================================

Above the boundary of Eq. (36) steady sliding stays stable and a stick-slip cycle exists beside
it. :func:`stickslip.sweep.basin.basin_stability` gives a certified verdict to every state of a
sample of disturbed starts; the fractions estimate how likely a knock is to start stick-slip.
"""

import matplotlib.pyplot as plt

from stickslip import Slider, critical_lambda_exact, rigid_base
from stickslip.sweep import basin_stability, sample_box

zeta = 0.1
structure, slider = rigid_base(zeta), Slider(1.5 * critical_lambda_exact(zeta))
states = sample_box(structure, slider, 3000, {"xi": (-6.0, 6.0), "v": (-4.0, 1.5)}, seed=1)
basin = basin_stability(structure, slider, states)
fractions, errors = basin.fractions, basin.standard_errors
for name, value in fractions.items():
    print(f"{name:16s} {value:.3f} +- {errors[name]:.3f}")

# %%
# Each sampled start coloured by its verdict, with the certified safe region.
fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
basin.plot(ax=ax, marker_size=3.0)
plt.show()
