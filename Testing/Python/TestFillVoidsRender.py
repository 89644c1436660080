"""What void filling changes on screen (issue #15, part 5), on the Rainier SRTM3 tile.

- Blocks coarsen: a block that touches a void keeps full resolution (its coarser levels
  would cover nodata), so at the same tau the filled DEM draws fewer triangles. A low
  orbit (geomipmap.flight, 600 m above the ground) and an overview, at tau = 1 px, are
  rendered over the tile read with and without FillNodata; the filled one must draw
  fewer triangles in total (the counts are printed for the record).
- The certified bound still holds on the filled DEM: on every frame, what the mapper drew
  measures within tau against the filled full-resolution heights
  (gmmtestutil.check_drawn_within_tau, independent of the engine), and leaves no more
  in-view samples uncovered than the full-resolution mesh does (filling leaves the nodata
  outside the tile's footprint, and a valid border sample between two of its samples can
  have no full-resolution triangle: one on the south-west corner of the tile, depending on
  the diagonals of the quads beside it).
- The filled samples can be coloured: the mapper colours by the "FilledNodata" array
  through a lookup table (0 grey, 1 red) in a top-down parallel view; every red pixel
  lies over a filled sample (within one sample), and the red area is about the filled
  samples' share of the view.
Needs the Rainier tile (skips without it) and an X display (xvfb-run ctest).
"""
import sys

import numpy as np
import geomipmap
import geomipmap.flight
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer

import refscene
from gmmdata import data_file
from gmmtestutil import check, check_drawn_within_tau

W, H = 640, 400
TAU = 1.0


def load(path, fill):
    r = geomipmap.vtkGeoMipMapTerrainReader()
    r.SetFileName(path)
    r.SetFillNodata(1 if fill else 0)
    r.Update()
    img = r.GetOutput().NewInstance()
    img.DeepCopy(r.GetOutput())
    return img


def scene(img):
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(img)
    mapper.SetPixelError(TAU)
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    ren = vtkRenderer()
    ren.AddActor(actor)
    win = refscene.window(W, H, ren)
    return mapper, actor, ren, win


def triangles_and_bound(path):
    plain, filled = load(path, False), load(path, True)
    orbit = geomipmap.flight.Orbit(plain, frames=6, clearance=600.0)
    views = ["orbit frame %d" % i for i in range(len(orbit))] + ["overview"]
    counts = {}
    for name, img in (("voids", plain), ("filled", filled)):
        mapper, actor, ren, win = scene(img)
        counts[name] = []
        for k, what in enumerate(views):
            if what == "overview":
                ren.ResetCamera()
                ren.GetActiveCamera().Elevation(-60)
                ren.GetActiveCamera().Zoom(1.4)
            else:
                orbit.apply(ren, k)
            ren.ResetCameraClippingRange()
            win.Render()
            counts[name].append(mapper.GetNumberOfRenderedTriangles())
            if name == "filled":
                check_drawn_within_tau(img, ren, actor, mapper, f"filled Rainier, {what}",
                                       uncovered_ok="as full resolution")
        win.Finalize()
    for k, what in enumerate(views):
        print(f"{what}: {counts['voids'][k]} triangles with voids, {counts['filled'][k]} filled "
              f"({100.0 * counts['filled'][k] / counts['voids'][k]:.1f} %)")
    total_v, total_f = sum(counts["voids"]), sum(counts["filled"])
    check(total_f < total_v, f"at tau {TAU:g} the filled tile draws fewer triangles: {total_f} "
          f"against {total_v} ({100.0 * total_f / total_v:.1f} %)")
    return filled


def coloured_by_mask(img):
    mapper, actor, ren, win = scene(img)
    actor.GetProperty().LightingOff()
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(2)
    lut.SetTableValue(0, 0.5, 0.5, 0.5, 1.0)
    lut.SetTableValue(1, 1.0, 0.0, 0.0, 1.0)
    lut.SetTableRange(0.0, 1.0)
    lut.Build()
    mapper.ScalarVisibilityOn()
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("FilledNodata")
    mapper.SetColorModeToMapScalars()
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(0.0, 1.0)
    ren.SetBackground(0.0, 0.0, 1.0)
    nx, ny, _ = img.GetDimensions()
    ox, oy, _ = img.GetOrigin()
    dx, dy, _ = img.GetSpacing()
    # A window onto the tile's middle, about 1.6 pixels per sample.
    cx, cy = ox + 0.5 * (nx - 1) * dx, oy + 0.5 * (ny - 1) * dy
    scale = 0.5 * H / 1.6 * dy
    cam = ren.GetActiveCamera()
    cam.SetParallelProjection(True)
    cam.SetFocalPoint(cx, cy, 2000.0)
    cam.SetPosition(cx, cy, 1.0e5)
    cam.SetViewUp(0, 1, 0)
    cam.SetParallelScale(scale)
    ren.ResetCameraClippingRange()
    win.Render()
    px = refscene.grab(win).astype(int)
    red = (px[:, :, 0] > 200) & (px[:, :, 1] < 60) & (px[:, :, 2] < 60)
    terrain = ~((px[:, :, 0] < 10) & (px[:, :, 1] < 10) & (px[:, :, 2] > 245))
    mask = vtk_to_numpy(img.GetPointData().GetArray("FilledNodata")).reshape(ny, nx)
    # Pixel centres to sample indices (row 0 of the grab is the bottom).
    per_px = 2.0 * scale / H
    rows, cols = np.nonzero(red)
    x = cx + (cols + 0.5 - 0.5 * W) * per_px
    y = cy + (rows + 0.5 - 0.5 * H) * per_px
    fi, fj = (x - ox) / dx, (y - oy) / dy
    near = np.zeros(len(rows), bool)
    for dj in (-1, 0, 1, 2):
        for di in (-1, 0, 1, 2):
            i = np.clip(np.floor(fi).astype(int) + di, 0, nx - 1)
            j = np.clip(np.floor(fj).astype(int) + dj, 0, ny - 1)
            near |= (mask[j, i] == 1) & (np.abs(i - fi) <= 1.0) & (np.abs(j - fj) <= 1.0)
    # The filled samples' share of the samples in view.
    i0, i1 = int((cx - 0.5 * W * per_px - ox) / dx), int((cx + 0.5 * W * per_px - ox) / dx)
    j0, j1 = int((cy - 0.5 * H * per_px - oy) / dy), int((cy + 0.5 * H * per_px - oy) / dy)
    share = mask[max(j0, 0):j1 + 1, max(i0, 0):i1 + 1].mean()
    win.Finalize()
    check(red.sum() > 100, f"coloured by FilledNodata: {red.sum()} red pixels")
    check(near.all(), f"every red pixel lies within one sample of a filled sample "
          f"({(~near).sum()} do not)")
    ratio = red.sum() / max(terrain.sum(), 1) / share
    check(0.5 < ratio < 1.5, f"red pixels {100.0 * red.sum() / terrain.sum():.3f} % of the "
          f"terrain, filled samples {100.0 * share:.3f} % of those in view (ratio {ratio:.2f})")


def main():
    path = data_file("mt_rainier_90m.tif")
    filled = triangles_and_bound(path)
    coloured_by_mask(filled)
    print("TestFillVoidsRender: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
