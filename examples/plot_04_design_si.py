"""
The design procedure in SI units (Fig. 16)
==========================================

A machine described in kilograms, newtons and metres per second:
:func:`stickslip.design_foundation` turns it into the dimensionless ``lambda`` and ``zeta``,
decides with Eq. (38) whether stick-slip is expected, recommends the foundation of
Eqs. (28)-(30) in SI units and checks the verdicts by simulation. This 2 kg slider on a
50 kN/m spring stick-slips on its rigid base at a belt speed of 0.2 m/s; the recommended
foundation (about 3.8 kg on 48 kN/m) makes it slide steadily.
"""

import matplotlib.pyplot as plt

from stickslip import PhysicalSystem, design_foundation

machine = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0, speed=0.2)
report = design_foundation(machine)
print(f"lambda = {report.lam:.3f}, zeta = {report.zeta:.4f}, zeta_eq = {report.zeta_eq:.4f}")
print("recommended foundation (SI):", report.recommended)
for name, verdict in report.verdicts.items():
    print(name, verdict)

# %%
# The procedure of the paper's Fig. 16 with this machine's numbers.
fig, ax = plt.subplots(figsize=(9, 8), layout="constrained")
report.plot(ax=ax)
plt.show()
