"""Frame time of vtkGeoMipMapMapper with Geomorphing and FrontToBack on and off, in one run.

    xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/python3 measure_mapper_options.py [N]

One fractal DEM (vtkGeoMipMapFractalSource, N x N, 30 m, seed 1; default 4097), one
window (1280 x 720, 50 degrees), tau = 1, an orbit of 14 frames (the first 2 not counted).
Each frame renders the four configurations in turn (one actor visible at a time), so load
from other processes hits them alike. Prints the median frame time (Render +
WaitForCompletion), the median LOD time (GetLastUpdateTime) and the mean triangle count.
"""
import math
import os
import statistics
import sys
import time

from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import geomipmap

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))  # refscene
import refscene  # noqa: E402

CONFIGS = [  # name, Geomorphing, FrontToBack
    ("morph + front-to-back", True, True),
    ("front-to-back only", False, True),
    ("morph only", True, False),
    ("neither", False, False),
]


def main(argv):
    n = int(argv[1]) if len(argv) > 1 else 4097
    image = refscene.fractal_image(n, n, 1)
    ren = vtkRenderer()
    win = vtkRenderWindow()
    win.SetSize(1280, 720)
    win.AddRenderer(ren)
    win.SetOffScreenRendering(1)
    actors = []
    for name, morph, sorted_draw in CONFIGS:
        mapper = geomipmap.vtkGeoMipMapMapper()
        mapper.SetInputData(image)
        mapper.SetPixelError(1.0)
        mapper.SetGeomorphing(morph)
        mapper.SetFrontToBack(sorted_draw)
        actor = vtkActor()
        actor.SetMapper(mapper)
        ren.AddActor(actor)
        actors.append((name, actor, mapper))
    b = image.GetBounds()
    cx, cy, radius = (b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[1] - b[0]) * 0.45
    cam = ren.GetActiveCamera()
    cam.SetViewAngle(50)
    frame_ms = {c[0]: [] for c in CONFIGS}
    lod_ms = {c[0]: [] for c in CONFIGS}
    tris = {c[0]: [] for c in CONFIGS}
    for k in range(14):
        angle = 2 * math.pi * k / 14
        cam.SetPosition(cx + radius * math.cos(angle), cy + radius * math.sin(angle), 2500)
        cam.SetFocalPoint(cx, cy, 500)
        cam.SetViewUp(0, 0, 1)
        ren.ResetCameraClippingRange()
        for name, actor, mapper in actors:
            for _, other, _ in actors:
                other.SetVisibility(other is actor)
            t = time.perf_counter()
            win.Render()
            win.WaitForCompletion()
            dt = time.perf_counter() - t
            if k >= 2:  # warm-up: uploads and table builds
                frame_ms[name].append(dt * 1e3)
                lod_ms[name].append(mapper.GetLastUpdateTime() * 1e3)
                tris[name].append(mapper.GetNumberOfRenderedTriangles())
    for name, _, _ in CONFIGS:
        print(f"{name:22s} frame median {statistics.median(frame_ms[name]):7.1f} ms  "
              f"LOD median {statistics.median(lod_ms[name]):6.2f} ms  "
              f"triangles {statistics.mean(tris[name]):.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
