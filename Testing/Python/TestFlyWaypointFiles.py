"""geomipmap-fly waypoint files, in-process (no rendering): every case of waypointcases.py.

Each malformed file must raise FlightError (the command prints it as one line and exits 2)
whose text names the file and holds the case's words; nothing else may escape. Each valid
file must give the expected path in local metres.
Usage: TestFlyWaypointFiles.py SCRATCH_DIR
"""

import os
import shutil
import sys

import numpy as np

from geomipmap.flight import FlightError
from geomipmap.flight.waypoints import read_waypoints
from waypointcases import BAD, GOOD, make_terrain, write

scratch = sys.argv[1]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
terrain = {False: make_terrain(False), True: make_terrain(True)}
failures = []


def fail(name, why):
    print(f"FAIL {name}: {why}")
    failures.append(name)


for name, (filename, content, words) in BAD.items():
    path = write(scratch, filename, content)
    try:
        read_waypoints(path, terrain[False], None)
        fail(name, "accepted")
        continue
    except FlightError as e:
        text = str(e)
    except Exception as e:  # noqa: BLE001: the point of the test
        fail(name, f"{type(e).__name__}: {e!s:.200}")
        continue
    missing = [w for w in [path] + words if w not in text]
    if missing or not text.isprintable():
        fail(name, f"error {text!r} lacks {missing} or is not one printable line")
    else:
        print(f"ok   {name}: {text[len(path):]}")

for name, (filename, content, geo, clearance, xy, heights, agl) in GOOD.items():
    path = write(scratch, filename, content)
    try:
        p = read_waypoints(path, terrain[geo], clearance)
    except Exception as e:  # noqa: BLE001
        fail(name, f"{type(e).__name__}: {e}")
        continue
    got = [tuple(v) for v in p.xy]
    same_xy = len(got) == len(xy) and all(
        want is None or np.allclose(g, want, atol=1e-6) for g, want in zip(got, xy))
    if not same_xy or not np.allclose(p.height, heights) or p.above_ground != agl:
        fail(name, f"got xy {got}, heights {list(p.height)}, above ground {p.above_ground}")
    else:
        print(f"ok   {name}")

if failures:
    print(f"TestFlyWaypointFiles: {len(failures)} case(s) failed: {', '.join(failures)}")
    sys.exit(1)
print(f"TestFlyWaypointFiles: passed ({len(BAD)} malformed, {len(GOOD)} valid files)")
