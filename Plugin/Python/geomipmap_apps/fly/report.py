"""Flight output for geomipmap-fly: per-frame CSV, terminal progress, summary table.

Why: the CSV is the machine-readable record (one row per rendered frame, flushed as it
goes so an interrupted flight still leaves data); the progress display must not spam log
files, so it is a redrawn bar only on a terminal and a few plain lines otherwise.
"""

import csv
import sys
import time

import numpy as np

COLUMNS = ("frame", "time_s", "lod_ms", "render_ms", "triangles", "visible_blocks",
           "culled_blocks", "certified_error_px", "reused")


class FrameLog:
    """Writes flight.csv and keeps the rows for the summary."""

    def __init__(self, filename):
        self.filename = filename
        self.file = open(filename, "w", newline="", encoding="utf-8")
        self.writer = csv.writer(self.file)
        self.writer.writerow(COLUMNS)
        self.rows = []

    def add(self, frame, time_s, stats):
        row = dict(stats, frame=frame, time_s=time_s)
        self.rows.append(row)
        self.writer.writerow([
            frame, f"{time_s:.4f}", f"{stats['lod_ms']:.3f}", f"{stats['render_ms']:.3f}",
            stats["triangles"], stats["visible_blocks"], stats["culled_blocks"],
            f"{stats['certified_error_px']:.4f}", "yes" if stats["reused"] else "no"])
        self.file.flush()

    def close(self):
        self.file.close()


class Progress:
    """A progress bar on a TTY (stderr), else a plain line every ~10 % of the frames."""

    def __init__(self, total, stream=sys.stderr):
        self.total = total
        self.stream = stream
        self.tty = hasattr(stream, "isatty") and stream.isatty()
        self.start = time.perf_counter()
        self.next_line = 0

    def update(self, done):
        elapsed = time.perf_counter() - self.start
        fps = done / elapsed if elapsed > 0 else 0.0
        if self.tty:
            width = 30
            fill = int(width * done / self.total)
            eta = (self.total - done) / fps if fps > 0 else 0.0
            self.stream.write(f"\r[{'#' * fill}{'.' * (width - fill)}] {done}/{self.total} "
                              f"frames  {fps:5.1f} fps  eta {eta:5.1f} s ")
            self.stream.flush()
        elif done >= self.next_line or done == self.total:
            self.stream.write(f"geomipmap-fly: frame {done}/{self.total} ({fps:.1f} fps)\n")
            self.stream.flush()
            self.next_line = done + max(self.total // 10, 1)

    def finish(self):
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()


def summary(rows, tau, where):
    """The end-of-flight table (mean / median / p95) as a string."""
    lines = [f"geomipmap-fly: {len(rows)} frames, tau = {tau:g} px", ""]
    lines.append(f"{'':<22}{'mean':>12}{'median':>12}{'p95':>12}{'max':>12}")
    for key, label, fmt in (("lod_ms", "LOD update (ms)", "{:.3f}"),
                            ("render_ms", "render (ms)", "{:.2f}"),
                            ("triangles", "triangles", "{:.0f}"),
                            ("visible_blocks", "visible blocks", "{:.0f}"),
                            ("certified_error_px", "certified error (px)", "{:.3f}")):
        v = np.array([r[key] for r in rows], float)
        cells = [fmt.format(x) for x in (v.mean(), np.median(v), np.percentile(v, 95), v.max())]
        lines.append(f"{label:<22}" + "".join(f"{c:>12}" for c in cells))
    reused = sum(1 for r in rows if r["reused"]) / len(rows)
    worst = max(r["certified_error_px"] for r in rows)
    lines.append("")
    lines.append(f"max certified error: {worst:.3f} px "
                 f"({'within' if worst <= tau + 1e-9 else 'ABOVE'} tau)")
    lines.append(f"indices reused: {100.0 * reused:.1f} % of frames")
    lines.extend(where)
    return "\n".join(lines)
