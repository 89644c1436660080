"""geomipmap-view over a real DEM (issue #15, part 1): loading progress of a large file,
then a recorded event stream, measured.

N48W125.hgt (SRTM 1", 3601 x 3601 = 13 M samples) with the table cache off, so that both
loading stages take long enough to report progress between 0 and 1 (measured: the reader
reports 0, 0.31, 0.61, 0.92, 1; the error tables about 15 fractions in 0.7 s). Checks:
each stage's intermediate fractions reached the window (the texts it rendered while
loading, recorded with the redraw throttle off: a fast disk reads the tile in under its
0.1 s) and the terminal; then an orbit drag, '+' and a fly-mode excursion are played and
the final frame measures within tau (gmmtestutil.check_drawn_within_tau; uncovered
samples allowed: the tile's north half is void, and a valid sample whose every quad
touches a void is drawn by no triangle; 17 of them in view here).
Missing data skips (or fails under GEOMIPMAP_REQUIRE_DATA=1).
Usage: TestViewerRealDEM.py SCRATCH_DIR
"""
import os
import re
import shutil
import sys

os.environ["GEOMIPMAP_CACHE_DIR"] = "off"  # the tables are built, with progress, every run

import refscene  # noqa: E402
from gmmdata import data_file  # noqa: E402
from gmmtestutil import check_within_tau  # noqa: E402
from viewtestutil import drag, key, keys, open_viewer_recording, stream  # noqa: E402

from geomipmap_apps.view import cli  # noqa: E402

dem = data_file("N48W125.hgt")
scratch = sys.argv[1]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
check = refscene.Checks()

v, shown, terminal = open_viewer_recording(
    [dem, "--size", "640x360", "--screenshot-dir", scratch], say=print)
for stage in ("reading DEM", "error tables"):
    percents = [int(m) for t in shown for m in re.findall(stage + r" +(\d+) %", t)]
    lines = re.findall(r"geomipmap-view: " + stage + r" +(\d+) %", terminal)
    check(any(0 < p < 100 for p in percents) and percents[-1] == 100,
          f"{stage}: the window showed progress between 0 and 100 % ({percents})")
    check(any(0 < int(p) < 100 for p in lines) and lines[-1] == "100",
          f"{stage}: the terminal showed progress between 0 and 100 % ({lines})")

mapper = v.mapper
cli.play(v, stream(drag(320, 180, 380, 160), key("plus")))
check(mapper.GetPixelError() == 2.0, f"'+': tau {mapper.GetPixelError()}")
cli.play(v, stream(key("f"), keys("Up", "Up"), drag(320, 180, 340, 190), key("f")))
check(v.mode == "orbit" and mapper.GetNumberOfRenderedTriangles() > 0,
      f"fly and back: {mapper.GetNumberOfRenderedTriangles()} triangles")
check_within_tau(check, v.image, v.renderer, v.actor, mapper, "N48W125 final frame",
                 uncovered_ok=True)
check.exit()
