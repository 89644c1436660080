"""vtkGeoMipMapMapper.Geomorphing: the vertex shader moves vertices exactly as the engine
does (issue #13).

A 257 x 193 fractal terrain (not square: columns and rows have different block bands) at
tau 2, block 32, seen low and oblique so that many blocks are
part-way through their morph. The mapper's depth buffer is compared with that of a stock
vtkPolyDataMapper drawing vtkGeoMipMapFilter's mesh for the same camera: with geomorphing
on (the default) the filter outputs the morphed heights gmm::morphedHeight computes on the
CPU, so the two depth buffers must agree (up to float rounding: the shader computes in
float, the filter in double); against the same triangles unmorphed they must not, or the
test would prove nothing. With geomorphing off, the mapper draws the filter's mesh with
geomorphing off (the coarsest levels within tau, unmorphed); and over a copy with voids.
Also:
the drawn (morphed) surface measures within tau by the independent measure, the mapper's
certified bound is <= tau, and no background shows through the morphed terrain (no crack).
"""

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkCamera, vtkRenderer

import geomipmap
import refscene
from gmmtestutil import ErrorCatcher, check_within_tau

W, H = 480, 320
TAU, BLOCK = 2.0, 32
check = refscene.Checks()

image = refscene.fractal_image(257, 193, seed=5)


def new_mapper():
    m = geomipmap.vtkGeoMipMapMapper()
    m.SetInputData(image)
    m.SetPixelError(TAU)
    m.SetBlockSize(BLOCK)
    m.ScalarVisibilityOff()
    a = vtkActor()
    a.SetMapper(m)
    return m, a


def new_filter(tau, camera=None):
    f = geomipmap.vtkGeoMipMapFilter()
    f.SetInputData(image)
    f.SetViewportSize(W, H)
    f.SetPixelError(tau)
    f.SetBlockSize(BLOCK)
    if camera is not None:
        f.SetCamera(camera)
    return f


mapper, actor = new_mapper()
check(mapper.GetGeomorphing(), "geomorphing is on by default")
# The measuring limit: a count, 0 for none, shared with the filter and printed.
for obj in (mapper, geomipmap.vtkGeoMipMapFilter()):
    check(obj.GetGeomorphMeasureSamples() == 131072, f"{obj.GetClassName()}: 131072 samples a frame by default")
    caught = ErrorCatcher(obj)
    obj.SetGeomorphMeasureSamples(-1)
    check(obj.GetGeomorphMeasureSamples() == 131072 and len(caught.messages) == 1
          and "GeomorphMeasureSamples -1 must be >= 0 (0: no limit)" in caught.messages[0],
          f"{obj.GetClassName()}: a negative limit is refused with an error ({caught.messages})")
    obj.SetGeomorphMeasureSamples(0)
    check(obj.GetGeomorphMeasureSamples() == 0 and "GeomorphMeasureSamples: 0" in str(obj),
          f"{obj.GetClassName()}: 0 (no limit) is taken and printed")
mapper.SetGeomorphMeasureSamples(131072)
ren = vtkRenderer()
ren.SetBackground(0.0, 0.0, 0.0)
ren.AddActor(actor)
win = refscene.window(W, H, ren)
x0, x1, y0, y1, z0, z1 = mapper.GetBounds()
cam = vtkCamera()
cam.SetPosition(x0 - 200.0, 0.5 * (y0 + y1), z1 + 150.0)
cam.SetFocalPoint(0.5 * (x0 + x1), 0.5 * (y0 + y1), z0)
cam.SetViewUp(0.0, 0.0, 1.0)
cam.SetViewAngle(45.0)
ren.SetActiveCamera(cam)
ren.ResetCameraClippingRange(x0, x1, y0, y1, z0, z1)


def filter_mesh(morph):
    f = new_filter(TAU, cam)
    f.SetGeomorphing(morph)
    f.Update()
    return f.GetOutput()


def depth_of(actor_):
    ren.RemoveAllViewProps()
    ren.AddActor(actor_)
    win.Render()
    d = refscene.depth(win)
    ren.RemoveAllViewProps()
    ren.AddActor(actor)
    return d


from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402

# The mapper's first frame is a fresh filter's (geomorphing's rise limit has no history yet).
mesh_on = filter_mesh(True)
# The same triangles unmorphed: every vertex is a sample, back at the sample's own height.
# (Geomorphing also chooses the levels, so the filter with geomorphing off, mesh_plain, draws
# other triangles.)
mesh_off = vtkPolyData()
mesh_off.DeepCopy(mesh_on)
P = vtk_to_numpy(mesh_off.GetPoints().GetData()).copy()
ox, oy, _ = image.GetOrigin()
sx, sy, _ = image.GetSpacing()
nx, ny, _ = image.GetDimensions()
heights = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(ny, nx)
gi = np.rint((P[:, 0] - ox) / sx).astype(int)
gj = np.rint((P[:, 1] - oy) / sy).astype(int)
z_on = P[:, 2].copy()
P[:, 2] = heights[gj, gi]
mesh_off.GetPoints().SetData(numpy_to_vtk(P, deep=True))
moved = np.count_nonzero(np.abs(z_on - P[:, 2]) > 1e-3)
check(moved > 200, f"the filter's morphed mesh moves {moved} of {len(z_on)} vertices")
mesh_plain = filter_mesh(False)

win.Render()
check(mapper.GetNumberOfRenderedTriangles() == mesh_on.GetNumberOfPolys(),
      f"mapper {mapper.GetNumberOfRenderedTriangles()} triangles, filter {mesh_on.GetNumberOfPolys()}")
check(0.0 < mapper.GetMaximumScreenSpaceError() <= TAU,
      f"certified bound of the morphed surface {mapper.GetMaximumScreenSpaceError():.4f} px <= tau")
gpu = refscene.depth(win)
cpu_on = depth_of(refscene.stock_actor(mesh_on))
cpu_off = depth_of(refscene.stock_actor(mesh_off))
terrain = cpu_off < 1.0
# Depth differences in window depth units, over the pixels the terrain covers.
eps = 5e-7  # float rounding reaches 2e-7 here (shader in float, filter in double)
off_on = np.count_nonzero(np.abs(gpu - cpu_on)[terrain] > eps)
off_off = np.count_nonzero(np.abs(gpu - cpu_off)[terrain] > eps)
n = np.count_nonzero(terrain)
print(f"morphed: {n} terrain pixels; depth differs (> {eps}) from the filter's morphed mesh at "
      f"{off_on}, from its unmorphed mesh at {off_off}")
check(n > 0.3 * W * H, f"the terrain covers {n} pixels")
check(off_on <= 0.002 * n, f"GPU morph = CPU morph: {off_on} of {n} pixels differ in depth")
check(off_off > 20 * max(off_on, 1) and off_off > 0.01 * n,
      f"... and the unmorphed mesh is visibly different ({off_off} pixels)")
# Cracks would show the background inside the terrain: pixels more than 4 px inside the
# unmorphed coverage (silhouettes move by up to tau) must all be drawn.
inside = ~refscene.dilate(~terrain, 4)
holes = np.count_nonzero(inside & (gpu >= 1.0))
check(holes == 0 and np.count_nonzero(inside) > 0.5 * n,
      f"no background through the morphed terrain ({holes} of {np.count_nonzero(inside)} pixels)")
check_within_tau(check, image, ren, actor, mapper, "morphed frame")

# Along a flight: how far a morph factor may rise depends on the frames drawn before
# (geomorphing's rise limit), in the mapper and in the filter alike. After the same eight
# cameras and tau changes, one frame each, the mapper still draws the filter's morphed mesh,
# which a fresh filter (no history) does not.
flier, flier_actor = new_mapper()
follower = new_filter(TAU)
ren.RemoveAllViewProps()
ren.AddActor(flier_actor)
start = cam.GetPosition()
for k in range(8):
    # Half way, a coarser tau: the factors may then rise only a little per frame.
    flier.SetPixelError(TAU if k < 4 else 1.5 * TAU)
    follower.SetPixelError(flier.GetPixelError())
    cam.SetPosition(start[0] + 12.0 * k, start[1] + 3.0 * k, start[2] - 2.0 * k)
    win.Render()
    follower.SetCamera(cam)
    follower.Modified()
    follower.Update()
gpu_flight = refscene.depth(win)
flown = vtkPolyData()
flown.DeepCopy(follower.GetOutput())
cpu_flight = depth_of(refscene.stock_actor(flown))
seen = cpu_flight < 1.0
flight_off = np.count_nonzero(np.abs(gpu_flight - cpu_flight)[seen] > eps)
fresh = new_filter(1.5 * TAU, cam)
fresh.Update()
fresh_off = np.count_nonzero(np.abs(gpu_flight - depth_of(refscene.stock_actor(fresh.GetOutput())))[seen] > eps)
check(np.count_nonzero(seen) > 0.3 * W * H and flight_off <= 0.002 * np.count_nonzero(seen),
      f"after an 8-frame flight the mapper draws the filter's morphed mesh ({flight_off} of "
      f"{np.count_nonzero(seen)} pixels differ in depth)")
check(fresh_off > 20 * max(flight_off, 1),
      f"... which a fresh filter's does not: {fresh_off} pixels differ (the rise limit's history)")
# The morph texture is rewritten only where a factor changed: a frozen frame keeps its
# factors, so after the first (which rebuilds the texture: removing the actor from the
# renderer above released it) it uploads none, and draws the flight's last depth.
moved = flier.GetLastMorphUploadBytes()
ren.RemoveAllViewProps()  # depth_of left the first mapper's actor
ren.AddActor(flier_actor)
flier.FreezeLevelOfDetailOn()
win.Render()
rebuilt = flier.GetLastMorphUploadBytes()
win.Render()
check(moved > 0 and rebuilt > 0 and flier.GetLastMorphUploadBytes() == 0,
      f"a second frozen frame uploads no geomorph factors ({flier.GetLastMorphUploadBytes()} bytes; "
      f"the first {rebuilt}, the last moving frame {moved})")
check(np.array_equal(refscene.depth(win), gpu_flight), "... and draws the same depth as the flight's last frame")
flier.FreezeLevelOfDetailOff()
ren.RemoveAllViewProps()
ren.AddActor(actor)
cam.SetPosition(*start)

# Another DEM on the same mapper with the same block grid (8 x 8 blocks) but other band
# starts (250 x 190 samples): the morph textures must follow the new quadtree, with no
# release of the mapper's GPU resources in between.
image2 = refscene.fractal_image(250, 190, seed=6)
win.Render()  # image's quadtree in the morph textures
mapper.SetInputData(image2)
win.Render()
gpu2 = refscene.depth(win)
f2 = geomipmap.vtkGeoMipMapFilter()
f2.SetInputData(image2)
f2.SetViewportSize(W, H)
f2.SetPixelError(TAU)
f2.SetBlockSize(BLOCK)
f2.SetCamera(cam)
f2.Update()
cpu2 = depth_of(refscene.stock_actor(f2.GetOutput()))
seen2 = cpu2 < 1.0
off2 = np.count_nonzero(np.abs(gpu2 - cpu2)[seen2] > eps)
check(np.count_nonzero(seen2) > 0.3 * W * H and off2 <= 0.002 * np.count_nonzero(seen2),
      f"a 250 x 190 DEM on the same mapper (same block grid, other bands): GPU morph = CPU "
      f"morph ({off2} of {np.count_nonzero(seen2)} pixels differ in depth)")
mapper.SetInputData(image)

# Block 8, with merges waiting for the geomorphing path (SetGeomorphMerges) on both: most
# blocks in view then morph toward their top level, one quad, split along the diagonal
# gmm::oneQuadAntiDiagonal picks for the block, and the shader must split it the same way
# (with the shader's split always along (i0, j0)-(i1, j1), 301 pixels differ here; with
# merges off, too few blocks morph that way to tell).
mapper.SetBlockSize(8)
mapper.GeomorphMergesOn()
win.Render()
gpu8 = refscene.depth(win)
f8 = new_filter(TAU, cam)
f8.SetBlockSize(8)
f8.GeomorphMergesOn()
f8.Update()
cpu8 = depth_of(refscene.stock_actor(f8.GetOutput()))
seen8 = cpu8 < 1.0
off8 = np.count_nonzero(np.abs(gpu8 - cpu8)[seen8] > eps)
check(mapper.GetNumberOfRenderedTriangles() == f8.GetOutput().GetNumberOfPolys(),
      f"block 8, merges on the path: mapper {mapper.GetNumberOfRenderedTriangles()} triangles, "
      f"filter {f8.GetOutput().GetNumberOfPolys()}")
check(np.count_nonzero(seen8) > 0.3 * W * H and off8 <= 0.0005 * np.count_nonzero(seen8),
      f"block 8, merges on the path: GPU morph = CPU morph ({off8} of {np.count_nonzero(seen8)} "
      f"pixels differ in depth)")
check_within_tau(check, image, ren, actor, mapper, "block 8, merges on the path")
mapper.SetBlockSize(BLOCK)
mapper.GeomorphMergesOff()

# Voids: blocks with nodata are drawn as cells (gmm HoleCells.h) and do not morph, the
# sides they share are at full resolution and do not move, and their neighbours morph
# beside them. The GPU must agree with the CPU there as well.
holed = refscene.fractal_image(257, 193, seed=5)
zh = vtk_to_numpy(holed.GetPointData().GetScalars()).reshape(ny, nx)
jj, ii = np.mgrid[0:ny, 0:nx]
voids = ((40, 60, 4), (90, 100, 6), (150, 70, 3), (200, 140, 5), (60, 150, 4))
for ci, cj, r in voids:
    zh[np.hypot(ii - ci, jj - cj) <= r] = np.nan
holed.Modified()
mapper.SetInputData(holed)
win.Render()
gpu_h = refscene.depth(win)
fh = new_filter(TAU, cam)
fh.SetInputData(holed)
fh.Update()
cpu_h = depth_of(refscene.stock_actor(fh.GetOutput()))
seen_h = cpu_h < 1.0
off_h = np.count_nonzero(np.abs(gpu_h - cpu_h)[seen_h] > eps)
check(np.count_nonzero(seen_h) > 0.3 * W * H and off_h <= 0.002 * np.count_nonzero(seen_h),
      f"voids: GPU morph = CPU morph ({off_h} of {np.count_nonzero(seen_h)} pixels differ in depth)")
check_within_tau(check, holed, ren, actor, mapper, "voids, morphed", uncovered_ok="as full resolution")
mapper.SetInputData(image)

mapper.GeomorphingOff()
win.Render()
gpu_plain = refscene.depth(win)
cpu_plain = depth_of(refscene.stock_actor(mesh_plain))
plain_off = np.count_nonzero(np.abs(gpu_plain - cpu_plain)[terrain] > eps)
print(f"geomorphing off: depth differs from the unmorphed mesh at {plain_off} pixels")
check(plain_off <= 0.002 * n, f"geomorphing off draws the unmorphed mesh ({plain_off} pixels differ)")
check_within_tau(check, image, ren, actor, mapper, "geomorphing off")
check.exit()
