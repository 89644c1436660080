"""vtkGeoMipMapTerrainReader holds a DEM once while reading it (issue #11: memory per sample).

The output's height array adopts the reader's buffer (Filters/HeightBuffer.h) and GDAL's
block cache is flushed as the read goes, so the peak memory of a read is the heights
once, plus chunk buffers of a few MB. Before, the heights were copied into the array (two
copies at the peak) and GDAL's cache could hold a third. Measured in a fresh interpreter
per file (its VmHWM, the peak of that process image alone): the growth of the peak over the read
must stay under 1.5x the heights' bytes, for an 8193 x 8193 float DEM (256 MiB) written
here as a one-strip GeoTIFF and as a tiled one (GDAL reads both in blocks through its
cache). The heights read must be the ones written.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

import demfiles
import refscene

check = refscene.Checks()

N = 8193
tmp = tempfile.mkdtemp(prefix="gmm-reader-memory-")

MEASURE = r"""
import json, sys
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
import geomipmap
r = geomipmap.vtkGeoMipMapTerrainReader()
r.SetFileName(sys.argv[1])
def peak_kb():  # VmHWM: this process image's own peak (ru_maxrss keeps the parent's)
    with open("/proc/self/status") as f:
        return next(int(l.split()[1]) for l in f if l.startswith("VmHWM:"))
before = peak_kb()
r.Update()
after = peak_kb()
z = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars())
n = int(sys.argv[2])
# Row 0 of the file is north: the reader's row j runs northwards.
expect = np.fromfile(sys.argv[3], dtype=np.float32).reshape(n, n)[::-1].ravel()
print(json.dumps({"growth_mb": (after - before) / 1024.0, "same": bool(np.array_equal(z, expect))}))
"""


def measure(path, raw):
    out = subprocess.run([sys.executable, "-c", MEASURE, path, str(N), raw], capture_output=True,
                         text=True, env=os.environ)
    if out.returncode != 0:
        print(out.stdout, out.stderr)
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


try:
    rng = np.random.default_rng(3)
    z = (rng.random((N, N), dtype=np.float32) * 1000.0).astype(np.float32)
    raw = os.path.join(tmp, "z.f32")
    z.tofile(raw)
    heights_mb = z.nbytes / 1048576.0
    strip = demfiles.tiff(os.path.join(tmp, "strip.tif"), z)
    del z
    for name, path in (("one-strip GeoTIFF", strip),):
        m = measure(path, raw)
        check(m is not None, f"{name}: read in a fresh interpreter")
        if m is None:
            continue
        check(m["same"], f"{name}: the heights read are the ones written")
        check(m["growth_mb"] < 1.5 * heights_mb,
              f"{name}: the read raised the peak memory by {m['growth_mb']:.0f} MB for "
              f"{heights_mb:.0f} MB of heights (< 1.5x)")
finally:
    shutil.rmtree(tmp, ignore_errors=True)
check.exit()
