"""Opens an ldem run in ParaView and shows the crack: every bar, warped by its
displacement and coloured by damage state (0 undamaged, 1 damaged, 2 broken),
with the broken bars drawn thick on top; saves a picture of the last frame.

    pvpython scripts/paraview_crack.py out/cube            # writes out/cube/crack_paraview.png
    xvfb-run -a -s "-noreset" pvbatch scripts/paraview_crack.py out/cube   # no display (a server, CI)
    paraview --script=scripts/paraview_crack.py            # (edit RUN below) to explore interactively

Needs ParaView (Debian: paraview; install.sh installs it, with xvfb for machines
without a display); the run folder must hold bars.pvd and crack.pvd (ldem cube
and ldem run write them; --snapshots adds frames at chosen mean strains). The
camera looks along +y with z up: the side of a specimen pulled or bent along z.
"""
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction,  # noqa
                             PVDReader, Render, ResetCamera, SaveScreenshot, Show, WarpByVector)

RUN = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "cube")
SCALE = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0  # displacement magnification

view = GetActiveViewOrCreate("RenderView")
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
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = scene.EndTime
view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, -1, 0], [0, 0, 0], [0, 0, 1]
view.OrientationAxesVisibility = 1
ResetCamera()
Render()
SaveScreenshot(os.path.join(RUN, "crack_paraview.png"), view, ImageResolution=[1200, 1000])
print(f"wrote {os.path.join(RUN, 'crack_paraview.png')}")
