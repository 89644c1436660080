"""geomipmap-fly --texture: a georeferenced image draped over the DEM by its coordinates.

A DEM with relief in UTM zone 10N and a magenta photo in lon/lat (EPSG:4326) over its
middle, both written here (demfiles). The command runs as a user runs it; its frames must
show the photo (magenta, shaded by the sun) and, outside the photo, the terrain's own
elevation colours; a photo over a part of the world the DEM does not cover leaves the
frames as without it. Bad --texture uses are in TestFlyBadInput.
Usage: TestFlyTexture.py GEOMIPMAP_FLY SCRATCH_DIR
"""
import glob
import math
import os

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import demfiles
from flytestutil import check, run, setup

exe, out = setup()
ys, xs = np.mgrid[0:129, 0:129]
z = (800.0 + 250.0 * np.sin(xs / 17.0) * np.cos(ys / 23.0)).astype(np.float32)
dem = demfiles.tiff(os.path.join(out, "dem.tif"), z, georef=(500000.0, 4000000.0, 30.0))
# The DEM spans x 500000..503870, y 3996130..4000000 (UTM 10N): about lon -123.0 .. -122.957,
# lat 36.10 .. 36.135. The photo covers lon -122.99 .. -122.97, lat 36.11 .. 36.125.
magenta = np.zeros((150, 200, 3), np.uint8)
magenta[:] = (230, 0, 230)
photo = demfiles.tiff(os.path.join(out, "photo.tif"), magenta, georef=(-122.99, 36.125, 0.0001),
                      rgb=True, geographic=True)
elsewhere = demfiles.tiff(os.path.join(out, "elsewhere.tif"), magenta,
                          georef=(10.0, 50.0, 0.0001), rgb=True, geographic=True)


def frame_colours(folder):
    """(share of magenta pixels, share of other terrain-coloured pixels) of the middle
    frame, where terrain means not sky (sky is clearly blue)."""
    pngs = sorted(glob.glob(os.path.join(folder, "frame_*.png")))
    check(len(pngs) == 3, f"{folder}: 3 frames, got {len(pngs)}")
    r = vtkPNGReader()
    r.SetFileName(pngs[1])
    r.Update()
    a = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3]
    red, green, blue = a[:, 0], a[:, 1], a[:, 2]
    is_magenta = (red > 2.0 * green + 20) & (blue > 2.0 * green + 20)
    sky = blue > np.maximum(red, green) + 8
    return float(is_magenta.mean()), float((~is_magenta & ~sky).mean())


common = ["--dem", dem, "--frames", "3", "--size", "240x135", "--pitch", "35", "--tau", "1"]
shares = {}
for name, extra in (("plain", []), ("photo", ["--texture", photo]),
                    ("elsewhere", ["--texture", elsewhere])):
    folder = os.path.join(out, name)
    rc, so, se = run(exe, *common, *extra, "--out", folder)
    check(rc == 0, f"{name}: exit {rc}: {se.strip()}")
    shares[name] = frame_colours(folder)
    print(f"{name}: {100 * shares[name][0]:.1f} % magenta, {100 * shares[name][1]:.1f} % "
          "other terrain colours")
check(shares["plain"][0] < 0.001, "without --texture no magenta")
check(shares["photo"][0] > 0.02 and shares["photo"][1] > 0.05,
      "with --texture the photo shows, and the terrain outside it keeps its colours")
check(shares["elsewhere"][0] < 0.001 and math.isclose(shares["elsewhere"][1], shares["plain"][1],
                                                      abs_tol=0.002),
      "a photo of another place leaves the terrain as without it (not stretched onto it)")
print("TestFlyTexture: passed")
