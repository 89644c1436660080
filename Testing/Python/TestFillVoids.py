"""vtkGeoMipMapTerrainReader's void filling (FillNodata; issue #15, part 5), no window.

On a synthetic GeoTIFF (a plane, written here, with holes of known size punched into
it, so the true height of every void is known) and on the Rainier SRTM3 tile (9 % voids):
- off by default, and with FillNodata off the output is the same as before: the same
  heights bit for bit, the same field data, no "FilledNodata" array;
- on: every void with a valid sample within the search distance (Euclidean, in samples,
  computed here by brute force) is filled and every other void stays NaN; every valid
  sample keeps its bits; "FilledNodata" marks exactly the filled samples;
- filled values are weighted means of valid samples within the distance, so on a plane
  of slope s they are within s * distance of the truth (the known plane);
- Rainier: the corners of its lon/lat grid, outside the tile's footprint, stay NaN (and
  unmarked); the share of voids before and after is printed;
- bad parameters (search distance <= 0, NaN, inf; smoothing iterations < 0 or > 1000)
  fail the update with an error naming the file and the parameter, and the reader reads
  again once they are fixed.
"""
import math
import os
import shutil
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import demfiles
from geomipmap import vtkGeoMipMapTerrainReader as Reader
from gmmdata import optional_data_file
from gmmtestutil import ErrorCatcher, check, read_dem, update

SLOPE = (0.5 / 30.0, 0.25 / 30.0)  # metres per metre east, north (30 m samples)
NY, NX = 150, 200
# Holes (column, row from the north, radius in samples): small, on the border, and one
# wider than the search distance used below.
HOLES = ((20, 20, 1.5), (60, 40, 3), (100, 30, 8), (0, 90, 5), (199, 0, 4), (140, 100, 30))


def read(path, **options):
    """(reader, image, heights (ny, nx) float32 copy, FilledNodata (ny, nx) or None)."""
    r, img = read_dem(path, **options)
    nx, ny, _ = img.GetDimensions()
    z = vtk_to_numpy(img.GetPointData().GetScalars()).reshape(ny, nx).copy()
    mask = img.GetPointData().GetArray("FilledNodata")
    return r, img, z, None if mask is None else vtk_to_numpy(mask).reshape(ny, nx).copy()


def field_data(img):
    fd = img.GetFieldData()
    out = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        out[a.GetName()] = [a.GetVariantValue(k).ToString() for k in range(a.GetNumberOfValues())]
    return out


def reachable(valid, distance):
    """Samples that have a valid sample within `distance` (Euclidean, in samples): per row
    offset dy, a window of +-floor(sqrt(d^2 - dy^2)) columns, summed with cumulative sums."""
    r = int(math.floor(distance))
    ny, nx = valid.shape
    pad = np.zeros((ny + 2 * r, nx + 2 * r + 1), np.int32)  # column 0: zero, for the sums
    pad[r:r + ny, r + 1:r + 1 + nx] = valid
    cs = np.cumsum(pad, axis=1)
    out = np.zeros_like(valid)
    for dy in range(-r, r + 1):
        w = int(math.floor(math.sqrt(distance * distance - dy * dy) + 1e-9))
        rows = slice(r + dy, r + dy + ny)
        out |= (cs[rows, r + 1 + w:r + 1 + w + nx] - cs[rows, r - w:r - w + nx]) > 0
    return out


def check_fill(what, before, after, mask, distance, region=None):
    """The checks every fill must pass, on the samples of `region` (default all: the
    nodes outside a lon/lat grid's footprint are no voids); returns (voids, filled)."""
    near = reachable(~np.isnan(before), distance)
    if region is not None:
        before, after, mask, near = before[region], after[region], mask[region], near[region]
    was_void = np.isnan(before)
    check(mask is not None and mask.dtype == np.uint8, f"{what}: FilledNodata is unsigned char")
    same = before[~was_void].view(np.uint32) == after[~was_void].view(np.uint32)
    check(same.all(), f"{what}: all {(~was_void).sum()} valid samples keep their bits "
          f"({(~same).sum()} differ)")
    check(np.isfinite(after[was_void & near]).all(),
          f"{what}: no NaN left within {distance:g} samples of a valid sample "
          f"({np.isnan(after[was_void & near]).sum()} left)")
    check(np.isnan(after[was_void & ~near]).all(),
          f"{what}: voids farther than {distance:g} samples stay NaN "
          f"({(was_void & ~near).sum()} of them)")
    filled = was_void & np.isfinite(after)
    check(np.array_equal(mask.astype(bool), filled),
          f"{what}: FilledNodata marks exactly the {filled.sum()} filled samples "
          f"({(mask.astype(bool) != filled).sum()} wrong)")
    return int(was_void.sum()), int(filled.sum())


def bad_parameters(path):
    r = Reader()
    r.SetFileName(path)
    r.FillNodataOn()
    errors = ErrorCatcher(r)
    cases = [("FillSearchDistance", v) for v in (-1.0, 0.0, float("nan"), float("inf"))]
    cases += [("FillSmoothingIterations", v) for v in (-1, 1001)]
    for name, value in cases:
        r.SetFillSearchDistance(100.0)
        r.SetFillSmoothingIterations(0)
        getattr(r, "Set" + name)(value)
        errors.clear()
        ok = update(r)
        text = " ".join(errors.messages)
        check(not ok and path in text and name in text,
              f"{name} = {value}: the update fails with an error naming the file and "
              f"{name} ({text!r})")
    r.SetFillSearchDistance(100.0)
    r.SetFillSmoothingIterations(0)
    errors.clear()
    check(update(r) and not errors.messages, "with the parameters fixed the reader reads again")
    # Filling off: the fill parameters are not used, so bad ones do not matter.
    r.FillNodataOff()
    r.SetFillSearchDistance(-5.0)
    check(update(r) and not errors.messages, "bad fill parameters are ignored with FillNodata off")


def synthetic(folder):
    ys, xs = np.mgrid[0:NY, 0:NX]
    truth_file = (1000.0 + SLOPE[0] * 30.0 * xs + SLOPE[1] * 30.0 * (NY - 1 - ys)).astype(np.float32)
    holes = np.zeros((NY, NX), bool)
    for cx, cy, rad in HOLES:
        holes |= np.hypot(xs - cx, ys - cy) <= rad
    z = np.where(holes, np.float32(-9999.0), truth_file)
    path = demfiles.tiff(os.path.join(folder, "plane_holes.tif"), z, nodata=-9999)
    truth = truth_file[::-1]  # the reader's rows run northwards

    default = Reader()
    check(default.GetFillNodata() == 0 and default.GetFillSearchDistance() == 100.0
          and default.GetFillSmoothingIterations() == 0,
          "defaults: FillNodata off, search distance 100 samples, no smoothing")
    _, img0, z0, m0 = read(path)
    _, img1, z1, m1 = read(path, FillNodata=0, FillSearchDistance=3.0, FillSmoothingIterations=7)
    check(m0 is None and m1 is None, "no FilledNodata array when filling is off")
    check(np.array_equal(z0.view(np.uint32), z1.view(np.uint32))
          and field_data(img0) == field_data(img1)
          and img0.GetPointData().GetNumberOfArrays() == 1 == img1.GetPointData().GetNumberOfArrays(),
          "FillNodata off: the same heights (bit for bit), arrays and field data as by default")
    check(np.array_equal(np.isnan(z0), holes[::-1]), f"the {holes.sum()} holes read as NaN")

    for distance, smoothing in ((10.0, 0), (10.0, 4), (100.0, 0)):
        what = f"plane, distance {distance:g}, smoothing {smoothing}"
        _, img, z, m = read(path, FillNodata=1, FillSearchDistance=distance,
                            FillSmoothingIterations=smoothing)
        check(field_data(img) == field_data(img0), f"{what}: field data as without filling")
        voids, filled = check_fill(what, z0, z, m, distance)
        err = np.abs(z[m == 1].astype(np.float64) - truth[m == 1])
        # a weighted mean of samples within d of a plane of slope s is within s * d of it;
        # each smoothing pass averages neighbours sqrt(2) samples away at most
        bound = np.hypot(*SLOPE) * 30.0 * (distance + np.sqrt(2.0) * smoothing) + 1e-3
        check(err.max() <= bound, f"{what}: {filled} of {voids} voids filled, largest error "
              f"against the plane {err.max():.3f} m (mean {err.mean():.3f} m) <= {bound:.2f} m")
    bad_parameters(path)


def rainier():
    path = optional_data_file("mt_rainier_90m.tif")
    if path is None:
        return
    _, img0, z0, _ = read(path)
    ny, nx = z0.shape
    ox, oy, _ = img0.GetOrigin()
    dx, dy, _ = img0.GetSpacing()
    lon0, lat0 = img0.GetFieldData().GetArray("GeographicOrigin").GetTuple2(0)
    step = 1.0 / 1200.0  # SRTM3: 3 arc-seconds; the tile holds 1201 x 1201 samples
    # Inside the source's footprint, per node (its lon/lat through the reader's frame).
    inside = np.zeros((ny, nx), bool)
    ll = [0.0, 0.0]
    for j in range(ny):
        for i in range(nx):
            Reader.LocalToGeographic(img0, ox + i * dx, oy + j * dy, ll)
            u, v = (ll[0] - lon0) / step, (ll[1] - lat0) / step
            inside[j, i] = -1e-6 <= u <= 1200 + 1e-6 and -1e-6 <= v <= 1200 + 1e-6
    voids0 = np.isnan(z0) & inside
    check(voids0.sum() > 8000, f"Rainier: {voids0.sum()} voids inside the footprint "
          f"({100.0 * voids0.sum() / inside.sum():.2f} % of {inside.sum()} nodes), "
          f"{(~inside).sum()} corner nodes outside it")
    for distance in (3.0, 100.0):
        what = f"Rainier, distance {distance:g}"
        _, img, z, m = read(path, FillNodata=1, FillSearchDistance=distance)
        voids, filled = check_fill(what, z0, z, m, distance, region=inside)
        check(np.isnan(z[~inside]).all() and not m[~inside].any(),
              f"{what}: the {(~inside).sum()} corner nodes outside the footprint stay NaN, unmarked")
        left = np.isnan(z) & inside
        print(f"{what}: voids {voids} ({100.0 * voids / inside.sum():.2f} %) -> {left.sum()} "
              f"({100.0 * left.sum() / inside.sum():.3f} %), {filled} filled")
        lo, hi = np.nanmin(z0), np.nanmax(z0)
        check(lo <= np.nanmin(z) and np.nanmax(z) <= hi,
              f"{what}: filled heights within the tile's own range {lo:.0f} .. {hi:.0f} m")


def main():
    folder = tempfile.mkdtemp(prefix="gmm-fill-")
    try:
        synthetic(folder)
        rainier()
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print("TestFillVoids: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
