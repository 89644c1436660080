"""geomipmap-view on bad input: every case exits 2 with ONE line on stderr naming the
problem (and the file where there is one), never a traceback or VTK's multi-line dumps.

Bad DEM files (missing, empty, garbage, a colour PNG without --terrain-rgb), nonsense
option values (shared with geomipmap-fly through command.py), the viewer's own options
(--play, --record, --screenshot-dir) and a missing X display. The command is run as a
user runs it (the launcher), under the test's Xvfb display except in the no-display case.
Usage: TestViewerBadInput.py GEOMIPMAP_VIEW SCRATCH_DIR
"""

import os
import subprocess

from flytestutil import bad_dem_files, check, run, setup
from gmmdata import optional_data_file

exe, out = setup()
garbage, empty = bad_dem_files(out)
a_file = os.path.join(out, "a_file.txt")
with open(a_file, "w") as f:
    f.write("not a folder\n")
events = os.path.join(out, "events.log")
with open(events, "w") as f:
    f.write("# StreamVersion 1.1\n")
small = ["--synthetic-size", "65", "--size", "64x64"]
nope = os.path.join(out, "nope.tif")

# case -> (arguments, words the error line must hold)
cases = {
    "missing DEM": ([nope], [nope, "not found"]),
    "garbage DEM": ([garbage], [garbage]),
    "empty DEM": ([empty], [empty]),
    "two DEMs": ([garbage, empty], ["unrecognized"]),
    "tau -1": (["--tau", "-1"], ["--tau"]),
    "tau nan": (["--tau", "nan"], ["--tau"]),
    "fps 0": (["--fps", "0"], ["--fps"]),
    "fps nan": (["--fps", "nan"], ["--fps"]),
    "size junk": (["--size", "big"], ["--size"]),
    "size 0x5": (["--size", "0x5"], ["--size"]),
    "block size 48": (["--block-size", "48"], ["--block-size", "4..1024"]),
    "synthetic size 1": (["--synthetic-size", "1"], ["--synthetic-size"]),
    "unknown option": (["--bogus"], ["--bogus"]),
    "colour name": (["--color", "rainbow"], ["rainbow"]),
    "missing texture": (["--color", "texture:" + nope.replace(".tif", ".png")] + small,
                        ["nope.png"]),
    "missing event stream": (["--play", nope + ".log"], [nope + ".log", "not found"]),
    "play and record": (["--play", events, "--record", events + "2"], ["--play", "--record"]),
    "record under a file": (["--record", os.path.join(a_file, "s.log")] + small,
                            [os.path.join(a_file, "s.log"), "not a folder"]),
    "screenshot dir is a file": (["--screenshot-dir", a_file] + small, [a_file]),
    "screenshot dir under a file": (["--screenshot-dir", os.path.join(a_file, "x")] + small,
                                    [a_file, "not a folder"]),
}
rgb = optional_data_file("fuji_terrain_rgb.png")
if rgb:
    cases["RGB PNG without --terrain-rgb"] = ([rgb], [rgb])

failures = []


def one_line_exit_2(name, rc, se, words):
    lines = [ln for ln in se.splitlines() if ln.strip()]
    missing = [w for w in words if not lines or w not in lines[0]]
    ok = (rc == 2 and len(lines) == 1 and "Traceback" not in se and not missing
          and lines[0].startswith("geomipmap-view: error:"))
    print(f"{'ok  ' if ok else 'FAIL'} {name}: rc {rc}: {se.strip()[:200]!r}"
          + (f" (lacks {missing})" if missing else ""))
    if not ok:
        failures.append(name)


for name, (args, words) in cases.items():
    # --play an empty stream: a case wrongly accepted ends instead of waiting for a user.
    extra = [] if "--play" in args or "--record" in args else ["--play", events]
    rc, so, se = run(exe, *args, *extra, timeout=120)
    one_line_exit_2(name, rc, se, words)

env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
p = subprocess.run([exe] + small + ["--play", events], capture_output=True, text=True,
                   timeout=60, env=env)
one_line_exit_2("no X display", p.returncode, p.stderr, ["DISPLAY", "xvfb-run"])

check(not failures, f"{len(failures)} case(s) failed: {', '.join(failures)}")
check(not [f for f in os.listdir(out) if f.endswith(".png")], "a failed run wrote a screenshot")
print(f"TestViewerBadInput: passed ({len(cases) + 1} cases)")
