"""vtkGeoMipMapTerrainReader on bad files, generated at test time in a temp folder.

Each bad file must: fail the update, raise an ErrorEvent whose text names the file, not
raise the peak memory (ru_maxrss) by more than 64 MB over all of them (the largest
legitimate decode here is a few MB; an absurd header honoured would need GBs), and leave the same reader able to
read a good file afterwards. Real-data variants (truncated copies) run only when the data
files exist (gmmdata.py: with GEOMIPMAP_REQUIRE_DATA=1 a missing file fails the test).
"""
import os
import shutil
import tempfile

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.util.vtkConstants import VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT

import demfiles
from geomipmap import vtkGeoMipMapTerrainReader
from gmmdata import optional_data_file
from gmmtestutil import ErrorCatcher, check, max_rss_mb, update

tmp = tempfile.mkdtemp(prefix="gmm-malformed-")


def path(name):
    return os.path.join(tmp, name)


def write(name, content):
    with open(path(name), "wb") as f:
        f.write(content.encode() if isinstance(content, str) else content)
    return path(name)


def png(name, channels, vtk_type, values):
    img = vtkImageData()
    img.SetDimensions(16, 8, 1)
    img.AllocateScalars(vtk_type, channels)
    for k in range(img.GetNumberOfPoints()):
        for c in range(channels):
            img.GetPointData().GetScalars().SetComponent(k, c, values)
    w = vtkPNGWriter()
    w.SetFileName(path(name))
    w.SetInputData(img)
    w.Write()
    return path(name)


good_asc = write("good.asc", "ncols 3\nnrows 2\nxllcorner 500000\nyllcorner 4000000\n"
                 "cellsize 10\nNODATA_value -9999\n1 2 3\n4 5 -9999\n")

bad = []  # (file, reader options)
bad.append((path("missing.tif"), {}))
bad.append((write("empty.tif", b""), {}))
bad.append((write("empty.hgt", b""), {}))
rng = np.random.default_rng(7)
for ext in ("tif", "dem", "asc", "png", "hgt", "bin"):
    bad.append((write("random." + ext, rng.integers(0, 256, 100000, dtype=np.uint8).tobytes()), {}))
for n in ("2147483648", "2147483647", "100000"):
    bad.append((write("huge%s.asc" % n, "ncols %s\nnrows %s\nxllcorner 0\nyllcorner 0\n"
                      "cellsize 1\nNODATA_value -9999\n1 2 3 4\n" % (n, n)), {}))
bad.append((write("short.asc", "ncols 300\nnrows 200\nxllcorner 0\nyllcorner 0\n"
                  "cellsize 1\n" + "1 " * 1000 + "\n"), {}))
bad.append((png("grey16.png", 1, VTK_UNSIGNED_SHORT, 1000), {"TerrainRGB": 1}))
bad.append((png("rgb.png", 3, VTK_UNSIGNED_CHAR, 100), {}))
# Wrong sample type: an ENVI raster of complex floats.
write("complex.hdr", "ENVI\nsamples = 4\nlines = 4\nbands = 1\nheader offset = 0\n"
      "file type = ENVI Standard\ndata type = 6\ninterleave = bsq\nbyte order = 0\n")
bad.append((write("complex.img", bytes(4 * 4 * 8)), {}))
bad.append((good_asc, {"Spacing": 0.0}))
# TIFFs with forged headers (demfiles writes them byte by byte): absurd ImageWidth x
# ImageLength on a 12-sample file, uncompressed and claiming deflate; wrong sample types.
z34 = np.arange(12, dtype=np.int16).reshape(3, 4)
for w, h in ((2 ** 31 - 1, 2 ** 31 - 1), (100000, 100000), (40000, 40000)):
    bad.append((demfiles.tiff(path("forged%dx%d.tif" % (w, h)), z34, width=w, height=h), {}))
bad.append((demfiles.tiff(path("forged_deflate.tif"), z34, width=40000, height=40000,
                          compression=8), {}))
bad.append((demfiles.tiff(path("complex.tif"), z34.astype(np.complex64)), {}))
bad.append((demfiles.tiff(path("rgb8.tif"), np.zeros((3, 4, 3), np.uint8), rgb=True), {}))
# SRTM tiles are identified by size: a wrong-sized .hgt is not silently reshaped.
bad.append((write("N00E000.hgt", bytes(1000)), {}))
bad.append((write("N01E000.hgt", bytes(1201 * 1201 * 2 - 2)), {}))
bad.append((png("grey8.png", 1, VTK_UNSIGNED_CHAR, 100), {"TerrainRGB": 1}))
for name, frac in (("N42E001.hgt", 0.5), ("mt_rainier_90m.tif", 0.5),
                   ("SainteHelens.dem", 0.3), ("ps_height_1k.png", 0.5),
                   ("fuji_terrain_rgb.png", 0.5), ("boulder_srtmgl3.asc", 0.4)):
    real = optional_data_file(name)
    if real is None:
        continue
    with open(real, "rb") as f:
        content = f.read()
    opts = {"TerrainRGB": 1} if name.startswith("fuji") else {}
    bad.append((write("truncated_" + name, content[: int(len(content) * frac)]), opts))

reader = vtkGeoMipMapTerrainReader()
errors = ErrorCatcher(reader)
rss0 = max_rss_mb()
failures = []
worst_rise = (0.0, None)  # largest rise of the peak memory during one bad file
for f, opts in bad:
    before = max_rss_mb()
    reader.SetTerrainRGB(0)
    reader.SetSpacing(1.0)
    for k, v in opts.items():
        getattr(reader, "Set" + k)(v)
    reader.SetFileName(f)
    errors.clear()
    ok = update(reader)
    named = any(os.path.basename(f) in m for m in errors.messages)
    rise = max_rss_mb() - before
    print("%-32s update=%s peak+%.1fMB error=%s" % (os.path.basename(f), ok, rise,
                                         [l for l in errors.messages[0].splitlines() if "Cannot read" in l][0].split(": ", 1)[-1][-170:] if errors.messages else None))
    if ok or not named:
        failures.append(os.path.basename(f))
    if rise > worst_rise[0]:
        worst_rise = (rise, os.path.basename(f))
    # The same reader reads a good file right after.
    reader.SetTerrainRGB(0)
    reader.SetSpacing(1.0)
    reader.SetFileName(good_asc)
    errors.clear()
    if not update(reader) or reader.GetOutput().GetDimensions() != (3, 2, 1):
        failures.append("good file after " + os.path.basename(f))
rss1 = max_rss_mb()

# A good file larger than the memory limit: refused before its samples are read, with an
# error naming the file, its size and the limit; read once the limit is lifted.
big = write("big.asc", "ncols 300\nnrows 200\nxllcorner 0\nyllcorner 0\ncellsize 30\n" +
            "\n".join(" ".join(str((i * j) % 97) for i in range(300)) for j in range(200)) + "\n")
reader.SetFileName(big)
reader.SetMemoryLimit(200000)  # 300 x 200 floats, twice: 480000 bytes
errors.clear()
refused = not update(reader)
text = " ".join(errors.messages)
check(refused and "big.asc" in text and "300 x 200" in text and "MemoryLimit" in text,
      "a file over MemoryLimit is refused with its name and size (%s)" % text[-160:])
reader.SetMemoryLimit(0)
errors.clear()
check(update(reader) and reader.GetOutput().GetDimensions() == (300, 200, 1),
      "the same file reads with the limit lifted")
shutil.rmtree(tmp, ignore_errors=True)
check(not failures, "every bad file fails with an error naming it (bad: %s)" % failures)
print("%d bad files; largest peak-memory rise in one file: %.1f MB (%s)"
      % (len(bad), worst_rise[0], worst_rise[1]))
check(rss1 - rss0 < 64, "peak memory rose %.1f MB over all bad files (< 64)" % (rss1 - rss0))
print("PASS")
