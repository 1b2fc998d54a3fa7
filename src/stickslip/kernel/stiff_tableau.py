"""The RODAS4 tableau: Hairer and Wanner's coefficients (rodas.f, METH = 1).

E. Hairer and G. Wanner, Solving Ordinary Differential Equations II, 2nd ed., Springer 1996,
Sec. IV.7, in the form of their code: ``A`` (stage points), ``C`` (stage couplings over ``h``),
``GAM`` (the diagonal), ``D`` (dense output). The method is stiffly accurate: the solution is
the last stage point plus the last stage, whose value is also the error estimate.
"""

from __future__ import annotations

import numpy as np

#: Stages.
STAGES = 6
GAM = 0.25
A21 = 1.544
A31 = 0.9466785280815826
A32 = 0.2557011698983284
A41 = 3.314825187068521
A42 = 2.896124015972201
A43 = 0.9986419139977817
A51 = 1.221224509226641
A52 = 6.019134481288629
A53 = 12.53708332932087
A54 = -0.6878860361058950
C21 = -5.6688
C31 = -2.430093356833875
C32 = -0.2063599157091915
C41 = -0.1073529058151375
C42 = -9.594562251023355
C43 = -20.47028614809616
C51 = 7.496443313967647
C52 = -10.24680431464352
C53 = -33.99990352819905
C54 = 11.70890893206160
C61 = 8.083246795921522
C62 = -7.981132988064893
C63 = -31.52159432874371
C64 = 16.31930543123136
C65 = -6.058818238834054
D21 = 10.12623508344586
D22 = -7.487995877610167
D23 = -34.80091861555747
D24 = -7.992771707568823
D25 = 1.025137723295662
D31 = -0.6762803392801253
D32 = 6.087714651680015
D33 = 16.43084320892478
D34 = 24.76722511418386
D35 = -6.594389125716872


#: The same coefficients as arrays, one row per stage ``s = 0..5`` for a loop over the stages:
#: stage ``s`` is evaluated at ``y + sum_j A_STAGE[s, j] k_j`` and its right-hand side is
#: ``f + sum_j C_STAGE[s, j] k_j / h`` (``j < s``); stage 6's point is stage 5's plus ``k_5``
#: (the method is stiffly accurate). The dense output's ``c3 = sum_j D2[j] k_j`` and
#: ``c4 = sum_j D3[j] k_j`` (``j < 5``).
A_STAGE = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [A21, 0.0, 0.0, 0.0, 0.0],
    [A31, A32, 0.0, 0.0, 0.0],
    [A41, A42, A43, 0.0, 0.0],
    [A51, A52, A53, A54, 0.0],
    [A51, A52, A53, A54, 1.0],
])
C_STAGE = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [C21, 0.0, 0.0, 0.0, 0.0],
    [C31, C32, 0.0, 0.0, 0.0],
    [C41, C42, C43, 0.0, 0.0],
    [C51, C52, C53, C54, 0.0],
    [C61, C62, C63, C64, C65],
])
D2 = np.array([D21, D22, D23, D24, D25])
D3 = np.array([D31, D32, D33, D34, D35])
