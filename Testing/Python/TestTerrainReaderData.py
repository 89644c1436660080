"""vtkGeoMipMapTerrainReader on every real DEM of ../shared/data (one case per run).

Expected values are the facts of ../shared/data/README.md, converted to what the reader
promises (metres, sample centres, j northwards). Tolerances:
- heights: integer sources convert to float32 exactly, so min/max are compared to 1e-3 m;
  decimetre sources (Puget PNG x 0.1, terrain-RGB / 10) to 0.01 m (float32 rounding of
  values near 4000 m is 2.4e-4 m; the README gives one decimal).
- geographic spacing: the reader's documented formula with M, N computed here in closed
  form (WGS84), to 1e-9 relative; origins in degrees to 1e-6 deg (README values given
  rounded to 4 decimals are compared to 1e-4 deg).
"""
import math
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from geomipmap import vtkGeoMipMapTerrainReader
from gmmtestutil import ErrorCatcher, check, data_file, update

A, F = 6378137.0, 1.0 / 298.257223563
E2 = F * (2 - F)


def radii(lat_deg):
    s = math.sin(math.radians(lat_deg))
    w = 1 - E2 * s * s
    return A * (1 - E2) / w ** 1.5, A / math.sqrt(w)  # meridional M, prime vertical N


def read(path, **opts):
    r = vtkGeoMipMapTerrainReader()
    r.SetFileName(path)
    for k, v in opts.items():
        getattr(r, "Set" + k)(v)
    errors = ErrorCatcher(r)
    check(update(r), "%s reads (errors: %s)" % (path, errors.messages))
    img = r.GetOutput()
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


def check_geographic(img, meta, nx, ny, lon0, lat0, step_deg, tol_deg=1e-6):
    check(img.GetDimensions()[:2] == (nx, ny), "dimensions %s" % (img.GetDimensions(),))
    check(img.GetOrigin()[:2] == (0.0, 0.0), "local frame origin at the south-west sample")
    g = meta["GeographicOrigin"].GetTuple2(0)
    check(abs(g[0] - lon0) <= tol_deg and abs(g[1] - lat0) <= tol_deg,
          "GeographicOrigin %r, expected (%r, %r)" % (g, lon0, lat0))
    latc = g[1] + (ny - 1) * step_deg / 2
    m, n = radii(latc)
    dx = math.radians(step_deg) * n * math.cos(math.radians(latc))
    dy = math.radians(step_deg) * m
    sp = img.GetSpacing()
    check(abs(sp[0] - dx) <= 1e-9 * dx and abs(sp[1] - dy) <= 1e-9 * dy,
          "spacing %r, expected (%r, %r) m" % (sp[:2], dx, dy))
    check(string(meta, "CRS").startswith("EPSG:4326"), "CRS " + string(meta, "CRS"))


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
    check_geographic(img, meta, 1201, 1201, -122.0, 46.0, 1.0 / 1200)
    check_heights(z, 263, 4371, 1e-3)
    check(nodata_count(z) == 9033, "9033 voids, got %d" % nodata_count(z))
    check(string(meta, "SourceFormat") == "GTiff", "SourceFormat GTiff")
elif case == "N42E001":
    img, z, meta = read(p("N42E001.hgt"))
    check_geographic(img, meta, 1201, 1201, 1.0, 42.0, 1.0 / 1200)
    check_heights(z, 349, 3100, 1e-3)
    check(nodata_count(z) < 0.01 * z.size, "few voids (%d)" % nodata_count(z))
    # Rows are stored north to south: the north-west sample of the file is our (0, ny-1).
    raw = np.fromfile(p("N42E001.hgt"), dtype=">i2").reshape(1201, 1201)
    ours = z.reshape(1201, 1201)
    same = (raw[::-1].astype(np.float32) == ours) | np.isnan(ours)
    check(bool(same.all()), "rows flipped to j northwards, values identical to the raw file")
elif case == "N48W125":
    img, z, meta = read(p("N48W125.hgt"))
    check_geographic(img, meta, 3601, 3601, -125.0, 48.0, 1.0 / 3600)
    frac = nodata_count(z) / z.size
    check(0.35 < frac < 0.65, "about half void (%.3f)" % frac)
elif case == "Boulder":
    img, z, meta = read(p("boulder_srtmgl3.asc"))
    # README: lower-left corner (-105.5504, 40.0904), rounded; centres are half a cell in.
    check_geographic(img, meta, 240, 144, -105.5504 + 0.5 / 1200, 40.0904 + 0.5 / 1200,
                     1.0 / 1200, tol_deg=1e-4)
    check_heights(z, 1943, 3286, 1e-3)
    check(nodata_count(z) == 0, "no voids")
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
