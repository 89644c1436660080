"""Vertex reuse on a software renderer (issue #11): the mapper draws sample (i, j) as
vertex j * pitch + i with gmm::drawPitch's pitch, so that Mesa's draw module, which finds a
draw's repeated vertices through a cache keyed by the vertex id modulo 256, shades each
vertex about once. With ids j * nx + i a 2^k + 1 DEM (nx % 256 == 1) shades about 1.6
vertices a triangle (every quad's two off-diagonal corners share a cache entry). The count
is the driver's own (GL_VERTEX_SHADER_INVOCATIONS), and the frames are checked to be the
filter's triangles at the filter's heights (depth buffers) on two grid widths, 513
(residue 1) and 600 x 437 (residue 88).
Skips (77) where the driver has no pipeline statistics query.
"""
import sys

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkCamera, vtkRenderer

import geomipmap
import refscene
from gmmtestutil import lod_mesh

W, H = 480, 320
TAU, BLOCK = 1.0, 32
check = refscene.Checks()


def frame(nx, ny):
    image = refscene.fractal_image(nx, ny, seed=3)
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(image)
    mapper.SetPixelError(TAU)
    mapper.SetBlockSize(BLOCK)
    mapper.ScalarVisibilityOff()
    mapper.SetCountFragments(True)
    actor = vtkActor()
    actor.SetMapper(mapper)
    ren = vtkRenderer()
    ren.SetBackground(0.0, 0.0, 0.0)
    ren.AddActor(actor)
    win = refscene.window(W, H, ren)
    x0, x1, y0, y1, z0, z1 = mapper.GetBounds()
    cam = vtkCamera()
    cam.SetPosition(x0 - 300.0, y0 - 200.0, z1 + 400.0)
    cam.SetFocalPoint(0.5 * (x0 + x1), 0.5 * (y0 + y1), z0)
    cam.SetViewUp(0.0, 0.0, 1.0)
    cam.SetViewAngle(45.0)
    ren.SetActiveCamera(cam)
    ren.ResetCameraClippingRange(x0, x1, y0, y1, z0, z1)
    win.Render()
    runs, triangles = mapper.GetLastVertexInvocations(), mapper.GetNumberOfRenderedTriangles()
    if runs < 0:
        print("SKIP: the driver has no GL_VERTEX_SHADER_INVOCATIONS query")
        sys.exit(77)
    gpu = refscene.depth(win)
    # The same frame from the filter (a fresh filter reproduces a mapper's first frame,
    # geomorphing included), drawn by VTK's own mapper from its points.
    mesh = lod_mesh(image, cam, (W, H), TAU, BLOCK)
    ren.RemoveAllViewProps()
    ren.AddActor(refscene.stock_actor(mesh))
    win.Render()
    cpu = refscene.depth(win)
    terrain = cpu < 1.0
    differ = np.count_nonzero(np.abs(gpu - cpu)[terrain] > 5e-7)
    n = np.count_nonzero(terrain)
    what = f"{nx} x {ny} (nx % 256 = {nx % 256})"
    print(f"{what}: {triangles} triangles, {runs} vertex shader runs ({runs / max(triangles, 1):.3f} a "
          f"triangle); {differ} of {n} terrain pixels differ in depth from the filter's mesh")
    check(triangles == mesh.GetNumberOfPolys() and triangles > 5000,
          f"{what}: the mapper draws the filter's {mesh.GetNumberOfPolys()} triangles")
    check(n > 0.3 * W * H and differ <= 0.002 * n, f"{what}: the frame is the filter's mesh")
    check(runs < 1.0 * triangles, f"{what}: fewer vertex shader runs than triangles")


frame(513, 513)
frame(600, 437)
check.exit()
