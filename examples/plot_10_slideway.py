"""
Your machine: a machine-tool slideway from its matrices to its absorber
=======================================================================

A table slides on the lubricated ways of a saddle, the saddle sits on a bed, a ball screw
pushes the table (``examples/slideway/make_matrices.py``: 6 degrees of freedom in the feed
direction, the matrices in Matrix Market files as a finite-element program exports them).
The friction contact is the table, DOF 2, in the middle of the structure. Everything here is
what ``stickslip simulate --config``, ``stickslip design --config``, ``stickslip tune --config``
and ``stickslip map --config`` print, in SI (the machine file is described in the
user guide's structures page, ``docs/structures.md``).
"""

# %%
# The machine file and its modes
# ------------------------------
# ``machine.toml`` names the three matrices, the contact DOF, the friction coefficients, the
# load on the ways and the feed speed, and an absorber mass to tune. The dimensionless groups
# are those of the contact DOF: ``m_ref = M[2, 2]``, ``k_ref = K[2, 2]``.
from pathlib import Path

import matplotlib.pyplot as plt

from stickslip import simulate
from stickslip.analysis.machine_absorber import CriticalPoint, tune_machine_absorber, with_absorber
from stickslip.io.machine_file import machine_from_file, read_machine_file
from stickslip.plot.operating import machine_modes_plot
from stickslip.sweep.grid import Axis
from stickslip.sweep.operating_map import operating_map

here = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
machine_file = read_machine_file(here / "slideway" / "machine.toml")
machine, _ = machine_from_file(machine_file, {"mu_s": 0.15, "mu_k": 0.10, "load": 2600.0,
                                              "speed": 0.5e-3})
print(machine.summary())
print("natural frequencies [Hz]:", ", ".join(f"{f:.1f}" for f in machine.natural_frequencies_hz()))
# the library draws on matplotlib Figures of its own; give it pyplot axes to show them here
_, mode_axes = plt.subplots(2, 3, figsize=(9.6, 5.2), layout="constrained")
machine_modes_plot(machine, ax=mode_axes)
plt.show()

# %%
# One run at the feed speed
# -------------------------
# The exact engine runs the dimensionless structure; the answers come back in seconds and
# metres through ``tau = omega_n t`` and displacements in units of ``V / omega_n``.
structure, slider = machine.to_dimensionless()
run = simulate(structure, slider)
ref = machine.reference_system()
print(run.verdict, "|", run.certificate)
print(f"period {run.period * ref.time_scale * 1e3:.2f} ms, amplitude "
      f"{run.amplitude * ref.length_scale * 1e6:.2f} um (half peak-to-peak at the table)")

# %%
# The critical speed, and the absorber that moves it
# --------------------------------------------------
# The critical feed speed is where a scan from high feed speeds down (steps of 25 % in
# ``lambda``, then bisected) first meets stick-slip (above the critical load). A 10 kg
# absorber on the table, tuned to the smallest peak receptance at the contact (the paper's
# H-infinity criterion on this structure), moves the onset: the critical speed drops (from
# about 0.77 to 0.60 mm/s) and the critical load rises (from about 1680 to 2170 N). A
# change of verdict narrower than the scan's step can be stepped over: from start-up, the
# tuned table also stick-slips between about 0.745 and 0.766 mm/s, and the bare one at
# 0.93-1.02 mm/s, and slides steadily at 0.61-0.66 mm/s (the boundary search at the end of
# this example; ``stickslip boundary --config machine.toml --range "0.5 mm/s:2 mm/s"
# --scan 41``). At this feed of 0.5 mm/s and 2600 N the table still stick-slips
# (the run below proves its cycle), and the map shows how far the feed or the load must move
# (or ``stickslip tune --config machine.toml --objective stick-slip`` searches the absorber
# for the critical speed directly).
bare = CriticalPoint.of(machine)
(hinf,) = tune_machine_absorber(machine, 10.0, 2, stick_slip=False)
print(f"bare machine:  stick-slip below V_c = {bare.speed * 1e3:.3f} mm/s "
      f"(at W = 2600 N; above W_c = {bare.load:.0f} N at 0.5 mm/s)")
print(f"with absorber: k_a = {hinf.stiffness:.3g} N/m, c_a = {hinf.damping:.3g} N s/m, "
      f"stick-slip below V_c = {hinf.critical.speed * 1e3:.3f} mm/s (W_c = {hinf.critical.load:.0f} N)")
tuned = with_absorber(machine, hinf.mass, hinf.stiffness, hinf.damping, 2)
print(f"at the feed speed with the absorber: {simulate(*tuned.to_dimensionless(), record=False).verdict}")

# %%
# Where it stick-slips: feed speed and load
# -----------------------------------------
# ``stickslip map --config machine.toml --speed log:... --load ...`` gives this map: each cell
# is a certified run with ``lambda = (mu_s - mu_k) W / (V sqrt(m_ref k_ref))``; the line is
# the onset ``lambda_c`` of the bare machine.
vw = operating_map(machine, Axis.parse("log:2e-4:5e-3:10", "speed"),
                   Axis.parse("log:500:5000:8", "load"))
print(vw.summary())
_, map_ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
vw.plot(critical_lambda=bare.lam, ax=map_ax)
plt.show()

# %%
# Every change of verdict along the feed speed
# --------------------------------------------
# The onset above is the first change only. The boundary search runs the bare table at 41
# feed speeds from 0.5 to 2 mm/s and bisects every change it brackets (to 0.1 %): five
# changes, so windows of steady sliding and of stick-slip alternate below 1.02 mm/s.
from stickslip.analysis.contact.boundary import contact_boundary  # noqa: E402

changes = contact_boundary(machine, "speed", 0.5e-3, 2e-3, n_scan=41)
for c in changes.crossings:
    print(f"{c.bracket[0] * 1e3:.4f}-{c.bracket[1] * 1e3:.4f} mm/s: {c.below.value} below, "
          f"{c.above.value} above")
