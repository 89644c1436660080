"""The reader's geographic frame, checked against GeographicLib's geodesics on lon/lat
rasters whose heights encode their own coordinates (no data folder needed).

For each case, two float32 GeoTIFFs in EPSG:4326 are written over the same 1 x 1 degree
lattice (6 arc-second steps): one whose height is (lon - west) * 1e4, one (lat - south) *
1e4. Both are linear in the sample indices, so the reader's bilinear resampling reproduces
them exactly (up to float32: 1e-7 degree, about 1 cm), and every node of the output grid
then tells which lon/lat its height was taken from, without using the reader's conversion
code. Checked:
- that lon/lat is the one vtkGeoMipMapTerrainReader::LocalToGeographic gives for the node
  (within 3e-7 degree, 3 cm; measured 1.2e-7 with float32 heights): the published
  conversion is where the heights come from;
- horizontal distances on the grid against WGS84 geodesic distances (Python GeographicLib,
  Karney's algorithm) between the decoded points, for random pairs of nodes at least 20 km
  apart: the relative error stays within the figure stated in the reader's header
  (GetGeographicDistanceError). The old equirectangular frame measured up to 0.9 % here.
Cases: Rainier's tile (46 N), the equator (the widest tile in metres: the worst case),
the south (56 S), and a tile across the antimeridian (179.5 E .. 179.5 W).
"""
import math
import os
import random
import sys
import tempfile

import numpy as np
from geographiclib.geodesic import Geodesic
from vtkmodules.util.numpy_support import vtk_to_numpy

import demfiles
from geomipmap import vtkGeoMipMapTerrainReader as Reader
from gmmtestutil import ErrorCatcher, update

STEP = 1.0 / 600  # 6 arc-seconds: 601 x 601 samples per degree
SCALE = 1e4       # height = degrees * SCALE
CASES = {"Rainier tile": (-122.0, 46.0), "equator": (10.0, -0.5), "south": (-70.0, -56.0),
         "antimeridian": (179.5, 60.0)}
bound = Reader.GetGeographicDistanceError()
failures = []


def read(path):
    r = Reader()
    r.SetFileName(path)
    errors = ErrorCatcher(r)
    if not update(r):
        raise AssertionError("%s: %s" % (path, errors.messages))
    img = r.GetOutput()
    return img, vtk_to_numpy(img.GetPointData().GetScalars()).astype(float)


tmp = tempfile.mkdtemp(prefix="gmm-geoframe-")
rng = random.Random(7)
for name, (west, south) in CASES.items():
    n = 601
    lon = west + STEP * np.arange(n)
    lat = south + STEP * np.arange(n)
    # row 0 = north in the file; the upper-left corner is half a pixel beyond the samples
    corner = (west - STEP / 2, south + (n - 1) * STEP + STEP / 2, STEP)
    f_lon = demfiles.tiff(os.path.join(tmp, "lon.tif"),
                          np.tile((lon - west) * SCALE, (n, 1)).astype(np.float32),
                          georef=corner, geographic=True)
    img, hx = read(f_lon)
    f_lat = demfiles.tiff(os.path.join(tmp, "lat.tif"),
                          np.tile(((lat - south) * SCALE)[::-1, None], (1, n)).astype(np.float32),
                          georef=corner, geographic=True)
    img2, hy = read(f_lat)
    nx, ny, _ = img.GetDimensions()
    dx, dy, _ = img.GetSpacing()
    ox, oy, _ = img.GetOrigin()
    if img2.GetDimensions() != img.GetDimensions() or img2.GetOrigin() != img.GetOrigin():
        failures.append(f"{name}: the two rasters gave different grids")
        continue
    valid = np.flatnonzero(np.isfinite(hx) & np.isfinite(hy))
    dec_lon = west + hx / SCALE
    dec_lat = south + hy / SCALE
    # 1. the published conversion is where the heights come from
    worst_pos = 0.0
    for k in rng.sample(list(valid), 2000):
        p = [0.0, 0.0]
        Reader.LocalToGeographic(img, ox + (k % nx) * dx, oy + (k // nx) * dy, p)
        worst_pos = max(worst_pos, abs(p[0] - dec_lon[k]), abs(p[1] - dec_lat[k]))
    # 2. distances against geodesics
    worst, pairs = 0.0, 0
    while pairs < 3000:
        a, b = valid[rng.randrange(len(valid))], valid[rng.randrange(len(valid))]
        d = math.hypot((b % nx - a % nx) * dx, (b // nx - a // nx) * dy)
        if d < 20000.0:
            continue
        g = Geodesic.WGS84.Inverse(dec_lat[a], dec_lon[a], dec_lat[b], dec_lon[b])["s12"]
        worst = max(worst, abs(d - g) / g)
        pairs += 1
    print(f"{name}: {nx} x {ny} nodes for 601 x 601 samples, {len(valid)} valid; decoded "
          f"lon/lat vs LocalToGeographic within {worst_pos:.2e} deg; distance error at most "
          f"{worst:.3e} (stated {bound:g})")
    # the footprint holds about as many nodes as the source has samples (its 600 x 600
    # cells at the centre's resolution), and no node inside it is left out
    if not 0.995 * 600 * 600 <= len(valid) <= 1.005 * 601 * 601:
        failures.append(f"{name}: {len(valid)} valid nodes for 601 x 601 samples")
    if not worst_pos <= 3e-7:
        failures.append(f"{name}: heights come from {worst_pos:.2e} deg away from where "
                        "LocalToGeographic puts the node")
    if not worst <= bound:
        failures.append(f"{name}: distance error {worst:.3e} above the stated {bound:g}")

if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("ok: the geographic frame is within its stated accuracy")
