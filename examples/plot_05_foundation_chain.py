"""
A chain of several foundation masses
====================================

:func:`stickslip.chain_structure` stacks foundation stages: the slider sits on the first mass,
each mass on the next, the last one anchored to the ground. Here a two-stage chain, the first
stage the absorber optimum of Eqs. (28)-(30), the second a heavy stiff base.
"""

import matplotlib.pyplot as plt

from stickslip import Foundation, Slider, chain_structure, optimal_foundation_fit, simulate

zeta = 0.1
chain = chain_structure(zeta, [optimal_foundation_fit(zeta), Foundation(10.0, 3.0, 0.5)])
print(chain.name, "mass matrix diagonal:", chain.mass.diagonal())
for lam in (2.0, 6.0):
    result = simulate(chain, Slider(lam))
    print(f"lambda = {lam}: {result.verdict} | {result.certificate}")

# %%
# The run at ``lambda = 6``: slider displacement, velocity and phase portrait.
fig, axes = plt.subplots(1, 3, figsize=(11, 3.8), layout="constrained")
result.plot(ax=axes)
plt.show()
