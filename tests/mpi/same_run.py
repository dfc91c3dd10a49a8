"""Checks that runs of one cube split over different numbers of MPI ranks gave
the same results, bit for bit: curve.csv and cracks.png byte-identical, summary.json equal
but for when, where and how it ran, and the bars of bars.vtu (one process) or
bars.pvtu (its pieces, in rank order) equal: ends, state, damage, strain,
force, G_f. Usage: same_run.py DIR DIR... (the first is the reference); exit 1
naming the first difference."""
import json
import os
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np

# How, where and when a run ran: not its results.
VOLATILE = {"wall_s", "provenance", "threads", "mpi_ranks"}


def bars(folder):
    """Per bar, in the whole lattice's order: its ends' coordinates and cell data."""
    path = os.path.join(folder, "bars.vtu")
    if os.path.exists(path):
        files = [path]
    else:
        root = ET.parse(os.path.join(folder, "bars.pvtu")).getroot()
        files = [os.path.join(folder, p.get("Source")) for p in root.iter("Piece")]
    out = {}
    for f in files:
        mesh = meshio.read(f)
        lines = mesh.cells_dict["line"]
        data = {"ends": mesh.points[lines].reshape(len(lines), -1),
                "displacement": mesh.point_data["displacement"][lines].reshape(len(lines), -1)}
        data.update({k: v[0] for k, v in mesh.cell_data.items()})
        for k, v in data.items():
            out.setdefault(k, []).append(v)
    return {k: np.concatenate(v) for k, v in out.items()}


def differences(ref, other):
    for name in ("curve.csv", "cracks.png"):  # the crack picture: drawn by rank 0 from the ranks' slices
        with open(os.path.join(ref, name), "rb") as a, open(os.path.join(other, name), "rb") as b:
            if a.read() != b.read():
                yield f"{name} differs"
    sa, sb = (json.load(open(os.path.join(d, "summary.json"))) for d in (ref, other))
    for key in sorted((set(sa) | set(sb)) - VOLATILE):
        if sa.get(key) != sb.get(key):
            yield f"summary.json: {key} {sa.get(key)!r} != {sb.get(key)!r}"
    ba, bb = bars(ref), bars(other)
    for key in ba:
        if ba[key].shape != bb[key].shape or not np.array_equal(ba[key], bb[key]):
            yield f"bars: {key} differs"


def main(folders):
    ref = folders[0]
    bad = 0
    for other in folders[1:]:
        for d in differences(ref, other):
            print(f"{other} against {ref}: {d}")
            bad = 1
    if not bad:
        print(f"same results in {', '.join(folders)}")
    return bad


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
