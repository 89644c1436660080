"""vtkGeoMipMapFilter's update costs memory that follows its output, not the DEM (issue #11).

Before, each update numbered the used samples through a table over all of the DEM's
samples (8 bytes each: 134 MB per update at 4097^2, 2 GiB at 16385^2, where an update took
6.1 s for 87 k triangles). Now the used samples are sorted instead. Measured here with the
process's peak RSS (VmHWM, reset through /proc/self/clear_refs before the update): after a
first update (tables built), an update from another view may grow the peak by at most 4x
the output mesh's own bytes; the table over all samples alone is 15x those. The output
must also be the mesh the samples say: each point at its sample's grid position, every
point used.
"""
import math
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkCamera

import geomipmap
import refscene

check = refscene.Checks()
N = 4097


def status_kb(key):
    with open("/proc/self/status") as f:
        return next(int(l.split()[1]) for l in f if l.startswith(key + ":"))


try:
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")  # resets VmHWM to VmRSS (Linux >= 4.0)
except OSError as e:
    print("SKIP: cannot reset the peak RSS here (%s)" % e)
    sys.exit(0)

src = geomipmap.vtkGeoMipMapFractalSource()
src.SetDimensions(N, N)
src.SetSeed(1)
src.Update()
image = src.GetOutput()
x0, x1, y0, y1, z0, z1 = image.GetBounds()
cx, cy, r = 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (x1 - x0)
cam = vtkCamera()
cam.SetViewAngle(45.0)
cam.SetViewUp(0.0, 0.0, 1.0)
cam.SetClippingRange(1.0, 4.0 * r)
f = geomipmap.vtkGeoMipMapFilter()
f.SetInputData(image)
f.SetCamera(cam)
f.SetViewportSize(1280, 720)
f.SetPixelError(1.0)


def update(k):
    a = 2.0 * math.pi * k / 8.0
    cam.SetPosition(cx + 0.7 * r * math.cos(a), cy + 0.7 * r * math.sin(a), z1 + 0.05 * r)
    cam.SetFocalPoint(cx, cy, z0)
    f.Modified()
    f.Update()


update(0)  # builds the tables
with open("/proc/self/clear_refs", "w") as fh:
    fh.write("5")
before = status_kb("VmRSS")
update(3)
growth = (status_kb("VmHWM") - before) * 1024.0
mesh = f.GetOutput()
n_pts, n_tris = mesh.GetNumberOfPoints(), mesh.GetNumberOfPolys()
out_bytes = n_pts * (24 + 4 + 12) + n_tris * (3 * 8 + 8)  # xyz, elevation, normals; cells
print("update from a new view: %d triangles, %d points, output %.1f MB, peak grew %.1f MB"
      % (n_tris, n_pts, out_bytes / 1e6, growth / 1e6))
check(n_tris > 10000, "the view draws a real mesh (%d triangles)" % n_tris)
check(growth <= 4.0 * out_bytes, "an update grows the peak by %.1f MB, at most 4x its output's "
      "%.1f MB (a table over the %d samples would be %.0f MB)"
      % (growth / 1e6, out_bytes / 1e6, N * N, 8.0 * N * N / 1e6))

# The output mesh, against the input grid: every point lies on a sample (x and y on the
# grid; geomorphing moves heights only), no sample twice, and every point is used.
xyz = vtk_to_numpy(mesh.GetPoints().GetData())
ox, oy, _ = image.GetOrigin()
dx, dy, _ = image.GetSpacing()
i = (xyz[:, 0] - ox) / dx
j = (xyz[:, 1] - oy) / dy
check(np.allclose(i, np.round(i), atol=1e-6) and np.allclose(j, np.round(j), atol=1e-6),
      "every point lies on a grid sample")
ids = np.round(j).astype(np.int64) * N + np.round(i).astype(np.int64)
check(len(np.unique(ids)) == n_pts, "no sample appears twice among the points")
conn = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray())
check(len(np.unique(conn)) == n_pts, "every point is used by a triangle")
check.exit()
