"""Draped imagery (issue #15, part 4): vtkGeoMipMapImageDrape + vtkGeoMipMapMapper.SetDrapeImage.

Synthetic orthophotos whose pattern is known, written here as GeoTIFFs (demfiles): a grey
field with coloured 3 x 3-pixel markers at known ground coordinates, covering only part of
a flat synthetic DEM. Rendered from straight above with a parallel projection, unlit, at a
known number of metres per pixel, the markers must appear where their ground coordinates
project (within 1 px), and the photo's edges where its extent projects (so it is not
stretched over the DEM), for:
- DEM and photo in UTM zone 10N (EPSG:32610): the photo's pixels as they are (no warp);
- DEM in UTM, photo in lon/lat (EPSG:4326): warped by GDAL; the expected positions come
  from the lon/lat -> UTM series computed here (Krueger's, independent of GDAL / PROJ);
- DEM in lon/lat (the reader's local transverse Mercator frame), photo in lon/lat: the
  expected positions from the reader's own vtkGeoMipMapTerrainReader.GeographicToLocal
  (GeographicLib), against GDAL's warp.
Also: outside the photo the terrain keeps its own colouring (the same pixels as without
the drape, lookup-table colours by height), and so it does through a transparent part of
an RGBA photo (as is, and warped); lighting modulates the photo (lit / unlit the
same for R, G and B); a drape larger than the OpenGL texture limit is refused with an error
and the terrain drawn as without it; bad files and settings fail with an error naming the
file and the problem; MaximumSize resamples and keeps the alignment.
Needs an X display (xvfb-run ctest); no data files.
"""
import math
import os
import shutil
import sys
import tempfile

import numpy as np
import geomipmap
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkmodules.util.numpy_support import vtk_to_numpy, numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer

import demfiles
import refscene
from gmmtestutil import ErrorCatcher, check, read_dem, update

W, H = 480, 360
MPP = 10.0  # metres per pixel of the renders
BG = (0.0, 0.0, 0.0)
GREY = (128, 128, 128)
MARKERS = {"red": (255, 0, 0), "green": (0, 255, 0), "blue": (0, 0, 255), "yellow": (255, 255, 0)}


def utm_forward(lon, lat, zone):
    """WGS 84 lon/lat (degrees) to UTM (easting, northing; northern hemisphere): Krueger's
    series to n^4 (Karney 2011, eqs. 7, 9, 11-12: sub-millimetre within the zone)."""
    a, f, k0 = 6378137.0, 1 / 298.257223563, 0.9996
    n = f / (2 - f)
    big_a = a / (1 + n) * (1 + n ** 2 / 4 + n ** 4 / 64)
    alpha = (n / 2 - 2 * n ** 2 / 3 + 5 * n ** 3 / 16 + 41 * n ** 4 / 180,
             13 * n ** 2 / 48 - 3 * n ** 3 / 5 + 557 * n ** 4 / 1440,
             61 * n ** 3 / 240 - 103 * n ** 4 / 140,
             49561 * n ** 4 / 161280)
    e = 2 * math.sqrt(n) / (1 + n)
    phi, lam = math.radians(lat), math.radians(lon - (zone * 6 - 183))
    t = math.sinh(math.atanh(math.sin(phi)) - e * math.atanh(e * math.sin(phi)))
    xi_, eta_ = math.atan2(t, math.cos(lam)), math.atanh(math.sin(lam) / math.sqrt(1 + t * t))
    xi = xi_ + sum(al * math.sin(2 * j * xi_) * math.cosh(2 * j * eta_)
                   for j, al in enumerate(alpha, 1))
    eta = eta_ + sum(al * math.cos(2 * j * xi_) * math.sinh(2 * j * eta_)
                     for j, al in enumerate(alpha, 1))
    return 500000.0 + k0 * big_a * eta, k0 * big_a * xi


def photo(ny, nx, markers):
    """A grey photo (ny x nx x 3, row 0 north) with 3 x 3 markers: {name: (row, col)} of
    their middle pixels."""
    img = np.empty((ny, nx, 3), np.uint8)
    img[:] = GREY
    for name, (r, c) in markers.items():
        img[r - 1:r + 2, c - 1:c + 2] = MARKERS[name]
    return img


def scene(dem_image, drape_image=None, lit=False, lut=None):
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(dem_image)
    mapper.SetPixelError(0.5)
    if lut is not None:
        mapper.SetLookupTable(lut)
        mapper.SetScalarRange(*dem_image.GetPointData().GetScalars().GetRange())
        mapper.ScalarVisibilityOn()
    else:
        mapper.ScalarVisibilityOff()
    if drape_image is not None:
        mapper.SetDrapeImage(drape_image)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.2, 0.4, 1.0)
    if not lit:
        actor.GetProperty().LightingOff()
    ren = vtkRenderer()
    ren.SetBackground(*BG)
    ren.AddActor(actor)
    return mapper, ren, shared_window(ren)


_WINDOW = []


def shared_window(ren):
    """One window for every render of this test, showing `ren` alone. A window per render
    opened a dozen X connections within two seconds, and once in a few parallel ctest runs
    the X server refused one (VTK then aborts: "bad X server connection")."""
    if not _WINDOW:
        _WINDOW.append(refscene.window(W, H))
    win = _WINDOW[0]
    win.GetRenderers().RemoveAllItems()
    win.AddRenderer(ren)
    return win


def top_down(ren, cx, cy):
    cam = ren.GetActiveCamera()
    cam.SetParallelProjection(True)
    cam.SetFocalPoint(cx, cy, 0.0)
    cam.SetPosition(cx, cy, 1.0e5)
    cam.SetViewUp(0.0, 1.0, 0.0)
    cam.SetParallelScale(0.5 * H * MPP)
    ren.ResetCameraClippingRange()


def to_pixel(x, y, cx, cy):
    """(column, row from the bottom) of the pixel whose centre sees ground (x, y)."""
    return (x - cx) / MPP + 0.5 * W - 0.5, (y - cy) / MPP + 0.5 * H - 0.5


def render(dem_image, drape_image, cx, cy, **kw):
    mapper, ren, win = scene(dem_image, drape_image, **kw)
    errors = ErrorCatcher(mapper)
    top_down(ren, cx, cy)
    win.Render()
    px = refscene.grab(win).astype(int)
    win.RemoveRenderer(ren)
    return px, errors.messages


def centroid(px, rgb):
    """Centroid (column, row) of the pixels close to colour rgb, weighted by closeness."""
    d = np.abs(px - np.array(rgb)).max(axis=2)
    w = np.clip(1.0 - d / 128.0, 0.0, None)
    w[d > 100] = 0.0
    if w.sum() < 1.0:
        return None
    rows, cols = np.nonzero(w)
    return float((cols * w[rows, cols]).sum() / w.sum()), float((rows * w[rows, cols]).sum() / w.sum())


def check_markers(what, px, expected):
    """expected: {name: (column, row)}; returns the largest distance in pixels."""
    worst = 0.0
    for name, (ec, er) in expected.items():
        got = centroid(px, MARKERS[name])
        check(got is not None, f"{what}: the {name} marker is visible")
        err = math.hypot(got[0] - ec, got[1] - er)
        print(f"{what}: {name} marker at ({got[0]:.2f}, {got[1]:.2f}) px, expected "
              f"({ec:.2f}, {er:.2f}): {err:.2f} px off")
        worst = max(worst, err)
    check(worst <= 0.35, f"{what}: every marker within 0.35 px of its ground position "
          f"(worst {worst:.2f} px)")
    return worst


def check_extent(what, px, corners):
    """The photo's grey area spans the projected extent: corners = (col0, col1, row0, row1)
    of its outermost pixel centres. Its edges may be off by half a pixel (the filtered
    border) plus 1 px."""
    grey = np.abs(px - np.array(GREY)).max(axis=2) <= 40
    rows, cols = np.nonzero(grey)
    got = (cols.min(), cols.max(), rows.min(), rows.max())
    off = max(abs(g - e) for g, e in zip(got, corners))
    check(off <= 1.5, f"{what}: the photo covers columns {got[0]}..{got[1]}, rows "
          f"{got[2]}..{got[3]}; its extent projects to {corners[0]:.1f}..{corners[1]:.1f}, "
          f"{corners[2]:.1f}..{corners[3]:.1f} (off by {off:.1f} px): not stretched")
    return grey


def try_drape(terrain, path, **options):
    """(the drape algorithm, whether its update succeeded, its error texts)."""
    d = geomipmap.vtkGeoMipMapImageDrape()
    d.SetFileName(path)
    d.SetTerrain(terrain)
    for key, value in options.items():
        getattr(d, "Set" + key)(value)
    errors = ErrorCatcher(d)
    return d, update(d), errors.messages


def drape_of(terrain, path, **options):
    d, ok, errors = try_drape(terrain, path, **options)
    check(ok, f"drape {os.path.basename(path)} {options} (errors: {errors})")
    return d.GetOutput()


def flat_dem(folder, name, **georef):
    z = np.full((100, 120), 100.0, np.float32)
    path = demfiles.tiff(os.path.join(folder, name), z, **georef)
    return read_dem(path)[1]


def utm_same_crs(folder):
    """DEM and photo in EPSG:32610: the photo's pixels as they are."""
    dem = flat_dem(folder, "dem_utm.tif", georef=(500000.0, 4000000.0, 30.0))
    # Photo: 10 m pixels, upper-left corner (500400, 3999500): covers x 500400..501600,
    # y 3998500..3999500, part of the DEM (x 500000..503600, y 3997000..4000000).
    marks = {"red": (20, 30), "green": (80, 100), "blue": (50, 10), "yellow": (5, 115)}
    west, north, step = 500400.0, 3999500.0, 10.0
    path = demfiles.tiff(os.path.join(folder, "photo_utm.tif"), photo(100, 120, marks),
                         georef=(west, north, step), rgb=True)
    drape = drape_of(dem, path)
    check(drape.GetFieldData().GetArray("DrapeWarped").GetValue(0) == 0,
          "same CRS, north-up: the photo's pixels are used as they are (not warped)")
    check(drape.GetDimensions()[:2] == (120, 100) and drape.GetSpacing()[:2] == (10.0, 10.0)
          and drape.GetOrigin()[:2] == (west + 5.0, north - 995.0),
          f"drape grid: pixel centres from the photo's geotransform ({drape.GetOrigin()})")
    cx, cy = 501800.0, 3998500.0
    px, errors = render(dem, drape, cx, cy)
    check(not errors, f"renders without errors ({errors})")
    expected = {n: to_pixel(west + (c + 0.5) * step, north - (r + 0.5) * step, cx, cy)
                for n, (r, c) in marks.items()}
    worst = check_markers("UTM photo on UTM DEM", px, expected)
    c0, r0 = to_pixel(west + 0.5 * step, north - 99.5 * step, cx, cy)
    c1, r1 = to_pixel(west + 119.5 * step, north - 0.5 * step, cx, cy)
    grey = check_extent("UTM photo on UTM DEM", px, (c0, c1, r0, r1))
    # Outside the photo: the terrain's own colouring (the actor's colour, unlit).
    dem_c0, dem_r0 = to_pixel(500015.0, 3997015.0, cx, cy)
    dem_c1, dem_r1 = to_pixel(503585.0, 3999985.0, cx, cy)
    outside = np.zeros(grey.shape, bool)
    # the DEM's area, less its edge pixels (which may fall either side of the edge)
    outside[int(dem_r0) + 2:int(dem_r1), int(dem_c0) + 2:int(dem_c1)] = True
    inside = np.zeros(grey.shape, bool)
    inside[int(r0) - 2:int(r1) + 4, int(c0) - 2:int(c1) + 4] = True
    outside &= ~inside
    actor_colour = np.round(np.array([0.2, 0.4, 1.0]) * 255)
    off = np.abs(px[outside] - actor_colour).max()
    check(outside.sum() > 10000 and off <= 2, f"outside the photo ({outside.sum()} px) the "
          f"terrain keeps the actor's colour (largest difference {off})")
    return worst


def lonlat_photo_on_utm(folder):
    """DEM in UTM zone 10N, photo in lon/lat (EPSG:4326): warped by GDAL."""
    dem = flat_dem(folder, "dem_utm2.tif", georef=(500000.0, 4000000.0, 30.0))
    # About 0.0001 deg = 9 m (east) / 11 m (north) pixels over x 500700..502400.
    west, north, step = -122.992, 36.138, 0.0001
    marks = {"red": (30, 40), "green": (90, 150), "blue": (60, 10), "yellow": (10, 170)}
    path = demfiles.tiff(os.path.join(folder, "photo_ll.tif"), photo(120, 180, marks),
                         georef=(west, north, step), rgb=True, geographic=True)
    drape = drape_of(dem, path)
    check(drape.GetFieldData().GetArray("DrapeWarped").GetValue(0) == 1,
          "lon/lat photo on a UTM DEM: warped")
    e, n = utm_forward(west + 90 * step, north - 60 * step, 10)
    cx, cy = round(e), round(n)
    px, errors = render(dem, drape, cx, cy)
    check(not errors, f"renders without errors ({errors})")
    expected = {}
    for name, (r, c) in marks.items():
        e, n = utm_forward(west + (c + 0.5) * step, north - (r + 0.5) * step, 10)
        expected[name] = to_pixel(e, n, cx, cy)
    return check_markers("lon/lat photo on UTM DEM", px, expected)


def lonlat_on_lonlat(folder):
    """DEM in lon/lat: the reader's local TM frame; photo in lon/lat."""
    z = np.full((240, 300), 500.0, np.float32)  # 3 arc-seconds, 0.25 x 0.2 degrees
    demstep = 1.0 / 1200.0
    path = demfiles.tiff(os.path.join(folder, "dem_ll.tif"), z, georef=(-121.9, 46.9, demstep),
                         geographic=True)
    dem = read_dem(path)[1]
    west, north, step = -121.80, 46.83, 0.00012
    marks = {"red": (20, 20), "green": (100, 200), "blue": (110, 30), "yellow": (15, 190)}
    ppath = demfiles.tiff(os.path.join(folder, "photo_ll2.tif"), photo(130, 220, marks),
                          georef=(west, north, step), rgb=True, geographic=True)
    drape = drape_of(dem, ppath)
    R = geomipmap.vtkGeoMipMapTerrainReader
    xy = [0.0, 0.0]
    R.GeographicToLocal(dem, west + 110 * step, north - 65 * step, xy)
    cx, cy = round(xy[0]), round(xy[1])
    px, errors = render(dem, drape, cx, cy)
    check(not errors, f"renders without errors ({errors})")
    expected = {}
    for name, (r, c) in marks.items():
        R.GeographicToLocal(dem, west + (c + 0.5) * step, north - (r + 0.5) * step, xy)
        expected[name] = to_pixel(xy[0], xy[1], cx, cy)
    return check_markers("lon/lat photo on lon/lat DEM", px, expected)


def transparent_parts(folder):
    """An RGBA photo with a transparent stripe: the terrain's colour shows through it, both
    when the photo's pixels are used as they are and when GDAL warps it (source alpha)."""
    dem = flat_dem(folder, "dem_a.tif", georef=(500000.0, 4000000.0, 30.0))
    rgba = np.zeros((100, 120, 4), np.uint8)
    rgba[..., :3] = GREY
    rgba[..., 3] = 255
    rgba[:, 40:80, 3] = 0  # columns 40..79: no data
    actor_colour = np.round(np.array([0.2, 0.4, 1.0]) * 255)
    cases = (("UTM", (500400.0, 3999500.0, 10.0), False),
             ("lon/lat", (-122.992, 36.138, 0.0001), True))
    for what, (west, north, step), geographic in cases:
        path = demfiles.tiff(os.path.join(folder, f"alpha{int(geographic)}.tif"), rgba,
                             georef=(west, north, step), rgb=True, geographic=geographic)
        drape = drape_of(dem, path)
        ground = utm_forward if geographic else (lambda lon, lat, _zone: (lon, lat))
        cx, cy = (round(v) for v in ground(west + 60 * step, north - 50 * step, 10))
        px, errors = render(dem, drape, cx, cy)
        check(not errors, f"renders without errors ({errors})")
        for col, colour, name in ((60, actor_colour, "the terrain's colour through the "
                                   "transparent stripe"), (20, GREY, "the photo beside it"),
                                  (100, GREY, "the photo beside it")):
            c, r = to_pixel(*ground(west + (col + 0.5) * step, north - 50.5 * step, 10), cx, cy)
            got = px[int(round(r)), int(round(c))]
            check(np.abs(got - np.array(colour)).max() <= 2,
                  f"RGBA {what} photo: at its column {col}, {name} ({got.tolist()})")


def colouring_and_lighting(folder):
    """Outside the photo the LUT colouring is unchanged; lighting modulates the photo."""
    ys, xs = np.mgrid[0:100, 0:120]
    z = (100.0 + 8.0 * xs + 3.0 * ys).astype(np.float32)  # a slope, so that light varies
    path = demfiles.tiff(os.path.join(folder, "dem_slope.tif"), z, georef=(500000.0, 4000000.0, 30.0))
    dem = read_dem(path)[1]
    ppath = demfiles.tiff(os.path.join(folder, "photo_c.tif"), photo(100, 120, {}),
                          georef=(500400.0, 3999500.0, 10.0), rgb=True)
    drape = drape_of(dem, ppath)
    lut = vtkLookupTable()
    lut.SetHueRange(0.66, 0.0)
    lut.Build()
    cx, cy = 501800.0, 3998500.0
    with_drape, e1 = render(dem, drape, cx, cy, lut=lut)
    without, e2 = render(dem, None, cx, cy, lut=lut)
    check(not e1 and not e2, f"renders without errors ({e1 + e2})")
    c0, r0 = to_pixel(500400.0, 3998500.0, cx, cy)
    c1, r1 = to_pixel(501600.0, 3999500.0, cx, cy)
    covered = np.zeros(with_drape.shape[:2], bool)
    covered[int(r0) - 1:int(r1) + 3, int(c0) - 1:int(c1) + 3] = True
    terrain = np.abs(without - np.array(BG)).max(axis=2) > 0
    same = np.abs(with_drape - without).max(axis=2) <= 1
    check(same[terrain & ~covered].all() and (terrain & ~covered).sum() > 10000,
          f"outside the photo the lookup-table colours are unchanged "
          f"({(~same[terrain & ~covered]).sum()} of {(terrain & ~covered).sum()} px differ)")
    inner = np.zeros_like(covered)
    inner[int(r0) + 2:int(r1) - 1, int(c0) + 2:int(c1) - 1] = True
    check(np.abs(with_drape[inner] - np.array(GREY)).max() <= 2,
          "inside it the photo replaces them (unlit: its own grey)")
    lit, e3 = render(dem, drape, cx, cy, lit=True)
    check(not e3, f"lit render without errors ({e3})")
    ratio = lit[inner].astype(float) / np.array(GREY, float)
    spread = float((ratio.max(axis=1) - ratio.min(axis=1)).max())
    mean = float(ratio.mean())
    check(0.05 < mean < 0.98 and spread <= 0.03, f"lit: the photo is shaded (lit / unlit "
          f"{mean:.3f} on average, the same for R, G and B within {spread:.3f})")


def refusals(folder):
    dem = flat_dem(folder, "dem_r.tif", georef=(500000.0, 4000000.0, 30.0))
    # A drape larger than the texture limit: an error, and the terrain as without it.
    big = vtkImageData()
    big.SetDimensions(16385, 2, 1)
    big.SetOrigin(500000.0, 3997000.0, 0.0)
    big.SetSpacing(0.1, 1000.0, 1.0)
    rgb = np.zeros((16385 * 2, 4), np.uint8)
    rgb[:] = (255, 0, 0, 255)
    arr = numpy_to_vtk(rgb, deep=True)
    arr.SetName("DrapeRGBA")
    big.GetPointData().SetScalars(arr)
    cx, cy = 501800.0, 3998500.0
    px, errors = render(dem, big, cx, cy)
    plain, _ = render(dem, None, cx, cy)
    check(any("16385 x 2" in e and "largest texture" in e for e in errors),
          f"a 16385-pixel-wide drape is refused naming its size ({errors})")
    check(np.array_equal(px, plain), "and the terrain is drawn as without it")

    good = demfiles.tiff(os.path.join(folder, "p.tif"), photo(40, 40, {}),
                         georef=(500400.0, 3999500.0, 10.0), rgb=True)
    nogeo = demfiles.tiff(os.path.join(folder, "nogeo.tif"), photo(40, 40, {}), georef=None,
                          rgb=True)
    deep = demfiles.tiff(os.path.join(folder, "u16.tif"), np.zeros((8, 8), np.uint16))
    png_dem = demfiles.png16(os.path.join(folder, "h.png"), np.zeros((8, 8), np.uint16))
    no_crs = read_dem(png_dem)[1]
    cases = [
        ("a missing file", os.path.join(folder, "missing.tif"), dem, {}, "not an image GDAL"),
        ("no georeference", nogeo, dem, {}, "no georeference"),
        ("16-bit bands", deep, dem, {}, "UInt16"),
        ("a terrain without CRS", good, no_crs, {}, "no CRS"),
        ("no terrain", good, None, {}, "no terrain"),
        ("MaximumSize -1", good, dem, {"MaximumSize": -1}, "MaximumSize"),
    ]
    for what, path, terrain, options, words in cases:
        _, ok, errors = try_drape(terrain, path, **options)
        text = " ".join(errors)
        check(not ok and path in text and words in text,
              f"{what}: fails with an error naming the file and '{words}' ({text.strip()[:200]!r})")


def maximum_size(folder):
    """MaximumSize resamples (warps) to fit and keeps the photo in place."""
    dem = flat_dem(folder, "dem_m.tif", georef=(500000.0, 4000000.0, 30.0))
    marks = {"red": (30, 30), "blue": (70, 90)}
    west, north, step = 500400.0, 3999500.0, 5.0
    path = demfiles.tiff(os.path.join(folder, "photo_m.tif"), photo(100, 120, marks),
                         georef=(west, north, step), rgb=True)
    drape = drape_of(dem, path, MaximumSize=60)
    dims = drape.GetDimensions()
    check(max(dims[:2]) <= 60 and drape.GetFieldData().GetArray("DrapeWarped").GetValue(0) == 1,
          f"MaximumSize 60: a 120 x 100 photo resampled to {dims[0]} x {dims[1]}")
    b = drape.GetBounds()
    sx, sy = drape.GetSpacing()[:2]
    check(abs(b[0] - 0.5 * sx - west) < 1e-6 and abs(b[3] + 0.5 * sy - north) < 1e-6,
          f"its corner stays at the photo's ({b[0] - 0.5 * sx}, {b[3] + 0.5 * sy})")


def main():
    folder = tempfile.mkdtemp(prefix="gmm-drape-")
    try:
        worst = [utm_same_crs(folder), lonlat_photo_on_utm(folder), lonlat_on_lonlat(folder)]
        transparent_parts(folder)
        colouring_and_lighting(folder)
        refusals(folder)
        maximum_size(folder)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print(f"TestDrape: passed (marker alignment: worst {max(worst):.2f} px; same CRS "
          f"{worst[0]:.2f}, lon/lat on UTM {worst[1]:.2f}, lon/lat on lon/lat {worst[2]:.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
