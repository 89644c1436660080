"""One vtkGeoMipMapMapper drawn in two render windows (issue #16, item 1).

Regression: rendering the second window crashed in RenderPieceDraw (exit 139), because the
mapper's graphics resources were created in the first window's OpenGL context and used in
the second's. Both windows, both alive, must draw the same terrain, again and again, and
closing one must leave the other drawing. Checked against a stock full-resolution
vtkPolyDataMapper in each window (coverage of the terrain, pixel for pixel within tau).
"""
import sys

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer

from geomipmap.geomipmapFilters import vtkGeoMipMapFractalSource
from geomipmap.geomipmapRendering import vtkGeoMipMapMapper
import refscene

BG = (0.1, 0.1, 0.2)
check = refscene.Checks()


src = vtkGeoMipMapFractalSource()
src.SetDimensions(257, 257)
src.SetSpacing(30.0)
src.SetSeed(5)
src.Update()
image = src.GetOutput()

mapper = vtkGeoMipMapMapper()
mapper.SetInputConnection(src.GetOutputPort())
mapper.SetPixelError(1.0)
ref = refscene.reference_actor(image)


def scene(actor, azimuth):
    ren = vtkRenderer()
    ren.SetBackground(*BG)
    ren.AddActor(actor)
    win = refscene.window(320, 240, ren)
    ren.ResetCamera()
    cam = ren.GetActiveCamera()
    cam.Elevation(-50)
    cam.Azimuth(azimuth)
    ren.ResetCameraClippingRange()
    return ren, win


actors = []
wins = []
for k, az in enumerate((0.0, 40.0)):
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().LightingOff()
    actors.append(actor)
    ren, win = scene(actor, az)
    wins.append((ren, win))

ref.GetProperty().LightingOff()
for frame in range(3):
    for k, (ren, win) in enumerate(wins):
        win.Render()
        tris = mapper.GetNumberOfRenderedTriangles()
        ours = refscene.covered(refscene.grab(win), BG)
        # Same camera, stock full-resolution mapper, its own window.
        rren, rwin = scene(ref, (0.0, 40.0)[k])
        rren.SetActiveCamera(ren.GetActiveCamera())
        rwin.Render()
        theirs = refscene.covered(refscene.grab(rwin), BG)
        missing = np.count_nonzero(theirs & ~refscene.dilate(ours, 2))
        extra = np.count_nonzero(ours & ~refscene.dilate(theirs, 2))
        check(tris > 0 and ours.sum() > 0.1 * ours.size,
              f"frame {frame} window {k}: {tris} triangles, {ours.sum()} terrain pixels")
        check(missing == 0 and extra == 0,
              f"frame {frame} window {k}: terrain pixels missing {missing}, extra {extra} "
              "against the stock mapper")
        del rwin

# Closing the first window releases what it holds; the second keeps drawing.
wins[0][1].Finalize()
del wins[0]
wins[0][1].Render()
check(mapper.GetNumberOfRenderedTriangles() > 0, "second window draws after the first closed")
check(refscene.covered(refscene.grab(wins[0][1]), BG).sum() > 0, "second window shows terrain")

check.exit()
