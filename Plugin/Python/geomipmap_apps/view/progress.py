"""Loading progress for geomipmap-view: the reader's and the error-table build's progress
events, shown in the terminal and in the window while a DEM loads.

Why: a 16385^2 DEM takes seconds to read and, on its first open, seconds more to build
its error tables (Documentation/benchmarks-core.md); a window that stays black meanwhile
looks hung. Each stage ("reading DEM", "error tables") reports fractions 0..1; the
terminal gets a redrawn line on a TTY, else a line per quarter (no spam in log files), and
the window a centred text, redrawn when it changes, at most every `interval` seconds
(rendering is not free) but always at a stage's start and end. So a stage faster than
`interval` shows only its 0 % and 100 % in the window.
"""

import sys
import time


class LoadProgress:
    """Shows load stages and their fractions. show(text) is the window's display: a
    callable that sets and renders the text (Overlay.show_loading), or None for the
    terminal only. interval: the least time between two window redraws within a stage,
    in seconds (None: WINDOW_INTERVAL_S); clock: a callable giving seconds."""

    WINDOW_INTERVAL_S = 0.1  # ten redraws a second: smooth, and costs little

    def __init__(self, prog, show=None, stream=sys.stderr, interval=None,
                 clock=time.perf_counter):
        self.prog = prog
        self.show = show
        self.stream = stream
        self.tty = hasattr(stream, "isatty") and stream.isatty()
        self.interval = self.WINDOW_INTERVAL_S if interval is None else interval
        self.clock = clock
        self.last_shown, self.last_text = -1e9, None
        self.quarter = {}  # stage -> last quarter printed (non-TTY)
        self.fractions = {}  # stage -> every fraction reported, in order

    def stage(self, name):
        """A callback fraction -> None for one stage (terrain.load_terrain's progress=)."""
        return lambda fraction: self.update(name, fraction)

    def update(self, name, fraction):
        fraction = min(max(float(fraction), 0.0), 1.0)
        seen = self.fractions.setdefault(name, [])
        first = not seen
        seen.append(fraction)
        text = f"{name} {100.0 * fraction:3.0f} %"
        if self.tty:
            self.stream.write(f"\r{self.prog}: {text} ")
            if fraction >= 1.0:
                self.stream.write("\n")
            self.stream.flush()
        else:
            q = int(4 * fraction)
            if self.quarter.get(name, -1) < q:
                self.quarter[name] = q
                self.stream.write(f"{self.prog}: {text}\n")
                self.stream.flush()
        now = self.clock()
        text = f"Loading: {text}"
        if self.show and text != self.last_text and (
                first or fraction >= 1.0 or now - self.last_shown >= self.interval):
            self.last_shown, self.last_text = now, text
            self.show(text)
