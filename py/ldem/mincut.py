"""The cheapest cut of a cube specimen: a lower bound of its fracture energy.

The cheapest cut is the minimum, over all sets of bars whose removal
disconnects every node of the upper face from every node of the lower face,
of the sum of the bars' rupture energies. A specimen split into two pieces
has broken such a set of bars, and each broken bar has dissipated its rupture
energy, so the energy dissipated by the run can never be less than the
cheapest cut: U_num >= U_mincut. It is computed as a max-flow/min-cut, in
integers (pkg/ldem/MaxFlow.hpp).
"""
import numpy as np

from . import _core

# Capacities in units of the upper face's cut / 2**28: exact integers for the
# flow, and fine enough (3e-9 U_min a bar; an int64 flow would allow finer
# units, these keep the committed studies' cuts to the bit).
_UNITS = 2 ** 28


def _face_cut(e, n1, n2, top):
    """The energy of the cut around the upper face: a valid cut, so >= the cheapest."""
    return float(e[np.isin(n1, top) != np.isin(n2, top)].sum())


def cheapest_cut(sim):
    """The cheapest cut of `sim`'s specimen between its upper and lower faces, J.

    Capacities are integers in units u = C_top / 2**28 (C_top, the cut around
    the upper face, is >= C; u ~ 3e-9 U_min), each rounded down. So the result
    R is a lower bound: C - n u < R <= C, C the exact cheapest cut and n the
    number of bars of the cut found (n ~ 4 N^2 for N^2 modules a face).
    """
    bars = sim.lattice.bar_table()
    n1, n2 = np.asarray(bars["n1"], np.int64), np.asarray(bars["n2"], np.int64)
    e = np.asarray(sim.rupture_energy, np.float64)
    m = sim.measures
    top, bottom = np.asarray(sim.group(m["loaded"]), np.int64), np.asarray(sim.group(m["support"]), np.int64)
    if np.intersect1d(top, bottom).size:
        raise ValueError("a node is on both faces: no cut separates them")
    upper = _face_cut(e, n1, n2, top)
    if upper <= 0.0:
        return 0.0  # the upper face hangs by bars that dissipate nothing
    unit = upper / _UNITS  # exact: a power-of-two scaling
    # The face cut is _UNITS units at most, so an edge of more can never be in
    # a cheapest cut: capping there (in float: the int cast of a huge ratio
    # would wrap) changes nothing and keeps the sums small.
    cap = np.minimum(np.floor(e / unit), _UNITS + 1).astype(np.int64)
    return _core.max_flow(sim.lattice.n_nodes, n1, n2, cap, top, bottom) * unit
