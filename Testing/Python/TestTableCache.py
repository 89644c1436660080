"""The error table cache through the VTK classes (issue #11): a second open of the same DEM
reads the tables instead of building them and draws the very same picture, certified by
the independent screen-error measure; a corrupt file is refused with a warning, rebuilt
and replaced; SetTableCache(False) writes nothing; $GEOMIPMAP_CACHE_DIR moves the default
location; vtkGeoMipMapFilter shares the cache.
"""
import glob
import os
import shutil
import sys

import numpy as np
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer

import geomipmap
import refscene
from gmmtestutil import check_drawn_within_tau

N = 1025  # 1,050,625 samples: at least the 2^20 below which nothing is cached
WORK = os.path.join(os.getcwd(), "TestTableCache.work")
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
ok = refscene.Checks()


def source():
    return refscene.fractal_image(N, N, seed=3)


class Warnings:
    """WarningEvent texts of one object (the cache warns through vtkGenericWarningMacro,
    which goes to the output window: captured there)."""

    def __init__(self):
        from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

        self.win = vtkStringOutputWindow()
        self.previous = vtkOutputWindow.GetInstance()
        vtkOutputWindow.SetInstance(self.win)

    def text(self):
        return self.win.GetOutput()

    def close(self):
        from vtkmodules.vtkCommonCore import vtkOutputWindow

        vtkOutputWindow.SetInstance(self.previous)


def render(directory=None, enabled=True):
    """Renders a fresh image of the DEM with a fresh mapper; returns (pixels, mapper,
    renderer, actor, image)."""
    image = source()
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(image)
    mapper.SetPixelError(1.5)
    mapper.SetTableCache(enabled)
    if directory is not None:
        mapper.SetTableCacheDirectory(directory)
    actor = vtkActor()
    actor.SetMapper(mapper)
    ren = vtkRenderer()
    ren.AddActor(actor)
    win = refscene.window(480, 320, ren)
    cam = ren.GetActiveCamera()
    ext = (N - 1) * 30.0
    cam.SetPosition(0.2 * ext, -0.1 * ext, 4000.0)
    cam.SetFocalPoint(0.6 * ext, 0.6 * ext, 0.0)
    cam.SetViewUp(0, 0, 1)
    ren.ResetCameraClippingRange()
    win.Render()
    ren._window = win  # the measure below needs the renderer's window alive
    return refscene.grab(win), mapper, ren, actor, image


def tables(directory):
    return sorted(glob.glob(os.path.join(directory, "*.gmmtable")))


# 1. First open builds and saves; the second reads; the pictures are identical.
cache = os.path.join(WORK, "cache")
first, m1, _, _, _ = render(cache)
ok(not m1.GetLastTablesFromCache(), "first open builds the tables")
files = tables(cache)
ok(len(files) == 1, "one table file written (%s)" % [os.path.basename(f) for f in files])
second, m2, ren2, actor2, image2 = render(cache)
ok(m2.GetLastTablesFromCache(), "second open reads them from the cache")
ok(m2.GetLastTerrainBuildTime() < m1.GetLastTerrainBuildTime(),
   "and takes less time (%.3f s against %.3f s)" % (m2.GetLastTerrainBuildTime(), m1.GetLastTerrainBuildTime()))
ok(np.array_equal(first, second), "same picture from cached and built tables")
ok(m2.GetNumberOfRenderedTriangles() == m1.GetNumberOfRenderedTriangles(), "same triangle count")
# Independent: the drawn surface against the full-resolution heights (the measuring filter
# reads the same cache, so this also covers vtkGeoMipMapFilter's use of it).
os.environ["GEOMIPMAP_CACHE_DIR"] = cache
check_drawn_within_tau(image2, ren2, actor2, m2, "cached tables")
ok(len(tables(cache)) == 1, "the filter found the mapper's file (no second table)")

# 2. A corrupt file: a warning naming it, tables rebuilt, the same picture, file replaced.
size = os.path.getsize(files[0])
with open(files[0], "r+b") as f:
    f.seek(size // 2)
    byte = f.read(1)
    f.seek(size // 2)
    f.write(bytes([byte[0] ^ 0x5A]))
w = Warnings()
third, m3, _, _, _ = render(cache)
w.close()
ok(not m3.GetLastTablesFromCache(), "corrupt file not used")
ok("checksum" in w.text() and os.path.basename(files[0]) in w.text(),
   "warning names the file and the problem: %r" % w.text().strip()[:200])
ok(np.array_equal(first, third), "same picture after the rebuild")
_, m4, _, _, _ = render(cache)
ok(m4.GetLastTablesFromCache(), "the rebuilt table replaced the corrupt file")

# 3. Off switch: nothing written.
off = os.path.join(WORK, "off")
render(off, enabled=False)
ok(not os.path.exists(off), "SetTableCache(False) writes nothing")

# 4. The default location follows $GEOMIPMAP_CACHE_DIR; "off" turns it off.
env_dir = os.path.join(WORK, "from-env")
os.environ["GEOMIPMAP_CACHE_DIR"] = env_dir
render()
ok(len(tables(env_dir)) == 1, "default directory from GEOMIPMAP_CACHE_DIR")
os.environ["GEOMIPMAP_CACHE_DIR"] = "off"
_, m5, _, _, _ = render()
ok(not m5.GetLastTablesFromCache() and len(tables(env_dir)) == 1, "GEOMIPMAP_CACHE_DIR=off: no cache")

# 5. An unwritable location: a warning, the terrain drawn all the same.
blocker = os.path.join(WORK, "a-file")
with open(blocker, "w") as f:
    f.write("not a directory")
w = Warnings()
pixels, m6, _, _, _ = render(os.path.join(blocker, "cache"))
w.close()
ok(np.array_equal(first, pixels), "unwritable cache location: same picture")
ok("cannot create" in w.text(), "and a warning: %r" % w.text().strip()[:200])

shutil.rmtree(WORK, ignore_errors=True)
ok.exit()
