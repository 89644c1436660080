"""geomipmap-fly on bad input: every case exits non-zero with ONE line on stderr.

Missing / empty / garbage DEM files, a DEM the reader refuses, waypoints outside the
terrain or malformed, and nonsense option values. No case may print a traceback or VTK's
multi-line error dumps. Malformed waypoint files (issue #16 item 6) must also exit 2
("bad input", not 1 "internal error") with a line naming the file and the problem: the
CSV line or the JSON waypoint number where it is.
"""

import os

from flytestutil import check, run, setup

exe, out = setup()
garbage = os.path.join(out, "garbage.tif")
with open(garbage, "wb") as f:
    f.write(b"this is not a raster\n" * 10)
empty = os.path.join(out, "empty.hgt")
open(empty, "wb").close()
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


def waypoint_file(name, content):
    """Write a waypoint file (str: UTF-8, bytes: as is); return its path."""
    path = os.path.join(out, name)
    with open(path, "wb") as f:
        f.write(content.encode("utf-8") if isinstance(content, str) else content)
    return path


# name -> (file name, content, words the error line must hold besides the file name).
# The synthetic 65 x 65 terrain at 30 m spans 0..1920 m: (100, 100) and (200, 200) lie on it.
bad_waypoints = {
    "extra field in a data row": ("extra.csv", "x,y,agl\n100,100,50\n200,200,50,7\n",
                                  ["line 3", "4 fields", "header has 3"]),
    "missing field in a data row": ("short.csv", "x,y,agl\n100,100,50\n200,200\n",
                                    ["line 3", "2 fields", "header has 3"]),
    "empty header": ("emptyheader.csv", ",,\n100,100,50\n200,200,50\n", ["need columns x,y"]),
    "header only": ("headeronly.csv", "x,y,agl\n", ["at least 2 waypoints, found 0"]),
    # A byte order mark (as Excel writes) is not part of the first column's name, so the
    # error is the bad value in line 3, not "no column x".
    "BOM, bad value": ("bom.csv", "\ufeffx,y,agl\n100,100,50\n200,200,abc\n",
                       ["line 3", "agl", "abc"]),
    "BOM JSON, outside": ("bom.json", '\ufeff[{"x": 100, "y": 100, "agl": 5}, '
                          '{"x": 1e7, "y": 100, "agl": 5}]', ["waypoint 2", "outside"]),
    "duplicate column": ("dup.csv", "x,y,x,agl\n100,100,5,50\n200,200,6,50\n",
                         ["column 'x'", "twice"]),
    "duplicate column, other case": ("dupcase.csv", "x,y,X,agl\n100,100,5,50\n200,200,6,50\n",
                                     ["column 'x'", "twice"]),
    "duplicate JSON key": ("dup.json", '[{"x": 100, "y": 100, "x": 5, "agl": 5}, '
                           '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "'x'", "twice"]),
    "non-object JSON row": ("list.json", '[{"x": 100, "y": 100, "agl": 5}, [200, 200, 5]]',
                            ["waypoint 2", "not an object"]),
    "JSON not a list": ("scalar.json", '{"waypoints": 5}', ["list of waypoint objects"]),
    "nested JSON value": ("nested.json", '[{"x": {"v": 100}, "y": 100, "agl": 5}, '
                          '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "x", "not a number"]),
    "JSON list value": ("listvalue.json", '[{"x": 100, "y": [100], "agl": 5}, '
                        '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "y", "not a number"]),
    "JSON boolean value": ("bool.json", '[{"x": 100, "y": 100, "agl": true}, '
                           '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "agl", "not a number"]),
    "JSON row without y": ("noy.json", '[{"x": 100, "y": 100, "agl": 5}, {"x": 200, "agl": 5}]',
                           ["waypoint 2", "no y"]),
    "NaN string": ("nan.csv", "x,y,agl\n100,100,nan\n200,200,50\n", ["line 2", "non-finite"]),
    "Inf string": ("inf.csv", "x,y,agl\n100,100,50\n-Infinity,200,50\n", ["line 3", "non-finite"]),
    "JSON NaN": ("nan.json", '[{"x": NaN, "y": 100, "agl": 5}, {"x": 200, "y": 200, "agl": 5}]',
                 ["waypoint 1", "non-finite"]),
    "huge number": ("huge.csv", "x,y,agl\n100,100,1e400\n200,200,50\n", ["line 2", "non-finite"]),
    "huge JSON integer": ("hugeint.json", '[{"x": 1' + "0" * 400 + ', "y": 100, "agl": 5}, '
                          '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "x", "out of range"]),
    "JSON integer of 5000 digits": ("digits.json", '[{"x": 1' + "0" * 5000 + ', "y": 100}]',
                                    ["cannot read waypoint file"]),
    "JSON nested 100000 deep": ("deep.json", "[" * 100000, ["cannot read waypoint file",
                                                          "nested"]),
    "huge coordinate": ("far.csv", "x,y,agl\n100,100,50\n1e300,200,50\n",
                        ["line 3", "outside the terrain"]),
    "non-UTF-8 bytes": ("latin1.csv", b"x,y,agl\n100,100,50\n200,200,50\xb0\n",
                        ["cannot read waypoint file", "UTF-8", "line 3"]),
    "NUL byte": ("nul.csv", "x,y,agl\n100,100,50\n200,200\x0050\n", ["line 3"]),
}

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
}
expected = {}  # case -> words its error line must hold
for name, (filename, content, words) in bad_waypoints.items():
    path = waypoint_file(filename, content)
    cases[f"waypoints: {name}"] = ["--waypoints", path] + small
    expected[f"waypoints: {name}"] = [path] + words
data = os.environ.get("GEOMIPMAP_DATA_DIR") or os.environ.get("GEOMIPMAP_DATA", "")
rgb = os.path.join(data, "fuji_terrain_rgb.png")
if os.path.isfile(rgb):
    cases["RGB PNG without --terrain-rgb"] = ["--dem", rgb] + small[2:]

failures = []
for name, args in cases.items():
    if "--out" not in args:
        args = args + ["--out", os.path.join(out, "o")]
    rc, so, se = run(exe, *args, timeout=120)
    lines = [ln for ln in se.splitlines() if ln.strip()]
    ok = (rc != 0 and len(lines) == 1 and "Traceback" not in se
          and lines[0].startswith("geomipmap-fly: error:"))
    if name in expected:  # a bad waypoint file: exit 2 and a line that says where and what
        missing = [w for w in expected[name] if w not in lines[0]] if lines else ["(no line)"]
        ok = ok and rc == 2 and not missing
        if missing:
            print(f"     {name}: the error line lacks {missing}")
    print(f"{'ok  ' if ok else 'FAIL'} {name}: rc {rc}: {se.strip()[:160]!r}")
    if not ok:
        failures.append(name)
check(not failures, f"{len(failures)} case(s) failed: {', '.join(failures)}")
check(not os.path.exists(os.path.join(out, "o")), "a failed run created its output folder")
print(f"TestFlyBadInput: passed ({len(cases)} cases)")
