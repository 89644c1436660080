"""The terrain under a flight: heights sampled in world x, y, and the reader's
geographic frame.

Why numpy and not the mapper: a path is planned before anything renders (terrain
following needs the ground under the whole path at once), in the same metres as the
reader's output, and lon/lat waypoints must land exactly where the reader put the
terrain, so the conversion is the reader's own (vtkGeoMipMapTerrainReader).
"""

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm

from ..geomipmapFilters import vtkGeoMipMapTerrainReader


class FlightError(ValueError):
    """Flight input that cannot be flown: a malformed waypoint file, a waypoint off the
    terrain, a zero-length path, a bad frame count... Its text is one line, naming the
    file and place where there is one."""


class Heights:
    """A DEM's elevation grid as numpy, with bilinear sampling in world x, y.

    image: the vtkImageData of heights (vtkGeoMipMapTerrainReader's or
    vtkGeoMipMapFractalSource's output, or any one-component image). The heights are
    copied, so a reader that runs again later does not change them; `image` keeps a
    shallow copy (its field data holds the reader's geographic frame, see GeoFrame).

    z[j, i] is the height of the sample at x = ox + i * dx, y = oy + j * dy (j northwards).
    NaN (nodata) samples are left out of the interpolation; a point with no finite
    neighbour gets NaN, which callers fill from the path's neighbours.
    """

    def __init__(self, image):
        if not isinstance(image, vtkImageData):
            raise TypeError(f"Heights needs a vtkImageData, got {type(image).__name__}")
        nx, ny, _ = image.GetDimensions()
        scalars = image.GetPointData().GetScalars()
        if scalars is None or nx < 2 or ny < 2:
            raise FlightError("terrain image has no elevation scalars (or fewer than 2 x 2 "
                              "samples)")
        self.image = vtkImageData()
        self.image.ShallowCopy(image)
        # A copy in the narrowest float type that holds the heights exactly (float32 for
        # 16-bit and float DEMs): 4 bytes a sample, where float64 took 2 GiB at 16385^2.
        a = vtk_to_numpy(scalars)
        if a.ndim > 1:
            a = a[:, 0]
        self.z = np.array(a, dtype=np.result_type(a.dtype, np.float32)).reshape(ny, nx)
        self.nx, self.ny = nx, ny
        self.ox, self.oy, _ = image.GetOrigin()
        self.dx, self.dy, _ = image.GetSpacing()
        finite = np.isfinite(self.z)  # a bool mask (1 byte a sample), no float copy
        if finite.any():
            self.zmin = float(self.z.min(where=finite, initial=np.inf))
            self.zmax = float(self.z.max(where=finite, initial=-np.inf))
        else:
            self.zmin = self.zmax = 0.0

    @property
    def bounds(self):
        """(xmin, xmax, ymin, ymax) of the sample positions."""
        return (self.ox, self.ox + (self.nx - 1) * self.dx,
                self.oy, self.oy + (self.ny - 1) * self.dy)

    def contains(self, x, y):
        """True when the point (x, y) lies within the grid's bounds."""
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
            v = self.z[j0 + dj, i0 + di].astype(np.float64)
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
    put the terrain. terrain: Heights, a vtkImageData or an algorithm producing one
    (as_heights). FlightError when the terrain has no such frame (not a lon/lat raster).
    """

    def __init__(self, terrain):
        self.image = as_heights(terrain).image
        fd = self.image.GetFieldData()
        arr = fd.GetArray("GeographicOrigin")
        if arr is None or arr.GetNumberOfValues() < 2 or fd.GetArray("CentralMeridian") is None:
            raise FlightError("waypoints are geographic (lon/lat) but the DEM has no "
                              "geographic origin (not a lon/lat raster); give local x,y in "
                              "metres")
        self.lon0, self.lat0 = arr.GetValue(0), arr.GetValue(1)

    def to_local(self, lon, lat):
        """(lon, lat) in degrees WGS 84 -> (x, y) in the terrain's metres."""
        xy = [0.0, 0.0]
        vtkGeoMipMapTerrainReader.GeographicToLocal(self.image, float(lon), float(lat), xy)
        return (xy[0], xy[1])

    def to_geographic(self, x, y):
        """(x, y) in the terrain's metres -> (lon, lat) in degrees WGS 84."""
        ll = [0.0, 0.0]
        vtkGeoMipMapTerrainReader.LocalToGeographic(self.image, float(x), float(y), ll)
        return (ll[0], ll[1])


def as_heights(terrain):
    """Heights for `terrain`: a Heights (returned as is), a vtkImageData, or an algorithm
    whose first output is one (a vtkGeoMipMapTerrainReader or vtkGeoMipMapFractalSource;
    it is updated first). FlightError when the algorithm fails or gives no samples."""
    if isinstance(terrain, Heights):
        return terrain
    if isinstance(terrain, vtkAlgorithm):
        if not terrain.GetExecutive().Update():
            raise FlightError(f"{terrain.GetClassName()} failed to produce the terrain")
        terrain = terrain.GetOutputDataObject(0)
    if isinstance(terrain, vtkImageData):
        return Heights(terrain)
    raise TypeError("expected Heights, a vtkImageData or an algorithm producing one, got "
                    f"{type(terrain).__name__}")
