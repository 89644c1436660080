"""geomipmap-fly on bad input: every case exits non-zero with ONE line on stderr.

Missing / empty / garbage DEM files, a DEM the reader refuses, waypoints outside the
terrain or malformed, a --texture that cannot be placed, and nonsense option values. No case may print a traceback or VTK's
multi-line error dumps. Malformed waypoint files (issue #16 item 6) must also exit 2
("bad input", not 1 "internal error") with a line naming the file and the problem: the
CSV line or the JSON waypoint number where it is. Every malformed waypoint file of
waypointcases.py is checked in-process by TestFlyWaypointFiles; the few here go through the
command (those that used to end in an internal error). Last, a DEM the default path cannot
see (an image without georeference, read with the default spacing and height scale) flies
without error but must be told why nothing was drawn.
"""

import os

import numpy as np

import demfiles
from flytestutil import bad_dem_files, check, run, setup
from gmmdata import optional_data_file
from waypointcases import BAD, THROUGH_COMMAND, write

exe, out = setup()
garbage, empty = bad_dem_files(out)
outside = os.path.join(out, "outside.csv")
with open(outside, "w") as f:
    f.write("x,y,agl\n100,100,50\n1e7,100,50\n")
nocols = os.path.join(out, "nocols.csv")
with open(nocols, "w") as f:
    f.write("a,b\n1,2\n3,4\n")
notnum = os.path.join(out, "notnum.csv")
with open(notnum, "w") as f:
    f.write("x,y,z\n100,100,abc\n200,200,300\n")
badjson = os.path.join(out, "bad.json")
with open(badjson, "w") as f:
    f.write("{not json")
geo_on_synth = os.path.join(out, "geo.csv")
with open(geo_on_synth, "w") as f:
    f.write("lon,lat,agl\n1.0,42.1,100\n1.1,42.2,100\n")


ortho = demfiles.tiff(os.path.join(out, "ortho.tif"), np.zeros((8, 8, 3), np.uint8), rgb=True)
nocrs = demfiles.tiff(os.path.join(out, "nocrs.tif"), np.zeros((8, 8), np.float32), georef=None)

small = ["--synthetic-size", "65", "--frames", "2", "--size", "64x64", "--out",
         os.path.join(out, "o")]
cases = {
    "missing DEM": ["--dem", os.path.join(out, "nope.tif")],
    "garbage DEM": ["--dem", garbage],
    "empty DEM": ["--dem", empty],
    "waypoint outside": ["--waypoints", outside] + small,
    "waypoint columns": ["--waypoints", nocols] + small,
    "waypoint not numeric": ["--waypoints", notnum] + small,
    "waypoint bad JSON": ["--waypoints", badjson] + small,
    "lon/lat on synthetic": ["--waypoints", geo_on_synth] + small,
    "missing waypoints": ["--waypoints", os.path.join(out, "nope.csv")],
    "tau -1": ["--tau", "-1"],
    "tau nan": ["--tau", "nan"],
    "size 0x5": ["--size", "0x5"],
    "size junk": ["--size", "big"],
    "frames 0": ["--frames", "0"],
    "frames and seconds": ["--frames", "3", "--seconds", "2"],
    "seconds 0": ["--seconds", "0"],
    "block size 48": ["--block-size", "48"],
    "pitch 100": ["--pitch", "100"],
    "every 0": ["--every", "0"],
    "synthetic size 1": ["--synthetic-size", "1"],
    "path spiral": ["--path", "spiral"],
    "unknown option": ["--bogus"],
    "missing texture": ["--color", "texture:" + os.path.join(out, "nope.png")] + small,
    "colour name": ["--color", "rainbow"],
    "fill distance without --fill-voids": ["--fill-distance", "10"] + small,
    "fill smoothing without --fill-voids": ["--fill-smoothing", "2"] + small,
    "fill distance -1": ["--fill-voids", "--fill-distance", "-1"] + small,
    "fill distance inf": ["--fill-voids", "--fill-distance", "inf"] + small,
    "fill smoothing 1001": ["--fill-voids", "--fill-smoothing", "1001"] + small,
    "fill smoothing -1": ["--fill-voids", "--fill-smoothing", "-1"] + small,
    "texture missing": ["--texture", os.path.join(out, "nope.tif")] + small,
    "texture and --color texture": ["--texture", garbage, "--color", "texture:" + garbage] + small,
    "texture on the synthetic terrain": ["--texture", ortho] + small,
    "texture not an image": ["--texture", garbage, "--dem", nocrs] + small[2:],
    "texture on a DEM without CRS": ["--texture", ortho, "--dem", nocrs] + small[2:],
    "texture size 20000": ["--texture-size", "20000"] + small,
}
expected = {  # case -> words its error line must hold
    "fill distance without --fill-voids": ["--fill-distance", "needs --fill-voids"],
    "fill smoothing without --fill-voids": ["--fill-smoothing", "needs --fill-voids"],
    "fill distance -1": ["--fill-distance"],
    "fill smoothing 1001": ["--fill-smoothing", "0..1000"],
    "texture missing": ["nope.tif"],
    "texture and --color texture": ["not both"],
    "texture on the synthetic terrain": ["--texture needs a georeferenced DEM"],
    "texture not an image": [garbage, "not an image"],
    "texture on a DEM without CRS": [ortho, "no CRS"],
    "texture size 20000": ["16384"],
}
for name in THROUGH_COMMAND:
    filename, content, words = BAD[name]
    path = write(out, filename, content)
    cases[f"waypoints: {name}"] = ["--waypoints", path] + small
    expected[f"waypoints: {name}"] = [path] + words
rgb = optional_data_file("fuji_terrain_rgb.png")
if rgb:
    cases["RGB PNG without --terrain-rgb"] = ["--dem", rgb] + small[2:]

failures = []
for name, args in cases.items():
    if "--out" not in args:
        args = args + ["--out", os.path.join(out, "o")]
    rc, so, se = run(exe, *args, timeout=120)
    lines = [ln for ln in se.splitlines() if ln.strip()]
    ok = (rc != 0 and len(lines) == 1 and "Traceback" not in se
          and lines[0].startswith("geomipmap-fly: error:"))
    if name in expected:  # exit 2 and a line that says where and what
        missing = [w for w in expected[name] if w not in lines[0]] if lines else ["(no line)"]
        ok = ok and rc == 2 and not missing
        if missing:
            print(f"     {name}: the error line lacks {missing}")
    print(f"{'ok  ' if ok else 'FAIL'} {name}: rc {rc}: {se.strip()[:160]!r}")
    if not ok:
        failures.append(name)
check(not failures, f"{len(failures)} case(s) failed: {', '.join(failures)}")

# A flight that sees nothing is not an error, but must say why: a 16-bit PNG read with the
# default spacing (1 m) and height scale (1) is 64 m wide and 60 km high, so the path flies
# far above it. With its spacing and height scale it is drawn, and nothing is said.
tall = demfiles.png16(os.path.join(out, "tall.png"),
                      (np.random.default_rng(3).random((65, 65)) * 60000).astype(np.uint16))
warned = ["--dem", tall, "--frames", "2", "--size", "64x64", "--no-frames", "--out", os.path.join(out, "w")]
rc, so, se = run(exe, *warned, timeout=120)
check(rc == 0 and "no frame drew any terrain" in se and "--spacing" in se and "--height-scale" in se,
      f"a flight that draws nothing warns with the options to set (rc {rc}): {se.strip()[:300]!r}")
rc, so, se = run(exe, *warned, "--spacing", "100", "--height-scale", "0.01", timeout=120)
check(rc == 0 and "no frame drew any terrain" not in se,
      f"the same DEM with its spacing and height scale draws without the warning (rc {rc}): {se.strip()[:300]!r}")
check(not os.path.exists(os.path.join(out, "o")), "a failed run created its output folder")
print(f"TestFlyBadInput: passed ({len(cases)} cases)")
