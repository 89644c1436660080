"""One DEM: load it, fly the path, time every method frame by frame.

Why interleaved: the machine is shared, so background load comes in bursts. Every frame
renders every method in turn (brute force first: its depth buffer is that frame's
reference), so a burst slows all methods of that frame alike instead of one method's
whole series; ratios against brute force stay meaningful.
Memory: a method whose estimated footprint exceeds the budget is skipped, with the reason.
"""

import os
import resource
import time

import numpy as np

from .. import command
from ..errors import AppError, VTKMessages
from ..scene import Scene
from ..terrain import load_terrain
from . import meshes
from .measure import Bench

# Read settings the files in ../shared/data need (its README.md): PNG heightmaps carry no
# spacing or height unit, and terrain-RGB is not auto-detected by the reader.
KNOWN_FILES = {
    "ps_height_1k.png": dict(height_scale=0.1, spacing=160.0),
    # z10 Web Mercator tile at 2x: 0.3516 deg of longitude at 35.32 N over 511 intervals.
    "fuji_terrain_rgb.png": dict(terrain_rgb=True, spacing=62.5),
}


# The mapper's configurations measured: (NormalMode by --normals name, Geomorphing) per method.
OURS_SETTINGS = {"ours": ("auto", True), "ours-fn": ("fragment", True), "ours-vn": ("vertex", True),
                 "ours-vn-nomorph": ("vertex", False)}
# The fill floor: ours with geomorphing and its cheapest shading (normals per vertex) at this
# pixel error, so large that every block takes its coarsest level and far nodes merge as far
# as the tree allows.
FLOOR_TAU = 1e6


class Config:
    """One timed series: a method (and tau), its actor and how to get its frame's mesh."""

    def __init__(self, method, tau, actor, mesh, build_s=0.0, before=None, extra=None):
        self.method, self.tau, self.actor, self.mesh = method, tau, actor, mesh
        self.build_s, self.before, self.extra = build_s, before, extra


def _rss_gb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20


def _gb(method, samples):
    return meshes.BYTES_PER_SAMPLE[method] * samples / 2**30


def run_dem(label, path, n, args, methods, budget_gb, out):
    from geomipmap import flight

    def skip(m, why):
        out.skip(label, m, why)
        print(f"[{label}] {m}: skipped: {why}", flush=True)

    if n and _gb("ours", n * n) > budget_gb:
        # Every other method is sized from ours' triangle counts: without ours, none runs.
        for m in methods:
            why = (f"needs about {_gb(m, n * n):.0f} GB (> {budget_gb:.1f} GB budget)"
                   if _gb(m, n * n) > budget_gb else
                   f"sized from ours' triangle counts, and ours needs about "
                   f"{_gb('ours', n * n):.0f} GB (> {budget_gb:.1f} GB budget)")
            skip(m, why)
        return
    messages = VTKMessages()
    settings = KNOWN_FILES.get(os.path.basename(path), {}) if path else {}
    t0 = time.perf_counter()
    try:
        image, heights = load_terrain(dem=path, synthetic_size=n or 0, messages=messages,
                                      fill=args.fill, **settings)
    except AppError as e:
        skip("all", f"cannot load: {e}")
        return
    samples = heights.nx * heights.ny
    out.note(label, f"{heights.nx} x {heights.ny} samples, block size {args.block_size}, loaded in "
             f"{time.perf_counter() - t0:.1f} s")
    over = {m: _gb(m, samples) > budget_gb for m in methods}
    if "ours" not in methods or over["ours"]:
        for m in methods:
            skip(m, "ours does not run (memory budget or --methods): no triangle counts")
        return
    scene = Scene(image, heights, block_size=args.block_size, tau=args.tau[0], size=args.size,
                  title="geomipmap-bench", messages=messages)
    route = (flight.Line if args.path == "line" else flight.Orbit)(
        heights, frames=args.frames, pitch=15.0, view_angle=50.0)
    bench = Bench(scene, image, heights, route, args.size)
    if args.geomorph_range is not None:
        scene.mapper.SetGeomorphRange(args.geomorph_range)
        for f in bench.filters.values():
            f.SetGeomorphRange(args.geomorph_range)
    if args.geomorph_measure_samples is not None:
        scene.mapper.SetGeomorphMeasureSamples(args.geomorph_measure_samples)
        for f in bench.filters.values():
            f.SetGeomorphMeasureSamples(args.geomorph_measure_samples)
    out.note(label, f"GeomorphRange {scene.mapper.GetGeomorphRange():g}, "
             f"GeomorphMeasureSamples {scene.mapper.GetGeomorphMeasureSamples()}")
    configs = _build(label, args, methods, over, budget_gb, bench, heights, image, skip, out)
    _fly(label, args, configs, bench, heights, out)
    out.note(label, f"peak RSS {_rss_gb():.1f} GB")
    scene.window.Finalize()


def _targets(args, bench):
    """Ours' mean triangle count per tau over the flight (vtkGeoMipMapFilter: the same
    engine call as the mapper), the count the other methods are built for."""
    counts = {tau: [] for tau in args.tau}
    for f in range(args.frames):
        bench.camera(f)
        for tau in args.tau:
            counts[tau].append(bench.ours_mesh(tau).GetNumberOfPolys())
    return {tau: int(round(np.mean(c))) for tau, c in counts.items()}


def _build(label, args, methods, over, budget_gb, bench, heights, image, skip, out):
    configs = []
    full = None
    if ("brute" in methods and not over["brute"]) or ("quadric" in methods and not over["quadric"]):
        t = time.perf_counter()
        full = meshes.grid_mesh(heights, 1)
        out.note(label, f"full-resolution mesh: {full.GetNumberOfPolys()} triangles, "
                 f"built in {time.perf_counter() - t:.1f} s")
    if "brute" in methods:
        if over["brute"]:
            skip("brute", f"needs about {_gb('brute', heights.nx * heights.ny):.1f} GB "
                 f"(> {budget_gb:.1f} GB budget); no depth reference")
        else:
            configs.append(Config("brute", None, bench.add_mesh(full), lambda f: full))
    m = bench.scene.mapper

    def lod_columns(m):
        def extra(row):
            row["lod_ms"] = m.GetLastUpdateTime() * 1000.0
            row["upload_ms"] = m.GetLastIndexUploadTime() * 1000.0
            row["render_ms"] = row["total_ms"] - row["lod_ms"] - row["upload_ms"]
            row["certified_px"] = m.GetMaximumScreenSpaceError()
        return extra

    ours_extra = lod_columns(m)

    def ours_before(tau, normals, geomorphing):
        def before():
            m.SetPixelError(tau)
            command.set_normal_mode(m, normals)
            m.SetGeomorphing(geomorphing)
        return before

    # ours-fn / ours-vn: the same mapper, selection and triangles, shaded per fragment / per
    # vertex whatever the error (ours' automatic normals pick one by it); ours-vn-nomorph:
    # also without geomorphing (its own selection: no level path, the levels tau allows).
    for method in (x for x in OURS_SETTINGS if x in methods):
        normals, geomorphing = OURS_SETTINGS[method]
        for tau in args.tau:
            configs.append(Config(method, tau, bench.scene.actor,
                                  lambda f, tau=tau, g=geomorphing: bench.ours_mesh(tau, g),
                                  before=ours_before(tau, normals, geomorphing),
                                  extra=ours_extra))
    if "floor" in methods:
        if over["floor"]:
            skip("floor", f"needs about {_gb('floor', heights.nx * heights.ny):.1f} GB "
                 f"(> {budget_gb:.1f} GB budget)")
        else:
            actor, mapper, mesh = bench.add_floor(FLOOR_TAU)
            configs.append(Config("floor", FLOOR_TAU, actor, mesh, extra=lod_columns(mapper)))
    targets = _targets(args, bench)
    nodata = not np.isfinite(heights.z).all()
    for mth in ("greedy", "uniform", "quadric"):
        if mth not in methods:
            continue
        if over[mth] or (mth == "quadric" and full is None):
            skip(mth, f"needs about {_gb(mth, heights.nx * heights.ny):.1f} GB (> "
                 f"{budget_gb:.1f} GB budget)")
            continue
        if mth == "greedy" and nodata:
            skip(mth, "the DEM has nodata samples; vtkGreedyTerrainDecimation has no nodata "
                 "support")
            continue
        for tau, tri in targets.items():
            t = time.perf_counter()
            if mth == "greedy":
                mesh, build = meshes.greedy_mesh(image, tri, args.greedy_budget)
                if mesh is None:
                    skip(mth, f"tau {tau:g}: {build}")
                    continue
            elif mth == "uniform":
                mesh = meshes.grid_mesh(heights, meshes.uniform_stride(heights, tri))
                build = time.perf_counter() - t
            else:
                mesh, build = meshes.quadric_mesh(full, heights, tri)
            out.note(label, f"{mth} tau {tau:g}: {mesh.GetNumberOfPolys()} triangles "
                     f"(ours' mean {tri}), built in {build:.1f} s")
            configs.append(Config(mth, tau, bench.add_mesh(mesh), lambda f, mesh=mesh: mesh,
                                  build_s=build))
    return configs


def _fly(label, args, configs, bench, heights, out):
    ctx = dict(dem=label, nx=heights.nx, ny=heights.ny)
    for c in configs:  # warm-up: each method's vertex buffers are uploaded once, untimed
        if c.before:
            c.before()
        bench.show(c.actor)
        bench.camera(0)
        bench.render()
    for f in range(args.frames):
        reference = None
        for c in configs:
            if c.before:
                c.before()
            row, shot = bench.frame(c.actor, c.mesh, f, reference, c.extra)
            if c.method == "brute":
                reference = shot
            out.frame(ctx, c.method, c.tau, c.build_s, row)
        out.flush()
        print(f"[{label}] frame {f + 1}/{args.frames}", flush=True)
