"""Terrain input for the geomipmap tools: load a DEM (or the synthetic terrain), sample it.

Why a separate module: every tool opens its terrain the same way (the reader or the
fractal source, with one-line errors), and the flight path needs ground heights under the
camera (terrain following) and a geographic -> local-metre conversion that must agree
exactly with what vtkGeoMipMapTerrainReader did to the raster; both depend only on the
image, not on rendering.
"""

import os

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from .errors import AppError, VTKMessages


def load_terrain(dem=None, height_scale=1.0, spacing=None, terrain_rgb=False,
                 synthetic_size=1025, seed=1, messages=None):
    """Run the reader on `dem`, or the fractal source when dem is None; return
    (vtkImageData, Heights).

    spacing: metres between samples for images without georeference (synthetic terrain:
    default 30). synthetic_size, seed: the fractal source's samples per side and seed.
    messages: the VTKMessages that capture VTK's errors (a new one when None).
    Raises AppError with one line for a missing / unreadable file or an empty image.
    """
    import geomipmap  # noqa: deferred so that --help works without the compiled package

    messages = messages or VTKMessages()
    if dem:
        if not os.path.isfile(dem):
            raise AppError(f"DEM file not found: {dem}")
        if not os.access(dem, os.R_OK):
            raise AppError(f"DEM file not readable: {dem}")
        algo = geomipmap.vtkGeoMipMapTerrainReader()
        algo.SetFileName(dem)
        algo.SetHeightScale(height_scale)
        if spacing is not None:
            algo.SetSpacing(spacing)
        algo.SetTerrainRGB(1 if terrain_rgb else 0)
        what = f"cannot read DEM {dem}"
    else:
        algo = geomipmap.vtkGeoMipMapFractalSource()
        algo.SetDimensions(synthetic_size, synthetic_size)
        algo.SetSpacing(spacing if spacing is not None else 30.0)
        algo.SetSeed(seed)
        what = "synthetic terrain failed"
    messages.observe(algo)
    ok = algo.GetExecutive().Update()
    image = algo.GetOutput()
    err = messages.first_error()
    dims = image.GetDimensions() if image is not None else (0, 0, 0)
    if not ok or err or dims[0] < 2 or dims[1] < 2:
        if err and dem and dem in err:
            raise AppError(err)  # the reader's message names the file already
        raise AppError(f"{what}: {err or 'no elevation samples in the output'}")
    image = image.NewInstance()
    image.ShallowCopy(algo.GetOutput())
    heights = Heights(image)
    if not np.isfinite(heights.z).any():
        raise AppError(f"{what}: every sample is nodata")
    return image, heights


class Heights:
    """The image's elevation grid as numpy, with bilinear sampling in world x, y.

    z[j, i] is the height of the sample at x = ox + i * dx, y = oy + j * dy (j northwards).
    NaN (nodata) samples are left out of the interpolation; a point with no finite
    neighbour gets NaN, which callers fill from the path's neighbours.
    """

    def __init__(self, image):
        nx, ny, _ = image.GetDimensions()
        scalars = image.GetPointData().GetScalars()
        if scalars is None:
            raise AppError("terrain image has no elevation scalars")
        self.z = vtk_to_numpy(scalars).astype(np.float64).reshape(ny, nx)
        self.nx, self.ny = nx, ny
        self.ox, self.oy, _ = image.GetOrigin()
        self.dx, self.dy, _ = image.GetSpacing()
        finite = self.z[np.isfinite(self.z)]
        self.zmin = float(finite.min()) if finite.size else 0.0
        self.zmax = float(finite.max()) if finite.size else 0.0

    @property
    def bounds(self):
        """(xmin, xmax, ymin, ymax) of the sample positions."""
        return (self.ox, self.ox + (self.nx - 1) * self.dx,
                self.oy, self.oy + (self.ny - 1) * self.dy)

    def contains(self, x, y):
        xmin, xmax, ymin, ymax = self.bounds
        return xmin <= x <= xmax and ymin <= y <= ymax

    def sample(self, x, y):
        """Bilinear heights at arrays x, y (clamped to the grid); NaN where all 4 are nodata."""
        fx = np.clip((np.asarray(x, float) - self.ox) / self.dx, 0, self.nx - 1)
        fy = np.clip((np.asarray(y, float) - self.oy) / self.dy, 0, self.ny - 1)
        i0 = np.minimum(np.floor(fx).astype(int), self.nx - 2)
        j0 = np.minimum(np.floor(fy).astype(int), self.ny - 2)
        tx, ty = fx - i0, fy - j0
        num = np.zeros_like(fx)
        den = np.zeros_like(fx)
        for di, dj, w in ((0, 0, (1 - tx) * (1 - ty)), (1, 0, tx * (1 - ty)),
                          (0, 1, (1 - tx) * ty), (1, 1, tx * ty)):
            v = self.z[j0 + dj, i0 + di]
            ok = np.isfinite(v)
            num += np.where(ok, v, 0.0) * w
            den += np.where(ok, w, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = np.where(den > 1e-12, num / np.maximum(den, 1e-12), np.nan)
        return out


class GeoFrame:
    """Geographic (lon, lat) <-> the reader's local metric frame, by the reader itself.

    vtkGeoMipMapTerrainReader resamples lon/lat rasters onto a regular grid in a local
    transverse Mercator frame (see its header) and records it in the field data
    ("GeographicOrigin", "CentralMeridian"); its static GeographicToLocal /
    LocalToGeographic convert with that frame, so waypoints land exactly where the reader
    put the terrain.
    """

    def __init__(self, image, heights):
        fd = image.GetFieldData()
        arr = fd.GetArray("GeographicOrigin")
        if arr is None or arr.GetNumberOfValues() < 2 or fd.GetArray("CentralMeridian") is None:
            raise AppError("waypoints are geographic (lon/lat) but the DEM has no geographic "
                           "origin (not a lon/lat raster); give local x,y in metres")
        import geomipmap

        self.image = image
        self.reader = geomipmap.vtkGeoMipMapTerrainReader
        self.lon0, self.lat0 = arr.GetValue(0), arr.GetValue(1)

    def to_local(self, lon, lat):
        xy = [0.0, 0.0]
        self.reader.GeographicToLocal(self.image, float(lon), float(lat), xy)
        return (xy[0], xy[1])

    def to_geographic(self, x, y):
        ll = [0.0, 0.0]
        self.reader.LocalToGeographic(self.image, float(x), float(y), ll)
        return (ll[0], ll[1])
