"""Accuracy where users look (issue #12, parts 1-3): datum, vertical exaggeration, heights.

1. Origin z (datum): an image whose origin z is z0 is drawn at z0 + h, as vtkWarpScalar
   would put it. For z0 in {0, 1000, 6.4e6} (the last with x, y at 6.4e6 too): the
   mapper's bounds and the filter's points are numpy's z0 + h; the picture seen by a camera
   moved by the same offset is the origin's; the filter's triangles (the mapper's, same
   engine call) measure <= tau with vtkGeoMipMapScreenError.
   Regression: z0 was ignored (same bounds for 0 and 1000).
2. Height scale s in {0.5, 1, 3, 10} along a 16-frame flight: the filter's triangles
   measured with the scaled surface (vtkGeoMipMapScreenError's HeightScale) stay <= tau on
   every frame, and the mapper with the same scale draws the same triangle counts.
3. GetHeightAt on the mapper and the filter equals an independent numpy evaluation of the
   level-0 triangulation (NaN over holes and outside), and vtkWorldPointPicker picks on the
   rendered terrain lie on the drawn triangles (the filter's, evaluated in numpy) within
   the pixel's own depth-buffer step, and within the frame's certified geometric error
   (plus that step) of GetHeightAt under them.
"""
import math

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkWorldPointPicker

import geomipmap
import refscene

W, H = 400, 300
TAU = 2.0
check = refscene.Checks()


# Heights rounded to the float step at 6.4e6 (0.5 m) so every placement holds the very
# same surface, and a few holes.
z = refscene.heights(refscene.fractal_image(257, 257, seed=9))
z = np.round(z * 2.0) / 2.0
z[100:104, 120:131] = np.nan
z[30, 200] = np.nan


def placed(x0, y0, z0):
    return refscene.image_from_heights(z.astype(np.float32), origin=(x0, y0, z0))


def camera(cam, off, f=0, frames=1):
    a = 2 * math.pi * f / frames
    cx, cy = 3840.0 + off[0], 3840.0 + off[1]
    cam.SetPosition(cx + 14000 * math.cos(a), cy + 14000 * math.sin(a), off[2] + 6000.0)
    cam.SetFocalPoint(cx + 600 * math.cos(a + 2), cy + 600 * math.sin(a + 2), off[2] + 500.0)
    cam.SetViewUp(0, 0, 1)
    cam.SetViewAngle(40)


def measure(img, mesh, cam, scale=1.0):
    e = geomipmap.vtkGeoMipMapScreenError()
    e.SetHeightfield(img)
    e.SetHeightScale(scale)
    e.SetMesh(mesh)
    e.SetProjectionMatrix(cam.GetCompositeProjectionTransformMatrix(W / H, -1, 1))
    e.SetViewportSize(W, H)
    assert e.Compute()
    return e


def filtered(img, cam, scale=1.0, tau=TAU):
    f = geomipmap.vtkGeoMipMapFilter()
    f.SetInputData(img)
    f.SetCamera(cam)
    f.SetViewportSize(W, H)
    f.SetPixelError(tau)
    f.SetHeightScale(scale)
    f.Update()
    return f


# 1. Datum.
shots = []
zmin, zmax = float(np.nanmin(z)), float(np.nanmax(z))
for off in ((0.0, 0.0, 0.0), (0.0, 0.0, 1000.0), (6.4e6, 6.4e6, 6.4e6)):
    img = placed(*off)
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(img)
    mapper.SetPixelError(TAU)
    mapper.ScalarVisibilityOff()
    b = mapper.GetBounds()
    want = (off[0], off[0] + 7680.0, off[1], off[1] + 7680.0, off[2] + zmin, off[2] + zmax)
    check(all(abs(g - w) <= 1e-9 * max(1.0, abs(w)) for g, w in zip(b, want)),
          f"datum {off[2]:g}: bounds {tuple(round(v, 3) for v in b)}")
    actor = vtkActor()
    actor.SetMapper(mapper)
    ren = vtkRenderer()
    ren.AddActor(actor)
    win = refscene.window(W, H, ren)
    camera(ren.GetActiveCamera(), off)
    ren.ResetCameraClippingRange()
    win.Render()
    shots.append(refscene.grab(win))
    f = filtered(img, ren.GetActiveCamera())
    win.Finalize()  # one X connection at a time
    out = f.GetOutput()
    from vtkmodules.util.numpy_support import vtk_to_numpy
    pts = vtk_to_numpy(out.GetPoints().GetData())
    elev = vtk_to_numpy(out.GetPointData().GetArray("Elevation"))
    # Elevation is the drawn (geomorphed) height as float32, the points are in double.
    check(out.GetNumberOfPolys() == mapper.GetNumberOfRenderedTriangles() and
          np.all(np.abs((pts[:, 2] - off[2]) - elev) <= 1.2e-7 * np.maximum(1.0, np.abs(elev))),
          f"datum {off[2]:g}: {out.GetNumberOfPolys()} filter triangles (mapper "
          f"{mapper.GetNumberOfRenderedTriangles()}), every point at datum + h")
    e = measure(img, out, ren.GetActiveCamera())
    check(e.GetNumberOfSamplesInView() > 10000 and 0.0 < e.GetMaximumError() <= TAU,
          f"datum {off[2]:g}: measured error {e.GetMaximumError():.4f} px over "
          f"{e.GetNumberOfSamplesInView()} samples")
for k, off in ((1, 1000.0), (2, 6.4e6)):
    d = np.count_nonzero(np.abs(shots[k].astype(int) - shots[0].astype(int)).max(axis=2) > 8)
    check(d <= W * H // 200, f"datum {off:g}: {d} pixels differ from the origin's picture")

# 2. Height scale along a flight.
img = placed(0.0, 0.0, 0.0)
mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputData(img)
mapper.SetPixelError(TAU)
actor = vtkActor()
actor.SetMapper(mapper)
ren = vtkRenderer()
ren.AddActor(actor)
win = refscene.window(W, H, ren)
cam = ren.GetActiveCamera()
for s in (0.5, 1.0, 3.0, 10.0):
    mapper.SetHeightScale(s)
    worst, agree, frames = 0.0, 0, 16
    for f in range(frames):
        camera(cam, (0.0, 0.0, 0.0), f, frames)
        cam.SetPosition(cam.GetPosition()[0], cam.GetPosition()[1], 500.0 + s * 4000.0)
        ren.ResetCameraClippingRange()
        win.Render()
        flt = filtered(img, cam, s)
        agree += flt.GetOutput().GetNumberOfPolys() == mapper.GetNumberOfRenderedTriangles()
        e = measure(img, flt.GetOutput(), cam, s)
        worst = max(worst, e.GetMaximumError())
    b = mapper.GetBounds()
    check(0.0 < worst <= TAU and agree == frames and abs(b[5] - s * zmax) < 1e-6 * s * zmax,
          f"height scale {s:g}: worst measured error {worst:.4f} px over {frames} frames, "
          f"mapper and filter agree on {agree} frames, top at {b[5]:.1f}")

# 3. GetHeightAt against numpy, and picks on the rendered terrain.
mapper.SetHeightScale(2.0)
flt = geomipmap.vtkGeoMipMapFilter()
flt.SetInputData(img)
flt.SetHeightScale(2.0)
rng = np.random.default_rng(4)


def numpy_height(x, y, s=2.0):
    gx, gy = x / 30.0, y / 30.0
    if not (0 <= gx <= 256 and 0 <= gy <= 256):
        return float("nan")
    i, j = min(int(gx), 255), min(int(gy), 255)
    fx, fy = gx - i, gy - j
    # The union jack: quad (i, j) split along (i, j)-(i+1, j+1) where i + j is even, along
    # (i+1, j)-(i, j+1) where it is odd.
    if (i + j) % 2 == 0:
        if fx >= fy:  # triangle (i, j), (i+1, j), (i+1, j+1)
            h = (1 - fx) * z[j, i] + (fx - fy) * z[j, i + 1] + fy * z[j + 1, i + 1]
        else:  # triangle (i, j), (i+1, j+1), (i, j+1)
            h = (1 - fy) * z[j, i] + (fy - fx) * z[j + 1, i] + fx * z[j + 1, i + 1]
    elif fx + fy <= 1:  # triangle (i, j), (i+1, j), (i, j+1)
        h = (1 - fx - fy) * z[j, i] + fx * z[j, i + 1] + fy * z[j + 1, i]
    else:  # triangle (i+1, j), (i+1, j+1), (i, j+1)
        h = (1 - fy) * z[j, i + 1] + (fx + fy - 1) * z[j + 1, i + 1] + (1 - fx) * z[j + 1, i]
    return s * h


worst, nans = 0.0, 0
for x, y in rng.uniform(-200.0, 7900.0, size=(3000, 2)):
    want = numpy_height(x, y)
    for got in (mapper.GetHeightAt(x, y), flt.GetHeightAt(x, y)):
        if math.isnan(want):
            nans += 1
            if not math.isnan(got):
                check(False, f"GetHeightAt({x:.1f}, {y:.1f}) = {got}, expected NaN")
        else:
            worst = max(worst, abs(got - want))
check(worst < 1e-6 and nans > 100, f"GetHeightAt: 3000 points, worst difference from numpy "
      f"{worst:.2e} m, {nans // 2} NaN (holes, outside)")

cam.SetPosition(1000.0, -2500.0, 6000.0)
cam.SetFocalPoint(3840.0, 3840.0, 1000.0)
ren.ResetCameraClippingRange()
# The picks are compared with a fresh filter's mesh for this camera. Geomorphing limits how
# fast a morph factor rises from the frames a mapper drew before, so the picked frame is a
# fresh mapper's first (which is the fresh filter's).
mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputData(img)
mapper.SetHeightScale(2.0)
actor.SetMapper(mapper)
mapper.SetPixelError(4.0)  # coarse on purpose: the pick sees the drawn surface
win.Render()
certified = mapper.GetMaximumGeometricError()
drawn = filtered(img, cam, 2.0, 4.0).GetOutput()
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
P = vtk_to_numpy(drawn.GetPoints().GetData())
T = vtk_to_numpy(drawn.GetPolys().GetConnectivityArray()).reshape(-1, 3)


def drawn_height(x, y):
    """The drawn triangles' height at (x, y), by barycentric coordinates in numpy."""
    a, b, c = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
    det = (b[:, 1] - c[:, 1]) * (a[:, 0] - c[:, 0]) + (c[:, 0] - b[:, 0]) * (a[:, 1] - c[:, 1])
    l1 = ((b[:, 1] - c[:, 1]) * (x - c[:, 0]) + (c[:, 0] - b[:, 0]) * (y - c[:, 1])) / det
    l2 = ((c[:, 1] - a[:, 1]) * (x - c[:, 0]) + (a[:, 0] - c[:, 0]) * (y - c[:, 1])) / det
    l3 = 1 - l1 - l2
    k = np.nonzero((l1 >= -1e-9) & (l2 >= -1e-9) & (l3 >= -1e-9))[0]
    return float(np.mean(l1[k] * a[k, 2] + l2[k] * b[k, 2] + l3[k] * c[k, 2])) if k.size else math.nan


picker = vtkWorldPointPicker()
worst_pick, worst_true, beyond, picks = -math.inf, 0.0, 0, 0
for px in range(20, W, 40):
    for py in range(20, H, 40):
        # At the pixel's centre, where its depth value was rasterised (the picker reads the
        # depth of pixel (int x, int y) and unprojects the display point as given).
        picker.Pick(px + 0.5, py + 0.5, 0, ren)
        x, y, zp = picker.GetPickPosition()
        zh, zd = mapper.GetHeightAt(x, y), drawn_height(x, y)
        depth = win.GetZbufferDataAtPoint(px, py)
        if depth >= 1.0 or math.isnan(zh) or math.isnan(zd):
            continue
        # This pixel's depth step: where the neighbouring depth values put the point.
        ends = []
        for dz in (-2.0 ** -22, 2.0 ** -22):  # +-4 steps of a 24-bit depth buffer
            ren.SetDisplayPoint(px + 0.5, py + 0.5, depth + dz)
            ren.DisplayToWorld()
            wp = ren.GetWorldPoint()
            ends.append(np.array(wp[:3]) / wp[3])
        step = float(np.linalg.norm(ends[1] - ends[0]))
        picks += 1
        worst_pick = max(worst_pick, abs(zp - zd) - step)
        worst_true = max(worst_true, abs(zp - zh))
        beyond += abs(zp - zh) > certified + step
check(picks > 20 and worst_pick <= 0.0,
      f"{picks} world-point picks at tau 4 lie on the drawn triangles within the pixel's depth "
      f"step (worst margin {-worst_pick:.3f} m)")
check(beyond == 0, f"picks vs GetHeightAt: worst {worst_true:.2f} m, within the frame's "
      f"certified {certified:.2f} m plus the depth step ({beyond} of {picks} beyond)")

check.exit()
