#!/usr/bin/env pvpython
"""Renders a cracked shell from an encounter's .xdmf sidecar with ParaView (README figure).

The shell triangles in grey, the failed shell springs (springs grid, cell array `failed` = 1)
as red tubes, seen from the direction of the failures' mean position (the side facing
pericenter, where most of them lie), at 1200 x 900 pixels on white.

Usage (the README's command; ParaView needs an X display, xvfb-run gives it one):
    xvfb-run -a pvpython tools/render_cracked_shell.py ENCOUNTER.xdmf OUT.png
On a heavily loaded machine ParaView sometimes aborts with "bad X server connection" while
xvfb-run's server starts; running the command again renders the same image.
"""
import math
import sys

from paraview import servermanager, simple


def main(sidecar, png):
    # Xdmf3ReaderT names the three grids as blocks (Xdmf3ReaderS returns them as unnamed pieces).
    reader = simple.Xdmf3ReaderT(FileName=[sidecar])
    shell = simple.ExtractBlock(Input=reader, Selectors=["/Root/shell"])
    springs = simple.ExtractBlock(Input=reader, Selectors=["/Root/springs"])
    failed = simple.Threshold(Input=springs, Scalars=["CELLS", "failed"], LowerThreshold=0.5, UpperThreshold=1.5)
    # Only shell springs can fail; their tubes sit just outside the surface they crack.
    cracks = simple.Tube(Input=simple.ExtractSurface(Input=failed), Radius=0.006, NumberofSides=12)
    centers = servermanager.Fetch(simple.CellCenters(Input=simple.MergeBlocks(Input=failed)))
    if centers.GetNumberOfPoints() == 0:
        sys.exit(f"{sidecar}: no failed spring to show")
    mean = [sum(centers.GetPoint(i)[k] for i in range(centers.GetNumberOfPoints())) for k in range(3)]
    norm = math.sqrt(sum(m * m for m in mean)) or 1.0
    eye = [4.5 * m / norm for m in mean]

    view = simple.CreateView("RenderView")
    view.ViewSize = [1200, 900]
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0
    shell_display = simple.Show(shell, view)
    shell_display.ColorArrayName = [None, ""]
    shell_display.DiffuseColor = [0.78, 0.80, 0.84]
    shell_display.Specular = 0.2
    crack_display = simple.Show(cracks, view)
    crack_display.ColorArrayName = [None, ""]
    crack_display.DiffuseColor = [0.80, 0.08, 0.05]

    view.CameraPosition = eye
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]  # the orbital plane's normal
    view.ResetCamera()  # keeps the direction, centres the shell (the body recoils off the origin)
    view.GetActiveCamera().Zoom(1.45)
    simple.SaveScreenshot(png, view, ImageResolution=[1200, 900])


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
