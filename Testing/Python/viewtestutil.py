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
    returns (viewer, the texts the window rendered while loading, the terminal's text)."""
    import io

    from geomipmap_apps.view import cli, viewer

    shown = []
    show_loading = viewer.Overlay.show_loading

    def recording_show(self, text):
        shown.append(text)
        show_loading(self, text)

    viewer.Overlay.show_loading = recording_show
    terminal = io.StringIO()
    try:
        args = cli.build_parser().parse_args(argv)
        cli.check(args)
        v = cli.open_viewer(args, stream=terminal, say=say)
    finally:
        viewer.Overlay.show_loading = show_loading
    print("window showed while loading:", shown)
    print("terminal:", terminal.getvalue().replace("\n", " | "))
    return v, shown, terminal.getvalue()
