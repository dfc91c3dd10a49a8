"""Where the cube's highest mode lives, and what raising the light nodes' masses would give.

The time step is a fraction of 2/omega_max. If omega_max were a mode of a few light
nodes (the corners carry 1/8 of an interior node's mass, the edges 1/4, the faces 1/2),
giving them more mass (selective mass scaling) would lengthen the step. This builds the
undamaged stiffness K of the cubic lattice (k = EA/L on n n^T per bar, the bar table's
EA, which carries the bar's share), solves the largest eigenvalue of M^-1/2 K M^-1/2, and
prints omega_max, the mode's energy per mass class of the free nodes, and omega_max with
every node's mass raised to at least a floor (a fraction of the heaviest node's), for the
cube free and with its loaded faces clamped (the study's uniform test).

    python3 dev/highest_mode.py [--modules 6,12]
"""
import argparse

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

import ldem._core as core

FLOORS = (0.25, 0.5, 1.0)


def stiffness(lat) -> sp.csr_matrix:
    t = lat.bar_table()
    x = np.stack([np.asarray(lat.x0), np.asarray(lat.y0), np.asarray(lat.z0)], 1)
    a, b = np.asarray(t["n1"]), np.asarray(t["n2"])
    d = x[b] - x[a]
    n = d / np.linalg.norm(d, axis=1)[:, None]
    k = np.asarray(t["EA"]) / np.asarray(t["length"])
    rows, cols, vals = [], [], []
    for i, j, sign in ((a, a, 1), (b, b, 1), (a, b, -1), (b, a, -1)):
        for p in range(3):
            for q in range(3):
                rows.append(3 * i + p), cols.append(3 * j + q), vals.append(sign * k * n[:, p] * n[:, q])
    size = 3 * lat.n_nodes
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(size, size))


def highest(K, mass, free):
    """omega_max and its mode (per DOF, 0 on held DOFs) for nodal masses `mass`."""
    scale = sp.diags(np.repeat(1 / np.sqrt(mass), 3))
    A = (scale @ K @ scale)[free][:, free]
    w, v = sla.eigsh(A, k=1, which="LA")
    mode = np.zeros(K.shape[0])
    mode[free] = v[:, 0]
    return np.sqrt(w[0]), mode


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--modules", default="6,12", help="modules along each edge, comma-separated")
    args = ap.parse_args()
    print("| modules | faces | omega_max [rad/s] (core's) | mode energy: corners, edges, faces, interior | "
          + " | ".join(f"floor {f:g}" for f in FLOORS) + " |")
    print("|---|---|---|---|" + "---|" * len(FLOORS))
    for n in (int(s) for s in args.modules.split(",")):
        lat = core.build_cubic_lattice(n, n, n, 0.02, core.Material())
        K, mass = stiffness(lat), np.asarray(lat.mass)
        z = np.asarray(lat.z0)
        clamped = np.isclose(z, z.min()) | np.isclose(z, z.max())
        relative = np.round(mass / mass.max(), 4)
        for name, held in (("free", np.zeros_like(clamped)), ("clamped", clamped)):
            free = ~np.repeat(held, 3)
            w, mode = highest(K, mass, free)
            reference = core.lattice_frequencies(lat, [7 if h else 0 for h in held])[1]
            energy = (mode.reshape(-1, 3) ** 2).sum(1)
            shares = [energy[np.isclose(relative, c) & ~held].sum() for c in (0.125, 0.25, 0.5, 1.0)]
            ratios = [w / highest(K, np.maximum(mass, f * mass.max()), free)[0] for f in FLOORS]
            print(f"| {n}^3 | {name} | {w:,.0f} ({reference:,.0f}) | " + ", ".join(f"{s:.2f}" for s in shares)
                  + " | " + " | ".join(f"{r:.3f}" for r in ratios) + " |")


if __name__ == "__main__":
    main()
