"""Software picking hits the terrain, not the flat input image (issue #16, item 3).

Regression: vtkCellPicker and vtkPointPicker intersect a mapper's input data set; for
vtkGeoMipMapMapper that is the 2D image, so picks returned z = 0 and an x, y off by up to
1.5 km. vtkGeoMipMapPicker (a vtkCellPicker) intersects the ray with the full-resolution
terrain exactly, whatever level of detail is drawn. Checked against the stock
vtkCellPicker on a stock full-resolution mesh of the same DEM (same triangulation), at a
grid of pixels, with and without an actor matrix:
- pick position within 0.5 m of the stock pick, and the same miss/hit outcome;
- PointId: the image sample nearest to the pick position; CellId: the image cell under it;
  DataSet: the input image;
- other actors in the same scene are still picked as vtkCellPicker picks them.
Data: SainteHelens.dem (UTM, nodata border).
"""
import math
import os
import sys

from vtkmodules.vtkCommonMath import vtkMatrix4x4
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import (vtkActor, vtkCamera, vtkCellPicker, vtkPolyDataMapper,
                                         vtkRenderer)

import geomipmap
import gmmtestutil
import refscene

W, H = 400, 300
check = refscene.Checks(verbose=False)


data = gmmtestutil.data_dir_or_skip()
reader = geomipmap.vtkGeoMipMapTerrainReader()
reader.SetFileName(os.path.join(data, "SainteHelens.dem"))
reader.Update()
image = reader.GetOutput()
nx, ny, _ = image.GetDimensions()
xs, ys = refscene.sample_xy(image)
hts = refscene.heights(image)

mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputConnection(reader.GetOutputPort())
mapper.SetPixelError(4.0)  # coarse LOD on purpose: the pick must not depend on it
ours = vtkActor()
ours.SetMapper(mapper)
ref = refscene.reference_actor(image)

ren = vtkRenderer()
win = refscene.window(W, H, ren)


def pick_all(actor, picker):
    ren.RemoveAllViewProps()
    ren.AddActor(actor)
    win.Render()
    out = []
    for py in range(10, H, 20):
        for px in range(10, W, 20):
            hit = picker.Pick(px, py, 0, ren)
            out.append((px, py, hit, picker.GetPickPosition(), picker.GetPointId(),
                        picker.GetCellId(), picker.GetDataSet()))
    return out


for name, scale in (("identity", None), ("scale z 3", (1.0, 1.0, 3.0))):
    for actor in (ours, ref):
        actor.SetScale(*(scale or (1, 1, 1)))
    ren.SetActiveCamera(vtkCamera())
    ren.AddActor(ref)
    ren.ResetCamera()
    ren.GetActiveCamera().Elevation(-50)
    ren.ResetCameraClippingRange()
    theirs = pick_all(ref, vtkCellPicker())
    mine = pick_all(ours, geomipmap.vtkGeoMipMapPicker())
    hits = worst = 0
    for a, b in zip(theirs, mine):
        px, py = a[0], a[1]
        check(a[2] == b[2], f"{name} pixel {px},{py}: stock hit {a[2]}, ours {b[2]}")
        if not (a[2] and b[2]):
            continue
        hits += 1
        d = math.dist(a[3], b[3])
        worst = max(worst, d)
        check(d <= 0.5, f"{name} pixel {px},{py}: pick {b[3]} is {d:.3f} m from the stock "
              f"pick {a[3]}")
        # Ids refer to the input image, in data coordinates (undo the actor matrix).
        mi = vtkMatrix4x4()
        mi.DeepCopy(ours.GetMatrix())
        mi.Invert()
        data_pt = mi.MultiplyPoint(list(b[3]) + [1.0])
        i = int(round((data_pt[0] - xs[0]) / (xs[1] - xs[0])))
        j = int(round((data_pt[1] - ys[0]) / (ys[1] - ys[0])))
        check(b[4] == j * nx + i, f"{name} pixel {px},{py}: PointId {b[4]}, nearest sample "
              f"({i}, {j}) is {j * nx + i}")
        ci = int((data_pt[0] - xs[0]) // (xs[1] - xs[0]))
        cj = int((data_pt[1] - ys[0]) // (ys[1] - ys[0]))
        check(b[5] == cj * (nx - 1) + ci, f"{name} pixel {px},{py}: CellId {b[5]}, "
              f"expected {cj * (nx - 1) + ci}")
        check(b[6] is not None and b[6].GetDimensions() == image.GetDimensions(),
              f"{name} pixel {px},{py}: DataSet is not the input image")
    print(f"{name}: {hits} hits of {len(theirs)} pixels, worst distance to the stock pick "
          f"{worst:.4f} m")
    check(hits >= 50, f"{name}: only {hits} hits")

# A sphere in front of the terrain: the picker still picks ordinary actors.
sphere = vtkSphereSource()
cam = ren.GetActiveCamera()
fp = cam.GetFocalPoint()
sphere.SetCenter(*fp)
sphere.SetRadius(800.0)
sphere.SetThetaResolution(32)
sphere.SetPhiResolution(32)
sm = vtkPolyDataMapper()
sm.SetInputConnection(sphere.GetOutputPort())
ball = vtkActor()
ball.SetMapper(sm)
ball.SetPosition(0, 0, 4000)
ren.RemoveAllViewProps()
ren.AddActor(ours)
ren.AddActor(ball)
win.Render()
picker = geomipmap.vtkGeoMipMapPicker()
stock = vtkCellPicker()
ren.RemoveAllViewProps()
ren.AddActor(ball)
win.Render()
ren.SetWorldPoint(fp[0], fp[1], fp[2] + 4000, 1.0)
ren.WorldToDisplay()
px, py, _ = ren.GetDisplayPoint()
stock.Pick(px, py, 0, ren)
ren.AddActor(ours)
picker.Pick(px, py, 0, ren)
check(picker.GetActor() is ball, "the sphere in front of the terrain is picked")
check(math.dist(picker.GetPickPosition(), stock.GetPickPosition()) < 1e-6,
      f"sphere pick {picker.GetPickPosition()} equals the stock pick {stock.GetPickPosition()}")

check.exit()
