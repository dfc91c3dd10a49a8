"""A run split over MPI ranks (`mpirun -np P ldem cube ...`): each rank holds
a slab of module layers along z (pkg/ldem/Slab.hpp) and the files are written
so that the results do not depend on P: curve.csv, summary.json and the
pictures by rank 0, the bars as a parallel VTK file (bars.pvtu, one piece
bars_pN.vtu per rank, each with the bars that rank owns, in the whole
lattice's order). Without mpirun everything here is the one-process case."""
from __future__ import annotations

import io as _bytes_io
import os
from typing import List

import numpy as np

from . import _core


def rank() -> int:
    return _core.mpi_rank()


def ranks() -> int:
    return _core.mpi_ranks()


def is_root() -> bool:
    return _core.mpi_rank() == 0


def split(sim) -> bool:
    """Whether sim is a slab of a lattice split over ranks."""
    return sim.lattice.is_slab


def gather_arrays(arrays: List[np.ndarray]) -> List[np.ndarray]:
    """Each array concatenated over the ranks in rank order, on rank 0 (None
    elsewhere); small data only (the crack picture's slice)."""
    buf = _bytes_io.BytesIO()
    np.savez(buf, *arrays)
    pieces = _core.mpi_gather_bytes(buf.getvalue())
    if not is_root():
        return None
    loaded = [np.load(_bytes_io.BytesIO(p)) for p in pieces]
    return [np.concatenate([z[f"arr_{k}"] for z in loaded]) for k in range(len(arrays))]


def owned(sim):
    """The slice of sim's bar arrays that this rank owns (all of them in one process)."""
    first, end = sim.lattice.owned_bars
    return slice(first, end)


def piece_name(path: str, r: int) -> str:
    """bars.vtu -> bars_p3.vtu: rank r's piece of a parallel file."""
    stem, _ = os.path.splitext(path)
    return f"{stem}_p{r}.vtu"
