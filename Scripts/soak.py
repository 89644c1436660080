#!/usr/bin/env python3
"""Soak test (not part of CI): a long random flight through vtkGeoMipMapMapper, checking that
memory does not grow.

Renders --frames frames (default 10 000) of a random flight over a vtkGeoMipMapFractalSource
terrain (default 1025 x 1025) in a small off-screen window, changing the camera every frame
(smooth random walk, a jump to a random place and height every 100 frames, and the pixel
error changed every 50 frames, so blocks are re-tessellated and index buffers re-uploaded
all the time, and the first 1000 frames already visit the extremes: low and close, fine tau).
Every --every frames (default 1000) it samples the process's resident memory (VmRSS, and
VmHWM) and prints it with the mapper's counters, then the growth from the first sample
(frame 1000) to the last. It exits 1 when RSS grows by more than --max-growth-mib (default
4 MiB) over the second half of the flight (frames 5000 -> 10000: a leak of 1 KiB per frame
adds 5 MiB there), or by more than --max-total-growth-mib (default 64 MiB) from the first
sample to the last. Why two bounds: until every extreme view has been met (close to the
ground at the finest pixel error), a frame with more triangles than any before raises the
high-water marks of glibc's heap and of the GL driver once; that warm-up growth comes in steps
in the first few thousand frames, while a leak grows steadily to the end.

VTK object counts are not sampled: Debian's VTK is built without VTK_DEBUG_LEAKS, so there is
no live-object counter to read; RSS covers our allocations and the GL driver's alike.

Usage (needs an X display; from the repository root, after Scripts/setup.sh):
  xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/python3 Scripts/soak.py [--build build]
"""
import argparse
import ctypes
import math
import os
import random
import sys
import time


def rss_kib():
    """VmRSS and VmHWM (peak) of this process in KiB, from /proc/self/status, after
    malloc_trim(0): glibc keeps freed heap pages mapped, so without the trim RSS follows the
    largest frame so far (a high-water mark) instead of what is live now."""
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass
    vals = {}
    with open("/proc/self/status") as f:
        for line in f:
            key, _, rest = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                vals[key] = int(rest.split()[0])
    return vals["VmRSS"], vals["VmHWM"]


def main():
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(here, "build"), help="build folder")
    ap.add_argument("--frames", type=int, default=10000)
    ap.add_argument("--every", type=int, default=1000, help="sample memory every N frames")
    ap.add_argument("--size", type=int, default=1025, help="terrain samples per side")
    ap.add_argument("--window", default="320x240")
    ap.add_argument("--max-growth-mib", type=float, default=4.0,
                    help="bound on RSS growth over the second half of the flight")
    ap.add_argument("--max-total-growth-mib", type=float, default=64.0,
                    help="bound on RSS growth from the first sample to the last")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    if args.frames < 2 * args.every:
        ap.error("--frames must be at least twice --every (growth is measured between samples)")
    sys.path.insert(0, os.path.join(args.build, "lib", "python3.11", "dist-packages"))
    try:
        from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
        import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL factory overrides)
        from geomipmap.geomipmapFilters import vtkGeoMipMapFractalSource
        from geomipmap.geomipmapRendering import vtkGeoMipMapMapper
    except ImportError as e:
        print(f"soak: cannot import the geomipmap package from {args.build}: {e}", file=sys.stderr)
        return 2
    width, height = (int(v) for v in args.window.split("x"))
    spacing = 10.0
    extent = (args.size - 1) * spacing

    src = vtkGeoMipMapFractalSource()
    src.SetDimensions(args.size, args.size)
    src.SetSpacing(spacing)
    src.SetSeed(args.seed)
    src.SetAmplitude(1500.0)
    mapper = vtkGeoMipMapMapper()
    mapper.SetInputConnection(src.GetOutputPort())
    mapper.SetPixelError(2.0)
    actor = vtkActor()
    actor.SetMapper(mapper)
    ren = vtkRenderer()
    ren.AddActor(actor)
    win = vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetSize(width, height)
    win.AddRenderer(ren)
    cam = ren.GetActiveCamera()
    cam.SetViewUp(0, 0, 1)

    rng = random.Random(args.seed)
    x, y, z = extent / 2, extent / 2, 2500.0
    heading, pitch = 0.0, -0.4
    samples = []  # (frame, rss KiB, peak KiB)
    triangles = 0
    last_time, last_frame = time.perf_counter(), 0
    print(f"soak: {args.frames} frames, terrain {args.size}^2, window {width}x{height}")
    for frame in range(1, args.frames + 1):
        if frame % 100 == 0:  # jump somewhere else
            x, y = rng.uniform(0, extent), rng.uniform(0, extent)
            z = rng.uniform(300.0, 8000.0)
            heading = rng.uniform(0, 2 * math.pi)
        if frame % 50 == 0:
            mapper.SetPixelError(rng.choice((0.5, 1.0, 2.0, 4.0, 8.0)))
        heading += rng.gauss(0.0, 0.05)
        pitch = min(-0.05, max(-1.4, pitch + rng.gauss(0.0, 0.03)))
        step = rng.uniform(5.0, 60.0)
        x += step * math.cos(heading)
        y += step * math.sin(heading)
        if not (0.0 <= x <= extent and 0.0 <= y <= extent):  # turn back towards the centre
            heading = math.atan2(extent / 2 - y, extent / 2 - x) + rng.gauss(0.0, 0.3)
        z = min(12000.0, max(200.0, z + rng.gauss(0.0, 20.0)))
        d = (math.cos(heading) * math.cos(pitch), math.sin(heading) * math.cos(pitch),
             math.sin(pitch))
        cam.SetPosition(x, y, z)
        cam.SetFocalPoint(x + 1000 * d[0], y + 1000 * d[1], z + 1000 * d[2])
        ren.ResetCameraClippingRange()
        win.Render()
        triangles += mapper.GetNumberOfRenderedTriangles()
        if frame % args.every == 0:
            rss, hwm = rss_kib()
            samples.append((frame, rss, hwm))
            now = time.perf_counter()
            rate = (frame - last_frame) / (now - last_time)
            last_time, last_frame = now, frame
            print(f"frame {frame:6d}: RSS {rss / 1024:8.1f} MiB  peak {hwm / 1024:8.1f} MiB  "
                  f"index uploads {mapper.GetNumberOfIndexUploads():6d}  "
                  f"height uploads {mapper.GetNumberOfHeightUploads()}  "
                  f"{rate:6.1f} frames/s", flush=True)
    if triangles == 0:
        print("soak: FAIL: nothing was rendered", file=sys.stderr)
        return 1
    first, last = samples[0], samples[-1]
    growth = (last[1] - first[1]) / 1024
    per_frame = (last[1] - first[1]) * 1024 / (last[0] - first[0])
    print(f"soak: RSS growth frame {first[0]} -> {last[0]}: {growth:+.2f} MiB "
          f"({per_frame:+.1f} bytes/frame); "
          f"mean {triangles / args.frames:.0f} triangles/frame")
    # A leak grows steadily; warm-up growth (a view with more triangles than any before
    # raises glibc's and the driver's high-water marks) comes in steps early on. So the
    # growth over the second half of the flight must stay below --max-growth-mib, and the
    # whole 1000 -> end growth below --max-total-growth-mib.
    mid = samples[(len(samples) - 1) // 2]
    half = (last[1] - mid[1]) / 1024
    print(f"soak: RSS growth frame {mid[0]} -> {last[0]}: {half:+.2f} MiB; "
          f"bounds: second half {args.max_growth_mib} MiB, whole {args.max_total_growth_mib} MiB")
    if half > args.max_growth_mib or growth > args.max_total_growth_mib:
        print("soak: FAIL: memory grew beyond the bound", file=sys.stderr)
        return 1
    print("soak: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
