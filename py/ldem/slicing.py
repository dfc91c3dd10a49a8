"""The central slice of a specimen's bars: the one computation behind every
crack picture (ldem.plots draws it) and behind a study case's slice.npz
(ldem.io writes it)."""
from __future__ import annotations

import numpy as np

from . import parallel


def central_slice(sim, axis: int = 1):
    """Bars whose both ends lie within L0/2 of the mid-plane normal to axis (y by
    default), projected on the two other axes: (segments, damage states).
    Under MPI every rank calls it; rank 0 gets the whole slice, the others None."""
    lat = sim.lattice
    bars = lat.bar_table()
    n1, n2 = bars["n1"], bars["n2"]
    x = np.column_stack([lat.x0, lat.y0, lat.z0])
    mid = 0.5 * (x[:, axis].min() + x[:, axis].max())
    near = np.abs(x[:, axis] - mid) <= 0.5 * lat.L0 + 1e-12
    keep = near[n1] & near[n2]
    mine = parallel.owned(sim)  # split over MPI ranks (a cut normal to z): each rank's own bars, gathered
    keep[:mine.start] = False
    keep[mine.stop:] = False
    plane = [a for a in range(3) if a != axis]
    seg = np.stack([x[n1[keep]][:, plane], x[n2[keep]][:, plane]], axis=1)
    if parallel.split(sim):
        return parallel.gather_arrays([seg, sim.damage_state[keep]])  # None on ranks other than 0
    return seg, sim.damage_state[keep]
