"""The competing meshes: full-resolution grid, uniform subsampling, greedy decimation,
quadric clustering. Each is a vtkPolyData of triangles in the terrain's world frame with
"Elevation" point scalars (colouring) and point normals (lighting), like the mapper's.

Why numpy for the grids: a 4097^2 grid has 33.5 M triangles; building its cell array in
Python loops would take minutes, numpy builds it in seconds with 32-bit indices (half the
memory of vtkIdType).
"""

import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

# Estimated peak bytes per full-resolution sample (vtkPolyData + the OpenGL copies llvmpipe
# keeps in host memory), for the memory budget; each run notes its measured peak RSS.
# ours: the input plus height and slope textures, 12.2 measured at the margin (16385^2
# peaks at 13.5 with the process's own ~400 MB); greedy: double points, its triangulation
# and a priority queue over every sample. ours-fn, ours-vn, ours-vn-nomorph and floor are the same mapper
# with other options.
BYTES_PER_SAMPLE = {"brute": 110, "ours": 16, "ours-fn": 16, "ours-vn": 16, "ours-vn-nomorph": 16, "floor": 16,
                    "greedy": 100, "uniform": 8, "quadric": 110}


def grid_axes(n, stride):
    """Sample indices 0, s, 2s, ... and always the last one (no strip is dropped)."""
    idx = np.arange(0, n, stride)
    return idx if idx[-1] == n - 1 else np.append(idx, n - 1)


def grid_mesh(heights, stride=1):
    """Triangles over every stride-th sample, each quad split as the engine splits cells (the
    union jack: quad (u, v) along its (u, v)-(u+1, v+1) diagonal where u + v is even, along the
    other where it is odd; at stride 1 the engine's full-resolution surface); quads touching
    nodata are left out."""
    ii, jj = grid_axes(heights.nx, stride), grid_axes(heights.ny, stride)
    z = heights.z[np.ix_(jj, ii)].astype(np.float32)
    xs = (heights.ox + ii * heights.dx).astype(np.float64)
    ys = (heights.oy + jj * heights.dy).astype(np.float64)
    ny, nx = z.shape
    pts = np.empty((ny, nx, 3), np.float32)
    pts[..., 0] = xs[None, :]
    pts[..., 1] = ys[:, None]
    pts[..., 2] = np.nan_to_num(z, nan=heights.zmin)
    normals = _grid_normals(z, xs, ys)
    ids = np.arange(nx * ny, dtype=np.int32).reshape(ny, nx)
    a, b = ids[:-1, :-1].ravel(), ids[:-1, 1:].ravel()
    c, d = ids[1:, :-1].ravel(), ids[1:, 1:].ravel()
    ok = np.isfinite(z)
    good = (ok[:-1, :-1] & ok[:-1, 1:] & ok[1:, :-1] & ok[1:, 1:]).ravel()
    vv, uu = np.indices((ny - 1, nx - 1))
    anti = ((uu + vv) % 2 == 1).ravel()[good]
    a, b, c, d = a[good], b[good], c[good], d[good]
    conn = np.empty((a.size, 6), np.int32)
    # a = (u, v), b = (u+1, v), c = (u, v+1), d = (u+1, v+1), counter-clockwise
    conn[:, 0], conn[:, 1], conn[:, 2] = a, b, np.where(anti, c, d)
    conn[:, 3], conn[:, 4], conn[:, 5] = np.where(anti, b, a), d, c
    del a, b, c, d, anti
    return _polydata(pts.reshape(-1, 3), conn.reshape(-1), normals.reshape(-1, 3),
                     pts[..., 2].reshape(-1))


def _grid_normals(z, xs, ys):
    """Unit normals by central differences, one-sided next to the border or nodata, as the
    mapper shades (vtkGeoMipMapConversion::SampleNormal): the reference the shading
    comparison is made against."""
    def slope(axis, coords):
        ok = np.isfinite(z)
        zz = np.where(ok, z, 0.0).astype(np.float64)
        n = z.shape[axis]
        if n < 2:
            return np.zeros_like(zz)
        lo = [slice(None)] * 2
        hi = [slice(None)] * 2
        mid = [slice(None)] * 2
        step = np.diff(coords)
        shape = [1, 1]
        shape[axis] = n - 1
        step = step.reshape(shape)
        # forward difference at k (to k+1) and backward at k (from k-1), where both exist
        lo[axis], hi[axis] = slice(0, -1), slice(1, None)
        fwd = np.zeros_like(zz)
        bwd = np.zeros_like(zz)
        fok = np.zeros(z.shape, bool)
        bok = np.zeros(z.shape, bool)
        d = (zz[tuple(hi)] - zz[tuple(lo)]) / step
        both = ok[tuple(hi)] & ok[tuple(lo)]
        fwd[tuple(lo)], fok[tuple(lo)] = d, both
        bwd[tuple(hi)], bok[tuple(hi)] = d, both
        # central: neighbours on both sides valid (the centre need not be)
        central = np.zeros_like(zz)
        cok = np.zeros(z.shape, bool)
        mid[axis] = slice(1, -1)
        a, b = [slice(None)] * 2, [slice(None)] * 2
        a[axis], b[axis] = slice(0, -2), slice(2, None)
        span = (coords[2:] - coords[:-2]).reshape([n - 2 if k == axis else 1 for k in range(2)])
        central[tuple(mid)] = (zz[tuple(b)] - zz[tuple(a)]) / span
        cok[tuple(mid)] = ok[tuple(a)] & ok[tuple(b)]
        return np.where(cok, central, np.where(fok, fwd, np.where(bok, bwd, 0.0)))

    gy, gx = slope(0, np.asarray(ys, float)), slope(1, np.asarray(xs, float))
    n = np.empty(z.shape + (3,), np.float32)
    n[..., 0], n[..., 1], n[..., 2] = -gx, -gy, 1.0
    n /= np.linalg.norm(n, axis=2, keepdims=True)
    return n


def _polydata(points, conn, normals, elevation):
    """vtkPolyData of triangles from flat numpy arrays (kept alive by the VTK arrays)."""
    pd = vtkPolyData()
    vp = vtkPoints()
    vp.SetData(numpy_to_vtk(np.ascontiguousarray(points, np.float32)))
    pd.SetPoints(vp)
    cells = vtkCellArray()
    offsets = np.arange(0, conn.size + 1, 3, dtype=conn.dtype)
    cells.SetData(numpy_to_vtk(offsets), numpy_to_vtk(np.ascontiguousarray(conn)))
    pd.SetPolys(cells)
    nv = numpy_to_vtk(np.ascontiguousarray(normals, np.float32))
    nv.SetName("Normals")
    pd.GetPointData().SetNormals(nv)
    ev = numpy_to_vtk(np.ascontiguousarray(elevation, np.float32))
    ev.SetName("Elevation")
    pd.GetPointData().SetScalars(ev)
    pd._keep = (offsets, conn)  # the numpy buffers behind the VTK arrays
    return pd


def uniform_stride(heights, triangles):
    """The grid stride whose triangle count is closest to `triangles`."""
    full = 2.0 * (heights.nx - 1) * (heights.ny - 1)
    best = min(range(1, max(heights.nx, heights.ny)),
               key=lambda s: abs(2.0 * (len(grid_axes(heights.nx, s)) - 1)
                                 * (len(grid_axes(heights.ny, s)) - 1) - triangles))
    return best if triangles < full else 1


def greedy_mesh(image, triangles, budget_s):
    """vtkGreedyTerrainDecimation to `triangles`; (mesh, seconds) or (None, reason)."""
    from vtkmodules.vtkCommonCore import vtkCommand
    from vtkmodules.vtkFiltersHybrid import vtkGreedyTerrainDecimation

    g = vtkGreedyTerrainDecimation()
    g.SetInputData(image)
    g.SetErrorMeasureToNumberOfTriangles()
    g.SetNumberOfTriangles(int(triangles))
    g.BoundaryVertexDeletionOn()
    g.ComputeNormalsOn()
    start = time.perf_counter()
    state = {"aborted": False}

    def on_progress(obj, _event):
        if time.perf_counter() - start > budget_s:
            state["aborted"] = True
            obj.SetAbortExecute(1)

    g.AddObserver(vtkCommand.ProgressEvent, on_progress)
    g.Update()
    seconds = time.perf_counter() - start
    if state["aborted"]:
        return None, f"over the greedy time budget ({budget_s:g} s; --greedy-budget)"
    out = vtkPolyData()
    out.ShallowCopy(g.GetOutput())
    _elevation_from_z(out)
    return out, seconds


def quadric_mesh(full_mesh, heights, triangles):
    """vtkQuadricClustering of the full mesh with an x-y bin grid sized for `triangles`.

    One bin layer in z: on a height field that puts one representative vertex per x-y
    column (a surface, not a point cloud), about two triangles per bin.
    """
    from vtkmodules.vtkFiltersCore import vtkPolyDataNormals, vtkQuadricClustering

    xmin, xmax, ymin, ymax = heights.bounds
    wx, wy = abs(xmax - xmin), abs(ymax - ymin)
    bins = max(triangles / 2.0, 4.0)
    nx = max(int(round(np.sqrt(bins * wx / wy))), 2)
    ny = max(int(round(bins / nx)), 2)
    start = time.perf_counter()
    q = vtkQuadricClustering()
    q.SetInputData(full_mesh)
    q.SetNumberOfDivisions(nx, ny, 1)
    q.AutoAdjustNumberOfDivisionsOff()
    q.CopyCellDataOff()
    q.Update()
    n = vtkPolyDataNormals()
    n.SetInputConnection(q.GetOutputPort())
    n.SplittingOff()
    n.ConsistencyOff()
    n.AutoOrientNormalsOff()
    n.Update()
    seconds = time.perf_counter() - start
    out = vtkPolyData()
    out.ShallowCopy(n.GetOutput())
    _elevation_from_z(out)
    return out, seconds


def _elevation_from_z(pd):
    from vtkmodules.util.numpy_support import vtk_to_numpy

    z = vtk_to_numpy(pd.GetPoints().GetData())[:, 2].astype(np.float32)
    ev = numpy_to_vtk(z, deep=1)
    ev.SetName("Elevation")
    pd.GetPointData().SetScalars(ev)
