"""What every geomipmap tool's command line shares: argument types, the terrain and
rendering options (geomipmap-fly and geomipmap-view take the same ones), one-line errors
and exit statuses.

Why: a tool must fail with one readable line, never a traceback or argparse's usage dump,
and the same failure must end the same way in every tool: "PROG: error: ..." on stderr
with exit status 2 for bad input, 1 (one line too) for an unexpected internal error,
130 when interrupted.
"""

import argparse
import math
import os
import sys

from .errors import AppError


class ArgumentParser(argparse.ArgumentParser):
    """argparse, but a bad option raises AppError (one line) instead of printing usage."""

    def error(self, message):
        raise AppError(message)


def positive(kind, minimum=0.0, strict=True):
    """Argument type: a finite `kind` (int, float) > minimum (>= when not strict)."""
    def check(text):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
        if not math.isfinite(v) or (v <= minimum if strict else v < minimum):
            rel = ">" if strict else ">="
            raise argparse.ArgumentTypeError(f"must be {rel} {minimum:g}, got {text}")
        return v
    return check


def window_size(text):
    """Argument type: WxH, each 16..16384 -> (width, height)."""
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected WxH, e.g. 1280x720, got {text!r}") from None
    if not (16 <= w <= 16384 and 16 <= h <= 16384):
        raise argparse.ArgumentTypeError(f"width and height must be 16..16384, got {text}")
    return (w, h)


def min_block_size():
    """The engine's one minimum block size (gmm::kMinBlockQuads), as the mapper states it."""
    from geomipmap import vtkGeoMipMapMapper

    return vtkGeoMipMapMapper.GetMinimumBlockSize()


def default_block_size():
    """The engine's one default block size (gmm::kDefaultBlockQuads), as the mapper states it."""
    from geomipmap import vtkGeoMipMapMapper

    return vtkGeoMipMapMapper.GetDefaultBlockSize()


def default_geomorph_range():
    """The engine's one default geomorphing range (gmm::kDefaultMorphRange), as a new mapper
    states it."""
    from geomipmap import vtkGeoMipMapMapper

    return vtkGeoMipMapMapper().GetGeomorphRange()


def add_block_size_option(group):
    """--block-size, with the mapper's default; check_block_size validates it."""
    default = default_block_size()
    group.add_argument("--block-size", type=int, default=default,
                       help=f"block size in quads, a power of two {min_block_size()}..1024 "
                       f"(default {default})")


def check_block_size(b):
    """The tools' rule for --block-size: a power of two from the engine's minimum to 1024."""
    least = min_block_size()
    if b < least or b > 1024 or b & (b - 1):
        raise AppError(f"--block-size must be a power of two in {least}..1024, got {b}")


def colour(text):
    """Argument type: 'elevation' or 'texture:FILE.png'."""
    if text == "elevation" or (text.startswith("texture:") and len(text) > 8):
        return text
    raise argparse.ArgumentTypeError(f"expected 'elevation' or 'texture:FILE.png', got {text!r}")


def add_terrain_options(parser, dem_positional=False):
    """The terrain options (DEM or synthetic terrain): the DEM is an optional positional
    argument when dem_positional, else --dem. Read by terrain.load_terrain_for(args)."""
    g = parser.add_argument_group("terrain")
    dem_help = ("any format the vtkGeoMipMapTerrainReader reads (GeoTIFF, SRTM .hgt, "
                "USGS .dem, ESRI .asc, 16-bit or float image heightmaps, terrain-RGB "
                "PNG); default: synthetic terrain")
    if dem_positional:
        g.add_argument("dem", nargs="?", metavar="DEM", help="the DEM to show: " + dem_help)
    else:
        g.add_argument("--dem", metavar="FILE", help="DEM to fly over: " + dem_help)
    g.add_argument("--height-scale", type=positive(float), default=1.0,
                   help="metres per stored height unit (default 1)")
    g.add_argument("--spacing", type=positive(float), default=None,
                   help="sample spacing in metres for images without georeference "
                   "(and the synthetic terrain, default 30)")
    g.add_argument("--terrain-rgb", action="store_true", help="decode an RGB PNG as terrain-RGB")
    from . import terrain  # (terrain imports this module)

    terrain.add_fill_arguments(g)
    g.add_argument("--synthetic-size", type=positive(int, 2, strict=False), default=1025,
                   help="synthetic terrain samples per side (default 1025)")
    g.add_argument("--seed", type=positive(int, 0, strict=False), default=1,
                   help="synthetic terrain seed (default 1)")
    return g


# --normals: the mapper's NormalMode by name.
NORMAL_MODES = ("auto", "vertex", "fragment")


def set_normal_mode(mapper, name):
    """vtkGeoMipMapMapper.SetNormalMode from a --normals name."""
    {"auto": mapper.SetNormalModeToAutomatic, "vertex": mapper.SetNormalModeToPerVertex,
     "fragment": mapper.SetNormalModeToPerFragment}[name]()


def add_rendering_options(parser, size=(1280, 720)):
    """The rendering options: --tau, --block-size, --size, --color, --texture,
    --texture-size, --no-lighting, --normals (--vertex-normals), --no-geomorphing (read by
    scene.Scene.from_args); returns the group so that a tool can add its own."""
    g = parser.add_argument_group("rendering")
    g.add_argument("--tau", type=positive(float, 0, strict=False), default=1.0,
                   help="pixel error bound (default 1)")
    add_block_size_option(g)
    g.add_argument("--size", type=window_size, default=size,
                   help=f"window WxH (default {size[0]}x{size[1]})")
    g.add_argument("--color", type=colour, default="elevation",
                   help="'elevation' (default) or 'texture:FILE.png' (stretched over the extent)")
    g.add_argument("--texture", metavar="FILE", help="drape a georeferenced image (GeoTIFF "
                   "orthophoto, any GDAL raster with RGB bands) over the terrain by its "
                   "coordinates, reprojected when its CRS differs from the DEM's; outside it "
                   "the terrain keeps --color")
    g.add_argument("--texture-size", type=positive(int, 1, strict=False), default=8192,
                   metavar="PIXELS", help="resample a --texture larger than this a side "
                   "(default 8192; at most 16384, the OpenGL texture limit)")
    g.add_argument("--no-lighting", action="store_true", help="flat colours, no sun")
    g.add_argument("--normals", choices=NORMAL_MODES, default="auto",
                   help="where lit terrain takes its normals: 'vertex' at the drawn vertices "
                   "(faster frames on a software renderer such as llvmpipe, less shading "
                   "detail in coarse triangles), 'fragment' at every pixel, 'auto' (default) "
                   "at every pixel on a GPU and, on a software renderer, per vertex while the "
                   "frame's certified error is at most 1 px, per pixel above")
    g.add_argument("--vertex-normals", dest="normals", action="store_const", const="vertex",
                   help="the same as --normals vertex")
    g.add_argument("--no-geomorphing", action="store_true",
                   help="levels switch at once (pops of up to --tau pixels) instead of gliding; "
                   "each block takes the coarsest level within --tau, so wide views draw fewer "
                   "triangles (up to 4x fewer at tau 1)")
    return g


def check_common(args):
    """Checks of the shared options argparse cannot express, and the X display VTK needs."""
    check_block_size(args.block_size)
    if args.dem and not os.path.isfile(args.dem):
        raise AppError(f"DEM file not found: {args.dem}")
    texture = args.color.split(":", 1)[1] if args.color.startswith("texture:") else None
    if texture and not os.path.isfile(texture):
        raise AppError(f"texture image not found: {texture}")
    if args.texture:
        if args.color != "elevation":
            raise AppError("give --texture (placed by its georeference) or --color texture:FILE "
                           "(stretched over the extent), not both")
        if not os.path.isfile(args.texture):
            raise AppError(f"texture image not found: {args.texture}")
        if not args.dem:
            raise AppError("--texture needs a georeferenced DEM: the synthetic terrain has no "
                           "coordinates to place the image by")
    if args.texture_size > 16384:
        raise AppError(f"--texture-size must be at most 16384, got {args.texture_size}")
    from . import terrain  # (terrain imports this module)

    terrain.fill_options(args)  # a fill option without --fill-voids, or out of range
    if not os.environ.get("DISPLAY"):
        raise AppError("no X display (DISPLAY is unset): VTK here renders through X; "
                       "run under xvfb-run -a")


def _bad_input():
    """The exceptions that mean bad input: AppError, and the flight API's FlightError once
    geomipmap.flight is loaded (the tools import it late, so that --help works without
    the compiled package)."""
    flight = sys.modules.get("geomipmap.flight")
    return (AppError, flight.FlightError) if flight else (AppError,)


def run(prog, body):
    """Call body() (the whole tool after its imports) and return the exit status: body's,
    or 2 after one line on stderr for bad input (AppError, geomipmap.flight.FlightError),
    a missing geomipmap package or memory, 130 when interrupted, 1 for anything else
    (GEOMIPMAP_DEBUG=1 re-raises it for a traceback)."""
    try:
        return body()
    except _bad_input() as e:
        print(f"{prog}: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return 130
    except ImportError as e:
        print(f"{prog}: error: cannot import the geomipmap package ({e}); "
              "is it built / installed next to this command?", file=sys.stderr)
        return 2
    except MemoryError:
        print(f"{prog}: error: out of memory", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001: last resort, still one line
        msg = " ".join(str(e).split())[:300]
        print(f"{prog}: internal error: {type(e).__name__}: {msg} "
              "(set GEOMIPMAP_DEBUG=1 for a traceback)", file=sys.stderr)
        if os.environ.get("GEOMIPMAP_DEBUG"):
            raise
        return 1
