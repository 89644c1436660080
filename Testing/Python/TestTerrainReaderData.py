"""vtkGeoMipMapTerrainReader on every real DEM of ../shared/data (one case per run).

Expected values are the facts of ../shared/data/README.md, converted to what the reader
promises (metres, sample centres, j northwards). Tolerances:
- heights: integer sources convert to float32 exactly, so min/max are compared to 1e-3 m;
  decimetre sources (Puget PNG x 0.1, terrain-RGB / 10) to 0.01 m (float32 rounding of
  values near 4000 m is 2.4e-4 m; the README gives one decimal).
- geographic rasters (resampled onto a transverse Mercator grid, see the reader's header):
  spacing by the reader's documented formula with M, N computed here in closed form
  (WGS84), to 1e-9 relative; origins in degrees to 1e-6 deg (README values given rounded
  to 4 decimals are compared to 1e-4 deg); the footprint (the source's boundary through
  GeographicToLocal) holds every valid node and no node outside it is valid; horizontal
  distances between random node pairs against WGS84 geodesics (Python GeographicLib)
  within the reader's stated GetGeographicDistanceError (the old equirectangular frame was
  off by up to 0.9 % on these tiles); heights min/max of a bilinear resampling: within the
  source's range and the maximum within 1 % of the source's.
"""
import math
import random
import sys

import numpy as np
from geographiclib.geodesic import Geodesic
from matplotlib.path import Path
from vtkmodules.util.numpy_support import vtk_to_numpy

from geomipmap import vtkGeoMipMapTerrainReader
from gmmtestutil import check, data_file, read_dem, resampling_mismatch

A, F = 6378137.0, 1.0 / 298.257223563
E2 = F * (2 - F)


def radii(lat_deg):
    s = math.sin(math.radians(lat_deg))
    w = 1 - E2 * s * s
    return A * (1 - E2) / w ** 1.5, A / math.sqrt(w)  # meridional M, prime vertical N


def read(path, **opts):
    _, img = read_dem(path, **opts)
    arr = img.GetPointData().GetScalars()
    check(arr is not None and arr.GetName() == "Elevation", "active scalars named Elevation")
    check(arr.GetDataType() == 10, "Elevation is float32")  # VTK_FLOAT
    check(img.GetDimensions()[2] == 1, "2D image")
    fd = img.GetFieldData()
    meta = {fd.GetAbstractArray(i).GetName(): fd.GetAbstractArray(i)
            for i in range(fd.GetNumberOfArrays())}
    return img, vtk_to_numpy(arr), meta


def string(meta, key):
    return meta[key].GetValue(0)


def check_heights(z, lo, hi, tol):
    zmin, zmax = float(np.nanmin(z)), float(np.nanmax(z))
    check(abs(zmin - lo) <= tol and abs(zmax - hi) <= tol,
          "heights %.4f .. %.4f, expected %g .. %g (tol %g)" % (zmin, zmax, lo, hi, tol))


def check_geographic(img, meta, z, nx, ny, lon0, lat0, step_deg, tol_deg=1e-6):
    """Checks a lon/lat raster of nx x ny samples from (lon0, lat0) by step_deg; returns the
    mask of nodes inside its footprint (by more than a twentieth of a sample)."""
    R = vtkGeoMipMapTerrainReader
    g = meta["GeographicOrigin"].GetTuple2(0)
    check(abs(g[0] - lon0) <= tol_deg and abs(g[1] - lat0) <= tol_deg,
          "GeographicOrigin %r, expected (%r, %r)" % (g, lon0, lat0))
    cm = meta["CentralMeridian"].GetValue(0)
    check(abs(cm - (g[0] + (nx - 1) * step_deg / 2)) <= 1e-9, "CentralMeridian %r" % cm)
    latc = g[1] + (ny - 1) * step_deg / 2
    m, n = radii(latc)
    dx = math.radians(step_deg) * n * math.cos(math.radians(latc))
    dy = math.radians(step_deg) * m
    sp = img.GetSpacing()
    check(abs(sp[0] - dx) <= 1e-9 * dx and abs(sp[1] - dy) <= 1e-9 * dy,
          "spacing %r, expected (%r, %r) m" % (sp[:2], dx, dy))
    check(string(meta, "CRS").startswith("EPSG:4326"), "CRS " + string(meta, "CRS"))
    xy = [1.0, 1.0]
    check(R.GeographicToLocal(img, g[0], g[1], xy) and abs(xy[0]) < 1e-6 and abs(xy[1]) < 1e-6,
          "GeographicOrigin maps to local (0, 0): %r" % xy)
    # the grid: nodes at multiples of the spacing from (0, 0), about the source's size
    gx, gy = img.GetDimensions()[:2]
    ox, oy = img.GetOrigin()[:2]
    check(abs(ox / dx - round(ox / dx)) < 1e-6 and abs(oy / dy - round(oy / dy)) < 1e-6,
          "origin %r on the node lattice through (0, 0)" % ((ox, oy),))
    check(nx <= gx <= 1.02 * nx + 4 and ny <= gy <= 1.02 * ny + 4,
          "%d x %d nodes for %d x %d samples" % (gx, gy, nx, ny))
    # The footprint: the source's boundary in the local frame, 40 points a side (the
    # parallels' images bend by under 0.1 m between points), grown or shrunk by a twentieth
    # of a sample. Nodes inside the shrunk outline's inner rectangle are inside, nodes
    # beyond the grown outline's bounding box outside; only the band between them is tested
    # point by point (Path.contains_points on every node of N48W125 took over a minute).
    def outline(grow):
        e = grow * step_deg
        w, s = g[0] - e, g[1] - e
        east, north = g[0] + (nx - 1) * step_deg + e, g[1] + (ny - 1) * step_deg + e
        t = np.linspace(0.0, 1.0, 40)
        sides = [(w + t * (east - w), np.full_like(t, s)), (np.full_like(t, east), s + t * (north - s)),
                 (east - t * (east - w), np.full_like(t, north)), (np.full_like(t, w), north - t * (north - s))]
        out = []
        for lons, lats in sides:
            pts = []
            for lon, lat in zip(lons, lats):
                R.GeographicToLocal(img, lon, lat, xy)
                pts.append(tuple(xy))
            out.append(np.array(pts))
        return out  # south, east, north, west sides
    shrunk, grown = outline(-0.05), outline(0.05)
    inner = (shrunk[3][:, 0].max(), shrunk[1][:, 0].min(), shrunk[0][:, 1].max(), shrunk[2][:, 1].min())
    allg = np.vstack(grown)
    outer = (allg[:, 0].min(), allg[:, 0].max(), allg[:, 1].min(), allg[:, 1].max())
    ii, jj = np.meshgrid(np.arange(gx), np.arange(gy))
    nodes = np.column_stack([ox + ii.ravel() * dx, oy + jj.ravel() * dy])
    x, y = nodes[:, 0], nodes[:, 1]
    surely_in = (x > inner[0]) & (x < inner[1]) & (y > inner[2]) & (y < inner[3])
    maybe_in = (x >= outer[0]) & (x <= outer[1]) & (y >= outer[2]) & (y <= outer[3])
    band = np.flatnonzero(maybe_in & ~surely_in)
    inside, near = surely_in.copy(), surely_in.copy()
    inside[band] = Path(np.vstack(shrunk)).contains_points(nodes[band])
    near[band] = Path(allg).contains_points(nodes[band])
    stray = int((np.isfinite(z) & ~near).sum())
    check(stray == 0, "%d valid nodes outside the footprint" % stray)
    # distances against geodesics between the points the nodes represent
    rng = random.Random(3)
    cand = np.flatnonzero(inside)
    worst = 0.0
    for _ in range(3000):
        a, b = int(cand[rng.randrange(len(cand))]), int(cand[rng.randrange(len(cand))])
        if a == b:
            continue
        p, q = [0.0, 0.0], [0.0, 0.0]
        R.LocalToGeographic(img, nodes[a][0], nodes[a][1], p)
        R.LocalToGeographic(img, nodes[b][0], nodes[b][1], q)
        geo = Geodesic.WGS84.Inverse(p[1], p[0], q[1], q[0])["s12"]
        worst = max(worst, abs(math.hypot(*(nodes[b] - nodes[a])) - geo) / geo)
    bound = R.GetGeographicDistanceError()
    check(worst <= bound, "grid distances within %.3e of geodesic distances (stated %g)"
          % (worst, bound))
    return inside


def check_resampled_heights(z, lo, hi):
    """A bilinear resampling stays within the source's range and keeps its maximum to 1 %."""
    zmin, zmax = float(np.nanmin(z)), float(np.nanmax(z))
    check(lo - 1e-3 <= zmin and zmax <= hi + 1e-3 and zmax >= hi - 0.01 * (hi - lo),
          "heights %.2f .. %.2f within the source's %g .. %g, maximum kept to 1 %%"
          % (zmin, zmax, lo, hi))


def nodata_count(z):
    return int(np.isnan(z).sum())


case = sys.argv[1]
p = data_file  # skips (or fails under GEOMIPMAP_REQUIRE_DATA=1) when the file is missing

if case == "SainteHelens":
    img, z, meta = read(p("SainteHelens.dem"))
    # GDAL places samples on the file's 30 m UTM lattice: the first profile's easting
    # (557820, record B) and the lowest profile start (5107980). vtkDEMReader (README:
    # 327 x 467, origin (557945, 5107991.5)) puts the quad's SW corner, which is no sample,
    # at sample (0, 0); GDAL covers the profiles' full y range, one row more.
    check(img.GetDimensions()[:2] == (327, 468), "dimensions %s" % (img.GetDimensions(),))
    check(img.GetOrigin()[:2] == (557820.0, 5107980.0), "UTM origin %s" % (img.GetOrigin(),))
    check(img.GetSpacing()[:2] == (30.0, 30.0), "30 m spacing")
    ox, oy = 557945.0, 5107991.5  # README origin lies within 5 samples of ours
    check(0 <= ox - 557820 <= 150 and 0 <= oy - 5107980 <= 150, "README origin nearby")
    check_heights(z, 682, 2543, 1e-3)
    check(string(meta, "SourceFormat") == "USGSDEM", "SourceFormat USGSDEM")
    check("Transverse_Mercator" in string(meta, "CRS") or "UTM" in string(meta, "CRS"), "UTM CRS")
    check(0 < nodata_count(z) < 0.05 * z.size, "only the quad's slanted corners are void")
elif case == "Rainier":
    img, z, meta = read(p("mt_rainier_90m.tif"))
    # Upper-left corner (-122.000417, 47.000417) + half a 3" pixel: first centre (-122, 47).
    inside = check_geographic(img, meta, z, 1201, 1201, -122.0, 46.0, 1.0 / 1200)
    check_resampled_heights(z, 263, 4371)
    # 9033 void samples in the source; resampled, a node is void when its nearest sample is
    # and one of its 4 is, at about the source's density: close to 9033 inside the footprint
    voids = int((np.isnan(z) & inside).sum())
    check(0.9 * 9033 <= voids <= 1.1 * 9033, "about 9033 voids inside the footprint, got %d"
          % voids)
    check(string(meta, "SourceFormat") == "GTiff", "SourceFormat GTiff")
elif case == "N42E001":
    img, z, meta = read(p("N42E001.hgt"))
    inside = check_geographic(img, meta, z, 1201, 1201, 1.0, 42.0, 1.0 / 1200)
    check_resampled_heights(z, 349, 3100)
    check(int((np.isnan(z) & inside).sum()) < 0.01 * z.size, "few voids")
    # Every node's height against the raw file (rows stored north to south), recomputed
    # from it at the node's lon/lat (gmmtestutil.resampling_mismatch), at 20000 nodes.
    raw = np.fromfile(p("N42E001.hgt"), dtype=">i2").reshape(1201, 1201)[::-1].astype(float)
    raw[raw == -32768] = np.nan
    bad, worst, n = resampling_mismatch(img, raw, 1.0, 42.0, 1.0 / 1200)
    check(bad == 0 and worst < 0.01, "heights from the raw file at their lon/lat (%d nodes): "
          "%d nodata mismatches, largest difference %.4f m" % (n, bad, worst))
elif case == "N48W125":
    img, z, meta = read(p("N48W125.hgt"))
    inside = check_geographic(img, meta, z, 3601, 3601, -125.0, 48.0, 1.0 / 3600)
    frac = float(np.isnan(z[inside]).mean())
    check(0.35 < frac < 0.65, "about half void inside the footprint (%.3f)" % frac)
elif case == "Boulder":
    img, z, meta = read(p("boulder_srtmgl3.asc"))
    # README: lower-left corner (-105.5504, 40.0904), rounded; centres are half a cell in.
    inside = check_geographic(img, meta, z, 240, 144, -105.5504 + 0.5 / 1200,
                              40.0904 + 0.5 / 1200, 1.0 / 1200, tol_deg=1e-4)
    check_resampled_heights(z, 1943, 3286)
    check(int(np.isnan(z[inside]).sum()) == 0, "no voids inside the footprint")
elif case == "PugetPNG":
    img, z, meta = read(p("ps_height_1k.png"), HeightScale=0.1, Spacing=160.0)
    check(img.GetDimensions()[:2] == (1025, 1025), "1025 x 1025")
    check(img.GetSpacing()[:2] == (160.0, 160.0), "160 m spacing")
    check_heights(z, 0.0, 4379.8, 0.01)
    check(string(meta, "SourceFormat") == "png" and string(meta, "CRS") == "none", "PNG, no CRS")
elif case == "FujiTerrainRGB":
    img, z, meta = read(p("fuji_terrain_rgb.png"), TerrainRGB=1, Spacing=30.0)
    check(img.GetDimensions()[:2] == (512, 512), "512 x 512")
    check_heights(z, 13.7, 3751, 0.01)
    check(string(meta, "HeightUnit") == "m", "terrain-RGB heights in metres")
    # The summit is near the middle of the tile, not at an edge (rows not scrambled).
    j, i = np.unravel_index(np.nanargmax(z), (512, 512))
    check(100 < i < 412 and 100 < j < 412, "summit inside the tile at (%d, %d)" % (i, j))
else:
    sys.exit("unknown case " + case)
print("PASS", case)
