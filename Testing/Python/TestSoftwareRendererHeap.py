"""On a software OpenGL (Mesa's llvmpipe), frames stop costing page faults once the
triangle count has stopped growing (vtkGeoMipMapSoftwareRenderer.h).

llvmpipe allocates and frees its vertex work buffers in every draw. With glibc's initial
heap policy the heap's top went back to the system after each frame and was faulted in
again in the next, page by page: in a frame-rate flight over Puget Sound, about 4000 faults
and half of each 100 ms frame, for 40 frames. The mapper sets the heap policy at its first
render on such a renderer.

The flight here is the one that showed it: a triangle budget that grows over the first
frames, as the frame-rate mode's does, then holds while the camera moves. Checked with the
process's minor page faults (getrusage), which the mapper does not report, in two fresh
processes: with vtkGeoMipMapMapper.SetGlobalRetainHeapOnSoftwareRenderer(False) the held
frames must fault (else this C library does not show the problem, and the test says so
and skips), and with the default they must touch (almost) no new page. Skipped, with a
message, on a hardware renderer and where the C library is not glibc.
"""

import ctypes
import json
import math
import platform
import resource
import statistics
import subprocess
import sys

from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer

import geomipmap
import refscene

W, H = 800, 450
check = refscene.Checks()

if platform.libc_ver()[0] != "glibc":
    print("SKIP: the heap policy is glibc's (libc here: %r)" % (platform.libc_ver(),))
    sys.exit(0)
if "--child" not in sys.argv:
    # Is malloc glibc's? Under a sanitizer's allocator (preloaded by Scripts/sanitize.sh)
    # mallopt is a stub that answers 0, and the mapper leaves the heap as it is. Asked in
    # this parent only, with glibc's own initial value (M_TRIM_THRESHOLD, 128 KiB): the
    # children, which measure, inherit nothing from it.
    if ctypes.CDLL(None).mallopt(-1, 128 * 1024) != 1:
        print("SKIP: malloc here is not glibc's (mallopt refused: a sanitizer's allocator?)")
        sys.exit(0)


def child(retain):
    """This test in a fresh process (the heap policy is process-wide and cannot be undone):
    the held frames' faults, or None when the renderer is not a software one."""
    out = subprocess.run([sys.executable, __file__, "--child", "on" if retain else "off"],
                         capture_output=True, text=True, timeout=600)
    sys.stdout.write(out.stdout)
    if out.returncode != 0:
        sys.stdout.write(out.stderr)
        raise RuntimeError("the child process failed (%d)" % out.returncode)
    return json.loads(out.stdout.strip().splitlines()[-1])


if "--child" not in sys.argv:
    off = child(False)
    if off is None:
        print("SKIP: not a software renderer")
        sys.exit(0)
    on = child(True)
    if statistics.median(off) <= 1024:
        print("SKIP: with the C library's own heap policy the held frames took %d faults each;"
              " nothing to fix here" % statistics.median(off))
        sys.exit(0)
    check(statistics.median(on) <= 256, "with the heap retained, held frames touch %d new pages "
          "each (%d with the C library's policy)" % (statistics.median(on), statistics.median(off)))
    check.exit()

geomipmap.vtkGeoMipMapMapper.SetGlobalRetainHeapOnSoftwareRenderer(sys.argv[-1] == "on")
image = refscene.fractal_image(1025, 1025, seed=5)
mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputData(image)
mapper.SetPixelError(0.0)
# From the first frame on, as in the frame-rate mode: a first frame of millions of triangles
# would free blocks large enough for glibc to raise its thresholds by itself.
mapper.SetTriangleBudget(65536)
actor = vtkActor()
actor.SetMapper(mapper)
ren = vtkRenderer()
ren.AddActor(actor)
win = refscene.window(W, H, ren)
win.Render()
renderer = win.ReportCapabilities()
if "llvmpipe" not in renderer and "softpipe" not in renderer:
    print("null")
    sys.exit(0)

x0, x1, y0, y1, z0, z1 = mapper.GetBounds()
cx, cy, r = 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (x1 - x0)
cam = ren.GetActiveCamera()
cam.SetViewUp(0.0, 0.0, 1.0)
cam.SetViewAngle(45.0)


def frame(k, budget):
    """One frame of an orbit at 0.6 r around the centre, looking across it; returns the
    minor page faults the frame took."""
    a = 2.0 * math.pi * k / 48.0
    cam.SetPosition(cx + 0.6 * r * math.cos(a), cy + 0.6 * r * math.sin(a), z1 + 0.05 * r)
    cam.SetFocalPoint(cx - 0.4 * r * math.cos(a), cy - 0.4 * r * math.sin(a), z0)
    ren.ResetCameraClippingRange(x0, x1, y0, y1, z0, z1)
    mapper.SetTriangleBudget(budget)
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    win.Render()
    win.WaitForCompletion()
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0


# Growth by a quarter per frame from 64 k triangles (the frame-rate mode's pace near its
# target), then the budget holds.
budget, k = 65536, 0
while budget < 140000:
    frame(k, budget)
    budget, k = int(budget * 1.25), k + 1
held = [frame(k + i, budget) for i in range(16)]
drawn = mapper.GetNumberOfRenderedTriangles()
if drawn < 0.8 * budget:
    raise RuntimeError("the budget holds %d triangles, not %d" % (budget, drawn))
# A page is 4 KiB: 256 faults a frame are 1 MiB of memory touched anew.
print("heap retained %s: minor faults per held frame (%d triangles) %s"
      % (sys.argv[-1], drawn, held))
print(json.dumps(held))
