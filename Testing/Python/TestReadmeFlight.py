"""Runs the README's flight script (geomipmap.flight in a user's own script) verbatim on
mt_rainier_90m.tif, then checks what it did against sources other than the flight API:

- the script is at most 15 lines (the README's promise of a short script);
- it printed one line per frame of the path, numbered 0 .. len(path) - 1;
- every printed height above ground is the one of the path's position for that frame
  over the mapper's own full-resolution surface (vtkGeoMipMapMapper.GetHeightAt, not the
  flight's numpy heights), so the camera was on the path in every frame, and at least the
  clearance (600 m, less 1 m for the printed rounding and the two surfaces' difference);
- the PNG frames were written at the window's size and show terrain, not a blank sky;
- the last frame's drawn triangles measure within the mapper's tau
  (gmmtestutil.check_drawn_within_tau, vtkGeoMipMapScreenError).
"""
import math
import os
import re
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from gmmdata import data_file
from gmmtestutil import check_drawn_within_tau
from readmeblock import readme_block, run_readme_block

HEADING = "### Flights in your own script"
CLEARANCE = 600.0
failures = []


def check(cond, msg):
    if not cond:
        print(f"FAIL: {msg}")
        failures.append(msg)


lines = [ln for ln in readme_block(HEADING).splitlines() if ln.strip()]
check(len(lines) <= 15, f"the README's flight script has {len(lines)} lines, more than 15")
dem = data_file("mt_rainier_90m.tif")
with run_readme_block(HEADING, [dem]) as (script, printed, tmp):
    path, mapper, ren = script["path"], script["mapper"], script["ren"]
    rows = re.findall(r"^frame (\d+): (\d+) triangles, (\S+) m above ground$", printed, re.M)
    check([int(r[0]) for r in rows] == list(range(len(path))),
          f"{len(rows)} frame lines for a path of {len(path)} frames")
    lowest, compared = math.inf, 0
    for (i, _, agl), (x, y, z) in zip(rows, path.positions):
        ground = mapper.GetHeightAt(x, y)
        if agl == "nan" or not math.isfinite(ground):
            continue  # over a void: no ground there
        compared += 1
        lowest = min(lowest, float(agl))
        check(abs(float(agl) - (z - ground)) <= 0.5,
              f"frame {i}: {agl} m above ground printed, the path's position is "
              f"{z - ground:.1f} m above the mapper's ground: the camera was not on the path")
        check(float(agl) >= CLEARANCE - 1.0, f"frame {i}: {agl} m above ground < {CLEARANCE}")
    check(compared >= 0.9 * len(path), f"only {compared} frames over ground")
    print(f"{compared} frames on the path, at least {lowest:.0f} m above the mapper's ground")
    check(np.allclose(ren.GetActiveCamera().GetPosition(), path.camera_at(len(path) - 1).position),
          "the camera is not at the path's last pose")
    pngs = sorted(f for f in os.listdir(tmp) if f.endswith(".png"))
    check(pngs == [f"frame_{i:02d}.png" for i in range(0, len(path), 12)], f"PNGs {pngs}")
    for name in pngs:
        reader = vtkPNGReader()
        reader.SetFileName(os.path.join(tmp, name))
        reader.Update()
        w, h, _ = reader.GetOutput().GetDimensions()
        rgb = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(float)
        terrain = float((rgb.max(axis=1) > 8).mean())  # the background is black
        check((w, h) == (640, 360), f"{name}: {w} x {h}, the window is 640 x 360")
        check(terrain > 0.3 and rgb.var() > 20.0,
              f"{name}: terrain on {terrain:.0%} of the pixels, variance {rgb.var():.1f}")
        print(f"{name}: {w} x {h}, terrain on {terrain:.0%} of the pixels")
    # Rainier has voids: in-view samples next to them are not covered, by design.
    check_drawn_within_tau(script["reader"].GetOutput(), ren, script["actor"], mapper,
                           "README flight, last frame", uncovered_ok=True)

if failures:
    print(f"TestReadmeFlight: {len(failures)} failure(s)")
    sys.exit(1)
print("TestReadmeFlight: passed")
