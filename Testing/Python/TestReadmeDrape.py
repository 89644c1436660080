"""Runs the README's drape script verbatim (readmeblock), on a DEM with relief in UTM zone
10N and a magenta photo in lon/lat (EPSG:4326) over part of it, both written here; then
checks what it did with sources other than the drape code:
- the drape's output was warped into the DEM's frame and its grid spans the photo's
  corners, projected to UTM by Krueger's series (TestDrape.utm_forward), within a pixel
  (the warp rounds its size up to whole pixels);
- draped.png was written at the window's size and shows the photo (magenta) and, outside
  it, the terrain coloured by height (no magenta there);
- the mapper reported no error.
"""
import os
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import demfiles
from gmmtestutil import ErrorCatcher, check
from readmeblock import run_readme_block
from TestDrape import utm_forward

folder = tempfile.mkdtemp(prefix="gmm-readme-drape-")
ys, xs = np.mgrid[0:129, 0:129]
z = (800.0 + 250.0 * np.sin(xs / 17.0) * np.cos(ys / 23.0)).astype(np.float32)
dem = demfiles.tiff(os.path.join(folder, "dem.tif"), z, georef=(500000.0, 4000000.0, 30.0))
west, north, step, ny, nx = -122.99, 36.125, 0.0001, 150, 200
magenta = np.zeros((ny, nx, 3), np.uint8)
magenta[:] = (230, 0, 230)
photo = demfiles.tiff(os.path.join(folder, "photo.tif"), magenta, georef=(west, north, step),
                      rgb=True, geographic=True)

with run_readme_block("### Draped imagery in your own script", [dem, photo]) as (ex, _, tmp):
    drape = ex["drape"].GetOutput()
    check(drape.GetFieldData().GetArray("DrapeWarped").GetValue(0) == 1,
          "the lon/lat photo was warped into the UTM DEM's frame")
    # The warp's grid is the photo's bounding box in UTM: compare its edges with the
    # photo's corners projected here.
    b, (sx, sy, _) = drape.GetBounds(), drape.GetSpacing()
    corners = [utm_forward(lon, lat, 10) for lon in (west, west + nx * step)
               for lat in (north, north - ny * step)]
    want = (min(e for e, _ in corners), max(e for e, _ in corners),
            min(n for _, n in corners), max(n for _, n in corners))
    got = (b[0] - 0.5 * sx, b[1] + 0.5 * sx, b[2] - 0.5 * sy, b[3] + 0.5 * sy)
    off = max(abs(g - w) for g, w in zip(got, want))
    check(off <= max(sx, sy), f"the drape spans the photo's corners in UTM: edges "
          f"{[round(g, 1) for g in got]} against {[round(w, 1) for w in want]} (off by "
          f"{off:.2f} m, pixel {sx:.2f} m)")
    errors = ErrorCatcher(ex["mapper"])
    ex["win"].Render()
    check(not errors.messages, f"the mapper renders without errors ({errors.messages})")
    r = vtkPNGReader()
    r.SetFileName(os.path.join(tmp, "draped.png"))
    r.Update()
    w, h, _ = r.GetOutput().GetDimensions()
    check((w, h) == (800, 450), f"draped.png is 800 x 450 ({w} x {h})")
    a = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(int)[:, :3]
    is_magenta = (a[:, 0] > 2 * a[:, 1] + 20) & (a[:, 2] > 2 * a[:, 1] + 20)
    terrain = a.max(axis=1) > 20  # the background is black
    share = is_magenta.sum() / max(terrain.sum(), 1)
    check(0.01 < share < 0.9, f"draped.png: the photo covers {100 * share:.1f} % of the terrain")
print("TestReadmeDrape: passed")
sys.exit(0)
