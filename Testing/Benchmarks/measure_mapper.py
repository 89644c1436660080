"""Memory and time of vtkGeoMipMapMapper on one synthetic DEM: one process, one figure set.

Why a process per DEM: peak RSS (ru_maxrss) is a process-lifetime figure, and on Mesa's
llvmpipe the "GPU" textures and buffers live in the same RSS, so one run per DEM size and
height type gives an honest bytes-per-sample figure, input image included.

    xvfb-run -a /usr/bin/python3 measure_mapper.py 8193 [float32|int16] [--frames 24]
        [--no-color] [--no-lighting] [--no-share] [--slope-texture | --no-slope-texture]
        [--block-size N]

--no-share: heights always in a texture (ShareHeights off), as on a GPU with its own memory.
--slope-texture: slopes from a slope texture (SlopeTexture on).
--no-slope-texture: slopes computed per fragment from the heights (SlopeTexture off, the
default since 2026-12-01; for the mapper before it).

Steps, each timed: generate the DEM (vtkGeoMipMapFractalSource; int16 = the same heights
rounded, converted in row bands so no second float copy is held), first frame (the
terrain's tables (read from the table cache on a second run, see tables_from_cache; set
GEOMIPMAP_CACHE_DIR=off to build them every time), the height upload and the first LOD and
draw), then an orbit of
--frames frames at tau = 1, 1280 x 720 (median frame time, Render + glFinish). Prints one
JSON object; frame_cpu_ms is the process's CPU time per frame (all threads, llvmpipe's
included), which other processes' load does not inflate as it does wall time. Works with the earlier, vertex-buffer mapper too (absent statistics are
null), so the two can be compared on the same flights.
"""
import json
import math
import os
import resource
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))  # refscene
import refscene  # noqa: E402


def rss_mb():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main(argv):
    n = int(argv[1])
    dtype = argv[2] if len(argv) > 2 and not argv[2].startswith("--") else "float32"
    frames = int(argv[argv.index("--frames") + 1]) if "--frames" in argv else 24
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    import geomipmap

    out = {"n": n, "dtype": dtype, "samples": n * n}
    base_mb = rss_mb()
    t = time.perf_counter()
    image = refscene.fractal_image(n, n, 1)
    if dtype == "int16":
        z = vtk_to_numpy(image.GetPointData().GetScalars())
        zi = np.empty(z.shape, np.int16)
        band = 1 << 22
        for k in range(0, z.size, band):
            zi[k:k + band] = np.round(z[k:k + band])
        img = vtkImageData()
        img.SetDimensions(n, n, 1)
        img.SetSpacing(30.0, 30.0, 1.0)
        a = numpy_to_vtk(zi, deep=False)
        a.SetName("Elevation")
        img.GetPointData().SetScalars(a)
        img._keep = zi
        del z
        image = img  # the float image's last reference goes
    out["generate_s"] = time.perf_counter() - t
    out["rss_after_input_mb"] = rss_mb()

    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(image)
    mapper.SetPixelError(1.0)
    if "--block-size" in argv:
        mapper.SetBlockSize(int(argv[argv.index("--block-size") + 1]))
    mapper.SetScalarRange(0.0, 1500.0)
    if "--no-color" in argv:
        mapper.ScalarVisibilityOff()
    if "--no-share" in argv and hasattr(mapper, "SetShareHeights"):
        mapper.SetShareHeights(False)
    if "--slope-texture" in argv:
        mapper.SetSlopeTexture(True)
    if "--no-slope-texture" in argv and hasattr(mapper, "SetSlopeTexture"):
        mapper.SetSlopeTexture(False)
    actor = vtkActor()
    actor.SetMapper(mapper)
    if "--no-lighting" in argv:
        actor.GetProperty().LightingOff()
    ren = vtkRenderer()
    ren.AddActor(actor)
    win = vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetSize(1280, 720)
    win.AddRenderer(ren)
    extent = (n - 1) * 30.0
    c = 0.5 * extent
    cam = ren.GetActiveCamera()
    cam.SetViewAngle(50.0)
    cam.SetViewUp(0, 0, 1)

    def place(f):
        a = 2 * math.pi * f / max(frames, 1)
        r, alt = 0.35 * extent, 1500.0 + 0.04 * extent
        x, y = c + r * math.cos(a), c + r * math.sin(a)
        ahead = a + 0.5 * math.pi + math.radians(20)  # counter-clockwise, a little inwards
        d = min(0.1 * extent, 2000.0) + 100.0
        cam.SetPosition(x, y, alt)
        cam.SetFocalPoint(x + d * math.cos(ahead), y + d * math.sin(ahead),
                          alt - d * math.tan(math.radians(15)))
        ren.ResetCameraClippingRange()

    t = time.perf_counter()
    place(0)  # the clipping range asks for bounds: the terrain (tables) is built here
    win.Render()
    win.WaitForCompletion()
    out["first_frame_s"] = time.perf_counter() - t
    for key, name in (("terrain_build_s", "GetLastTerrainBuildTime"),
                      ("height_upload_s", "GetLastHeightUploadTime"),
                      ("gpu_bytes", "GetGPUMemoryBytes"),
                      ("tables_from_cache", "GetLastTablesFromCache"),
                      ("heights_shared", "GetHeightsShared")):
        out[key] = getattr(mapper, name)() if hasattr(mapper, name) else None
    out["rss_after_first_frame_mb"] = rss_mb()
    times, cpu, tris, faults = [], [], [], []

    def cpu_s():
        r = resource.getrusage(resource.RUSAGE_SELF)
        return r.ru_utime + r.ru_stime

    def minor_faults():
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt

    for f in range(frames):
        place(f)
        t, c0, f0 = time.perf_counter(), cpu_s(), minor_faults()
        win.Render()
        win.WaitForCompletion()
        times.append((time.perf_counter() - t) * 1000.0)
        cpu.append((cpu_s() - c0) * 1000.0)  # all threads: robust to other processes' load
        faults.append(minor_faults() - f0)
        tris.append(mapper.GetNumberOfRenderedTriangles())
    out["frame_ms_median"] = statistics.median(times)
    out["frame_ms_mean"] = statistics.mean(times)
    out["frame_cpu_ms_median"] = statistics.median(cpu)
    # Pages first touched per frame: on llvmpipe, memory the C heap gave back to the system
    # and took again (see Documentation/design.md, "Software rendering and the C heap").
    out["frame_minor_faults_median"] = statistics.median(faults)
    out["lod_ms_last"] = mapper.GetLastUpdateTime() * 1000.0
    out["triangles_mean"] = statistics.mean(tris)
    out["peak_rss_mb"] = peak_mb()
    out["process_base_mb"] = base_mb
    out["bytes_per_sample_peak"] = out["peak_rss_mb"] * 1048576.0 / (n * n)
    print(json.dumps(out))
    win.Finalize()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
