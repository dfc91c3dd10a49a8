"""pvbatch pvtu_cells.py DIR: ParaView opens DIR/bars.pvtu (one piece per MPI
rank) and DIR/bars.pvd; prints their cells and checks they are the run's bars."""
import json
import os
import sys

from paraview.simple import OpenDataFile, servermanager

folder = sys.argv[1]
with open(os.path.join(folder, "summary.json")) as f:
    bars = json.load(f)["n_bars"]
for name in ("bars.pvtu", "bars.pvd"):
    reader = OpenDataFile(os.path.join(folder, name))
    reader.UpdatePipeline()
    data = servermanager.Fetch(reader)
    cells = data.GetNumberOfCells()
    arrays = [data.GetCellData().GetArrayName(i) for i in range(data.GetCellData().GetNumberOfArrays())]
    print(f"{name}: {cells} cells, cell arrays {', '.join(arrays)}")
    if cells != bars or "damage_state" not in arrays:
        sys.exit(f"{name}: {cells} cells, the run has {bars} bars")
