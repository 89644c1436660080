"""geomipmap-fly on the built-in synthetic terrain: the README's demo, shrunk.

The orbit runs in this process (flytestutil.measured_flight: the command's own code) so that
every frame's drawn triangles can be measured against the full-resolution terrain,
independently of the engine's bound. Checks: exit 0, a CSV with one row per frame and sane
values, PNG frames that are not blank and show terrain under a sky, the summary table on
stdout, the measured screen error of every frame within tau (513 x 513 at tau 2: measured
1.2 .. 1.6 px; with the engine's projection halved, 2.2 .. 2.7 px, so the check bites);
then a line flight as a command (the launcher) with terrain following (--clearance) and
--every / --seconds, the same with --vertex-normals (similar pictures, not the same) and
with --normals fragment (the same pictures: automatic normals are per fragment at tau 2), and
with --no-geomorphing (fewer triangles: geomorphing's level path holds blocks finer than tau
needs).
"""

import glob
import os

from flytestutil import (check, check_measured, measured_flight, png_pixels, png_stats, read_csv,
                         run, setup)

exe, out = setup()
d1 = os.path.join(out, "orbit")
orbit = ["--frames", "10", "--size", "320x180", "--synthetic-size", "513", "--tau", "2"]
rc, so, se, frames = measured_flight(orbit + ["--out", d1])
check(rc == 0, f"orbit flight exited {rc}: {se.strip()}")
check("Traceback" not in se, "traceback on stderr")
rows = read_csv(os.path.join(d1, "flight.csv"))
check(len(rows) == 10, f"expected 10 CSV rows, got {len(rows)}")
check([int(r["frame"]) for r in rows] == list(range(10)), "frame numbers")
for r in rows:
    check(int(r["triangles"]) > 0, f"frame {r['frame']}: no triangles")
    check(float(r["render_ms"]) > 0, f"frame {r['frame']}: render_ms")
    check(float(r["certified_error_px"]) >= 0, f"frame {r['frame']}: certified_error_px column")
    check(r["reused"] in ("yes", "no"), "reused column")
pngs = sorted(glob.glob(os.path.join(d1, "frame_*.png")))
check(len(pngs) == 10, f"expected 10 PNGs, got {len(pngs)}")
for p in (pngs[0], pngs[5]):
    w, h, var, terrain = png_stats(p)
    check((w, h) == (320, 180), f"{p}: size {w}x{h}")
    check(var > 20.0, f"{p}: blank image (variance {var:.1f})")
    check(0.2 < terrain < 0.98, f"{p}: terrain covers {terrain:.0%} (expected land and sky)")
for word in ("median", "p95", "LOD update", "render", "triangles", "certified error",
             "indices reused", "CSV:", "frames:"):
    check(word in so, f"summary lacks {word!r}:\n{so}")

check_measured(frames, rows, tau=2.0)

d2 = os.path.join(out, "line")
rc, so, se = run(exe, "--path", "line", "--clearance", "150", "--seconds", "1", "--fps", "8",
                 "--every", "4", "--size", "200x120", "--synthetic-size", "129", "--tau", "2",
                 "--out", d2)
check(rc == 0, f"line flight exited {rc}: {se.strip()}")
check(len(read_csv(os.path.join(d2, "flight.csv"))) == 8, "--seconds 1 --fps 8: 8 rows")
check(len(glob.glob(os.path.join(d2, "frame_*.png"))) == 2, "--every 4 of 8: 2 PNGs")

# --vertex-normals reaches the mapper: the same flight's pictures shaded per vertex look
# like the default's (whose automatic normals shade per fragment at tau 2: same terrain,
# same colours) but are not the same pixels.
d3 = os.path.join(out, "line-vertex-normals")
rc, so, se = run(exe, "--path", "line", "--clearance", "150", "--seconds", "1", "--fps", "8",
                 "--every", "4", "--size", "200x120", "--synthetic-size", "129", "--tau", "2",
                 "--vertex-normals", "--out", d3)
check(rc == 0, f"--vertex-normals flight exited {rc}: {se.strip()}")
for name in sorted(os.path.basename(p) for p in glob.glob(os.path.join(d2, "frame_*.png"))):
    a, b = png_pixels(os.path.join(d2, name))[2], png_pixels(os.path.join(d3, name))[2]
    diff = abs(a - b).max(axis=1)
    check(a.shape == b.shape and 0 < (diff > 0).mean() and (diff > 24).mean() < 0.05,
          f"{name}: --vertex-normals changed {100 * (diff > 0).mean():.1f} % of the pixels, "
          f"{100 * (diff > 24).mean():.2f} % by more than 24 levels")

# --normals fragment reaches the mapper too, and at tau 2 the default's automatic normals are
# per fragment (they shade per vertex only in frames certified within 1 px): the same pixels.
d5 = os.path.join(out, "line-fragment-normals")
rc, so, se = run(exe, "--path", "line", "--clearance", "150", "--seconds", "1", "--fps", "8",
                 "--every", "4", "--size", "200x120", "--synthetic-size", "129", "--tau", "2",
                 "--normals", "fragment", "--out", d5)
check(rc == 0, f"--normals fragment flight exited {rc}: {se.strip()}")
for name in sorted(os.path.basename(p) for p in glob.glob(os.path.join(d2, "frame_*.png"))):
    a, b = png_pixels(os.path.join(d2, name))[2], png_pixels(os.path.join(d5, name))[2]
    check(a.shape == b.shape and (a == b).all(),
          f"{name}: --normals fragment draws the default's pixels at tau 2")

# --no-geomorphing reaches the mapper: without the level path each block takes the coarsest
# level within tau, so the same flight draws fewer triangles (513^2: the 129^2 line flight
# above is drawn near full resolution either way).
counts = {}
for flag in ("", "--no-geomorphing"):
    d4 = os.path.join(out, "line-513" + flag.replace("--", "-"))
    rc, so, se = run(exe, "--path", "line", "--clearance", "150", "--seconds", "1", "--fps",
                     "8", "--every", "8", "--size", "200x120", "--synthetic-size", "513",
                     "--tau", "2", "--out", d4, *([flag] if flag else []))
    check(rc == 0, f"line flight {flag} exited {rc}: {se.strip()}")
    counts[flag] = sum(int(r["triangles"]) for r in read_csv(os.path.join(d4, "flight.csv")))
print(f"line flight 513^2, tau 2: {counts['']} triangles with geomorphing, "
      f"{counts['--no-geomorphing']} without")
check(0 < counts["--no-geomorphing"] < counts[""], f"--no-geomorphing: "
      f"{counts['--no-geomorphing']} triangles over the flight, not fewer than {counts['']} "
      f"with geomorphing")
print("TestFlySynthetic: passed")
