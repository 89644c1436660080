"""geomipmap-bench command line: for each DEM, fly one path and time every method.

Methods (same window, camera path, colouring and lighting, one at a time):
  brute    the full-resolution mesh in a stock vtkPolyDataMapper (uploaded once)
  ours     vtkGeoMipMapMapper at each tau, as configured by default (its automatic normals:
           per vertex at a certified error of at most 1 px, per fragment above)
  ours-fn  the same mapper and triangles with normals per fragment at every tau
  ours-vn  the same with normals per vertex at every tau (as the stock mapper shades the
           other methods' meshes)
  ours-vn-nomorph  ours-vn with Geomorphing off: levels switch at once (pops of up to tau)
           and each block takes the coarsest level within tau, not geomorphing's level
           path; what smooth level changes cost
  floor    the fill floor: ours-vn at a pixel error so large (1e6) that every block takes
           its coarsest level and far nodes merge whole; the same pixels with the fewest
           triangles and the cheapest shading ours has, so no configuration of ours is
           faster and brute force / floor is the most ours can gain over brute force here
  greedy   vtkGreedyTerrainDecimation at ours' mean triangle count per tau (built once)
  uniform  every s-th sample, s chosen for the same triangle count
  quadric  vtkQuadricClustering (what vtkQuadricLODActor uses) at the same count
vtkLODActor is not measured: its lower levels are point clouds and an outline, not
surfaces, so they have no screen-space error to compare (Documentation/benchmarks.md).
Exit status: 0 ok, 2 bad input (one line on stderr), 1 internal error.
"""

import argparse
import os
import shlex
import sys

from .. import command, terrain
from ..errors import AppError
from . import report
from .run import run_dem

PROG = "geomipmap-bench"
METHODS = ("brute", "ours", "ours-fn", "ours-vn", "ours-vn-nomorph", "floor", "greedy", "uniform", "quadric")


def _list(kind, allow_empty=False):
    def parse(text):
        if allow_empty and not text.strip():
            return []
        try:
            vals = [kind(v) for v in text.split(",") if v.strip()]
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a comma-separated list, got {text!r}") from None
        if not vals or any(v <= 0 for v in vals):
            raise argparse.ArgumentTypeError(f"values must be > 0, got {text!r}")
        return vals
    return parse


def build_parser():
    p = command.ArgumentParser(prog=PROG, description=__doc__.split("\n")[0],
                epilog=__doc__.split("\n", 1)[1], formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dem", action="append", default=[], metavar="FILE",
                   help="a DEM to add (repeatable)")
    p.add_argument("--data-dir", default=os.environ.get("GEOMIPMAP_DATA_DIR", "../shared/data"),
                   help="every DEM in this folder is added when it exists (default "
                        "$GEOMIPMAP_DATA_DIR or ../shared/data); '' for none")
    terrain.add_fill_arguments(p)
    p.add_argument("--synthetic", type=_list(int, True), default=[4097, 16385], metavar="N,N",
                   help="synthetic DEM sizes (default 4097,16385; '' for none)")
    p.add_argument("--tau", type=_list(float), default=[0.5, 1, 2, 4, 8], metavar="T,T",
                   help="pixel error bounds for ours (default 0.5,1,2,4,8)")
    p.add_argument("--methods", default=",".join(METHODS), help="subset of " + ",".join(METHODS))
    p.add_argument("--frames", type=int, default=12, help="frames per method (default 12)")
    p.add_argument("--geomorph-range", type=command.positive(float), default=None, metavar="R",
                   help="GeomorphRange of ours' mapper and of the filters that measure its "
                        f"frames (default: the mapper's, {command.default_geomorph_range():g}): "
                        "what geomorphing's level path costs against how gradually it changes "
                        "levels")
    p.add_argument("--geomorph-measure-samples", type=command.positive(int, 0, strict=False), default=None,
                   metavar="N",
                   help="GeomorphMeasureSamples of ours' mapper and its filters (default: the "
                        "mapper's; 0: no limit): the exact errors geomorphing measures a frame "
                        "when the camera jumps, the rest waiting for later frames")
    command.add_block_size_option(p)
    p.add_argument("--path", choices=("orbit", "line"), default="orbit")
    p.add_argument("--size", type=command.window_size, default=(1280, 720),
                   help="window WxH (default 1280x720)")
    p.add_argument("--memory-budget-gb", type=float, default=None,
                   help="skip a method whose estimated memory exceeds this (default: 60%% "
                        "of MemAvailable at start)")
    p.add_argument("--greedy-budget", type=float, default=600.0, metavar="S",
                   help="abort a greedy decimation build after S seconds (default 600)")
    p.add_argument("--out", default="geomipmap-bench", help="output folder")
    p.add_argument("--replot", nargs="+", metavar="DIR",
                   help="no run: rewrite summary.md and bench.png in --out from the "
                        "frames.csv / notes.json of earlier runs (merged)")
    p.add_argument("--quick", action="store_true",
                   help="smoke test: synthetic 513^2 only, 3 frames, tau 1,4")
    return p


def _mem_available_gb():
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) / 2**20
    except OSError:
        pass
    return 8.0


def dem_list(args):
    dems = [("synthetic %d^2" % n, None, n) for n in args.synthetic]
    if args.data_dir and os.path.isdir(args.data_dir):
        for name in sorted(os.listdir(args.data_dir)):
            path = os.path.join(args.data_dir, name)
            if os.path.isfile(path) and not name.lower().endswith((".md", ".txt", ".json")):
                dems.append((name, path, None))
    for path in args.dem:
        if not os.path.isfile(path):
            raise AppError(f"DEM file not found: {path}")
        dems.append((os.path.basename(path), path, None))
    return dems


def main(argv=None):
    def body():
        args = build_parser().parse_args(argv)
        if args.quick:
            args.synthetic, args.frames, args.tau, args.data_dir = [513], 3, [1.0, 4.0], ""
        methods = [m.strip() for m in args.methods.split(",") if m.strip()]
        bad = [m for m in methods if m not in METHODS]
        if bad:
            raise AppError(f"--methods: unknown {','.join(bad)} (choose from {','.join(METHODS)})")
        args.fill = terrain.fill_options(args)
        if args.frames < 1:
            raise AppError(f"--frames must be >= 1, got {args.frames}")
        command.check_block_size(args.block_size)
        if args.replot:
            for d in args.replot:
                if not os.path.isfile(os.path.join(d, "notes.json")):
                    raise AppError(f"--replot: {d} has no notes.json (not a finished run)")
            report.write_report(args.replot, args.out)
            print(f"{PROG}: wrote {args.out}/summary.md, {args.out}/bench.png")
            return 0
        budget = args.memory_budget_gb or 0.6 * _mem_available_gb()
        dems = dem_list(args)  # checks the --dem files before any output is written
        os.makedirs(args.out, exist_ok=True)
        cmd = shlex.join([PROG] + (sys.argv[1:] if argv is None else list(argv)))
        out = report.Output(args.out, cmd, args)
        for label, path, n in dems:
            run_dem(label, path, n, args, methods, budget, out)
            out.flush()
        out.finish()
        print(f"{PROG}: wrote {out.csv_path}, {out.summary_path}, {out.plot_path}")
        return 0

    return command.run(PROG, body)
