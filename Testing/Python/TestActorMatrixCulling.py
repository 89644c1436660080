"""Terrain under a non-uniform actor matrix is neither culled nor beyond tau (issue #16, item 2).

Regression: with actor.SetScale(1, 1, S) the view conversion divided distances and clipping
planes by the cube root of the matrix determinant, which only holds for a uniform scale: at
S = 3 the measured error was about twice tau, at S = 5 half the terrain was culled, at
S = 10 the frame was blank. For each matrix (vertical exaggeration 3, 5, 10, a squashed
0.5, an anisotropic x/y scale and a rotation with shear) the mapper's frame is compared
with a stock full-resolution vtkPolyDataMapper under the same actor matrix:
- coverage: no terrain pixel of the stock render is missing from ours, and ours draws none
  where the stock render has none (both up to 2 px: tau plus rasterisation);
- error: the mapper's triangles (vtkGeoMipMapFilter with the same camera, viewport and
  actor matrix) measured by vtkGeoMipMapScreenError with the data->clip matrix, <= tau.
Data: SainteHelens.dem (UTM coordinates, nodata border) from the shared data folder.
"""
import os
import sys

import numpy as np
from vtkmodules.vtkCommonMath import vtkMatrix4x4
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkRenderingCore import vtkActor, vtkCamera, vtkRenderer

import geomipmap
import gmmtestutil
import refscene

TAU = 1.0
BG = (0.1, 0.1, 0.2)
W, H = 480, 320
check = refscene.Checks()


data = gmmtestutil.data_dir_or_skip()
reader = geomipmap.vtkGeoMipMapTerrainReader()
reader.SetFileName(os.path.join(data, "SainteHelens.dem"))
reader.Update()
image = reader.GetOutput()

mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputConnection(reader.GetOutputPort())
mapper.SetPixelError(TAU)
ours = vtkActor()
ours.SetMapper(mapper)
ours.GetProperty().LightingOff()
ref = refscene.reference_actor(image)
ref.GetProperty().LightingOff()

ren = vtkRenderer()
ren.SetBackground(*BG)
win = refscene.window(W, H, ren)

centre = [0.5 * (a + b) for a, b in zip(image.GetBounds()[0::2], image.GetBounds()[1::2])]


def sheared():
    t = vtkTransform()
    t.PostMultiply()
    t.Translate(-centre[0], -centre[1], 0)
    t.RotateZ(30)
    m = vtkMatrix4x4()
    m.SetElement(0, 2, 0.4)  # x += 0.4 z: a shear
    t.Concatenate(m)
    t.Scale(1.0, 1.0, 4.0)
    t.Translate(centre[0], centre[1], 0)
    return t.GetMatrix()


CASES = [("scale z 3", (1, 1, 3)), ("scale z 5", (1, 1, 5)), ("scale z 10", (1, 1, 10)),
         ("scale z 0.5", (1, 1, 0.5)), ("scale x 2 y 0.5 z 2", (2, 0.5, 2)),
         ("rotation + shear + z 4", None)]

for name, scale in CASES:
    for actor in (ours, ref):
        actor.SetScale(1, 1, 1)
        actor.SetUserMatrix(None)
        if scale:
            actor.SetOrigin(*centre)
            actor.SetScale(*scale)
        else:
            actor.SetUserMatrix(sheared())
    # Camera framed on the stock actor, as a user would: ResetCamera, then tilt.
    ren.RemoveAllViewProps()
    ren.AddActor(ref)
    ren.SetActiveCamera(vtkCamera())
    ren.ResetCamera()
    cam = ren.GetActiveCamera()
    cam.Elevation(-50)
    ren.ResetCameraClippingRange()
    win.Render()
    theirs = refscene.covered(refscene.grab(win), BG)
    ren.RemoveAllViewProps()
    ren.AddActor(ours)
    win.Render()
    mine = refscene.covered(refscene.grab(win), BG)
    missing = np.count_nonzero(theirs & ~refscene.dilate(mine, 2))
    extra = np.count_nonzero(mine & ~refscene.dilate(theirs, 2))
    check(missing == 0 and extra == 0,
          f"{name}: {mapper.GetNumberOfRenderedTriangles()} triangles, "
          f"{mapper.GetNumberOfCulledBlocks()} blocks culled; terrain pixels missing "
          f"{missing}, extra {extra} (stock render covers {theirs.sum()})")

    # The drawn triangles, measured independently with the data -> clip matrix.
    matrix = ours.GetMatrix()
    filt = geomipmap.vtkGeoMipMapFilter()
    filt.SetInputConnection(reader.GetOutputPort())
    filt.SetCamera(cam)
    filt.SetViewportSize(W, H)
    filt.SetPixelError(TAU)
    filt.SetModelMatrix(matrix)
    filt.Update()
    drawn = filt.GetOutput()
    check(drawn.GetNumberOfCells() == mapper.GetNumberOfRenderedTriangles(),
          f"{name}: filter gives the mapper's {mapper.GetNumberOfRenderedTriangles()} "
          f"triangles ({drawn.GetNumberOfCells()})")
    clip = vtkMatrix4x4()
    vtkMatrix4x4.Multiply4x4(cam.GetCompositeProjectionTransformMatrix(W / H, -1, 1), matrix,
                             clip)
    measure = geomipmap.vtkGeoMipMapScreenError()
    measure.SetHeightfield(image)
    measure.SetMesh(drawn)
    measure.SetProjectionMatrix(clip)
    measure.SetViewportSize(W, H)
    check(measure.Compute(), f"{name}: measured")
    check(measure.GetNumberOfSamplesInView() > 1000 and measure.GetMaximumError() <= TAU,
          f"{name}: measured error {measure.GetMaximumError():.3f} px over "
          f"{measure.GetNumberOfSamplesInView()} samples (tau {TAU})")

check.exit()
