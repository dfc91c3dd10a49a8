"""ParaView's files of a run: bars.vtu (every bar at its reference position,
the displacements as a point vector), crack.vtu (the broken bars), the series
bars_NNNN.vtu / crack_NNNN.vtu with their collections bars.pvd / crack.pvd,
and under MPI the pieces with their .pvtu. Registers the writer "vtk"."""
from __future__ import annotations

import os
from typing import List

import numpy as np

from .. import parallel
from .files import atomic
from .registry import register_writer


def bar_arrays(sim) -> dict:
    """Per bar: damage_state (0 undamaged, 1 damaged, 2 broken), damage
    (kappa/eps_r), the law's state through its interface (sim.law_state(): every
    law's kappa and eps_r, and its own, e.g. the bilinear law's eps_k), strain,
    force [N], G_f, kind."""
    law = sim.law_state()
    return {"damage_state": sim.damage_state.astype(np.int32),
            "damage": np.minimum(law["kappa"] / law["eps_r"], 1.0),
            **law,
            "strain": sim.bar_strain,
            "force": sim.bar_force,
            "G_f": sim.fracture_energy_field,
            "kind": sim.lattice.bar_table()["kind"].astype(np.int32)}


def write_vtu(sim, path: str, broken_only: bool = False) -> None:
    """Every bar (or only the broken ones: the crack) as a VTK line cell, at its
    reference position with the node displacements as a point vector (ParaView:
    Warp By Vector), and per bar the arrays of bar_arrays."""
    import meshio

    lat = sim.lattice
    bars = lat.bar_table()
    per_bar = bar_arrays(sim)
    state = per_bar["damage_state"]
    keep = state == 2 if broken_only else np.ones(len(state), dtype=bool)
    mine = parallel.owned(sim)  # a slab's halo bars are written by their owners
    keep[:mine.start] = False
    keep[mine.stop:] = False
    cells = [("line", np.column_stack([bars["n1"], bars["n2"]])[keep].astype(np.int64))]
    mesh = meshio.Mesh(np.column_stack([lat.x0, lat.y0, lat.z0]), cells,
                       point_data={"displacement": sim.displacement},
                       cell_data={k: [v[keep]] for k, v in per_bar.items()})
    with atomic(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")


# The arrays of write_vtu's files: name -> (VTK type, components), for a .pvtu.
VTU_POINT_ARRAYS = {"displacement": ("Float64", 3)}


def vtu_cell_arrays(sim) -> dict:
    """The cell arrays of sim's write_vtu files: name -> (VTK type, components)."""
    return {k: ("Int32" if v.dtype == np.int32 else "Float64", 1) for k, v in bar_arrays(sim).items()}


def write_pvtu(path: str, pieces: List[str], point_arrays: dict, cell_arrays: dict) -> None:
    """The parallel VTK file (.pvtu) that names the pieces (written by rank 0);
    arrays: name -> (VTK type, components)."""
    def decl(arrays):
        return "".join(f'      <PDataArray type="{t}" Name="{n}" NumberOfComponents="{c}"/>\n'
                       for n, (t, c) in arrays.items())
    text = ('<?xml version="1.0"?>\n'
            '<VTKFile type="PUnstructuredGrid" version="0.1" byte_order="LittleEndian">\n'
            '  <PUnstructuredGrid GhostLevel="0">\n'
            f'    <PPointData>\n{decl(point_arrays)}    </PPointData>\n'
            f'    <PCellData>\n{decl(cell_arrays)}    </PCellData>\n'
            '    <PPoints>\n      <PDataArray type="Float64" NumberOfComponents="3"/>\n    </PPoints>\n'
            + "".join(f'    <Piece Source="{os.path.basename(p)}"/>\n' for p in pieces)
            + '  </PUnstructuredGrid>\n</VTKFile>\n')
    with atomic(path) as tmp, open(tmp, "w") as f:
        f.write(text)


def write_bars(sim, path: str, broken_only: bool = False) -> str:
    """write_vtu; for a lattice split over MPI ranks, this rank's piece (bars_pN.vtu
    for bars.vtu) and, on rank 0, bars.pvtu naming the pieces. Returns the name
    of the file ParaView opens (bars.vtu or bars.pvtu)."""
    if not parallel.split(sim):
        write_vtu(sim, path, broken_only)
        return os.path.basename(path)
    write_vtu(sim, parallel.piece_name(path, parallel.rank()), broken_only)
    whole = os.path.splitext(path)[0] + ".pvtu"
    if parallel.is_root():
        write_pvtu(whole, [parallel.piece_name(path, r) for r in range(parallel.ranks())],
                   VTU_POINT_ARRAYS, vtu_cell_arrays(sim))
    return os.path.basename(whole)


def write_pvd(path: str, frames) -> None:
    """A ParaView collection: frames are (time, file name relative to path's
    folder); ParaView's time is the mean strain."""
    rows = "".join(f'    <DataSet timestep="{t!r}" group="" part="0" file="{name}"/>\n' for t, name in frames)
    with atomic(path) as tmp, open(tmp, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
                f"  <Collection>\n{rows}  </Collection>\n</VTKFile>\n")


class Snapshots:
    """An observer of CubeTest.run: bars_NNNN.vtu and crack_NNNN.vtu (the
    broken bars) when the mean strain first reaches each of `strains`; finish()
    adds the final state (bars.vtu, crack.vtu) and writes bars.pvd and
    crack.pvd, the time series ParaView opens."""

    def __init__(self, sim, out: str, strains=()):
        self.sim, self.out, self.todo = sim, out, sorted(strains)
        self.frames = []

    def __call__(self, row: dict) -> None:
        while self.todo and row["mean_strain"] >= self.todo[0]:
            self.todo.pop(0)
            k = len(self.frames)
            self._write(row["mean_strain"], f"bars_{k:04d}.vtu", f"crack_{k:04d}.vtu")

    def _write(self, strain, bars, crack):
        bars = write_bars(self.sim, os.path.join(self.out, bars))
        crack = write_bars(self.sim, os.path.join(self.out, crack), broken_only=True)
        self.frames.append((strain, bars, crack))

    def finish(self, result) -> None:
        self._write(float(result.curve["mean_strain"][-1]), "bars.vtu", "crack.vtu")
        if parallel.is_root():
            write_pvd(os.path.join(self.out, "bars.pvd"), [(t, b) for t, b, _ in self.frames])
            write_pvd(os.path.join(self.out, "crack.pvd"), [(t, c) for t, _, c in self.frames])


def _snapshots_writer(run) -> Snapshots:
    """Snapshots at the strains of run.options["snapshots"] the run has not
    passed yet (a restart continues the series)."""
    previous = run.previous
    strains = [s for s in run.options.get("snapshots", ()) if not previous or s > previous[-1]["mean_strain"]]
    return Snapshots(run.sim, run.out, strains)


register_writer("vtk", _snapshots_writer, 20,
                "bars.vtu and crack.vtu (and their series at the snapshot strains, bars.pvd, crack.pvd)")
