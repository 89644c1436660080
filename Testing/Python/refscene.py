"""A stock full-resolution VTK scene to check vtkGeoMipMapMapper against, and pixel tools.

Why: a test of the LOD mapper must compare it with something that does not use the engine.
reference_mesh() builds every full-resolution quad of a DEM image as two triangles with
plain numpy and vtkPolyData (the same diagonal the engine uses, quads touching nodata left
out, point id = image point id), drawn by a stock vtkPolyDataMapper: what the terrain
looks like without level of detail.
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderWindow,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL factory overrides)


def heights(image):
    """(ny, nx) float64 heights of a 2D image's active scalars (NaN = nodata)."""
    nx, ny, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).astype(np.float64).reshape(ny, nx)


def image_from_heights(z, spacing=(30.0, 30.0), origin=(0.0, 0.0, 0.0), name="Elevation"):
    """A 2D image whose point scalars are a copy of the (ny, nx) array z, in z's own type
    (the inverse of heights()); spacing (x, y), origin (x, y, z)."""
    img = vtkImageData()
    img.SetDimensions(z.shape[1], z.shape[0], 1)
    img.SetSpacing(spacing[0], spacing[1], 1.0)
    img.SetOrigin(*origin)
    a = numpy_to_vtk(np.ascontiguousarray(z).ravel(), deep=True)
    a.SetName(name)
    img.GetPointData().SetScalars(a)
    return img


def fractal_image(nx, ny, seed, spacing=30.0):
    """vtkGeoMipMapFractalSource's nx x ny terrain (seed, spacing in metres) as an image."""
    import geomipmap
    src = geomipmap.vtkGeoMipMapFractalSource()
    src.SetDimensions(nx, ny)
    src.SetSpacing(spacing)
    src.SetSeed(seed)
    src.Update()
    return src.GetOutput()


def sample_xy(image):
    """World x (per column) and y (per row) of the samples (axis-aligned images)."""
    nx, ny, _ = image.GetDimensions()
    ox, oy, _ = image.GetOrigin()
    sx, sy, _ = image.GetSpacing()
    e = image.GetExtent()
    return ox + (e[0] + np.arange(nx)) * sx, oy + (e[2] + np.arange(ny)) * sy


def reference_mesh(image, normals=True):
    """Every valid full-resolution quad as two triangles, the union jack the engine draws at
    full resolution (quad (i, j) split along (i, j)-(i+1, j+1) where i + j is even, along
    (i+1, j)-(i, j+1) where it is odd); z = origin z + height."""
    nx, ny, _ = image.GetDimensions()
    h = heights(image)
    xs, ys = sample_xy(image)
    z0 = image.GetOrigin()[2]
    X, Y = np.meshgrid(xs, ys)
    Z = np.where(np.isfinite(h), h, np.nanmin(h) if np.isfinite(h).any() else 0.0) + z0
    pts = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    ok = np.isfinite(h)
    quad = ok[:-1, :-1] & ok[:-1, 1:] & ok[1:, :-1] & ok[1:, 1:]
    j, i = np.nonzero(quad)
    a = j * nx + i
    b, c, d = a + 1, a + nx + 1, a + nx
    main = (i + j) % 2 == 0
    tris = np.concatenate([np.column_stack([a, b, c])[main], np.column_stack([a, c, d])[main],
                           np.column_stack([a, b, d])[~main], np.column_stack([b, c, d])[~main]])
    if (image.GetSpacing()[0] < 0) != (image.GetSpacing()[1] < 0):
        tris = tris[:, [0, 2, 1]]  # keep counter-clockwise seen from +z
    cells = np.column_stack([np.full(len(tris), 3), tris]).ravel().astype(np.int64)
    poly = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(pts, deep=True))
    poly.SetPoints(points)
    ca = vtkCellArray()
    ca.SetCells(len(tris), numpy_to_vtkIdTypeArray(cells, deep=True))
    poly.SetPolys(ca)
    scal = numpy_to_vtk(h.ravel().astype(np.float32), deep=True)
    scal.SetName("Elevation")
    poly.GetPointData().SetScalars(scal)
    if not normals:
        return poly
    n = vtkPolyDataNormals()
    n.SetInputData(poly)
    n.SplittingOff()
    n.ConsistencyOff()
    n.Update()
    return n.GetOutput()


def stock_actor(mesh):
    """`mesh` (a vtkPolyData) in a stock vtkPolyDataMapper, one colour."""
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(mesh)
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    return actor


def reference_actor(image):
    return stock_actor(reference_mesh(image))


def window(width, height, renderer=None):
    """Off-screen window without multisampling (deterministic pixels)."""
    win = vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(0)
    win.SetSize(width, height)
    if renderer is not None:
        win.AddRenderer(renderer)
    return win


def renders_on_cpu(win):
    """Whether the window's OpenGL runs on the CPU (Mesa's llvmpipe or softpipe), as the
    mapper's automatic normals ask."""
    caps = win.ReportCapabilities() or ""
    return "llvmpipe" in caps or "softpipe" in caps


def grab(win):
    """The window's RGB pixels as a (height, width, 3) uint8 array, row 0 at the bottom."""
    w2i = vtkWindowToImageFilter()
    w2i.SetInput(win)
    w2i.SetInputBufferTypeToRGB()
    w2i.ReadFrontBufferOff()
    w2i.Update()
    img = w2i.GetOutput()
    w, h, _ = img.GetDimensions()
    return vtk_to_numpy(img.GetPointData().GetScalars()).reshape(h, w, 3).copy()


def depth(win):
    """The window's depth buffer as a (height, width) float array."""
    from vtkmodules.vtkCommonCore import vtkFloatArray

    w, h = win.GetSize()
    buf = vtkFloatArray()
    win.GetZbufferData(0, 0, w - 1, h - 1, buf)
    return vtk_to_numpy(buf).reshape(h, w).copy()


def covered(pixels, background):
    """Mask of pixels that differ from the background colour (0..1 floats)."""
    bg = np.round(np.asarray(background) * 255).astype(int)
    return np.abs(pixels.astype(int) - bg).max(axis=2) > 2


def dilate(mask, r):
    """Square dilation by r pixels (numpy only)."""
    out = mask.copy()
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out |= np.roll(np.roll(mask, dy, axis=0), dx, axis=1)
    return out


class Checks:
    """Collects named checks: prints each ("ok: ..." / "FAIL: ..."), and exit() ends the
    test with status 1 when any failed."""

    def __init__(self, verbose=True):
        self.failures = []
        self.verbose = verbose

    def __call__(self, cond, what):
        if self.verbose or not cond:
            print(("ok: " if cond else "FAIL: ") + what)
        if not cond:
            self.failures.append(what)
        return cond

    def exit(self):
        print("PASS" if not self.failures else f"{len(self.failures)} failure(s)")
        sys.exit(1 if self.failures else 0)
