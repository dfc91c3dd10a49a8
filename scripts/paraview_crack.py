"""Opens an ldem run in ParaView and shows the crack: every bar, warped by its
displacement and coloured by damage state (0 undamaged, 1 damaged, 2 broken),
with the broken bars drawn thick on top; saves a picture of the last frame,
titled (the run, its mean strain, the warp factor) with its colour legend.

    pvpython scripts/paraview_crack.py out/cube            # writes out/cube/crack_paraview.png
    pvpython scripts/paraview_crack.py out/cube 50         # displacements magnified 50 times
    xvfb-run -a -s "-noreset" pvbatch scripts/paraview_crack.py out/cube   # no display (a server, CI)
    paraview --script=scripts/paraview_crack.py            # (edit RUN below) to explore interactively

Needs ParaView (Debian: paraview; install.sh installs it, with xvfb for machines
without a display); the run folder must hold bars.pvd and crack.pvd (ldem cube
and ldem run write them; --snapshots adds frames at chosen mean strains). The
camera looks along +y with z up: the side of a specimen pulled or bent along z.
"""
import json
import math
import os
import sys


def arguments(argv):
    """RUN [SCALE] (the displacement magnification); a bad one is one line and
    exit code 2, as ldem's, before ParaView loads."""
    run = argv[1] if len(argv) > 1 else os.path.join("out", "cube")
    try:
        scale = float(argv[2]) if len(argv) > 2 else 1.0
    except ValueError:
        scale = math.nan
    why = "usage: paraview_crack.py RUN [SCALE]" if len(argv) > 3 else \
        f"SCALE must be a positive number (got {argv[2]!r})" if not (0 < scale < math.inf) else \
        f"{run} holds no bars.pvd and crack.pvd (ldem cube and ldem run write them)" if not all(
            os.path.isfile(os.path.join(run, n)) for n in ("bars.pvd", "crack.pvd")) else ""
    if why:
        print(f"paraview_crack.py: error: {why}", file=sys.stderr)
        sys.exit(2)
    return run, scale


RUN, SCALE = arguments(sys.argv)

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction,  # noqa
                             GetScalarBar, PVDReader, Render, ResetCamera, SaveScreenshot, Show, Text,
                             WarpByVector)



def run_title(run: str) -> str:
    """The run's title, from its summary.json: a specimen's own, or the cube's size, load and seed."""
    try:
        with open(os.path.join(run, "summary.json")) as f:
            p = json.load(f)["parameters"]
    except (OSError, ValueError, KeyError):
        return run
    if "description" in p:
        return f"{p['description'].get('title', run)}, seed {p['parameters']['seed']}"
    return f"{p['size']:g} m cube, {p['load']}, seed {p['seed']}"


view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1200, 1000]  # the picture's: its fonts at the sizes given below
for name, width in (("bars.pvd", 1.0), ("crack.pvd", 4.0)):
    reader = PVDReader(FileName=os.path.join(RUN, name))
    warp = WarpByVector(Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=SCALE)
    display = Show(warp, view)
    display.LineWidth = width
    ColorBy(display, ("CELLS", "damage_state"))
lut = GetColorTransferFunction("damage_state")
lut.InterpretValuesAsCategories = 1
lut.Annotations = ["0", "undamaged", "1", "damaged", "2", "broken"]
lut.IndexedColors = [0.0, 1.0, 1.0, 1.0, 0.65, 0.0, 1.0, 0.0, 0.0]  # the study's cyan, orange, red
display.SetScalarBarVisibility(view, True)  # the colour legend
bar = GetScalarBar(lut, view)
bar.Title, bar.ComponentTitle, bar.TitleFontSize, bar.LabelFontSize = "damage state", "", 22, 20
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = scene.EndTime
strain = reader.TimestepValues  # the last frame's mean strain (one frame: a number, not a list)
strain = strain[-1] if isinstance(strain, (list, tuple)) or hasattr(strain, "__len__") else strain
title = Text(Text=f"{run_title(RUN)}: mean strain {strain:.3g}\ndisplacements x {SCALE:g} (warp factor)")
label = Show(title, view)
label.WindowLocation, label.FontSize, label.Justification = "Upper Center", 22, "Center"
view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, -1, 0], [0, 0, 0], [0, 0, 1]
view.OrientationAxesVisibility = 1
ResetCamera()
Render()
SaveScreenshot(os.path.join(RUN, "crack_paraview.png"), view, ImageResolution=[1200, 1000])
print(f"wrote {os.path.join(RUN, 'crack_paraview.png')}")
