"""vtkGeoMipMapMapper.FreezeLevelOfDetail: the LOD selected for one camera, seen from another
(issue #15, part 1: geomipmap-view's freeze key).

Camera A looks low across a corner of a 257^2 synthetic terrain (fine blocks near, coarse
far); camera B looks down from high above, where the live LOD is much coarser. Frozen at
A and rendered from B, the mapper must keep A's selection: the same triangle count and
certified error, no index upload, no LOD work, IndicesReused. That the drawn triangles
are A's is checked independently of the mapper's own figures: its wireframe from B is
compared pixel by pixel with a stock vtkPolyDataMapper drawing vtkGeoMipMapFilter's mesh
for camera A (what the mapper drew there, TestGeoMipMapFilterAgreement): measured here,
0 of 28 790 line pixels differ, against 12 382 for the filter's mesh for camera B. A tau change waits while frozen;
unfrozen, B's own LOD is drawn and measures within tau; a new input while frozen is
selected for the current camera (there is nothing of it to keep).
"""

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkCamera, vtkRenderer

import geomipmap
import refscene
from gmmtestutil import check_within_tau, lod_mesh

W, H = 400, 300
TAU, BLOCK = 1.0, 32
check = refscene.Checks()



def fractal(n, spacing, seed):
    return refscene.fractal_image(n, n, seed=seed, spacing=spacing)


image = fractal(257, 30.0, 3)
mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputData(image)
mapper.SetPixelError(TAU)
mapper.SetBlockSize(BLOCK)
mapper.ScalarVisibilityOff()
actor = vtkActor()
actor.SetMapper(mapper)
ren = vtkRenderer()
ren.SetBackground(0.0, 0.0, 0.0)
ren.AddActor(actor)
win = refscene.window(W, H, ren)
x0, x1, y0, y1, z0, z1 = mapper.GetBounds()


def camera(position, focal):
    cam = vtkCamera()
    cam.SetPosition(*position)
    cam.SetFocalPoint(*focal)
    cam.SetViewUp(0.0, 0.0, 1.0)
    cam.SetViewAngle(40.0)
    return cam


cam_a = camera((x0 - 300.0, y0 - 300.0, z1 + 200.0), (0.5 * (x0 + x1), 0.5 * (y0 + y1), z0))
cam_b = camera((0.5 * (x0 + x1) + 1.0, 0.5 * (y0 + y1) - 6000.0, z1 + 14000.0),
               (0.5 * (x0 + x1), 0.5 * (y0 + y1), z0))


def use(cam):
    ren.SetActiveCamera(cam)
    ren.ResetCameraClippingRange(x0, x1, y0, y1, z0, z1)


def filter_mesh(cam):
    """vtkGeoMipMapFilter's copy of what the mapper draws for `cam` (same tau, block, size)."""
    return lod_mesh(image, cam, (W, H), TAU, BLOCK)


def wireframe_of(actor_):
    prop = actor_.GetProperty()
    prop.SetRepresentationToWireframe()
    prop.LightingOff()
    prop.SetColor(1.0, 1.0, 1.0)
    ren.RemoveAllViewProps()
    ren.AddActor(actor_)
    win.Render()
    lines = refscene.grab(win).max(axis=2) > 128
    ren.RemoveAllViewProps()
    ren.AddActor(actor)
    return lines


# Live at A, then live at B: the two selections must differ for the test to mean anything.
use(cam_b)  # sets B's clipping range, which its filter mesh needs too
use(cam_a)
win.Render()
tri_a, err_a = mapper.GetNumberOfRenderedTriangles(), mapper.GetMaximumScreenSpaceError()
mesh_a, mesh_b = filter_mesh(cam_a), filter_mesh(cam_b)
check(mesh_a.GetNumberOfPolys() == tri_a, f"filter at A: {mesh_a.GetNumberOfPolys()} "
      f"triangles, mapper {tri_a}")
check(0 < mesh_b.GetNumberOfPolys() < 0.5 * tri_a,
      f"B's live LOD ({mesh_b.GetNumberOfPolys()} triangles) is far coarser than A's ({tri_a})")

# Frozen at A, rendered from B.
mapper.FreezeLevelOfDetailOn()
uploads = mapper.GetNumberOfIndexUploads()
use(cam_b)
win.Render()
check(mapper.GetNumberOfRenderedTriangles() == tri_a,
      f"frozen, from B: {mapper.GetNumberOfRenderedTriangles()} triangles (A had {tri_a})")
check(mapper.GetMaximumScreenSpaceError() == err_a,
      f"frozen: certified error {mapper.GetMaximumScreenSpaceError():.4f} px is A's {err_a:.4f}")
check(mapper.GetNumberOfIndexUploads() == uploads,
      f"frozen: {mapper.GetNumberOfIndexUploads() - uploads} index uploads")
check(mapper.GetIndicesReused() and mapper.GetLastUpdateTime() == 0.0,
      f"frozen: IndicesReused {mapper.GetIndicesReused()}, LastUpdateTime "
      f"{mapper.GetLastUpdateTime()}")
mapper.SetPixelError(8.0)
win.Render()
check(mapper.GetNumberOfRenderedTriangles() == tri_a and mapper.GetPixelError() == 8.0,
      f"frozen: tau 8 waits ({mapper.GetNumberOfRenderedTriangles()} triangles)")
mapper.SetPixelError(TAU)

# The drawn lines are A's mesh, not B's: wireframes from B, pixel by pixel.
frozen_lines = wireframe_of(actor)
check(mapper.GetNumberOfRenderedTriangles() == tri_a, "frozen wireframe: still A's triangles")
lines_a = wireframe_of(refscene.stock_actor(mesh_a))
lines_b = wireframe_of(refscene.stock_actor(mesh_b))
off_a = np.count_nonzero(frozen_lines ^ lines_a)  # pixels on in one drawing only
off_b = np.count_nonzero(frozen_lines ^ lines_b)
total = np.count_nonzero(frozen_lines)
print(f"frozen wireframe: {total} line pixels; differing from A's mesh {off_a}, "
      f"from B's mesh {off_b}")
check(total > 1000 and off_a <= 0.02 * total,
      f"frozen wireframe from B is A's mesh ({off_a} pixels differ, of {total})")
check(off_b > 0.2 * total, f"... and not B's ({off_b} pixels differ)")
actor.GetProperty().SetRepresentationToSurface()
actor.GetProperty().LightingOn()

# Unfrozen: B's own LOD, within tau by the independent measure.
mapper.FreezeLevelOfDetailOff()
win.Render()
check(mapper.GetNumberOfRenderedTriangles() == mesh_b.GetNumberOfPolys(),
      f"unfrozen at B: {mapper.GetNumberOfRenderedTriangles()} triangles, filter "
      f"{mesh_b.GetNumberOfPolys()}")
check_within_tau(check, image, ren, actor, mapper, "unfrozen at B")

# A new input while frozen: nothing of it to keep, so it is selected for B.
mapper.FreezeLevelOfDetailOn()
image = fractal(193, 40.0, 4)
mapper.SetInputData(image)
win.Render()
want = filter_mesh(cam_b).GetNumberOfPolys()
check(mapper.GetNumberOfRenderedTriangles() == want and want > 0,
      f"frozen, new input: selected for the current camera "
      f"({mapper.GetNumberOfRenderedTriangles()} triangles, filter {want})")
check.exit()
