"""vtkGeoMipMapScreenError against a hand-computed case.

A 5 x 5 grid (spacing 1) samples the tilted plane z = 0.5 x, except the sample at
(3, 2), raised by 1. The mesh is two triangles over the four corners (the plane itself).
A camera straight above (2, 2, 10), looking down, 90 degree view angle, 200 x 200 pixels:
a point at height z and x = 2 + d maps to pixel column 100 + 100 d / (10 - z). The raised
sample's true point (z 2.5) and drawn point (z 1.5) are 100 (1 / 7.5 - 1 / 8.5) =
1.568627 px apart; every other sample lies on the mesh (0 px).
Also: negative y spacing (same geometry, rows flipped), a nodata sample, a mesh with a hole
(uncovered samples) and bad input (a clear error, no crash).
"""

import sys

import numpy as np
import geomipmap
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData
from vtkmodules.vtkRenderingCore import vtkCamera

EXPECTED = 100.0 * (1.0 / 7.5 - 1.0 / 8.5)
failures = []


def check(what, got, want, tol):
    if not abs(got - want) <= tol:
        failures.append(f"{what}: got {got}, expected {want} (+-{tol})")


def grid(z, origin=(0.0, 0.0), spacing=(1.0, 1.0)):
    img = vtkImageData()
    img.SetDimensions(z.shape[1], z.shape[0], 1)
    img.SetOrigin(origin[0], origin[1], 0.0)
    img.SetSpacing(spacing[0], spacing[1], 1.0)
    img.GetPointData().SetScalars(numpy_to_vtk(z.astype(np.float32).ravel(), deep=1))
    return img


def mesh(points, triangles):
    pd = vtkPolyData()
    pts = vtkPoints()
    for p in points:
        pts.InsertNextPoint(*p)
    pd.SetPoints(pts)
    cells = vtkCellArray()
    for t in triangles:
        cells.InsertNextCell(3, t)
    pd.SetPolys(cells)
    return pd


def measure(img, pd):
    cam = vtkCamera()
    cam.SetPosition(2, 2, 10)
    cam.SetFocalPoint(2, 2, 0)
    cam.SetViewUp(0, 1, 0)
    cam.SetViewAngle(90)
    cam.SetClippingRange(1, 100)
    e = geomipmap.vtkGeoMipMapScreenError()
    e.SetHeightfield(img)
    e.SetMesh(pd)
    e.SetViewportSize(200, 200)
    e.SetProjectionMatrix(cam.GetCompositeProjectionTransformMatrix(1.0, -1, 1))
    ok = e.Compute()
    return ok, e


x = np.arange(5.0)
z = np.tile(0.5 * x, (5, 1))  # z[j, i] = 0.5 * i
z[2, 3] += 1.0
plane = mesh([(0, 0, 0), (4, 0, 2), (4, 4, 2), (0, 4, 0)], [(0, 1, 2), (0, 2, 3)])

ok, e = measure(grid(z), plane)
check("Compute", ok, True, 0)
check("max", e.GetMaximumError(), EXPECTED, 1e-4)
check("mean", e.GetMeanError(), EXPECTED / 25, 1e-5)
check("p99 (24 of 25 samples exact)", e.GetPercentile99Error(), 0.0, 1e-4)
check("in view", e.GetNumberOfSamplesInView(), 25, 0)
check("uncovered", e.GetNumberOfUncoveredSamples(), 0, 0)

# Negative y spacing: rows stored north to south, same world geometry.
ok, e = measure(grid(z[::-1], origin=(0.0, 4.0), spacing=(1.0, -1.0)), plane)
check("flipped max", e.GetMaximumError(), EXPECTED, 1e-4)
check("flipped in view", e.GetNumberOfSamplesInView(), 25, 0)

# Nodata: the raised sample is NaN, so it is skipped and nothing else is off the plane.
zn = z.copy()
zn[2, 3] = np.nan
ok, e = measure(grid(zn), plane)
check("nodata in view", e.GetNumberOfSamplesInView(), 24, 0)
check("nodata max", e.GetMaximumError(), 0.0, 1e-4)

# A hole: only the triangle x >= y is drawn; the 10 samples with x < y are uncovered.
half = mesh([(0, 0, 0), (4, 0, 2), (4, 4, 2)], [(0, 1, 2)])
ok, e = measure(grid(z), half)
check("hole uncovered", e.GetNumberOfUncoveredSamples(), 10, 0)
check("hole max", e.GetMaximumError(), EXPECTED, 1e-4)

# ReferenceMesh (the popping measure): the full-resolution mesh of z as the reference and
# the plane as the mesh, over a flat heightfield (which then only gives the grid): the same
# 1.568627 px at the raised sample. Swapping the two meshes projects the other way round:
# drawn 2.5 (1 / 7.5) against reference 1.5 (1 / 8.5), the same distance. Over the
# half-plane mesh, the 10 samples it leaves uncovered are uncovered here too.
full = mesh([(i, j, z[j, i]) for j in range(5) for i in range(5)],
            [t for j in range(4) for i in range(4)
             for t in (((j * 5 + i), (j * 5 + i + 1), ((j + 1) * 5 + i + 1)),
                       ((j * 5 + i), ((j + 1) * 5 + i + 1), ((j + 1) * 5 + i)))])
for what, drawn, ref, uncovered in (("reference", plane, full, 0), ("swapped", full, plane, 0),
                                     ("reference, half mesh", half, full, 10)):
    cam = vtkCamera()
    cam.SetPosition(2, 2, 10)
    cam.SetFocalPoint(2, 2, 0)
    cam.SetViewUp(0, 1, 0)
    cam.SetViewAngle(90)
    cam.SetClippingRange(1, 100)
    e = geomipmap.vtkGeoMipMapScreenError()
    e.SetHeightfield(grid(np.zeros((5, 5))))
    e.SetMesh(drawn)
    e.SetReferenceMesh(ref)
    e.SetViewportSize(200, 200)
    e.SetProjectionMatrix(cam.GetCompositeProjectionTransformMatrix(1.0, -1, 1))
    check(what + " Compute", e.Compute(), True, 0)
    check(what + " max", e.GetMaximumError(), EXPECTED, 1e-4)
    check(what + " in view", e.GetNumberOfSamplesInView(), 25, 0)
    check(what + " uncovered", e.GetNumberOfUncoveredSamples(), uncovered, 0)

# Bad input: no mesh -> False with an error event, results zero.
errors = []
bad = geomipmap.vtkGeoMipMapScreenError()
bad.AddObserver(vtkCommand.ErrorEvent, lambda *a: errors.append(a))
bad.SetHeightfield(grid(z))
check("no mesh returns False", bad.Compute(), False, 0)
check("no mesh reports an error", len(errors), 1, 0)

if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print(f"ok: raised sample measures {EXPECTED:.6f} px as computed by hand")
