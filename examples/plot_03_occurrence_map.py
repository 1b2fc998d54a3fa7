"""
An occurrence map on a small grid
=================================

:func:`stickslip.occurrence_map` gives a certified verdict for every cell of a
``lambda x zeta`` grid (here the optimally tuned foundation of Eqs. 28-30, as in the paper's
Fig. 8b, on a coarse grid so that it runs in seconds).
"""

import matplotlib.pyplot as plt
import numpy as np

from stickslip import occurrence_map

lams = np.geomspace(0.5, 30.0, 24)
zetas = np.linspace(0.02, 0.4, 12)
result = occurrence_map(lams, zetas, "optimal")
print(result.dataset)

# %%
# The map with the analytic boundaries of the paper.
fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
result.plot(ax=ax)
plt.show()
