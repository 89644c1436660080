"""geomipmap-view command line: parse and check options, load the terrain with progress,
then hand the window to the user (or play a recorded event stream).

Why: every check on user input happens here, before anything heavy is built, and every
failure (ours or VTK's) ends as one line "geomipmap-view: error: ..." on stderr with exit
status 2 (1 for an unexpected internal error), never a traceback. Options shared with
geomipmap-fly (terrain, rendering) come from command.py.
"""

import argparse
import os
import sys

from .. import command
from ..errors import AppError, VTKMessages

PROG = "geomipmap-view"


def _epilog():
    from .viewer import FLY_HELP, KEYS, ORBIT_HELP

    keys = "\n".join("  " + doc for _, _, doc in KEYS)
    return f"""\
keys:
{keys}
{ORBIT_HELP}
{FLY_HELP}

overlay: tau, the certified screen-space error of the frame (pixels), triangles, visible
blocks, the last frame's time (render + GPU finish) and the LOD update time.

examples:
  geomipmap-view                                   # synthetic terrain
  geomipmap-view ../shared/data/mt_rainier_90m.tif --tau 2
  geomipmap-view dem.tif --record session.log      # then: --play session.log

exit status: 0 ok, 2 bad input (one line on stderr), 1 internal error.
"""


def build_parser():
    p = command.ArgumentParser(
        prog=PROG, description="Explore a DEM in a window, rendered with GeoMipMapping LOD "
        "within a certified screen-space error: orbit and fly cameras, tau and wireframe "
        "keys, a frozen LOD to inspect, screenshots, live statistics.",
        epilog=_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    command.add_terrain_options(p, dem_positional=True)
    command.add_rendering_options(p)
    g = p.add_argument_group("viewer")
    g.add_argument("--fly", action="store_true", help="start in fly mode (default: orbit)")
    g.add_argument("--fps", type=command.positive(float), default=None, metavar="RATE",
                   help="hold RATE frames a second while a mouse button moves the camera: "
                   "each such frame draws the triangles that fit in 1/RATE s, learnt from "
                   "the mapper's own frames, with the smallest error they allow, never "
                   "finer than --tau; the frame on release is drawn at --tau (default: off)")
    g.add_argument("--screenshot-dir", default=".", metavar="DIR",
                   help="where 's' writes geomipmap-view-NNNN.png (default: .; made "
                   "when missing)")
    g.add_argument("--record", metavar="FILE",
                   help="record the session's events to FILE (vtkInteractorEventRecorder)")
    g.add_argument("--play", metavar="FILE",
                   help="play a recorded event stream from FILE, then exit")
    return p


def _check_folder(folder, what):
    """A folder that is, or can be made (its first existing ancestor is a writable folder)."""
    path = os.path.abspath(folder)
    while not os.path.exists(path):
        path = os.path.dirname(path)
    if not os.path.isdir(path):
        raise AppError(f"{what}: {path} is not a folder")
    if not os.access(path, os.W_OK):
        raise AppError(f"{what}: folder {path} is not writable")


def check(args):
    """Cross-option checks argparse cannot express."""
    if args.play and args.record:
        raise AppError("give --play or --record, not both")
    if args.play and not os.path.isfile(args.play):
        raise AppError(f"event stream file not found: {args.play}")
    if args.record:
        _check_folder(os.path.dirname(os.path.abspath(args.record)),
                      f"cannot write event stream {args.record}")
    _check_folder(args.screenshot_dir, "--screenshot-dir")
    command.check_common(args)


def open_viewer(args, stream=sys.stderr, say=None):
    """Opens the window, loads the terrain (progress in the terminal and the window) and
    builds its error tables, then returns the Viewer with its first frame drawn."""
    from vtkmodules.vtkCommonCore import vtkCommand
    from vtkmodules.vtkRenderingCore import vtkRenderWindow

    from .. import scene, terrain
    from .progress import LoadProgress
    from .viewer import Overlay, Viewer

    messages = VTKMessages()
    what = args.dem or f"the synthetic terrain ({args.synthetic_size}^2, seed {args.seed})"
    window = vtkRenderWindow()
    window.SetSize(*args.size)
    window.SetWindowName(f"{PROG}: {os.path.basename(args.dem) if args.dem else 'synthetic'}")
    window.SetMultiSamples(0)
    overlay = Overlay(window)
    overlay.show_loading(f"Loading {os.path.basename(args.dem) if args.dem else 'synthetic terrain'}")
    progress = LoadProgress(PROG, overlay.show_loading, stream)
    image, heights = terrain.load_terrain_for(
        args, messages, progress.stage("reading DEM" if args.dem else "generating terrain"))
    view = scene.Scene.from_args(image, heights, args, on_screen=True, title=PROG,
                                 messages=messages, window=window)
    # The error tables are built (or read from the table cache) when the mapper first
    # needs the terrain; asking for its bounds does it now, reporting progress.
    view.mapper.Update()  # the mapper's own pipeline pass reports 0 and 1: not the tables'
    tables = progress.stage("error tables")
    tag = view.mapper.AddObserver(vtkCommand.ProgressEvent,
                                  lambda obj, _event: tables(obj.GetProgress()))
    view.mapper.GetBounds()
    view.mapper.RemoveObserver(tag)
    if err := messages.first_error():
        raise AppError(f"cannot show {what}: {err}")
    viewer = Viewer(view, image, overlay, screenshot_dir=args.screenshot_dir, fly=args.fly,
                    prog=PROG, say=say, fps=args.fps)
    viewer.initialize()
    if err := messages.first_error():
        raise AppError(f"rendering failed: {err}")
    return viewer


def play(viewer, events):
    """Plays an event stream (vtkInteractorEventRecorder format) on the viewer; `events`
    is the stream's text."""
    from vtkmodules.vtkRenderingCore import vtkInteractorEventRecorder

    recorder = vtkInteractorEventRecorder()
    recorder.SetInteractor(viewer.interactor)
    recorder.ReadFromInputStringOn()
    recorder.SetInputString(events)
    recorder.Play()
    recorder.Off()


def record(viewer, filename):
    """Starts recording the viewer's events to `filename` (played back by --play);
    returns the recorder (Stop() and Off() end it)."""
    from vtkmodules.vtkRenderingCore import vtkInteractorEventRecorder

    recorder = vtkInteractorEventRecorder()
    recorder.SetInteractor(viewer.interactor)
    recorder.SetFileName(filename)
    recorder.On()
    recorder.Record()
    return recorder


def main(argv=None):
    def body():
        args = build_parser().parse_args(argv)
        check(args)
        viewer = open_viewer(args)
        if args.play:
            with open(args.play, encoding="utf-8") as f:
                play(viewer, f.read())
            return 0
        if args.record:
            os.makedirs(os.path.dirname(os.path.abspath(args.record)), exist_ok=True)
            recorder = record(viewer, args.record)
            viewer.start()
            recorder.Stop()
            recorder.Off()
            print(f"{PROG}: events recorded in {args.record} (replay with --play)")
            return 0
        viewer.start()
        return 0

    return command.run(PROG, body)
