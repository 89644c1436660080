"""Mapper bounds are those of the valid samples (issue #16, item 5).

Regression: on SainteHelens.dem the mapper's y bounds were 5107980..5121990 while the
valid samples span 5108010..5121960 (the first and last rows are all nodata), so
ResetCamera framed 30 m of nothing. Checked against numpy over the reader's output, for
the DEM as read and for a copy with whole nodata columns and rows added around it, and
for an image whose samples are all nodata (uninitialised bounds, as VTK's empty data).
"""
import os

import numpy as np

import geomipmap
import gmmtestutil
import refscene

check = refscene.Checks()


def expected(image):
    h = refscene.heights(image)
    xs, ys = refscene.sample_xy(image)
    ok = np.isfinite(h)
    cols, rows = np.nonzero(ok.any(axis=0))[0], np.nonzero(ok.any(axis=1))[0]
    x = xs[cols]
    y = ys[rows]
    z0 = image.GetOrigin()[2]
    return (x.min(), x.max(), y.min(), y.max(), z0 + np.nanmin(h), z0 + np.nanmax(h))


def padded(image, left, right, bottom, top):
    h = refscene.heights(image)
    ny, nx = h.shape
    out = np.full((ny + bottom + top, nx + left + right), np.nan, np.float32)
    out[bottom:bottom + ny, left:left + nx] = h
    sx, sy, _ = image.GetSpacing()
    ox, oy, oz = image.GetOrigin()
    return refscene.image_from_heights(out, (sx, sy), (ox - left * sx, oy - bottom * sy, oz))


data = gmmtestutil.data_dir_or_skip()
reader = geomipmap.vtkGeoMipMapTerrainReader()
reader.SetFileName(os.path.join(data, "SainteHelens.dem"))
reader.Update()
image = reader.GetOutput()

for name, img in (("SainteHelens.dem", image),
                  ("padded with nodata", padded(image, 3, 5, 2, 7))):
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(img)
    got = mapper.GetBounds()
    want = expected(img)
    check(all(abs(g - w) <= 1e-6 * max(1.0, abs(w)) for g, w in zip(got, want)),
          f"{name}: bounds {tuple(round(v, 3) for v in got)} == valid samples "
          f"{tuple(round(v, 3) for v in want)}")

empty = padded(image, 0, 0, 0, 0)
empty.GetPointData().GetScalars().Fill(float("nan"))
mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputData(empty)
b = mapper.GetBounds()
check(b[0] > b[1], f"all-nodata image: uninitialised bounds, got {b}")

check.exit()
