"""geomipmap-fly over a real DEM with geographic (lon, lat, agl) waypoints.

Uses mt_rainier_90m.tif (SRTM3 N46W122, EPSG:4326, voids) from the shared data folder
(gmmdata.py: $GEOMIPMAP_DATA_DIR, else ../shared/data beside the source tree); skips
(exit 77) when it is absent, or fails when GEOMIPMAP_REQUIRE_DATA=1. The main flight runs in
this process (flytestutil.measured_flight: the command's own code) so that every 5th frame's
drawn triangles can be measured against the full-resolution DEM, independently of the
engine's bound; the other flights run the command. Checks: exit 0, 10 CSV rows, frames
showing terrain, the measured screen error within tau, and with --fill-voids the same
within tau with every sample in view covered; the lon/lat -> local metre
conversion against GeographicLib's geodesic distances; JSON waypoints with absolute
altitudes; a waypoint outside the tile.
"""

import glob
import json
import os

import geomipmap  # PYTHONPATH from CTest
import numpy as np
from geographiclib.geodesic import Geodesic
from geomipmap import flight
from vtkmodules.util.numpy_support import vtk_to_numpy

from flytestutil import check, check_measured, measured_flight, png_stats, read_csv, run, setup
from gmmdata import data_file

exe, out = setup()
dem = data_file("mt_rainier_90m.tif")

# The tile spans lon -122 .. -121, lat 46 .. 47; Mount Rainier's summit is near
# (-121.760, 46.853). A flight from the south-west past the summit, 700 m above ground.
wp = os.path.join(out, "rainier.csv")
with open(wp, "w") as f:
    f.write("# lon, lat in degrees (WGS 84); agl: metres above the ground under the camera\n")
    f.write("lon,lat,agl\n-121.95,46.70,700\n-121.82,46.78,700\n-121.66,46.88,900\n"
            "-121.55,46.95,700\n")
tau = "1.5"
main_flight = ["--dem", dem, "--waypoints", wp, "--frames", "10", "--size", "320x180", "--tau", tau]
rc, so, se, frames = measured_flight(main_flight + ["--out", os.path.join(out, "csv")], every=5)
check(rc == 0, f"exit {rc}: {se.strip()}")
rows = read_csv(os.path.join(out, "csv", "flight.csv"))
check(len(rows) == 10, f"expected 10 rows, got {len(rows)}")
for r in rows:
    check(int(r["triangles"]) > 0, f"frame {r['frame']}: no triangles")
pngs = sorted(glob.glob(os.path.join(out, "csv", "frame_*.png")))
check(len(pngs) == 10, f"expected 10 PNGs, got {len(pngs)}")
_, _, var, terrain = png_stats(pngs[0])
check(var > 20.0 and terrain > 0.3, f"{pngs[0]}: variance {var:.1f}, terrain {terrain:.0%}")
check("within tau" in so, f"summary does not certify the error:\n{so}")
check_measured(frames, rows, tau=float(tau))

# --fill-voids: the same flight over the tile with its voids filled (every void of this
# tile is within the default fill distance). What is drawn still measures within tau
# (against the filled heights), and covers every sample in view, where the flight with
# voids leaves the samples between them uncovered. (Filling once also drew fewer
# triangles; since blocks with voids draw side strips where their voids leave their border
# rows, the voids cost less than their filled surfaces: the ratio is printed.)
rc, so, se, filled = measured_flight(main_flight + ["--fill-voids", "--out",
                                                    os.path.join(out, "filled")], every=5)
check(rc == 0, f"--fill-voids: exit {rc}: {se.strip()}")
filled_rows = read_csv(os.path.join(out, "filled", "flight.csv"))
check(len(filled_rows) == 10, f"--fill-voids: expected 10 rows, got {len(filled_rows)}")
check_measured(filled, filled_rows, tau=float(tau))
tri_voids = sum(int(r["triangles"]) for r in rows)
tri_filled = sum(int(r["triangles"]) for r in filled_rows)
print(f"--fill-voids: {tri_filled} triangles over the flight against {tri_voids} with voids "
      f"({100.0 * tri_filled / tri_voids:.1f} %)")
uncovered_voids = sum(m.uncovered for _, _, m in frames if m is not None)
uncovered_filled = sum(m.uncovered for _, _, m in filled if m is not None)
check(uncovered_voids > 0, "the flight with voids leaves no sample uncovered: the check sees no hole")
check(uncovered_filled == 0, f"--fill-voids leaves {uncovered_filled} samples in view uncovered")

# Conversion check: waypoints go through the reader's own frame (flight.GeoFrame ->
# vtkGeoMipMapTerrainReader.GeographicToLocal); checked against facts from outside: the
# summit's published position lands on the DEM's highest node, and the distance between two
# waypoints matches GeographicLib's geodesic within the reader's stated accuracy.
rd = geomipmap.vtkGeoMipMapTerrainReader()
rd.SetFileName(dem)
rd.Update()
img = rd.GetOutput()
frame = flight.GeoFrame(img)
x0, y0 = frame.to_local(frame.lon0, frame.lat0)
check(abs(x0) < 1e-6 and abs(y0) < 1e-6, "GeographicOrigin maps to local (0, 0)")
# Mount Rainier's summit, 46.8529 N 121.7604 W (USGS), is the DEM's highest point: the
# highest node must lie within one 90 m sample of where the waypoint frame puts it.
z = vtk_to_numpy(img.GetPointData().GetScalars())
top = int(np.nanargmax(z))
nx, ny, _ = img.GetDimensions()
dx, dy, _ = img.GetSpacing()
ox, oy, _ = img.GetOrigin()
xs, ys = frame.to_local(-121.7604, 46.8529)
off = ((ox + top % nx * dx - xs) ** 2 + (oy + top // nx * dy - ys) ** 2) ** 0.5
check(off < 100.0, f"summit waypoint {off:.1f} m from the DEM's highest node")
print(f"summit waypoint {off:.1f} m from the DEM's highest node")
# Against GeographicLib's geodesic: within the reader's stated accuracy (the former
# equirectangular frame was off by up to 0.9 % east-west on this tile).
(xa, ya), (xb, yb) = frame.to_local(-121.95, 46.70), frame.to_local(-121.55, 46.95)
geo = Geodesic.WGS84.Inverse(46.70, -121.95, 46.95, -121.55)["s12"]
local = ((xb - xa) ** 2 + (yb - ya) ** 2) ** 0.5
bound = geomipmap.vtkGeoMipMapTerrainReader.GetGeographicDistanceError()
check(abs(local - geo) / geo <= bound,
      f"local distance {local:.3f} m vs geodesic {geo:.3f} m (stated accuracy {bound:g})")
print(f"waypoint distance {local:.3f} m, geodesic {geo:.3f} m: relative error "
      f"{abs(local - geo) / geo:.2e}")
# Terrain following: the camera stays at least the clearance above the ground.
hts = flight.Heights(img)
path = flight.Waypoints.from_file(wp, hts, frames=200)
ground = hts.sample(path.positions[:, 0], path.positions[:, 1])
ok = ~np.isnan(ground)
low = float((path.positions[ok, 2] - ground[ok]).min())
check(low >= 700.0 - 1.0, f"camera {low:.1f} m above ground, clearance 700")
lon, lat = frame.to_geographic(xa, ya)
check(abs(lon + 121.95) < 1e-9 and abs(lat - 46.70) < 1e-9, "round trip lon/lat")

# JSON, absolute altitudes (metres above the DEM's datum), higher than the summit.
wj = os.path.join(out, "rainier.json")
with open(wj, "w") as f:
    json.dump({"waypoints": [{"lon": -121.9, "lat": 46.6, "alt": 5200},
                             {"lon": -121.6, "lat": 46.9, "alt": 5200}]}, f)
rc, so, se = run(exe, "--dem", dem, "--waypoints", wj, "--frames", "3", "--size", "160x90",
                 "--no-frames", "--out", os.path.join(out, "json"))
check(rc == 0, f"JSON waypoints: exit {rc}: {se.strip()}")
check(len(read_csv(os.path.join(out, "json", "flight.csv"))) == 3, "JSON flight rows")

# A waypoint outside the tile: one line, non-zero.
with open(wp, "a") as f:
    f.write("-120.50,46.95,700\n")
rc, so, se = run(exe, "--dem", dem, "--waypoints", wp, "--frames", "2", "--out",
                 os.path.join(out, "outside"))
check(rc != 0 and "outside the terrain" in se and len(se.strip().splitlines()) == 1,
      f"outside waypoint: rc {rc}, stderr {se!r}")
print("TestFlyRealDEM: passed")
