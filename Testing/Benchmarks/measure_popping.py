"""Popping along a slow flight, geomorphing on against off, in one run.

    /usr/bin/python3 measure_popping.py [--dem FILE.png --spacing M --zscale S] [--n 1025]
        [--dem FILE [--fill-voids]] [--tau 2] [--frames 120] [--step 0.02] [--block 64]
        [--size 1280x720] [--range R] [--no-merges] [--quick]

The terrain: a 16-bit PNG DEM (e.g. ../shared/data/ps_height_1k.png, --spacing 160
--zscale 0.1), any other DEM through vtkGeoMipMapTerrainReader (e.g.
../shared/data/mt_rainier_90m.tif: its voids stay nodata, or are filled with --fill-voids),
or, by default, vtkGeoMipMapFractalSource (n x n, 30 m, seed 1). The camera
flies a straight line across the middle of the terrain, --step blocks (block size x
spacing) per frame, at 250 m above the highest summit, looking ahead and 20 degrees down.
--no-merges turns off SetGeomorphMerges (on by default: merges wait for the geomorphing
path) in both modes.

Popping of frame k: vtkGeoMipMapScreenError with frame k's mesh (vtkGeoMipMapFilter's
output for frame k's camera: morphed heights when geomorphing) against frame k-1's mesh as
the reference, both projected with frame k's camera, at every full-resolution sample in
view: the screen displacement of the drawn surface that the camera motion does not
explain. Reported per mode: max and 99th percentile over the flight, the frames with any
popping (> 1e-3 px), the largest screen error of a frame against the true surface (the
certificate: <= tau), the mean triangles per frame (geomorphing also chooses the levels:
a block moves through them no faster than vtkGeoMipMapFilter::GeomorphRange allows, so it
draws more), the filter's median time per frame (CPU, LOD + morph + output) and,
through vtkGeoMipMapMapper on the same flight (needs a display: xvfb-run), the median
frame time (Render + glFinish), off and on alternating frame by frame. Prints one JSON
object.
"""

import json
import math
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))  # refscene
import refscene  # noqa: E402


def arg(argv, name, default, kind=float):
    return kind(argv[argv.index(name) + 1]) if name in argv else default


def load_terrain(argv):
    dem = argv[argv.index("--dem") + 1] if "--dem" in argv else None
    if dem and not dem.lower().endswith(".png"):
        # Any DEM the reader takes (GeoTIFF, SRTM .hgt, ...), its voids as NaN, or filled
        # with --fill-voids (the reader's FillNodata).
        import geomipmap
        r = geomipmap.vtkGeoMipMapTerrainReader()
        r.SetFileName(dem)
        r.SetFillNodata("--fill-voids" in argv)
        r.Update()
        return r.GetOutput()
    if dem:
        from vtkmodules.vtkIOImage import vtkPNGReader
        from vtkmodules.vtkImagingCore import vtkImageCast, vtkImageShiftScale
        r = vtkPNGReader()
        r.SetFileName(argv[argv.index("--dem") + 1])
        r.Update()
        s = vtkImageShiftScale()
        s.SetInputConnection(r.GetOutputPort())
        s.SetScale(arg(argv, "--zscale", 1.0))
        s.SetOutputScalarTypeToFloat()
        s.Update()
        img = s.GetOutput()
        sp = arg(argv, "--spacing", 30.0)
        img.SetSpacing(sp, sp, 1.0)
        return img
    n = arg(argv, "--n", 1025, int)
    return refscene.fractal_image(n, n, 1)


def main(argv):
    import geomipmap
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from vtkmodules.vtkRenderingCore import vtkCamera

    quick = "--quick" in argv
    image = load_terrain(argv if not quick else argv + ["--n", "257"])
    tau = arg(argv, "--tau", 2.0)
    frames = arg(argv, "--frames", 24 if quick else 120, int)
    step_blocks = arg(argv, "--step", 0.02)
    block = arg(argv, "--block", 32 if quick else 64, int)
    w, h = (int(v) for v in arg(argv, "--size", "640x360" if quick else "1280x720", str).split("x"))
    nx, ny, _ = image.GetDimensions()
    sx, sy, _ = image.GetSpacing()
    ox, oy, _ = image.GetOrigin()
    zmin, zmax = image.GetPointData().GetScalars().GetRange()
    step = step_blocks * block * sx
    y = oy + 0.5 * (ny - 1) * sy
    x0 = ox + 0.1 * (nx - 1) * sx
    alt = zmax + 250.0
    pitch = math.radians(20.0)

    def camera(f):
        cam = vtkCamera()
        x = x0 + f * step
        cam.SetPosition(x, y, alt)
        cam.SetFocalPoint(x + 1000.0 * math.cos(pitch), y, alt - 1000.0 * math.sin(pitch))
        cam.SetViewUp(0, 0, 1)
        cam.SetViewAngle(50.0)
        cam.SetClippingRange(1.0, 4.0 * max(nx * sx, ny * sy))
        return cam

    out = {"samples": nx * ny, "tau": tau, "frames": frames, "step_blocks": step_blocks,
           "step_m": step, "block": block, "viewport": [w, h]}
    for mode in ("off", "on"):
        filt = geomipmap.vtkGeoMipMapFilter()
        filt.SetInputData(image)
        filt.SetBlockSize(block)
        filt.SetPixelError(tau)
        filt.SetViewportSize(w, h)
        filt.SetGeomorphing(mode == "on")
        if "--range" in argv:
            filt.SetGeomorphRange(arg(argv, "--range", 3.0))
        filt.SetGeomorphMerges("--no-merges" not in argv)
        prev = None
        pops, p99s, errors, times, tris = [], [], [], [], []
        for f in range(frames):
            cam = camera(f)
            filt.SetCamera(cam)
            t = time.process_time()
            filt.Update()
            times.append((time.process_time() - t) * 1000.0)
            mesh = vtkPolyData()
            mesh.DeepCopy(filt.GetOutput())
            tris.append(mesh.GetNumberOfPolys())
            matrix = cam.GetCompositeProjectionTransformMatrix(w / h, -1, 1)
            e = geomipmap.vtkGeoMipMapScreenError()
            e.SetHeightfield(image)
            e.SetViewportSize(w, h)
            e.SetProjectionMatrix(matrix)
            e.SetMesh(mesh)
            e.Compute()
            errors.append(e.GetMaximumError())
            if prev is not None:
                e.SetReferenceMesh(prev)
                e.Compute()
                pops.append(e.GetMaximumError())
                p99s.append(e.GetPercentile99Error())
            prev = mesh
        out[mode] = {
            "pop_max_px": max(pops),
            "pop_p99_max_px": max(p99s),
            "pop_mean_of_frame_max_px": statistics.mean(pops),
            "frames_popping": sum(1 for p in pops if p > 1e-3),
            "frames_over_half_px": sum(1 for p in pops if p > 0.5),
            "triangles_mean": statistics.mean(tris),
            "screen_error_max_px": max(errors),
            "filter_ms_median": statistics.median(times),
        }
    # Frame time through the mapper (run under xvfb-run): the same flight, morphing off and
    # on, alternating frame by frame so that both see the same machine load; Render +
    # glFinish, median. --no-render skips it.
    if "--no-render" not in argv:
        from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
        import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
        ms = {"off": [], "on": []}
        rigs = {}
        for mode in ("off", "on"):
            mapper = geomipmap.vtkGeoMipMapMapper()
            mapper.SetInputData(image)
            mapper.SetBlockSize(block)
            mapper.SetPixelError(tau)
            mapper.SetGeomorphing(mode == "on")
            if "--range" in argv:
                mapper.SetGeomorphRange(arg(argv, "--range", 3.0))
            mapper.SetGeomorphMerges("--no-merges" not in argv)
            actor = vtkActor()
            actor.SetMapper(mapper)
            ren = vtkRenderer()
            ren.AddActor(actor)
            win = vtkRenderWindow()
            win.SetOffScreenRendering(1)
            win.SetSize(w, h)
            win.AddRenderer(ren)
            rigs[mode] = (ren, win)
        for f in range(frames):
            for mode in ("off", "on"):
                ren, win = rigs[mode]
                ren.SetActiveCamera(camera(f))
                t = time.perf_counter()
                win.Render()
                win.WaitForCompletion()
                if f > 0:  # the first frame builds the textures
                    ms[mode].append((time.perf_counter() - t) * 1000.0)
        for mode in ("off", "on"):
            out[mode]["mapper_frame_ms_median"] = statistics.median(ms[mode])
        out["mapper_frame_time_ratio_on_over_off"] = (out["on"]["mapper_frame_ms_median"] /
                                                      out["off"]["mapper_frame_ms_median"])
    out["pop_ratio_off_over_on"] = out["off"]["pop_max_px"] / max(out["on"]["pop_max_px"], 1e-12)
    out["triangle_ratio_on_over_off"] = out["on"]["triangles_mean"] / out["off"]["triangles_mean"]
    out["filter_time_ratio_on_over_off"] = out["on"]["filter_ms_median"] / out["off"]["filter_ms_median"]
    print(json.dumps(out, indent=1))
    return out


if __name__ == "__main__":
    main(sys.argv[1:])
