"""geomipmap-fly command line: parse and check options, run the flight, report.

Why: every check on user input happens here, before anything heavy is built, and every
failure (ours or VTK's) ends as one line "geomipmap-fly: error: ..." on stderr with
exit status 2 (1 for an unexpected internal error), never a traceback.
"""

import argparse
import glob
import os
import sys

from .. import command, terrain, video
from ..errors import AppError, VTKMessages

PROG = "geomipmap-fly"


EPILOG = """\
waypoint files (--waypoints): CSV with a header row, or JSON (a list of objects, or
{"waypoints": [...]}), with keys
  x,y      local metres in the DEM image's frame, or
  lon,lat  degrees WGS 84 (DEMs in a lon/lat CRS only; converted like the reader does),
and a height
  agl      metres above the ground under the camera (terrain following), or
  z / alt  absolute metres (the DEM's height datum).
--clearance M overrides the heights: terrain following at M metres for every path.
Files are UTF-8 (a byte order mark is fine); names are case-insensitive and each may
appear once. In CSV files every row has as many fields as the header, and blank lines
and lines starting with # are ignored.

examples:
  geomipmap-fly                                    # orbit over synthetic terrain
  geomipmap-fly --dem tile.hgt --clearance 300 --seconds 10 --fps 30 --video tile.mp4
  geomipmap-fly --dem srtm_with_voids.tif --fill-voids --fill-distance 50
  geomipmap-fly --dem dem_utm.tif --texture ortho_lonlat.tif --pitch 40
  geomipmap-fly --dem dem.tif --waypoints route.csv --tau 2 --every 10 --size 1920x1080

output: DIR/frame_NNNNN.png, DIR/flight.csv (frame, time_s, lod_ms, render_ms, triangles,
visible_blocks, culled_blocks, certified_error_px, reused), with --video a video of every
frame at --fps (.mp4: H.264 by ffmpeg, even width and height; .ogv: Ogg Theora by ffmpeg,
or by VTK's vtkOggTheoraWriter where ffmpeg is missing, whole --fps), and a summary on
stdout.
exit status: 0 ok, 2 bad input (one line on stderr), 1 internal error.
"""


def build_parser():
    p = command.ArgumentParser(prog=PROG, description="Fly a camera over a DEM rendered with GeoMipMapping "
                "LOD; write PNG frames, a per-frame CSV of LOD statistics and a summary.",
                epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    command.add_terrain_options(p)
    g = p.add_argument_group("path")
    g.add_argument("--path", choices=("orbit", "line"), default="orbit",
                   help="orbit around the centre (default) or a straight line across")
    g.add_argument("--waypoints", metavar="FILE", help="CSV/JSON waypoints: columns x,y or "
                   "lon,lat, and agl (metres above ground) or z/alt (absolute metres)")
    g.add_argument("--clearance", type=command.positive(float), default=None, metavar="M",
                   help="follow the terrain at M metres above the ground (smoothed)")
    g.add_argument("--frames", type=command.positive(int, 1, strict=False), default=None,
                   help="number of frames (default 300)")
    g.add_argument("--seconds", type=command.positive(float), default=None,
                   help="flight duration; frames = seconds * fps")
    g.add_argument("--fps", type=command.positive(float), default=30.0, help="frame rate (default 30)")
    g.add_argument("--pitch", type=float, default=15.0,
                   help="look-down angle in degrees, -89..89 (default 15)")
    g.add_argument("--view-angle", type=float, default=50.0,
                   help="vertical field of view in degrees (default 50)")
    g = command.add_rendering_options(p)
    g.add_argument("--interactive", action="store_true",
                   help="on-screen window, then explore the terrain as in geomipmap-view")
    g = p.add_argument_group("output")
    g.add_argument("--out", default="geomipmap-flight", help="output folder "
                   "(default ./geomipmap-flight)")
    g.add_argument("--every", type=command.positive(int, 1, strict=False), default=1,
                   help="write every K-th frame as PNG (default 1)")
    g.add_argument("--no-frames", action="store_true", help="write no PNG frames")
    g.add_argument("--video", metavar="FILE", help="also write the flight as a video, "
                   "every frame at --fps: FILE.mp4 (H.264, needs ffmpeg) or FILE.ogv "
                   "(Ogg Theora)")
    g.add_argument("--video-encoder", choices=video.ENCODERS, default="auto",
                   help="auto (default): ffmpeg when it is on PATH, else VTK's "
                   "vtkOggTheoraWriter (.ogv only)")
    return p


def check(args):
    """Cross-option checks argparse cannot express."""
    if not -89.0 <= args.pitch <= 89.0:
        raise AppError(f"--pitch must be in -89..89 degrees, got {args.pitch:g}")
    if not 1.0 <= args.view_angle <= 170.0:
        raise AppError(f"--view-angle must be in 1..170 degrees, got {args.view_angle:g}")
    if args.frames is not None and args.seconds is not None:
        raise AppError("give --frames or --seconds, not both")
    if args.seconds is not None:
        args.frames = int(round(args.seconds * args.fps))
        if args.frames < 1:
            raise AppError(f"--seconds {args.seconds:g} at --fps {args.fps:g} gives no frame")
    elif args.frames is None:
        args.frames = 300
    if args.waypoints and not os.path.isfile(args.waypoints):
        raise AppError(f"waypoint file not found: {args.waypoints}")
    if args.video:
        video.check(args.video, args.size, args.fps, args.video_encoder)
    command.check_common(args)


def nothing_drawn(heights):
    """Why a flight may have drawn no terrain at all, with the DEM's extent and heights: the
    usual cause is an image without georeference read with the default spacing (1 m) and
    height scale (1), whose heights then dwarf its extent and put the path far above it."""
    xmin, xmax, ymin, ymax = heights.bounds
    return (f"no frame drew any terrain: the DEM spans {xmax - xmin:g} x {ymax - ymin:g} m with "
            f"heights {heights.zmin:g} .. {heights.zmax:g} m, and the camera path did not see it. "
            "For an image without georeference, give its sample spacing (--spacing, metres) and "
            "the metres per stored height unit (--height-scale).")


def fly(args):
    """Everything after option parsing; returns the summary text."""
    from geomipmap import flight

    from .. import scene
    from . import report

    messages = VTKMessages()
    image, heights = terrain.load_terrain_for(args, messages)
    how = dict(clearance=args.clearance, frames=args.frames, pitch=args.pitch,
               view_angle=args.view_angle)
    if args.waypoints:
        path = flight.Waypoints.from_file(args.waypoints, heights, **how)
    elif args.path == "line":
        path = flight.Line(heights, **how)
    else:
        path = flight.Orbit(heights, **how)
    view = scene.Scene.from_args(image, heights, args, on_screen=args.interactive,
                                 title=PROG, messages=messages)
    # Only now, when the input is known good, touch the output folders.
    folder = args.out
    try:
        os.makedirs(folder, exist_ok=True)
        for old in glob.glob(os.path.join(folder, "frame_[0-9][0-9][0-9][0-9][0-9].png")):
            os.remove(old)  # frames of an earlier flight would be mixed with this one's
        if args.video:
            folder = os.path.dirname(os.path.abspath(args.video))
            os.makedirs(folder, exist_ok=True)
    except OSError as e:
        raise AppError(f"cannot write to output folder {folder}: {e.strerror}") from None
    csv_name = os.path.join(args.out, "flight.csv")
    log = report.FrameLog(csv_name)
    movie = video.VideoWriter(args.video, args.size, args.fps, args.video_encoder) \
        if args.video else None
    progress = report.Progress(len(path))
    written = 0
    try:
        for i in range(len(path)):
            path.apply(view.renderer, i)
            stats = view.render()
            if i == 0 and (err := messages.first_error()):
                raise AppError(f"rendering failed: {err}")
            log.add(i, i / args.fps, stats)
            png = not args.no_frames and i % args.every == 0
            if png or movie:
                frame = view.capture()
            if png:
                view.write_png(os.path.join(args.out, f"frame_{i:05d}.png"))
                written += 1
            if movie:
                movie.add(frame)
            progress.update(i + 1)
    except BaseException:
        if movie:
            movie.close(quiet=True)  # what was rendered stays playable; the error is told
        raise
    finally:
        progress.finish()
        log.close()
    if movie:
        movie.close()
    for line in messages.warnings:  # e.g. a DEM without georeference, a photo without CRS
        print(f"{PROG}: warning: {line}", file=sys.stderr)
    if log.rows and not any(r["triangles"] for r in log.rows):
        print(f"{PROG}: warning: {nothing_drawn(heights)}", file=sys.stderr)
    where = [f"CSV: {os.path.abspath(csv_name)}"]
    where.append(f"frames: {written} PNG in {os.path.abspath(args.out)}" if written
                 else "frames: none written (--no-frames)")
    if movie:
        where.append(movie.describe())
    text = report.summary(log.rows, args.tau, where)
    if args.interactive:
        from ..view.viewer import Overlay, Viewer

        print(text)
        explore = Viewer(view, image, Overlay(view.window), prog=PROG)
        explore.initialize()
        explore.start()
        return None
    return text


def main(argv=None):
    def body():
        args = build_parser().parse_args(argv)
        check(args)
        text = fly(args)
        if text:
            print(text)
        return 0

    return command.run(PROG, body)
