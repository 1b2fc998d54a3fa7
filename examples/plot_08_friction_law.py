"""
Velocity-dependent friction: a linear law and a Stribeck curve
==============================================================

Friction that weakens with the sliding speed destabilises steady sliding. A linear law stays
exact in the engine; a Stribeck law is integrated exactly on an interpolant within a stated
tolerance. Both are given to the slider (:class:`stickslip.Slider`, ``friction=``).
"""

import matplotlib.pyplot as plt

from stickslip import Slider, rigid_base, simulate
from stickslip.model.friction_input import parse_friction

structure = rigid_base(0.1)
for spec in ("coulomb", "linear:0.05", "stribeck:vs=1.05,n=6,viscous=0.5"):
    result = simulate(structure, Slider(1.0, friction=parse_friction(spec)))
    print(f"{spec:34s} {result.verdict!s:18s} growth rate {result.growth_rate:+.4f}")

# %%
# A light damping and a Stribeck law: the slider oscillates without ever sticking
# (verdict ``slip-oscillation``).
run = simulate(rigid_base(0.02), Slider(1.0, friction=parse_friction("stribeck:vs=1.05,n=6,viscous=0.5")))
print(run.verdict, "|", run.certificate)
fig, axes = plt.subplots(1, 3, figsize=(11, 3.8), layout="constrained")
run.plot(ax=axes)
plt.show()
