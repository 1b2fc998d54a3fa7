"""Write the 6-DOF machine-tool slideway of examples/slideway as Matrix Market files (SI).

A lumped model in the feed direction (x) of a table on a saddle on a bed, the table driven by
a ball screw and pushed over its lubricated ways (the frictional contact):

    DOF 0  bed                 1200 kg   on its levelling mounts to the floor   5.0e8 N/m
    DOF 1  saddle               350 kg   clamped to the bed                      2.0e8 N/m
    DOF 2  table (contact)      180 kg   on the saddle's ways (contact DOF)
    DOF 3  ball-screw nut        15 kg   table -- nut (nut housing)              1.5e8 N/m
    DOF 4  motor + screw (eq.)   40 kg   nut -- screw axial                      1.0e8 N/m,
                                         screw -- bed (axial bearing + servo)    5.0e7 N/m
    DOF 5  workpiece + fixture   90 kg   clamped to the table                    4.0e8 N/m

Damping: a dashpot on every element with 3 % of the element's critical damping,
``c = 0.06 sqrt(k m_e)`` with ``m_e`` the lighter of its two masses (non-proportional).
The values are plausible for a medium machining centre, not measured on one.

Run: python examples/slideway/make_matrices.py  (rewrites M.mtx, K.mtx, C.mtx here)
"""

from pathlib import Path

import numpy as np
import scipy.io
import scipy.sparse

MASSES = [1200.0, 350.0, 180.0, 15.0, 40.0, 90.0]
#: (DOF a, DOF b or None for the floor, stiffness N/m)
ELEMENTS = [(0, None, 5.0e8), (1, 0, 2.0e8), (2, 3, 1.5e8), (3, 4, 1.0e8), (4, 0, 5.0e7),
            (5, 2, 4.0e8)]
#: The table also rests on the saddle's ways: a soft coupling in x through the oil film
WAYS = (2, 1, 2.0e7)


def matrices() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mass, damping and stiffness, kg, N s/m, N/m."""
    n = len(MASSES)
    mass = np.diag(MASSES)
    stiffness = np.zeros((n, n))
    damping = np.zeros((n, n))
    for a, b, k in [*ELEMENTS, WAYS]:
        m_e = MASSES[a] if b is None else min(MASSES[a], MASSES[b])
        c = 0.06 * np.sqrt(k * m_e)
        for mat, value in ((stiffness, k), (damping, c)):
            mat[a, a] += value
            if b is not None:
                mat[b, b] += value
                mat[a, b] -= value
                mat[b, a] -= value
    return mass, damping, stiffness


if __name__ == "__main__":
    here = Path(__file__).parent
    m, c, k = matrices()
    for name, mat in (("M", m), ("C", c), ("K", k)):
        scipy.io.mmwrite(str(here / f"{name}.mtx"), scipy.sparse.coo_matrix(mat), symmetry="symmetric",
                         comment=f"slideway 6-DOF model, {name} in SI units (see make_matrices.py)")
