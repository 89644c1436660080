"""Event streams for the geomipmap-view tests, in vtkInteractorEventRecorder's format,
and the viewer opened with what it shows while loading recorded.

Why: the viewer is tested the way VTK tests interaction, with recorded events played on
the window's interactor; writing the streams from a few builders (a key, a drag) keeps
each test's script readable. Format of VTK 9.1 (stream version 1.1), one event a line:
    EventName X Y MODIFIERS KEYCODE REPEATCOUNT KEYSYM
with MODIFIERS a bit mask (1 Shift, 2 Control). This is what the recorder writes (checked
by TestViewerInteraction, which records a session and plays it back).
"""

HEADER = "# StreamVersion 1.1\n"
KEYCODES = {"plus": 43, "minus": 45, "Escape": 27, "question": 63}


def key(sym, shift=False, x=10, y=10):
    """A key press (the viewer acts on KeyPressEvent) of the key with this key symbol."""
    code = KEYCODES.get(sym, ord(sym) if len(sym) == 1 else 0)
    return f"KeyPressEvent {x} {y} {1 if shift else 0} {code} 1 {sym}\n" \
        f"KeyReleaseEvent {x} {y} {1 if shift else 0} {code} 1 {sym}\n"


def keys(*syms, shift=False):
    return "".join(key(s, shift=shift) for s in syms)


def drag(x0, y0, x1, y1, steps=8, button="Left"):
    """Press `button` at (x0, y0), move in `steps` steps to (x1, y1), release."""
    out = [f"MouseMoveEvent {x0} {y0} 0 0 0 None\n",
           f"{button}ButtonPressEvent {x0} {y0} 0 0 0 None\n"]
    for i in range(1, steps + 1):
        x = round(x0 + (x1 - x0) * i / steps)
        y = round(y0 + (y1 - y0) * i / steps)
        out.append(f"MouseMoveEvent {x} {y} 0 0 0 None\n")
    out.append(f"{button}ButtonReleaseEvent {x1} {y1} 0 0 0 None\n")
    return "".join(out)


def stream(*parts):
    return HEADER + "".join(parts)


def open_viewer_recording(argv, say=None):
    """Runs geomipmap-view's own loading (cli.open_viewer) for the command line `argv`;
    returns (viewer, the texts the window rendered while loading, the terminal's text).
    The window's redraw throttle is off meanwhile: a stage faster than its interval shows
    only 0 and 100 % (check_progress_throttle tests that), and whether a read takes more
    than 0.1 s depends on the machine, so the recording gets every distinct text."""
    import io

    from geomipmap_apps.view import cli, viewer
    from geomipmap_apps.view.progress import LoadProgress

    shown = []
    show_loading = viewer.Overlay.show_loading

    def recording_show(self, text):
        shown.append(text)
        show_loading(self, text)

    viewer.Overlay.show_loading = recording_show
    interval = LoadProgress.WINDOW_INTERVAL_S
    LoadProgress.WINDOW_INTERVAL_S = 0.0
    terminal = io.StringIO()
    try:
        args = cli.build_parser().parse_args(argv)
        cli.check(args)
        v = cli.open_viewer(args, stream=terminal, say=say)
    finally:
        viewer.Overlay.show_loading = show_loading
        LoadProgress.WINDOW_INTERVAL_S = interval
    print("window showed while loading:", shown)
    print("terminal:", terminal.getvalue().replace("\n", " | "))
    return v, shown, terminal.getvalue()


def check_progress_throttle(check):
    """The window's loading text under a fake clock: within a stage a redraw waits
    LoadProgress's interval, except at the stage's start and end; a text that did not
    change is not redrawn. Expected sequences written by hand from that rule."""
    import io

    from geomipmap_apps.view.progress import LoadProgress

    now = [0.0]
    shown = []
    progress = LoadProgress("p", shown.append, io.StringIO(), interval=0.1,
                            clock=lambda: now[0])
    stage = progress.stage("reading DEM")
    for t, fraction in ((0.0, 0.0), (0.05, 0.3), (0.12, 0.6), (0.15, 0.9), (0.16, 1.0)):
        now[0] = t
        stage(fraction)
    want = ["Loading: reading DEM   0 %", "Loading: reading DEM  60 %",
            "Loading: reading DEM 100 %"]
    check(shown == want, f"throttle: 0.3 within 0.1 s of 0 and 0.9 of 0.6 skipped ({shown})")
    shown.clear()
    tables = progress.stage("error tables")
    for t, fraction in ((0.17, 0.0), (0.30, 0.001), (0.41, 0.002), (0.52, 0.5)):
        now[0] = t
        tables(fraction)
    want = ["Loading: error tables   0 %", "Loading: error tables  50 %"]
    check(shown == want, f"throttle: a new stage shows at once; 0 % again not redrawn ({shown})")
