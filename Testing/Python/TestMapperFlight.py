"""vtkGeoMipMapMapper along a 50-frame flight over synthetic terrain (vtkGeoMipMapFractalSource).

Checks the mapper's frame statistics behave sensibly: triangles > 0 every frame, the
screen error of what was drawn, measured independently (gmmtestutil.measure_drawn:
vtkGeoMipMapFilter's copy of the drawn triangles against the full-resolution heightfield
through vtkGeoMipMapScreenError), <= tau on every 5th frame, indices reused (and no index
upload) while the camera is static, heights uploaded once for the whole flight, and fewer
visible
blocks when looking down at a small region than over the whole terrain.
Run under an X display (xvfb-run). Exit 0 = pass, 1 = fail.
"""
import math
import sys

from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL factory overrides)
from geomipmap.geomipmapFilters import vtkGeoMipMapFractalSource
from geomipmap.geomipmapRendering import vtkGeoMipMapMapper
from gmmtestutil import check_drawn_within_tau

TAU = 2.0
failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)
        print("FAIL:", msg)


src = vtkGeoMipMapFractalSource()
src.SetDimensions(513, 513)
src.SetSpacing(20.0)
src.SetSeed(3)
src.SetAmplitude(1500.0)
mapper = vtkGeoMipMapMapper()
mapper.SetInputConnection(src.GetOutputPort())
mapper.SetPixelError(TAU)
mapper.SetBlockSize(32)
actor = vtkActor()
actor.SetMapper(mapper)
ren = vtkRenderer()
ren.AddActor(actor)
win = vtkRenderWindow()
win.SetOffScreenRendering(1)
win.SetSize(400, 300)
win.AddRenderer(ren)
cam = ren.GetActiveCamera()
cam.SetViewUp(0, 0, 1)
extent = 512 * 20.0
centre = extent / 2

# 50 frames: a circle around the centre at 2 km above the terrain's top, looking inwards.
tris = []
for f in range(50):
    a = 2 * math.pi * f / 50
    cam.SetPosition(centre + 4000 * math.cos(a), centre + 4000 * math.sin(a), 3500)
    cam.SetFocalPoint(centre, centre, 500)
    ren.ResetCameraClippingRange()
    win.Render()
    n = mapper.GetNumberOfRenderedTriangles()
    tris.append(n)
    check(n > 0, f"frame {f}: no triangles")
    if f % 5 == 0:
        try:
            check_drawn_within_tau(src.GetOutput(), ren, actor, mapper, f"frame {f}")
        except AssertionError as e:
            check(False, str(e))
print(f"flight: triangles min {min(tris)} max {max(tris)}, "
      f"last LOD update {mapper.GetLastUpdateTime() * 1e3:.2f} ms")
check(len(set(tris)) > 1, "triangle count never changed along the flight")
check(mapper.GetNumberOfHeightUploads() == 1,
      f"heights uploaded {mapper.GetNumberOfHeightUploads()} times, expected once")

# Static camera: indices reused, nothing uploaded.
uploads = mapper.GetNumberOfIndexUploads()
for _ in range(3):
    win.Render()
    check(mapper.GetIndicesReused(), "static camera: indices not reused")
check(mapper.GetNumberOfIndexUploads() == uploads, "static camera re-uploaded the indices")

# Whole terrain from high above vs a small region from close above: fewer visible blocks.
cam.SetPosition(centre, centre - 1, 60000)
cam.SetFocalPoint(centre, centre, 0)
ren.ResetCameraClippingRange()
win.Render()
whole = mapper.GetNumberOfVisibleBlocks()
cam.SetPosition(1000, 999, 2600)
cam.SetFocalPoint(1000, 1000, 0)
cam.SetViewAngle(20)
ren.ResetCameraClippingRange()
win.Render()
small = mapper.GetNumberOfVisibleBlocks()
print(f"visible blocks: whole terrain {whole}, small region {small}, "
      f"culled {mapper.GetNumberOfCulledBlocks()}")
check(small < whole, f"small region shows {small} blocks, whole terrain {whole}")
check(mapper.GetNumberOfCulledBlocks() > 0, "nothing culled when looking at a small region")

sys.exit(1 if failures else 0)
