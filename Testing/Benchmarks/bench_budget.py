"""Frame budgets and front-to-back drawing of vtkGeoMipMapMapper (issue #14), measured.

    xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/python3 bench_budget.py \
        [--dems sthelens,rainier,puget,synthetic4097] [--frames 60] [--fps 10] \
        [--size 960x540] [--measure-every 6] [--budget 150000] [--no-lod-actors] [--trace]
        [--slope-texture] [--no-retain-heap]

Like the tools, it restarts itself first with glibc's heap on huge pages
(geomipmap_apps/hugeheap.py; GEOMIPMAP_HUGE_HEAP=0 to measure without: session 24 measured
both, Documentation/benchmarks.md). The JSON says which ("huge_heap").

Per DEM, one orbit (geomipmap.flight.Orbit, terrain following at 300 m clearance, pitch 15,
--frames frames) flown in five ways in the same process:

1. frame-rate mode: FollowAllocatedRenderTime, the window's DesiredUpdateRate = --fps,
   tau 0 (the budget alone decides: the smallest error the frame time allows; a frame
   that reaches the full resolution early is faster than the target and counted apart). Frame time = win.Render() + WaitForCompletion (glFinish), wall clock.
   Reported: the fraction of frames after a 10-frame warm-up within +-20 % of 1/fps, the
   budget in force and the certified error. Also reported apart: the same fraction over the
   frames the budget decided (frames drawn at full resolution before the budget was spent,
   or whose coarsest selection is over it, cannot be steered). Every --measure-every frames
   the drawn mesh (vtkGeoMipMapFilter, same camera, tau and budget: same triangle count as
   drawn, which is checked) is measured with the independent vtkGeoMipMapScreenError,
   after the flight: measuring between frames slowed the next frame by up to 1.5x.
   Then the same flight again at one fixed budget, the median of the budgets in force:
   how steady frames of a fixed count are on this machine along this flight. Reported:
   the fraction within +-20 % of the flight's median, and of the median of the 5 frames
   before each. The latter is what a controller that tracked the flight's frame times
   perfectly from past frames would hold: no cost model learnt from past frames does
   better, so it tells the machine's share of the misses from the controller's.
2. vtkQuadricLODActor and vtkLODActor over the full-resolution mesh, driven by the same
   DesiredUpdateRate: frame times the same way; the quadric LOD mesh (its LODFilter output,
   what it draws at an interactive rate) measured with vtkGeoMipMapScreenError; vtkLODActor's
   choice told from the image (its LODs are a point cloud and an outline: covered pixels
   far below the full mesh's mean it drew one of those, which is no surface).
3. a fixed triangle budget (--budget): triangles <= budget on every frame; on measured
   frames, the tau-driven frame with the most triangles within the budget (PixelError
   bisected with the filter, 14 steps) against the budgeted one, both certified and
   measured.
4. front to back against block order at tau 1: depth-passing samples (GL_SAMPLES_PASSED)
   summed over the flight, and the median frame time with a deliberately heavy fragment
   shader (300 dependent sin() per fragment, spliced in with a shader replacement).
Prints one JSON object per DEM.
"""
import argparse
import json
import math
import os
import resource
import statistics
import sys
import time

import numpy as np


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--dems", default="sthelens,rainier,puget,synthetic4097")
    p.add_argument("--frames", type=int, default=60)
    p.add_argument("--fps", type=float, default=10.0)
    p.add_argument("--size", default="960x540")
    p.add_argument("--measure-every", type=int, default=6)
    p.add_argument("--budget", type=int, default=150000)
    p.add_argument("--no-lod-actors", action="store_true")
    p.add_argument("--modes", default="rate,lod,fixed,order",
                   help="which of the four parts to run (rate, lod, fixed, order)")
    p.add_argument("--block-order", action="store_true",
                   help="FrontToBack off in modes 1 and 3 (for comparison runs)")
    p.add_argument("--slope-texture", action="store_true",
                   help="SlopeTexture on in modes 1 and 3 (the default before 2026-12-01, session 5)")
    p.add_argument("--no-retain-heap", action="store_true",
                   help="leave the C library's heap policy alone on llvmpipe "
                        "(vtkGeoMipMapMapper.SetGlobalRetainHeapOnSoftwareRenderer(False); "
                        "the mapper before 2026-12-01, session 7)")
    p.add_argument("--trace", action="store_true",
                   help="print each frame of the frame-rate mode (ms, budget, triangles, error)")
    p.add_argument("--data", default=os.environ.get("GEOMIPMAP_DATA_DIR", os.path.join(
        os.path.dirname(__file__), "..", "..", "..", "shared", "data")))
    return p.parse_args()


DEMS = {"sthelens": "SainteHelens.dem", "rainier": "mt_rainier_90m.tif", "puget": "ps_height_1k.png"}
WARMUP = 10
HEAVY = """{
  vec4 heavyC = gl_FragData[0];
  for (int k = 0; k < 300; ++k) { heavyC.rgb = fract(heavyC.rgb * 1.0001 + 0.0001 * sin(heavyC.gbr + float(k))); }
  gl_FragData[0] = vec4(mix(gl_FragData[0].rgb, heavyC.rgb, 0.001), gl_FragData[0].a);
}
//VTK::ZBuffer::Impl"""


def load(name, data):
    from geomipmap_apps.terrain import load_terrain

    if name.startswith("synthetic"):
        n = int(name[len("synthetic"):])
        return load_terrain(None, synthetic_size=n, seed=1)
    spacing = 160.0 if name == "puget" else None
    return load_terrain(os.path.join(data, DEMS[name]), spacing=spacing)


class Scene:
    """One prop in an off-screen window with an interactor (never started) whose
    DesiredUpdateRate is the target: what an interactive application has, and what
    vtkQuadricLODActor needs (it reads the interactor's rate; without one it crashes in
    VTK 9.1)."""

    def __init__(self, image, size, prop, fps):
        from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindowInteractor
        import refscene

        self.ren = vtkRenderer()
        self.ren.SetBackground(0.0, 0.0, 0.0)
        self.ren.AddActor(prop)
        self.win = refscene.window(size[0], size[1], self.ren)
        self.iren = vtkRenderWindowInteractor()
        self.iren.SetRenderWindow(self.win)
        self.iren.SetDesiredUpdateRate(fps)
        self.prop = prop

    def frame(self, flight, k):
        flight.apply(self.ren, k)
        t = time.perf_counter()
        self.win.Render()
        self.win.WaitForCompletion()
        return time.perf_counter() - t

    def close(self):
        self.win.Finalize()


def screen_error(image, ren, mesh, size):
    import geomipmap
    from vtkmodules.vtkCommonMath import vtkMatrix4x4

    clip = vtkMatrix4x4()
    clip.DeepCopy(ren.GetActiveCamera().GetCompositeProjectionTransformMatrix(
        ren.GetTiledAspectRatio(), -1, 1))
    e = geomipmap.vtkGeoMipMapScreenError()
    e.SetHeightfield(image)
    e.SetMesh(mesh)
    e.SetViewportSize(*size)
    e.SetProjectionMatrix(clip)
    if not e.Compute():
        raise RuntimeError("vtkGeoMipMapScreenError failed")
    return e.GetMaximumError(), e.GetNumberOfUncoveredSamples() / max(e.GetNumberOfSamplesInView(), 1)


def lod_mesh(image, ren, size, tau, budget, start=0.0):
    """The filter's mesh for the camera; `start`: the mapper's GetLastBudgetStartTau() of
    the frame to reproduce (its budgeted search started there)."""
    import geomipmap

    f = geomipmap.vtkGeoMipMapFilter()
    f.SetInputData(image)
    f.SetCamera(ren.GetActiveCamera())
    f.SetViewportSize(*size)
    f.SetPixelError(tau)
    f.SetTriangleBudget(budget)
    f.SetBudgetStartTau(start)
    f.Update()
    return f


def med(values):
    v = list(values)
    return statistics.median(v) if v else None


def measured_frames(flight, args):
    """The frames whose error is measured: every --measure-every after the warm-up."""
    return [k for k in range(WARMUP, len(flight)) if k % args.measure_every == 0]


def within(times, target):
    t = np.asarray(times[WARMUP:])
    return float(np.mean(np.abs(t - target) <= 0.2 * target)) if len(t) else float("nan")


def within_where(times, keep, target):
    """within() over the frames after the warm-up for which keep[k] holds."""
    t = [x for k, x in enumerate(times) if k >= WARMUP and keep[k]]
    return float(np.mean(np.abs(np.asarray(t) - target) <= 0.2 * target)) if t else float("nan")


def within_of_previous(times, n):
    """The fraction of frames after the warm-up within +-20 % of the median of the n
    frames before each."""
    t = np.asarray(times)
    hits = [abs(t[k] - np.median(t[k - n:k])) <= 0.2 * np.median(t[k - n:k])
            for k in range(max(WARMUP, n), len(t))]
    return float(np.mean(hits)) if hits else float("nan")


def pct(v, q):
    return float(np.percentile(v, q)) if len(v) else float("nan")


def frame_rate_mode(image, flight, args, size, out):
    import geomipmap

    m = geomipmap.vtkGeoMipMapMapper()
    m.SetInputData(image)
    m.SetPixelError(0.0)
    m.SetFrontToBack(not args.block_order)
    m.SetSlopeTexture(args.slope_texture)
    m.FollowAllocatedRenderTimeOn()
    from vtkmodules.vtkRenderingCore import vtkActor
    a = vtkActor()
    a.SetMapper(m)
    s = Scene(image, size, a, args.fps)
    s.win.SetDesiredUpdateRate(args.fps)
    s.frame(flight, 0)  # tables and uploads: not a frame of the flight
    times, mapper_times, budgets, errs, tris, measured, ratio = [], [], [], [], [], [], []
    starts = []
    steered = []
    exact_early = over = 0
    for k in range(len(flight)):
        faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        times.append(s.frame(flight, k))
        faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults
        over += k >= WARMUP and m.GetOverTriangleBudget()
        if k >= WARMUP and not m.GetTriangleBudgetReached() and times[-1] < 0.8 / args.fps:
            exact_early += 1
        if args.trace:
            print("frame %3d %7.1f ms (mapper %7.1f, LOD %5.1f, upload %5.1f ms %6.2f MB) budget %8d "
                  "drawn %8d err %.3g%s, %d page faults"
                  % (k, 1000 * times[-1], 1000 * m.GetLastRenderTime(), 1000 * m.GetLastUpdateTime(),
                     1000 * m.GetLastIndexUploadTime(), m.GetLastIndexUploadBytes() / 1e6,
                     m.GetTriangleBudgetInForce(), m.GetNumberOfRenderedTriangles(),
                     m.GetMaximumScreenSpaceError(), "" if m.GetTriangleBudgetReached() else " (tau)", faults),
                  file=sys.stderr)
        mapper_times.append(m.GetLastRenderTime())
        budgets.append(m.GetTriangleBudgetInForce())
        starts.append(m.GetLastBudgetStartTau())
        errs.append(m.GetMaximumScreenSpaceError())
        tris.append(m.GetNumberOfRenderedTriangles())
        steered.append(m.GetTriangleBudgetReached() and not m.GetOverTriangleBudget())
    # Measured after the flight, not between its frames: the measure's own work (a filter
    # run and a rasterisation of the mesh) slowed the frame after it by up to 1.5x.
    for k in measured_frames(flight, args):
        flight.apply(s.ren, k)
        f = lod_mesh(image, s.ren, size, 0.0, budgets[k], starts[k])
        assert f.GetOutput().GetNumberOfPolys() == tris[k], "filter mesh is not the drawn one"
        e, _ = screen_error(image, s.ren, f.GetOutput(), size)
        measured.append(e)
        ratio.append(e / errs[k] if errs[k] > 0 else 0.0)
    # The flight again at one fixed budget (the median in force): its frames' steadiness.
    fixed = int(statistics.median(budgets[WARMUP:]))
    m.FollowAllocatedRenderTimeOff()
    m.SetTriangleBudget(fixed)
    fixed_times = [s.frame(flight, k) for k in range(len(flight))]
    target = 1.0 / args.fps
    out["frame_rate_mode"] = {
        "target_ms": 1000 * target,
        "within_20pct": within(times, target),
        "faster_at_full_resolution": exact_early / max(len(times) - WARMUP, 1),
        "frames_budget_decided": sum(steered[WARMUP:]),
        "within_20pct_budget_decided": within_where(times, steered, target),
        "frames_coarsest_over_budget": over,
        "mapper_within_20pct": within(mapper_times, target),
        "frame_ms_median": 1000 * statistics.median(times[WARMUP:]),
        "frame_ms_p90": 1000 * pct(times[WARMUP:], 90),
        "budget_median": statistics.median(budgets[WARMUP:]),
        "triangles_median": statistics.median(tris[WARMUP:]),
        "certified_px_median": statistics.median(errs[WARMUP:]),
        "certified_px_p90": pct(errs[WARMUP:], 90),  # inf: a frame over budget (see design.md)
        "certified_px_max": max(errs[WARMUP:]),
        "measured_px_max": max(measured) if measured else None,
        "measured_over_certified_max": max(ratio) if ratio else None,
        "frames_measured": len(measured),
        "steadiness_budget": fixed,
        "steadiness_frame_ms_median": 1000 * statistics.median(fixed_times[WARMUP:]),
        "steadiness_within_20pct_of_median": within(fixed_times, statistics.median(fixed_times[WARMUP:])),
        "steadiness_within_20pct_of_previous_5": within_of_previous(fixed_times, 5),
    }
    s.close()


def lod_actor_modes(image, flight, args, size, out):
    import refscene
    from vtkmodules.vtkRenderingCore import vtkPolyDataMapper
    from vtkmodules.vtkRenderingLOD import vtkLODActor, vtkQuadricLODActor

    mesh = refscene.reference_mesh(image, normals=False)
    target = 1.0 / args.fps
    for name, cls in (("vtkQuadricLODActor", vtkQuadricLODActor), ("vtkLODActor", vtkLODActor)):
        pm = vtkPolyDataMapper()
        pm.SetInputData(mesh)
        pm.ScalarVisibilityOff()
        a = cls()
        a.SetMapper(pm)
        if name == "vtkQuadricLODActor":
            a.SetDataConfigurationToXYPlane()
        s = Scene(image, size, a, args.fps)
        s.win.SetDesiredUpdateRate(0.0001)
        s.frame(flight, 0)  # a still full-resolution frame first: uploads, and the
        still = refscene.covered(refscene.grab(s.win), (0, 0, 0)).mean()  # full mesh's coverage
        s.win.SetDesiredUpdateRate(args.fps)
        times, measured, uncovered, surface = [], [], [], 0
        checked = measured_frames(flight, args)
        for k in range(len(flight)):
            times.append(s.frame(flight, k))
            if name == "vtkLODActor" and k in checked:
                # What it drew is told from this frame's image (a read-back).
                cov = refscene.covered(refscene.grab(s.win), (0, 0, 0)).mean()
                surface += cov > 0.5 * still
        if name == "vtkQuadricLODActor":
            for k in checked:  # after the flight, as for ours
                flight.apply(s.ren, k)
                e, u = screen_error(image, s.ren, a.GetLODFilter().GetOutput(), size)
                measured.append(e)
                uncovered.append(u)
        r = {"within_20pct": within(times, target),
             "frame_ms_median": 1000 * statistics.median(times[WARMUP:]),
             "frame_ms_p90": 1000 * pct(times[WARMUP:], 90)}
        if measured:
            r.update({"measured_px_median": statistics.median(measured),
                      "measured_px_max": max(measured),
                      "uncovered_fraction_max": max(uncovered),
                      "lod_triangles": a.GetLODFilter().GetOutput().GetNumberOfPolys()})
        if name == "vtkLODActor":
            r["frames_drawing_a_surface"] = f"{surface} of {len(checked)} checked"
        out[name] = r
        s.close()
    del mesh


def fixed_budget_mode(image, flight, args, size, out):
    import geomipmap
    from vtkmodules.vtkRenderingCore import vtkActor

    m = geomipmap.vtkGeoMipMapMapper()
    m.SetInputData(image)
    m.SetPixelError(0.0)
    m.SetFrontToBack(not args.block_order)
    m.SetSlopeTexture(args.slope_texture)
    m.SetTriangleBudget(args.budget)
    a = vtkActor()
    a.SetMapper(m)
    s = Scene(image, size, a, args.fps)
    over, coarsest_over, worst, rows, times, drawn, certified = 0, 0, 0.0, [], [], [], []
    starts = []
    for k in range(len(flight)):
        times.append(s.frame(flight, k))
        n = m.GetNumberOfRenderedTriangles()
        over += n > args.budget and not m.GetOverTriangleBudget()
        coarsest_over += m.GetOverTriangleBudget()
        if not m.GetOverTriangleBudget():
            worst = max(worst, n / args.budget)
        drawn.append(None if m.GetOverTriangleBudget() else n)
        starts.append(m.GetLastBudgetStartTau())
        certified.append(m.GetMaximumScreenSpaceError())
    # Measured after the flight (see frame_rate_mode), so that the frame times above are
    # those of a flight.
    for k in range(0, len(flight), args.measure_every):
        if drawn[k] is None:
            continue
        flight.apply(s.ren, k)
        n, eb = drawn[k], certified[k]
        fb = lod_mesh(image, s.ren, size, 0.0, args.budget, starts[k])
        assert fb.GetOutput().GetNumberOfPolys() == n, "filter mesh is not the drawn one"
        mb, _ = screen_error(image, s.ren, fb.GetOutput(), size)
        lo, hi = 1e-3, 1e4  # the finest tau-driven frame within the budget
        for _ in range(14):
            mid = math.sqrt(lo * hi)
            if lod_mesh(image, s.ren, size, mid, 0).GetOutput().GetNumberOfPolys() <= args.budget:
                hi = mid
            else:
                lo = mid
        ft = lod_mesh(image, s.ren, size, hi, 0)
        if ft.GetOutput().GetNumberOfPolys() > args.budget:
            continue  # no tau-driven frame fits (the coarsest selection is over the budget)
        mt, _ = screen_error(image, s.ren, ft.GetOutput(), size)
        # The tau-driven frame's certified error, from the mapper itself at that tau.
        m.SetTriangleBudget(0)
        m.SetPixelError(hi)
        s.win.Render()
        et = m.GetMaximumScreenSpaceError()
        assert m.GetNumberOfRenderedTriangles() == ft.GetOutput().GetNumberOfPolys()
        m.SetTriangleBudget(args.budget)
        m.SetPixelError(0.0)
        rows.append((eb, mb, et, mt, ft.GetOutput().GetNumberOfPolys(), n))
    out["fixed_budget"] = {
        "budget": args.budget,
        "frames_over_budget": over,
        "frames_coarsest_over_budget": coarsest_over,
        # How steady a frame of a fixed triangle count is along the flight (the floor of
        # any triangle-budget controller): frames within +-20 % of their own median.
        "frame_ms_median": 1000 * statistics.median(times[WARMUP:]),
        "within_20pct_of_own_median": within(times, statistics.median(times[WARMUP:])),
        "max_triangles_over_budget": worst,  # frames whose coarsest selection fits
        "measured_frames": len(rows),
        "budgeted_certified_px_median": med(r[0] for r in rows),
        "tau_driven_certified_px_median": med(r[2] for r in rows),
        "budgeted_measured_px_median": med(r[1] for r in rows),
        "tau_driven_measured_px_median": med(r[3] for r in rows),
        "frames_budgeted_certified_worse": sum(r[0] > r[2] * (1 + 1e-9) for r in rows),
        "mean_triangles_budgeted_vs_tau": statistics.mean(r[5] / r[4] for r in rows) if rows else None,
    }
    s.close()


def front_to_back(image, flight, args, size, out):
    import geomipmap
    from vtkmodules.vtkRenderingCore import vtkActor

    m = geomipmap.vtkGeoMipMapMapper()
    m.SetInputData(image)
    m.SetPixelError(1.0)
    a = vtkActor()
    a.SetMapper(m)
    s = Scene(image, size, a, args.fps)
    s.frame(flight, 0)
    m.SetCountFragments(True)
    passed = {True: 0, False: 0}
    for k in range(len(flight)):
        flight.apply(s.ren, k)
        for order in (False, True):
            m.SetFrontToBack(order)
            s.win.Render()
            passed[order] += m.GetLastFragmentsPassed()
    m.SetCountFragments(False)
    a.GetShaderProperty().AddFragmentShaderReplacement("//VTK::ZBuffer::Impl", True, HEAVY, False)
    times = {True: [], False: []}
    for k in range(0, len(flight), 2):
        for order in (False, True):
            m.SetFrontToBack(order)
            flight.apply(s.ren, k)
            s.win.Render()  # the same frame twice: the second is timed (no index upload)
            times[order].append(s.frame(flight, k))
    out["front_to_back"] = {
        "samples_passed_block_order": passed[False],
        "samples_passed_front_to_back": passed[True],
        "samples_ratio": passed[True] / max(passed[False], 1),
        "heavy_shader_ms_block_order": 1000 * statistics.median(times[False]),
        "heavy_shader_ms_front_to_back": 1000 * statistics.median(times[True]),
        "heavy_shader_time_ratio": statistics.median(times[True]) / statistics.median(times[False]),
    }
    s.close()


def main():
    from geomipmap_apps.hugeheap import TUNABLE, restart_with_huge_heap
    restart_with_huge_heap()  # before anything allocates (does not return when it restarts)
    args = parse()
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "Python"))
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    import vtkmodules.vtkInteractionStyle  # noqa: F401
    from geomipmap.flight import Orbit

    size = tuple(int(v) for v in args.size.split("x"))
    if args.no_retain_heap:
        import geomipmap
        geomipmap.vtkGeoMipMapMapper.SetGlobalRetainHeapOnSoftwareRenderer(False)
    results = []
    for name in args.dems.split(","):
        t0 = time.perf_counter()
        image, heights = load(name, args.data)
        flight = Orbit(heights, clearance=300.0, frames=args.frames, pitch=15.0, view_angle=45.0)
        out = {"dem": name, "samples": image.GetNumberOfPoints(), "frames": args.frames,
               "size": list(size), "fps": args.fps, "load_average": os.getloadavg()[0],
               "huge_heap": TUNABLE in os.environ.get("GLIBC_TUNABLES", "")}
        modes = args.modes.split(",")
        if "rate" in modes:
            frame_rate_mode(image, flight, args, size, out)
        if "lod" in modes and not args.no_lod_actors:
            lod_actor_modes(image, flight, args, size, out)
        if "fixed" in modes:
            fixed_budget_mode(image, flight, args, size, out)
        if "order" in modes:
            front_to_back(image, flight, args, size, out)
        out["seconds"] = time.perf_counter() - t0
        print(json.dumps(out), flush=True)
        results.append(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
