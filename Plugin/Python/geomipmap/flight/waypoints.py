"""Waypoint files (CSV or JSON) -> a Path in the terrain's metres.

Why so strict: a waypoint file is typed or exported by hand, so every malformed one must
end in one line that names the file and the CSV line or JSON waypoint where it goes
wrong (FlightError), never a traceback; Testing/Python/TestFlyWaypointFiles.py holds
every case and TestFlyWaypointFuzz.py mutates them.
"""

import csv
import io
import json
import math
import os

from .heights import FlightError, GeoFrame, as_heights
from .paths import points_path

GEO_KEYS = ("lon", "lat")
LOCAL_KEYS = ("x", "y")
HEIGHT_KEYS = ("agl", "z", "alt")  # agl: above ground; z / alt: absolute metres


def read_waypoints(filename, terrain, clearance=None):
    """Read a CSV (header row) or JSON waypoint file into a Path in the terrain's metres.

    See parse_waypoints for the format; this only reads the file's bytes.
    """
    if not os.path.isfile(filename):
        raise FlightError(f"waypoint file not found: {filename}")
    try:
        with open(filename, "rb") as f:
            data = f.read()
    except OSError as e:
        raise FlightError(f"cannot read waypoint file {filename}: {e.strerror}") from None
    return parse_waypoints(data, filename, terrain, clearance)


def parse_waypoints(data, filename, terrain, clearance=None):
    """The bytes of a waypoint file -> Path in the terrain's metres; FlightError if malformed.

    terrain: Heights, a vtkImageData or an algorithm producing one (as_heights).
    filename names the file in messages and picks the format (.json: JSON, else CSV).
    Text is UTF-8, with or without a byte order mark. Columns / keys: x, y (metres, the
    image's frame) or lon, lat (degrees WGS84, converted like the reader does, see
    GeoFrame); then one of agl (metres above the ground under the camera), z or alt
    (absolute metres, the DEM's height datum). Names are case-insensitive and must be
    unique; other columns are ignored. clearance (not None) overrides the heights with a
    constant clearance (terrain following). CSV: a header row, then one waypoint a row,
    each with as many fields as the header; blank lines and lines starting with # are
    skipped. JSON: a list of objects with those keys, or {"waypoints": [...]}; values are
    numbers (or numeric strings). Messages name the CSV line or the JSON waypoint number.
    """
    heights = as_heights(terrain)
    text = _decode(data, filename)
    if filename.lower().endswith(".json"):
        rows = _json_rows(text, filename)
    else:
        rows = _csv_rows(text, filename)
    if len(rows) < 2:
        raise FlightError(f"{filename}: need at least 2 waypoints, found {len(rows)}")
    keys = set(rows[0][1])
    if all(k in keys for k in GEO_KEYS):
        pos = GEO_KEYS
        try:
            frame = GeoFrame(heights)
        except FlightError as e:
            raise FlightError(f"{filename}: {e}") from None
    elif all(k in keys for k in LOCAL_KEYS):
        pos, frame = LOCAL_KEYS, None
    else:
        raise FlightError(f"{filename}: need columns x,y (metres) or lon,lat (degrees); "
                          f"found {_shown(','.join(sorted(keys)), 80) if keys else 'none'}")
    hkey = next((k for k in HEIGHT_KEYS if k in keys), None)
    if hkey is None and clearance is None:
        raise FlightError(f"{filename}: need a height column agl (above ground) or z/alt "
                          "(absolute metres), or give a clearance (--clearance)")

    def points():  # row by row: a row's numbers are checked before the next row's
        for where, row in rows:
            a, b = (_number(row, k, f"{filename}: {where}") for k in pos)
            h = _number(row, hkey, f"{filename}: {where}") if hkey else 0.0
            yield where, a, b, h

    return points_path(points(), heights, frame, hkey == "agl", clearance, f"{filename}: ")


def _decode(data, filename):
    """UTF-8 (a leading byte order mark, as spreadsheets write it, is dropped)."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        raise FlightError(f"cannot read waypoint file {filename}: line {line} is not UTF-8 "
                       f"text (byte 0x{data[e.start]:02x})") from None


def _csv_rows(text, filename):
    """CSV text -> [(where, {column: field})]; where names the waypoint and its line."""
    # Line numbers are the file's (as an editor shows them), so skipped lines are counted.
    kept = [(n, ln) for n, ln in enumerate(io.StringIO(text, newline=""), start=1)
            if ln.strip() and not ln.lstrip().startswith("#")]
    reader = csv.reader(ln for _, ln in kept)
    header, rows, used = None, [], 0
    try:
        for fields in reader:
            line, used = kept[used][0], reader.line_num  # a quoted field may span lines
            if header is None:
                header = [f.strip().lower() for f in fields]
                _unique([(h, None) for h in header], f"{filename}: line {line}: column")
                continue
            if len(fields) != len(header):
                raise FlightError(f"{filename}: line {line} has {len(fields)} fields, "
                               f"the header has {len(header)}")
            where = f"waypoint {len(rows) + 1} (line {line})"
            rows.append((where, {h: f.strip() for h, f in zip(header, fields) if h}))
    except csv.Error as e:
        line = kept[min(used, len(kept) - 1)][0]
        raise FlightError(f"cannot read waypoint file {filename}: line {line}: {e}") from None
    return rows


class _Object(tuple):
    """A JSON object as its (key, value) pairs, so that repeated keys can be reported."""


def _json_rows(text, filename):
    """JSON text -> [(where, {key: value})]; where names the waypoint by its number."""
    try:
        # Integers as floats: a 400-digit one is then out of range like 1e400, not an
        # OverflowError, and Python's 4300-digit limit on int() never applies.
        data = json.loads(text, object_pairs_hook=_Object, parse_int=float)
    except json.JSONDecodeError as e:
        raise FlightError(f"cannot read waypoint file {filename}: {e}") from None
    except RecursionError:
        raise FlightError(f"cannot read waypoint file {filename}: JSON nested too deeply") from None
    if isinstance(data, _Object):
        data = dict(data).get("waypoints")
    if not isinstance(data, list):
        raise FlightError(f"{filename}: expected a list of waypoint objects "
                       "(or {\"waypoints\": [...]})")
    rows = []
    for n, item in enumerate(data, start=1):
        where = f"waypoint {n}"
        if not isinstance(item, _Object):
            raise FlightError(f"{filename}: {where} is not an object: {_shown(item)}")
        pairs = [(str(k).strip().lower(), v) for k, v in item]
        rows.append((where, _unique(pairs, f"{filename}: {where}: key")))
    return rows


def _unique(pairs, context):
    """dict(pairs) without empty names; FlightError if a name appears twice."""
    out = {}
    for name, value in pairs:
        if name in out:
            raise FlightError(f"{context} {_shown(name)} appears twice")
        if name:
            out[name] = value
    return out


def _number(row, key, context):
    """row[key] as a finite float: a JSON number or a numeric string (not true/false)."""
    if key not in row:
        raise FlightError(f"{context} has no {key}")
    value = row[key]
    try:
        if isinstance(value, str):
            v = float(value.strip())
        elif isinstance(value, float):
            v = value
        else:  # true/false, null, a list or an object
            raise ValueError
    except ValueError:
        raise FlightError(f"{context}: {key} is not a number: {_shown(value)}") from None
    if not math.isfinite(v):
        raise FlightError(f"{context}: {key} is non-finite or out of range: {_shown(value)}")
    return v


def _shown(value, limit=40):
    """A value (from the file) as a short, one-line quote for an error message."""
    if isinstance(value, _Object):
        text = "an object"
    elif isinstance(value, list):
        text = "a list"
    elif value is None or isinstance(value, bool):
        text = json.dumps(value)
    else:
        text = repr(value)  # escapes newlines and control characters
    return text if len(text) <= limit else text[:limit - 3] + "..."
