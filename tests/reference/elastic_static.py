"""The static elastic response of the finite lattice cube on rollers, by the
reference (ldem_ref.py's stiffness matrix, a direct solve): the expected
values of tests/cpp/test_elastic.cpp.

    /usr/bin/python3 tests/reference/elastic_static.py [4 6 8]

The cube of n^3 modules (L0 = 0.02 m, Table 2's material): lower face z held,
in-plane rigid motion removed by holding x, y of the corner (0, 0, 0) and y of
(n, 0, 0) (statically determinate: no effect on strains or stresses), upper face
z = eps H, x and y free. Prints E_app / E (the mean of the two face stresses
over eps) and nu from the mid-height corner nodes (k = n/2), as the test measures.
"""
import os
import sys

import numpy as np
import scipy.linalg

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ldem_ref as R  # noqa: E402


def static_rollers(n, L0=0.02, eps=2e-5):
    mat = R.Material()
    lat = R.Lattice(n, n, n, L0, mat)
    K, N, H, W, X = lat.stiffness(), lat.n_nodes, n * L0, n * L0, lat.X
    bottom = np.flatnonzero(np.abs(X[:, 2]) < 1e-9 * L0)
    top = np.flatnonzero(np.abs(X[:, 2] - H) < 1e-9 * L0)
    presc, val = np.zeros((N, 3), bool), np.zeros((N, 3))
    presc[bottom, 2] = presc[top, 2] = True
    val[top, 2] = eps * H
    c00, cn0 = lat.index[("c", 0, 0, 0)], lat.index[("c", n, 0, 0)]
    presc[c00, 0] = presc[c00, 1] = presc[cn0, 1] = True
    p = presc.reshape(-1)
    f = ~p
    u = val.reshape(-1).copy()
    u[f] = scipy.linalg.solve(K[np.ix_(f, f)], -K[np.ix_(f, p)] @ u[p], assume_a="sym")
    F = (K @ u).reshape(N, 3)       # the force the supports apply
    stress = 0.5 * (-F[bottom, 2].sum() + F[top, 2].sum()) / (W * W)
    U, k = u.reshape(N, 3), n // 2
    ex = np.mean([(U[lat.index[("c", n, j, k)], 0] - U[lat.index[("c", 0, j, k)], 0]) / W for j in range(n + 1)])
    return stress / eps / mat.E, -ex / eps


if __name__ == "__main__":
    for n in [int(a) for a in sys.argv[1:]] or [4, 6, 8]:
        E, nu = static_rollers(n)
        print(f"{n}^3: E_app/E = {E!r}, nu = {nu!r}")
