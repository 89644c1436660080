"""vtkGeoMipMapTerrainReader holds a DEM once while reading it (issue #11: memory per sample).

The output's height array adopts the reader's buffer (Filters/HeightBuffer.h), GDAL's
block cache is flushed as the read goes, and scanline images are decoded in chunks, so the
peak memory of a read is the heights once, plus chunk buffers of a few MB. Before, the
heights were copied into the array (two copies at the peak), GDAL's cache could hold a
third, and a PNG's decoded image was held whole beside the heights. Measured in a fresh
interpreter per file (its VmHWM, the peak of that process image alone), for 8193 x 8193
samples (256 MiB of float heights): the growth of the peak over the read must stay under
1.5x the heights' bytes for a float one-strip GeoTIFF (GDAL reads it in blocks through its
cache; 2.1x before), and under 1.25x for a 16-bit PNG (OpenImageIO; 1.5x before). The
heights read must be the ones written.
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
expect = np.fromfile(sys.argv[2], dtype=np.float32)  # in the reader's order: row 0 south
print(json.dumps({"growth_mb": (after - before) / 1024.0, "same": bool(np.array_equal(z, expect))}))
"""


def measure(path, raw):
    out = subprocess.run([sys.executable, "-c", MEASURE, path, raw], capture_output=True,
                         text=True, env=os.environ)
    if out.returncode != 0:
        print(out.stdout, out.stderr)
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


try:
    rng = np.random.default_rng(3)
    z = (rng.random((N, N), dtype=np.float32) * 1000.0).astype(np.float32)
    heights_mb = z.nbytes / 1048576.0
    tiff_raw = os.path.join(tmp, "tiff.f32")
    z[::-1].tofile(tiff_raw)  # the file's row 0 is north; the reader's row 0 is south
    cases = [("one-strip float GeoTIFF", demfiles.tiff(os.path.join(tmp, "strip.tif"), z), tiff_raw, 1.5)]
    del z
    j, i = np.mgrid[0:N, 0:N]
    u = ((i * 7 + j * 3) % 65536).astype(np.uint16)
    del i, j
    png_raw = os.path.join(tmp, "png.f32")
    u.astype(np.float32).tofile(png_raw)
    cases.append(("16-bit PNG", demfiles.png16(os.path.join(tmp, "u16.png"), u), png_raw, 1.25))
    del u
    for name, path, raw, most in cases:
        m = measure(path, raw)
        check(m is not None, f"{name}: read in a fresh interpreter")
        if m is None:
            continue
        check(m["same"], f"{name}: the heights read are the ones written")
        check(m["growth_mb"] < most * heights_mb,
              f"{name}: the read raised the peak memory by {m['growth_mb']:.0f} MB for "
              f"{heights_mb:.0f} MB of heights (< {most}x)")
finally:
    shutil.rmtree(tmp, ignore_errors=True)
check.exit()
