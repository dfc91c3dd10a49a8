"""Curves of several specimens on one strain grid: their mean, and its peak."""
from __future__ import annotations

from typing import Sequence

import numpy as np


def mean_curve(curves: Sequence[dict], column: str, scale=1.0, after_end=None, n: int = 400, log_from=None,
               upto=None):
    """Mean of a curve column over specimens on a common mean-strain grid of n
    points (linear from 0, or geometric from log_from) up to the largest strain
    reached (or upto: a zoom's grid, fine enough for the peak). A specimen that stopped
    early carries on at after_end (0 for the stress of a separated specimen), or
    at its last value (the final fracture energy)."""
    top = max(c["mean_strain"][-1] for c in curves) if upto is None else upto
    grid = np.linspace(0.0, top, n) if log_from is None else np.geomspace(log_from, top, n)
    ys = [np.interp(grid, c["mean_strain"], c[column] * scale,
                    right=(c[column] * scale)[-1] if after_end is None else after_end) for c in curves]
    return grid, np.mean(ys, axis=0)


def mean_curve_peak(curves: Sequence[dict]) -> tuple:
    """(peak stress [MPa], its mean strain) of the specimens' mean stress-strain
    curve, on a grid finer than the records (about 1e-8 in strain) up to twice
    the largest strain at a specimen's own peak. Beyond it every specimen is
    past its own peak, and a later maximum of the mean would need specimens to
    harden again: the grid does not look for one. A grid up to the curves' ends
    (a separation strain, 1e2 to 1e3 times the peak's) was as coarse as the
    records and moved with where the last specimen separated."""
    top = 2 * max(c["mean_strain"][int(np.argmax(c["stress_MPa"]))] for c in curves)
    grid, stress = mean_curve(curves, "stress_MPa", after_end=0.0, n=20001, upto=top)
    i = int(np.argmax(stress))
    return float(stress[i]), float(grid[i])
