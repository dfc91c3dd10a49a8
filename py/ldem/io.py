"""Files of a run: the output folder, curve.csv (row by row), summary.json and
bars.vtu. Writers take data (rows, the summary dict, the final state); nothing
here computes physics."""
from __future__ import annotations

import contextlib
import csv
import json
import os
import time
from typing import List, Sequence

import numpy as np

from . import parallel


@contextlib.contextmanager
def atomic(path: str):
    """Yields a temporary name beside path (same extension); renamed to path
    when the block ends without error, removed otherwise: a file is whole or
    absent, never cut by a full disk or a kill."""
    folder, base = os.path.split(path)
    tmp = os.path.join(folder, f".{base}.{os.getpid()}.tmp{os.path.splitext(base)[1]}")
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException as e:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        if isinstance(e, OSError):
            raise _naming(e, path) from e
        raise


def _naming(e: OSError, path: str) -> OSError:
    """The same error, naming the file the user knows (not a temporary one)."""
    return OSError(e.errno, e.strerror or str(e), path)


def prepare_dir(path: str) -> None:
    """Creates the output folder and checks it is writable, before any computing."""
    try:
        os.makedirs(path, exist_ok=True)
        probe = os.path.join(path, ".ldem-write-test")
        with open(probe, "w"):
            pass
        os.remove(probe)
    except OSError as e:
        raise ValueError(f"cannot write to output folder {path}: {e.strerror}") from None


def _cell(v) -> str:
    """Ten significant digits, as C's %.10g; counts as integers."""
    return str(v) if isinstance(v, int) else format(v, ".10g")


class CurveCsv:
    """curve.csv, a row per record, flushed as it is written so that a run that
    fails or is interrupted keeps every row up to that point. An observer of
    CubeTest.run."""

    def __init__(self, path: str, append: bool = False):
        self.path = path
        self._f = open(path, "a" if append else "w")
        self._columns = None  # the header's, once known
        if append:
            with open(path) as f:
                self._columns = f.readline().strip().split(",")

    def __call__(self, row: dict) -> None:
        if self._columns is None:  # the header: the cube's columns, then a specimen's probes
            self._columns = list(row)
            self._write(",".join(self._columns) + "\n")
        self._write(",".join(_cell(row[c]) for c in self._columns) + "\n")

    def _write(self, line: str) -> None:
        try:
            self._f.write(line)
            self._f.flush()
        except OSError as e:
            raise _naming(e, self.path) from e

    def close(self) -> None:
        with contextlib.suppress(OSError):  # a row cut by a full disk was reported already
            self._f.close()


def write_summary(summary: dict, path: str) -> None:
    with atomic(path) as tmp, open(tmp, "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")


def write_vtu(sim, path: str, broken_only: bool = False) -> None:
    """Every bar (or only the broken ones: the crack) as a VTK line cell, at its
    reference position with the node displacements as a point vector (ParaView:
    Warp By Vector), and per bar: damage_state (0 undamaged, 1 damaged, 2
    broken), damage (kappa/eps_r), kappa, eps_r, strain, force [N], G_f, kind."""
    import meshio

    lat = sim.lattice
    bars = lat.bar_table()
    kappa, eps_r, state = sim.kappa, sim.eps_r, sim.damage_state
    keep = state == 2 if broken_only else np.ones(len(kappa), dtype=bool)
    mine = parallel.owned(sim)  # a slab's halo bars are written by their owners
    keep[:mine.start] = False
    keep[mine.stop:] = False
    cells = [("line", np.column_stack([bars["n1"], bars["n2"]])[keep].astype(np.int64))]
    per_bar = {
        "damage_state": state.astype(np.int32),
        "damage": np.minimum(kappa / eps_r, 1.0),
        "kappa": kappa,
        "eps_r": eps_r,
        "strain": sim.bar_strain,
        "force": sim.bar_force,
        "G_f": sim.fracture_energy_field,
        "kind": bars["kind"].astype(np.int32),
    }
    mesh = meshio.Mesh(np.column_stack([lat.x0, lat.y0, lat.z0]), cells,
                       point_data={"displacement": sim.displacement},
                       cell_data={k: [v[keep]] for k, v in per_bar.items()})
    with atomic(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")


# The arrays of write_vtu's files: name -> (VTK type, components), for a .pvtu.
VTU_POINT_ARRAYS = {"displacement": ("Float64", 3)}
VTU_CELL_ARRAYS = {"damage_state": ("Int32", 1), "damage": ("Float64", 1), "kappa": ("Float64", 1),
                   "eps_r": ("Float64", 1), "strain": ("Float64", 1), "force": ("Float64", 1), "G_f": ("Float64", 1),
                   "kind": ("Int32", 1)}


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
                            VTU_POINT_ARRAYS, VTU_CELL_ARRAYS)
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

    def finish(self, final_strain: float) -> None:
        self._write(final_strain, "bars.vtu", "crack.vtu")
        if parallel.is_root():
            write_pvd(os.path.join(self.out, "bars.pvd"), [(t, b) for t, b, _ in self.frames])
            write_pvd(os.path.join(self.out, "crack.pvd"), [(t, c) for t, _, c in self.frames])


def write_slice(path: str, segments, states) -> None:
    """The central slice of a run (plots.central_slice), for study figures."""
    with atomic(path) as tmp:
        np.savez_compressed(tmp, segments=np.asarray(segments, dtype=np.float32), states=states)


def read_slice(path: str) -> tuple:
    with np.load(path) as z:
        return z["segments"], z["states"]


def read_summary(path: str) -> dict:
    with open(path) as f:
        return json.load(f)


def read_curve(path: str) -> dict:
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {k: np.atleast_1d(data[k]) for k in data.dtype.names}


def write_table(path: str, rows: Sequence[dict], columns: Sequence[str]) -> None:
    with atomic(path) as tmp, open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(columns), extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def write_text(path: str, text: str) -> None:
    with atomic(path) as tmp, open(tmp, "w") as f:
        f.write(text)


def read_table(path: str) -> List[dict]:
    def conv(v):
        try:
            return int(v)
        except ValueError:
            try:
                return float(v)
            except ValueError:
                return v
    with open(path, newline="") as f:
        return [{k: conv(v) for k, v in r.items()} for r in csv.DictReader(f)]


# -- checkpoints -----------------------------------------------------------------
def write_checkpoint(path: str, state: dict, parameters: dict, wall_s: float = 0.0) -> None:
    """checkpoint.npz: the arrays of Simulation.checkpoint() (nodes: u_*, v_*,
    f_* by component; bars: kappa, eps_r; rows: softening; the run's scalars,
    counters, events and load-loss window), the test's parameters as JSON and
    the wall time the run had taken. npz, not HDF5: numpy reads it with
    nothing else installed, and it holds named arrays, which is all a
    checkpoint is."""
    with atomic(path) as tmp:
        np.savez(tmp, parameters=np.array(json.dumps(parameters)), wall_s=np.array(wall_s), **state)


def read_checkpoint(path: str) -> tuple:
    """(state for Simulation.restore, parameters, wall time the run had taken [s])."""
    with np.load(path) as z:
        state = {k: z[k] for k in z.files if k not in ("parameters", "wall_s")}
        return state, json.loads(str(z["parameters"])), float(z["wall_s"]) if "wall_s" in z.files else 0.0


def cut_curve_after(path: str, step: int) -> List[dict]:
    """Drops curve.csv's rows after `step` (a restart writes them again) and
    returns the rows kept, as numbers."""
    with open(path) as f:
        lines = f.readlines()
    keep = [lines[0]] + [ln for ln in lines[1:] if ln.endswith("\n") and int(ln.split(",", 1)[0]) <= step]
    with atomic(path) as tmp, open(tmp, "w") as f:
        f.writelines(keep)
    columns = keep[0].strip().split(",")
    return [dict(zip(columns, (float(x) for x in ln.split(",")))) for ln in keep[1:]]


class Checkpoints:
    """An observer of CubeTest.run: checkpoint.npz every `every` curve rows
    and/or every `seconds` of wall time (0: not on that count); wall_before:
    the wall time of the run before this piece of it (a restart)."""

    def __init__(self, sim, path: str, every: int, parameters: dict, seconds: float = 0.0, wall_before: float = 0.0):
        self.sim, self.path, self.every, self.parameters, self.seconds = sim, path, every, parameters, seconds
        self.rows, self.wall_before = 0, wall_before
        self.start = self.last = time.monotonic()

    def __call__(self, row: dict) -> None:
        self.rows += 1
        now = time.monotonic()
        if (self.every and self.rows % self.every == 0) or (self.seconds and now - self.last >= self.seconds):
            self.write()

    def write(self) -> None:  # of the record being observed (also at a SIGTERM or SIGINT: ldem.runner)
        self.last = now = time.monotonic()
        write_checkpoint(self.path, self.sim.checkpoint(), self.parameters, self.wall_before + now - self.start)
