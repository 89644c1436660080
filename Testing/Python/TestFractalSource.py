"""vtkGeoMipMapFractalSource: determinism, odd sizes, range, and clean failures."""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from geomipmap import vtkGeoMipMapFractalSource
from gmmtestutil import ErrorCatcher, check, update


def make(nx, ny, seed=1, spacing=30.0, amplitude=1500.0):
    s = vtkGeoMipMapFractalSource()
    s.SetDimensions(nx, ny)
    s.SetSeed(seed)
    s.SetSpacing(spacing)
    s.SetAmplitude(amplitude)
    errors = ErrorCatcher(s)
    ok = update(s)
    return s, ok, errors


def heights(nx, ny, **kw):
    s, ok, errors = make(nx, ny, **kw)
    check(ok and not errors.messages, "%d x %d generates (%s)" % (nx, ny, errors.messages))
    img = s.GetOutput()
    check(img.GetDimensions() == (nx, ny, 1), "dimensions %s" % (img.GetDimensions(),))
    arr = img.GetPointData().GetScalars()
    check(arr.GetName() == "Elevation" and arr.GetDataType() == 10, "float32 Elevation scalars")
    return vtk_to_numpy(arr).copy()


a = heights(257, 129, seed=5)
b = heights(257, 129, seed=5)
c = heights(257, 129, seed=6)
check(np.array_equal(a, b), "same seed, same heights (bit-identical)")
check(not np.array_equal(a, c), "different seed, different heights")
check(np.isfinite(a).all() and a.min() >= 0 and a.max() <= 1500 + 1e-3, "heights in [0, 1500]")
check(a.max() - a.min() > 750, "uses most of the amplitude (%.1f)" % (a.max() - a.min()))
check(float(np.abs(np.diff(a.reshape(129, 257), axis=1)).mean()) > 0.1, "not flat")
for nx, ny in ((2, 2), (1000, 37), (37, 1000), (101, 103), (257, 2), (2, 257)):
    z = heights(nx, ny)
    check(np.isfinite(z).all(), "%d x %d finite" % (nx, ny))
d = heights(101, 103, amplitude=3000.0)
check(d.max() <= 3000 + 1e-3 and d.max() > 1500, "amplitude scales heights")

for dims in ((1, 5), (5, 1), (0, 0), (-3, 10), (70000, 70000)):
    s, ok, errors = make(*dims)
    check(not ok and errors.messages, "%s fails with an error: %s" % (dims, errors.messages))
s, ok, errors = make(10, 10, spacing=0.0)
check(not ok and errors.messages, "spacing 0 fails")
s, ok, errors = make(10, 10)
check(ok, "a good size works again after failures")
print("PASS")
