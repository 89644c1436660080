"""A DEM larger than GL_MAX_TEXTURE_SIZE drawn by vtkGeoMipMapMapper, seams checked against
a stock full-resolution render: one process, one figure set (too big for CTest; the CTest
twin at 16385 x 33 is geomipmapPython.TestHeightTextures).

    xvfb-run -a /usr/bin/python3 check_large_dem.py 20000 9000
    xvfb-run -a /usr/bin/python3 check_large_dem.py 16385 16385

Why these views: the mapper cuts the heights into evenly sized texture layers when the DEM
is wider or taller than GL_MAX_TEXTURE_SIZE (queried here as the mapper does), and a seam
between layers is where a wrong texel address would show. For every seam (the middle of
each layer boundary, and each corner where four layers meet) the script looks straight
down (parallel projection, 64 samples across) at tau = 0.5, coloured by height through a
lookup table over the crop's height range (lighting from above alone hardly varies), and
compares the picture with a stock vtkPolyDataMapper drawing every full-resolution triangle
of a 160-sample crop around the same point (refscene.reference_mesh: no engine code).
Pixels more than 8 levels apart must stay under 1 % (reading one sample off gives 23 %).
It also draws the whole DEM obliquely and reports how much of the window the terrain
covers. Prints one JSON object; exit status 1 when a seam fails.
"""
import json
import resource
import sys
import time

import numpy as np


def main(argv):
    nx, ny = int(argv[1]), int(argv[2])
    from vtkmodules.vtkCommonCore import vtkLookupTable
    from vtkmodules.vtkRenderingCore import vtkActor, vtkCamera, vtkRenderer
    from vtkmodules.vtkRenderingOpenGL2 import vtkTextureObject
    import geomipmap
    import refscene

    spacing, bg, size = 30.0, (0.1, 0.1, 0.2), (480, 480)
    out = {"nx": nx, "ny": ny}
    t = time.perf_counter()
    image = refscene.fractal_image(nx, ny, 7, spacing)
    z = refscene.heights(image)
    out["generate_s"] = round(time.perf_counter() - t, 1)

    ren = vtkRenderer()
    ren.SetBackground(*bg)
    win = refscene.window(*size, ren)
    win.Render()
    max_size = vtkTextureObject.GetMaximumTextureSize(win)
    out["GL_MAX_TEXTURE_SIZE"] = max_size
    # The mapper's layout rule (vtkGeoMipMapTileLayout::Plan): evenly sized tiles.
    tiles_x, tiles_y = -(-nx // max_size), -(-ny // max_size)
    tile_w, tile_h = -(-nx // tiles_x), -(-ny // tiles_y)
    out["layers"] = [tiles_x, tiles_y, tile_w, tile_h]

    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(image)
    mapper.SetPixelError(0.5)
    mapper.ScalarVisibilityOff()
    ours = vtkActor()
    ours.SetMapper(mapper)

    def look(actor, i=None, j=None):
        ren.RemoveAllViewProps()
        ren.AddActor(actor)
        cam = vtkCamera()
        ren.SetActiveCamera(cam)
        ren.ResetCamera()
        if i is None:
            cam.Elevation(-50.0)
        else:
            x, y = i * spacing, j * spacing
            cam.SetFocalPoint(x, y, 0.0)
            cam.SetPosition(x, y, 1.0e5)
            cam.SetViewUp(0, 1, 0)
            cam.SetParallelProjection(True)
            cam.SetParallelScale(32 * spacing)
        ren.ResetCameraClippingRange()
        win.Render()
        return refscene.grab(win)

    t = time.perf_counter()
    whole = look(ours)
    out["first_frame_s"] = round(time.perf_counter() - t, 1)
    out["whole_view_triangles"] = mapper.GetNumberOfRenderedTriangles()
    out["whole_view_terrain_fraction"] = round(float(refscene.covered(whole, bg).mean()), 3)
    out["gpu_bytes"] = mapper.GetGPUMemoryBytes()

    points = [(tx * tile_w, min(ny - 1, tile_h // 2 + ty * tile_h))
              for tx in range(1, tiles_x) for ty in range(tiles_y)]
    points += [(min(nx - 1, tile_w // 2 + tx * tile_w), ty * tile_h)
               for tx in range(tiles_x) for ty in range(1, tiles_y)]
    points += [(tx * tile_w, ty * tile_h) for tx in range(1, tiles_x) for ty in range(1, tiles_y)]
    seams = []
    for i, j in points:
        i0, j0 = max(0, i - 80), max(0, j - 80)
        crop = z[j0:min(ny, j + 81), i0:min(nx, i + 81)]
        img = refscene.image_from_heights(crop, (spacing, spacing), (i0 * spacing, j0 * spacing, 0.0))
        lut = vtkLookupTable()
        lut.SetTableRange(float(np.nanmin(crop)), float(np.nanmax(crop)))
        lut.SetNumberOfTableValues(256)
        lut.Build()
        ref = refscene.reference_actor(img)
        for m in (mapper, ref.GetMapper()):
            m.SetLookupTable(lut)
            m.UseLookupTableScalarRangeOn()
            m.ScalarVisibilityOn()
            m.InterpolateScalarsBeforeMappingOn()
        mine = look(ours, i, j)
        stock = look(ref, i, j)
        levels = np.abs(mine.astype(int) - stock.astype(int)).max(axis=2)
        seams.append({"sample": [i, j],
                      "pixels_differing_pct": round(100 * float((levels > 8).mean()), 3),
                      "max_level_difference": int(levels.max()),
                      "terrain_fraction": round(float(refscene.covered(stock, bg).mean()), 3)})
    mapper.ScalarVisibilityOff()
    out["seams"] = seams
    out["peak_rss_mb"] = round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)
    print(json.dumps(out))
    worst = max((s["pixels_differing_pct"] for s in seams), default=0.0)
    return 0 if seams and worst < 1.0 and out["whole_view_triangles"] > 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
