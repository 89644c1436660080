"""Seeded mutation fuzzing of geomipmap-fly's waypoint parser, in-process (no rendering).

Every input goes straight to geomipmap.flight.waypoints.parse_waypoints, the parser behind
read_waypoints (which only adds reading the file: no disk I/O per input here). The outcome
must be a valid Path (at least 2 waypoints, all finite, all on the terrain) or a FlightError
whose text is one printable line naming the file; any other exception fails the test, and
the input that raised it is saved for replay.

Inputs: the valid (more often) and malformed files of waypointcases.py, mutated 1 to 4 times each (bit
flips, random and "interesting" bytes, inserted separators, quotes, newlines and tokens such
as NaN, 1e400, a 5000-digit integer or a byte order mark, long runs of '[' or '{', deleted,
duplicated and spliced ranges, truncation, a swapped .csv/.json name), plus random JSON
documents (random structures, and waypoint lists with random keys and values). Terrain
local or geographic, --clearance on or off, all drawn from the same seeded generator.

Usage: TestFlyWaypointFuzz.py SCRATCH_DIR [ITERATIONS [SEED]]   (default 15000, 1)
Replay a saved failure: read_waypoints() on SCRATCH_DIR/failure-N.csv|json (the line
printed for it gives the terrain and clearance).
"""

import json
import os
import random
import shutil
import sys
import time
import traceback

import numpy as np

from geomipmap.flight import FlightError, Path
from geomipmap.flight.waypoints import parse_waypoints
from waypointcases import BAD, GOOD, make_terrain

scratch = sys.argv[1]
iterations = int(sys.argv[2]) if len(sys.argv) > 2 else 15000
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)

KEYS = ["x", "y", "lon", "lat", "agl", "z", "alt", "X", " y ", "LAT", "", "waypoints", "name"]
TOKENS = [b",", b'"', b"\n", b"\r\n", b"\r", b"#", b" ", b"\t", b"\x00", b"\xff", b"\xc3",
          b"\xef\xbb\xbf", b"{", b"}", b"[", b"]", b":", b'""', b",,,", b"nan", b"-inf",
          b"Infinity", b"NaN", b"1e400", b"-0", b"1" + b"0" * 400, b"1" + b"0" * 5000,
          b"true", b"null", b"[]", b"{}", b'"x"', b'"waypoints"', b"x", b"lon", b"agl",
          b"1e308", b"5e-324", b"0x10", b"1_000", b"\\u0000", b"\\ud800", b"\xe2\x80\xa8"]


def content_bytes(content):
    return content.encode("utf-8") if isinstance(content, str) else content


GOOD_SEEDS = [(f, content_bytes(c)) for f, c, *_ in GOOD.values()]
SEEDS = GOOD_SEEDS + [(f, content_bytes(c)) for f, c, *_ in BAD.values()]


def mutate(rng, data):
    """One random edit of data (bytes) -> bytes."""
    b = bytearray(data)
    op = rng.randrange(9)
    at = rng.randint(0, len(b))
    if op == 0 and b:  # flip a bit
        i = rng.randrange(len(b))
        b[i] ^= 1 << rng.randrange(8)
    elif op == 1 and b:  # any byte
        b[rng.randrange(len(b))] = rng.randrange(256)
    elif op == 2:  # a separator, quote, newline or token
        b[at:at] = rng.choice(TOKENS)
    elif op == 3 and b:  # delete a range
        b[at:at + rng.randint(1, 16)] = b""
    elif op == 4 and b:  # duplicate a range elsewhere
        i = rng.randrange(len(b))
        b[at:at] = b[i:i + rng.randint(1, 64)]
    elif op == 5:  # truncate
        del b[at:]
    elif op == 6:  # a long run of one byte: deep JSON nesting, huge fields
        b[at:at] = bytes([rng.choice(b'[{0,"9 ')]) * rng.choice((2000, 20000, 200000))
    elif op == 7:  # splice in part of another seed
        other = rng.choice(SEEDS)[1]
        i = rng.randint(0, len(other))
        b[at:] = other[i:]
    else:  # replace a byte by a token
        b[at:at + 1] = rng.choice(TOKENS)
    return bytes(b)


def random_value(rng, depth=0):
    """A random JSON value, mostly numbers near the terrain."""
    r = rng.random()
    if depth < 3 and r < 0.08:
        return [random_value(rng, depth + 1) for _ in range(rng.randrange(4))]
    if depth < 3 and r < 0.14:
        return {rng.choice(KEYS): random_value(rng, depth + 1) for _ in range(rng.randrange(4))}
    return rng.choice([
        lambda: rng.uniform(-100.0, 2100.0),
        lambda: rng.randint(-10, 2000),
        lambda: str(rng.uniform(0.0, 1900.0)),
        lambda: rng.uniform(0.9, 1.1) if rng.random() < 0.5 else rng.uniform(41.9, 42.1),
        lambda: rng.choice([float("nan"), float("inf"), -float("inf"), 1e308, -0.0, 5e-324]),
        lambda: 10 ** rng.choice((20, 400, 5000)),
        lambda: rng.choice([True, False, None, "", "abc", " 12 ", "1e400", "nan"]),
    ])()


def random_json(rng):
    """A random JSON document: a waypoint list (perhaps wrapped) or any structure."""
    if rng.random() < 0.25:
        doc = random_value(rng)
    else:
        names = (rng.sample(KEYS, rng.randint(1, 5)) if rng.random() < 0.5
                 else ["x", "y", rng.choice(["agl", "z", "alt"])])
        rows = [{k: random_value(rng) for k in rng.sample(names, rng.randint(0, len(names)))}
                for _ in range(rng.randrange(6))]
        if rng.random() < 0.1:
            rows.insert(rng.randint(0, len(rows)), random_value(rng))
        doc = {"waypoints": rows} if rng.random() < 0.3 else rows
    old = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)  # let json.dumps write the 5000-digit integers
    try:
        return json.dumps(doc, allow_nan=True).encode("utf-8")
    finally:
        sys.set_int_max_str_digits(old)


def check_path(p, heights):
    """The properties every accepted path must have; returns what is wrong, or None."""
    if not isinstance(p, Path):
        return f"returned {type(p).__name__}, not a Path"
    if p.xy.ndim != 2 or p.xy.shape[1:] != (2,) or len(p.xy) < 2:
        return f"xy has shape {p.xy.shape}"
    if p.height.shape != (len(p.xy),):
        return f"{len(p.height)} heights for {len(p.xy)} waypoints"
    if not (np.isfinite(p.xy).all() and np.isfinite(p.height).all()):
        return "non-finite coordinate or height"
    if not all(heights.contains(x, y) for x, y in p.xy):
        return "a waypoint outside the terrain"
    return None


terrain = {False: make_terrain(False), True: make_terrain(True)}
rng = random.Random(seed)
outcomes = {"path": 0, "FlightError": 0}
failures = []
start = time.perf_counter()
for it in range(iterations):
    if rng.random() < 0.15:
        name, data = "wp.json", random_json(rng)
    else:
        name, data = rng.choice(GOOD_SEEDS if rng.random() < 0.6 else SEEDS)
        for _ in range(rng.choice((1, 1, 2, 3, 4))):
            data = mutate(rng, data)
        name = "wp" + os.path.splitext(name)[1]
        if rng.random() < 0.1:
            name = "wp.csv" if name.endswith(".json") else "wp.json"
    geo = rng.random() < 0.3
    clearance = 120.0 if rng.random() < 0.2 else None
    path = os.path.join(scratch, name)  # named in messages; written only on failure
    heights = terrain[geo]
    problem = None
    try:
        problem = check_path(parse_waypoints(data, path, heights, clearance), heights)
        outcomes["path"] += 1
    except FlightError as e:
        text = str(e)
        if path not in text or not text.isprintable() or len(text) > 1000:
            problem = f"FlightError is not one short printable line naming the file: {text[:300]!r}"
        outcomes["FlightError"] += 1
    except Exception as e:  # noqa: BLE001: any other exception is the bug we look for
        problem = f"{type(e).__name__}: {str(e)[:200]}\n" + traceback.format_exc(limit=4)
    if problem:
        keep = os.path.join(scratch, f"failure-{len(failures) + 1}{os.path.splitext(name)[1]}")
        with open(keep, "wb") as f:
            f.write(data)
        failures.append(it)
        print(f"FAIL iteration {it} (seed {seed}; geographic terrain {geo}, clearance "
              f"{clearance}; input saved as {keep}, {len(data)} bytes: {data[:120]!r}): {problem}")
        if len(failures) >= 10:
            break
elapsed = time.perf_counter() - start
print(f"{it + 1} inputs in {elapsed:.1f} s ({(it + 1) / elapsed:.0f}/s): {outcomes['path']} "
      f"valid paths, {outcomes['FlightError']} FlightErrors, {len(failures)} failure(s)")
if failures:
    sys.exit(1)
print("TestFlyWaypointFuzz: passed")
