"""Machines in SI shared by tests and benchmarks."""

from __future__ import annotations

import numpy as np

from stickslip.model.machine import Machine


def grounded_chain_machine(n_dof: int) -> Machine:
    """A grounded chain of ``n_dof - 1`` nodes with a slider on its middle node (SI).

    Nodes of 5 kg, 2e7 N/m to ground and 1e8 N/m between neighbours; the slider (1 kg, the last
    DOF, the contact) on a 1e6 N/m spring with a 40 N s/m dashpot; stiffness-proportional
    damping 2e-5 K; mu_s = 0.5, mu_k = 0.3, 1000 N at 0.2 m/s. At 60 DOF it stick-slips with
    a period of 6.61 ms (an independent audit's structure, made for the proofs of large
    structures: benchmarks/bench_cycle_proof.py and tests/test_cycle_proof.py).
    """
    nodes = n_dof - 1
    mass = np.diag(np.append(np.full(nodes, 5.0), 1.0))
    stiffness = np.zeros((n_dof, n_dof))
    for i in range(nodes):
        stiffness[i, i] += 2e7
    for i in range(nodes - 1):
        stiffness[i:i + 2, i:i + 2] += 1e8 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    slider, node = nodes, nodes // 2
    pair = np.ix_([slider, node], [slider, node])
    stiffness[pair] += 1e6 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    damping = 2e-5 * stiffness
    damping[pair] += 40.0 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    return Machine(mass, damping, stiffness, slider, 0.5, 0.3, 1000.0, 0.2)
