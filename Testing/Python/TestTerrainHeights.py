"""Heights through vtkGeoMipMapTerrainReader, vtkGeoMipMapMapper and vtkGeoMipMapFilter.

DEM files written by this test (GeoTIFF int16 / uint16 / float32 / float64, ESRI ASCII, SRTM
.hgt) hold -11000 .. 8848 m, nodata holes and a whole nodata block, +-Inf, float64 values
beyond float range, a flat DEM, an all-nodata DEM and a GeoTIFF without georeference. Each
must read back exactly (nodata, +-Inf and out-of-range values as NaN; the lon/lat .hgt,
which the reader resamples onto its transverse Mercator grid, as its documented bilinear
resampling of those values), render through the
mapper without VTK errors, and give vtkGeoMipMapFilter output whose points are finite and
whose heights stay inside the file's valid range (no nodata fill, no Inf, no garbage).
Decisions asserted: the all-nodata DEM reads with a warning and renders nothing (0
triangles, empty filter output, no error); the GeoTIFF without georeference reads with a
warning, origin (0, 0) and the reader's Spacing.
Run under an X display (xvfb-run). Exit 0 = pass, 1 = fail.
"""
import os
import shutil
import sys
import tempfile

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkFiltersCore import vtkPassThrough
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

import demfiles
from geomipmap import vtkGeoMipMapFilter, vtkGeoMipMapMapper, vtkGeoMipMapTerrainReader
from gmmtestutil import resampling_mismatch
from robustutil import Scene, VtkMessages, filter_points

messages = VtkMessages()
tmp = tempfile.mkdtemp(prefix="gmm-heights-")
failures = []


def check(cond, what):
    print(("ok:   " if cond else "FAIL: ") + what)
    if not cond:
        failures.append(what)


def surface(nx, ny):
    """Heights spanning exactly -11000 .. 8848 m, row 0 = north (file order)."""
    x, y = np.meshgrid(np.linspace(0, 1, nx), np.linspace(0, 1, ny))
    t = 0.6 * x + 0.4 * y + 0.15 * np.sin(9 * x) * np.cos(7 * y)
    t = (t - t.min()) / (t.max() - t.min())
    return -11000.0 + 19848.0 * t


NX, NY = 129, 97
base = surface(NX, NY)
hole = np.zeros((NY, NX), bool)
hole[::17, ::13] = True            # scattered single voids
hole[30:70, 40:90] = True          # a whole block of nodata (several engine blocks)


def with_nodata(values, mask, fill):
    out = values.copy()
    out[mask] = fill
    return out


cases = []  # (name, path, expected heights in file order with NaN = nodata, reader opts)
i16 = np.round(base).astype(np.int16)
cases.append(("GeoTIFF int16 -11000..8848 with holes",
              demfiles.tiff(os.path.join(tmp, "i16.tif"), with_nodata(i16, hole, -32768),
                            nodata=-32768),
              with_nodata(i16.astype(float), hole, np.nan)))
u16 = np.round(np.clip(base, 0, None)).astype(np.uint16)
cases.append(("GeoTIFF uint16 0..8848 with holes",
              demfiles.tiff(os.path.join(tmp, "u16.tif"), with_nodata(u16, hole, 65535),
                            nodata=65535),
              with_nodata(u16.astype(float), hole, np.nan)))
f32 = base.astype(np.float32)
f32_special = f32.copy()
f32_special[hole] = np.nan
f32_special[5, 5], f32_special[6, 100] = np.inf, -np.inf
f32_special[90, 3:9] = np.inf
cases.append(("GeoTIFF float32 with NaN holes and +-Inf",
              demfiles.tiff(os.path.join(tmp, "f32.tif"), f32_special),
              np.where(np.isfinite(f32_special), f32_special, np.nan)))
f64 = base.copy()
f64[hole] = -9999.0
f64[10, 10], f64[11, 20] = 1e300, -1e300   # beyond float: nodata, not +-Inf or FLT_MAX
# Undeclared sentinels beyond the engine's +-1e38 height range (-FLT_MAX is common): nodata.
f64[12, 30], f64[13, 40] = -np.finfo(np.float32).max, 2e38
beyond = np.abs(f64) > 1e38
expect64 = np.where((f64 == -9999.0) | beyond, np.nan, np.where(beyond, 0, f64).astype(np.float32))
cases.append(("GeoTIFF float64 with nodata and +-1e300",
              demfiles.tiff(os.path.join(tmp, "f64.tif"), f64, nodata=-9999), expect64))
asc = with_nodata(np.round(base, 2), hole, np.nan)
cases.append(("ESRI ASCII with nodata block",
              demfiles.esri_ascii(os.path.join(tmp, "grid.asc"), asc, nodata=-32768),
              asc.astype(np.float32)))
srtm = np.round(surface(1201, 1201)).astype(np.int16)
srtm[400:600, 300:700] = -32768
cases.append(("SRTM .hgt int16 1201x1201 with voids",
              demfiles.hgt(os.path.join(tmp, "N46W122.hgt"), srtm),
              np.where(srtm == -32768, np.nan, srtm.astype(np.float32))))
flat = np.full((NY, NX), 1234.5, np.float32)
cases.append(("GeoTIFF float32 flat", demfiles.tiff(os.path.join(tmp, "flat.tif"), flat), flat))
void = np.full((NY, NX), -9999.0, np.float32)
cases.append(("GeoTIFF float32 all nodata",
              demfiles.tiff(os.path.join(tmp, "void.tif"), void, nodata=-9999),
              np.full((NY, NX), np.nan)))
cases.append(("TIFF without georeference",
              demfiles.tiff(os.path.join(tmp, "nogeo.tif"), i16, georef=None),
              i16.astype(np.float32)))

scene = Scene(160, 120)
cam = scene.cam
reader = vtkGeoMipMapTerrainReader()
messages.take()


def look_at(bounds, zmin, zmax):
    """Oblique view of the whole DEM from the south-west, above its top."""
    cx, cy = (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2
    ext = max(bounds[1] - bounds[0], bounds[3] - bounds[2])
    cam.SetFocalPoint(cx, cy, (zmin + zmax) / 2)
    cam.SetPosition(cx - ext, cy - 1.5 * ext, zmax + ext)
    cam.SetViewUp(0, 0, 1)
    cam.SetViewAngle(30)
    scene.ren.ResetCameraClippingRange()


def drawn_pixels():
    grab = vtkWindowToImageFilter()
    grab.SetInput(scene.win)
    grab.Update()
    rgb = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())
    return int(np.count_nonzero(rgb.max(axis=1)))


def render_and_filter(name, port, valid, empty):
    """Mapper render and filter output for one image; checks what the docstring says."""
    mapper = vtkGeoMipMapMapper()
    mapper.SetInputConnection(port)
    mapper.SetPixelError(2.0)
    mapper.ScalarVisibilityOff()
    scene.actor.SetMapper(mapper)
    image = port.GetProducer().GetOutputDataObject(port.GetIndex())
    zmin, zmax = (np.nanmin(valid), np.nanmax(valid)) if not empty else (0.0, 0.0)
    look_at(image.GetBounds(), zmin, zmax)
    scene.win.Render()
    tris, drawn = mapper.GetNumberOfRenderedTriangles(), drawn_pixels()
    filt = vtkGeoMipMapFilter()
    filt.SetInputConnection(port)
    filt.SetCamera(cam)
    filt.SetViewportSize(160, 120)
    filt.SetPixelError(2.0)
    filt.Update()
    xyz, ftris = filter_points(filt)
    errors, warnings = messages.take()
    print("%s: %d triangles, %d pixels drawn, filter %d points %d triangles, %d warnings"
          % (name, tris, drawn, len(xyz), ftris, len(warnings)))
    check(not errors, name + ": no VTK error while rendering/filtering %s" % errors[:2])
    check(np.isfinite(xyz).all(), name + ": filter output points are all finite")
    check(ftris == tris, name + ": filter and mapper draw the same triangles")
    if empty:
        check(tris == 0 and drawn == 0 and len(xyz) == 0, name + ": nothing drawn")
    else:
        check(tris > 0 and drawn > 0, name + ": terrain drawn")
        check(len(xyz) > 0 and zmin <= xyz[:, 2].min() and xyz[:, 2].max() <= zmax,
              name + ": filter heights %g..%g inside the valid range [%g, %g]"
              % (xyz[:, 2].min(), xyz[:, 2].max(), zmin, zmax))


for name, path, expected in cases:
    reader.SetFileName(path)
    ok = reader.GetExecutive().Update() == 1
    errors, warnings = messages.take()
    out = reader.GetOutput()
    check(ok and not errors, name + ": reads without error")
    if not ok:
        continue
    got = vtk_to_numpy(out.GetPointData().GetScalars()).reshape(out.GetDimensions()[1],
                                                                 out.GetDimensions()[0])
    want = np.flipud(np.asarray(expected, dtype=np.float32))  # reader rows run northwards
    if path.endswith(".hgt"):  # lon/lat: resampled (vtkGeoMipMapTerrainReader.h)
        bad, worst, n = resampling_mismatch(out, want.astype(float), -122.0, 46.0, 1.0 / 1200)
        inside = np.isfinite(got)
        check(bad == 0 and worst < 0.01 and np.nanmin(got) >= np.nanmin(want) and
              np.nanmax(got) <= np.nanmax(want),
              name + ": heights resampled from the file's values (%d nodes: %d nodata "
              "mismatches, largest difference %.4f m), within the valid range" % (n, bad, worst))
        render_and_filter(name, reader.GetOutputPort(), got[inside], False)
        continue
    same = got.shape == want.shape and np.array_equal(np.isnan(got), np.isnan(want)) and \
        np.array_equal(got[~np.isnan(got)], want[~np.isnan(want)])
    check(same, name + ": heights read back exactly (nodata, +-Inf, out-of-range -> NaN)")
    empty = bool(np.isnan(want).all())
    if empty:
        check(any("every sample is nodata" in w for w in warnings),
              name + ": warns that every sample is nodata")
    if "georeference" in name:
        check(any("no georeference" in w for w in warnings) and out.GetOrigin()[:2] == (0, 0)
              and out.GetSpacing()[:2] == (1, 1),
              name + ": warns, origin (0, 0), Spacing 1")
    elif path.endswith(".tif") or path.endswith(".asc"):
        check(out.GetOrigin()[0] == 500015.0 and out.GetSpacing()[:2] == (30.0, 30.0),
              name + ": georeference kept")
    render_and_filter(name, reader.GetOutputPort(), want, empty)

# In memory, bypassing the reader: float64 heights with +-Inf, NaN and +-1e300.
mem = base.copy()
mem[hole] = np.nan
mem[3, 3], mem[4, 4], mem[50, 2], mem[60, 7] = np.inf, -np.inf, 1e300, -1e300
image = vtkImageData()
image.SetDimensions(NX, NY, 1)
image.SetSpacing(30, 30, 1)
image.SetOrigin(6.4e6, 6.4e6, 0)  # and at a large offset
arr = numpy_to_vtk(np.flipud(mem).ravel().copy(), deep=1,
                   array_type=vtkDoubleArray().GetDataType())
arr.SetName("Elevation")
image.GetPointData().SetScalars(arr)
source = vtkPassThrough()
source.SetInputData(image)
source.Update()
valid = np.where(np.isfinite(mem) & (np.abs(mem) < 1e30), mem, np.nan).astype(np.float32)
render_and_filter("in-memory float64 with +-Inf, NaN, +-1e300", source.GetOutputPort(), valid, False)

shutil.rmtree(tmp, ignore_errors=True)
if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("PASS")
