"""Camera paths for geomipmap-fly: orbit, line, waypoint files; constant speed; heights.

Why: the LOD statistics of a flight are only comparable between runs if the camera
position depends on the frame number alone (as in the NDL paper's test flight), so a path
is a dense polyline parametrised by arc length, sampled at equal distances per frame.
Heights either come from the path (absolute) or follow the terrain with a clearance; the
ground profile is smoothed so that the camera does not jitter, and never dips below the
clearance at the sampled points (running maximum, then a moving average narrower than it).
"""

import csv
import io
import json
import math
import os

import numpy as np

from .errors import AppError
from .terrain import GeoFrame

GEO_KEYS = ("lon", "lat")
LOCAL_KEYS = ("x", "y")
HEIGHT_KEYS = ("agl", "z", "alt")  # agl: above ground; z / alt: absolute metres


class Path:
    """A 3D polyline; heights are absolute (z) or above ground (agl) per vertex."""

    def __init__(self, xy, height, above_ground, closed=False, look_yaw=0.0):
        self.look_yaw = look_yaw  # degrees to the left of "ahead" (orbit: towards the centre)
        self.xy = np.asarray(xy, float)
        self.height = np.asarray(height, float)
        self.above_ground = above_ground
        self.closed = closed


def default_altitude(heights):
    """A flight altitude above the highest summit, scaled with the terrain's extent."""
    xmin, xmax, ymin, ymax = heights.bounds
    extent = min(xmax - xmin, ymax - ymin)
    relief = heights.zmax - heights.zmin
    return heights.zmax + max(0.04 * extent, 0.3 * relief, 10.0)


def orbit_path(heights, clearance):
    """A circle around the centre, radius 35 % of the smaller extent."""
    xmin, xmax, ymin, ymax = heights.bounds
    cx, cy = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
    r = 0.35 * min(xmax - xmin, ymax - ymin)
    t = np.linspace(0.0, 2 * math.pi, 721)  # counter-clockwise; last == first
    xy = np.column_stack([cx + r * np.cos(t), cy + r * np.sin(t)])
    path = _flat(xy, heights, clearance, closed=True)
    path.look_yaw = 20.0  # counter-clockwise: a little inwards keeps the DEM's edge out of view
    return path


def line_path(heights, clearance):
    """A straight line across, south-west to north-east, 10 % in from the edges."""
    xmin, xmax, ymin, ymax = heights.bounds
    wx, wy = xmax - xmin, ymax - ymin
    xy = [(xmin + 0.1 * wx, ymin + 0.1 * wy), (xmax - 0.1 * wx, ymax - 0.1 * wy)]
    return _flat(xy, heights, clearance, closed=False)


def _flat(xy, heights, clearance, closed):
    if clearance is not None:
        return Path(xy, np.full(len(xy), clearance), True, closed)
    return Path(xy, np.full(len(xy), default_altitude(heights)), False, closed)


def read_waypoints(filename, image, heights, clearance):
    """Read a CSV (header row) or JSON waypoint file into a Path in local metres.

    See parse_waypoints for the format; this only reads the file's bytes.
    """
    if not os.path.isfile(filename):
        raise AppError(f"waypoint file not found: {filename}")
    try:
        with open(filename, "rb") as f:
            data = f.read()
    except OSError as e:
        raise AppError(f"cannot read waypoint file {filename}: {e.strerror}") from None
    return parse_waypoints(data, filename, image, heights, clearance)


def parse_waypoints(data, filename, image, heights, clearance):
    """The bytes of a waypoint file -> Path in local metres; AppError if malformed.

    filename names the file in messages and picks the format (.json: JSON, else CSV).
    Text is UTF-8, with or without a byte order mark. Columns / keys: x, y (local metres,
    the image's frame) or lon, lat (degrees WGS84, converted like the reader does, see
    terrain.GeoFrame); then one of agl (metres above the ground under the camera), z or alt
    (absolute metres, the DEM's height datum). Names are case-insensitive and must be
    unique; other columns are ignored. --clearance (clearance not None) overrides the
    heights with a constant clearance. CSV: a header row, then one waypoint a row, each
    with as many fields as the header; blank lines and lines starting with # are skipped.
    JSON: a list of objects with those keys, or {"waypoints": [...]}; values are numbers
    (or numeric strings). Messages name the CSV line or the JSON waypoint number.
    """
    text = _decode(data, filename)
    if filename.lower().endswith(".json"):
        rows = _json_rows(text, filename)
    else:
        rows = _csv_rows(text, filename)
    if len(rows) < 2:
        raise AppError(f"{filename}: need at least 2 waypoints, found {len(rows)}")
    keys = set(rows[0][1])
    if all(k in keys for k in GEO_KEYS):
        pos = GEO_KEYS
        try:
            frame = GeoFrame(image, heights)
        except AppError as e:
            raise AppError(f"{filename}: {e}") from None
    elif all(k in keys for k in LOCAL_KEYS):
        pos, frame = LOCAL_KEYS, None
    else:
        raise AppError(f"{filename}: need columns x,y (metres) or lon,lat (degrees); "
                       f"found {_shown(','.join(sorted(keys)), 80) if keys else 'none'}")
    hkey = next((k for k in HEIGHT_KEYS if k in keys), None)
    if hkey is None and clearance is None:
        raise AppError(f"{filename}: need a height column agl (above ground) or z/alt "
                       "(absolute metres), or give --clearance")
    xy, hs = [], []
    for where, row in rows:
        a, b = (_number(row, k, f"{filename}: {where}") for k in pos)
        h = _number(row, hkey, f"{filename}: {where}") if hkey else 0.0
        x, y = frame.to_local(a, b) if frame else (a, b)
        if not heights.contains(x, y):
            at = f"lon {a:g} lat {b:g}" if frame else f"x {a:g} y {b:g}"
            raise AppError(f"{filename}: {where} at {at} is outside the terrain")
        xy.append((x, y))
        hs.append(h)
    if clearance is not None:
        return Path(xy, np.full(len(xy), clearance), True)
    return Path(xy, hs, hkey == "agl")


def _decode(data, filename):
    """UTF-8 (a leading byte order mark, as spreadsheets write it, is dropped)."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        raise AppError(f"cannot read waypoint file {filename}: line {line} is not UTF-8 "
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
                raise AppError(f"{filename}: line {line} has {len(fields)} fields, "
                               f"the header has {len(header)}")
            where = f"waypoint {len(rows) + 1} (line {line})"
            rows.append((where, {h: f.strip() for h, f in zip(header, fields) if h}))
    except csv.Error as e:
        line = kept[min(used, len(kept) - 1)][0]
        raise AppError(f"cannot read waypoint file {filename}: line {line}: {e}") from None
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
        raise AppError(f"cannot read waypoint file {filename}: {e}") from None
    except RecursionError:
        raise AppError(f"cannot read waypoint file {filename}: JSON nested too deeply") from None
    if isinstance(data, _Object):
        data = dict(data).get("waypoints")
    if not isinstance(data, list):
        raise AppError(f"{filename}: expected a list of waypoint objects "
                       "(or {\"waypoints\": [...]})")
    rows = []
    for n, item in enumerate(data, start=1):
        where = f"waypoint {n}"
        if not isinstance(item, _Object):
            raise AppError(f"{filename}: {where} is not an object: {_shown(item)}")
        pairs = [(str(k).strip().lower(), v) for k, v in item]
        rows.append((where, _unique(pairs, f"{filename}: {where}: key")))
    return rows


def _unique(pairs, context):
    """dict(pairs) without empty names; AppError if a name appears twice."""
    out = {}
    for name, value in pairs:
        if name in out:
            raise AppError(f"{context} {_shown(name)} appears twice")
        if name:
            out[name] = value
    return out


def _number(row, key, context):
    """row[key] as a finite float: a JSON number or a numeric string (not true/false)."""
    if key not in row:
        raise AppError(f"{context} has no {key}")
    value = row[key]
    try:
        if isinstance(value, str):
            v = float(value.strip())
        elif isinstance(value, float):
            v = value
        else:  # true/false, null, a list or an object
            raise ValueError
    except ValueError:
        raise AppError(f"{context}: {key} is not a number: {_shown(value)}") from None
    if not math.isfinite(v):
        raise AppError(f"{context}: {key} is non-finite or out of range: {_shown(value)}")
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


class Flight:
    """Camera positions and look-at points per frame, at constant speed along a Path."""

    def __init__(self, path, heights, frames, pitch_deg, clearance_smoothing=None):
        xy = path.xy
        seg = np.hypot(*np.diff(xy, axis=0).T)
        keep = np.concatenate([[True], seg > 1e-9])
        xy, hgt = xy[keep], path.height[keep]
        if len(xy) < 2:
            raise AppError("the flight path has zero length")
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])
        self.length = float(s[-1])
        # Dense profile at 1/4 sample spacing: frame-count independent heights.
        step = max(0.25 * min(heights.dx, heights.dy), self.length / 50000.0)
        sd = np.linspace(0.0, self.length, max(int(self.length / step) + 1, 2))
        xd = np.column_stack([np.interp(sd, s, xy[:, 0]), np.interp(sd, s, xy[:, 1])])
        hd = np.interp(sd, s, hgt)
        ground = _fill_nan(heights.sample(xd[:, 0], xd[:, 1]), heights.zmin)
        # Smoothing radius (metres of path): a few clearances (a low camera must follow
        # the relief more closely), at least 10 samples, at most 4 % of the path.
        spacing = min(heights.dx, heights.dy)
        typical = float(np.median(hgt)) if path.above_ground else 0.0
        window = clearance_smoothing or min(0.04 * self.length,
                                            max(5.0 * typical, 10.0 * spacing))
        smooth = _smooth_envelope(ground, max(int(window / (sd[1] - sd[0])), 1), path.closed)
        zd = smooth + hd if path.above_ground else np.maximum(hd, smooth + 2.0)
        # Frame stations: a closed path does not repeat its first point at the end.
        n = frames
        if path.closed:
            fs = np.arange(n) * self.length / n
        else:
            fs = np.linspace(0.0, self.length, n) if n > 1 else np.zeros(1)
        self.positions = np.column_stack(
            [np.interp(fs, sd, xd[:, 0]), np.interp(fs, sd, xd[:, 1]), np.interp(fs, sd, zd)])
        self.ground = np.interp(fs, sd, ground)
        # Look ahead along the path (smooths corners): direction to the point L metres on.
        look = min(0.05 * self.length, 2000.0)
        ahead = fs + max(look, 1e-6)
        if path.closed:
            ahead = np.mod(ahead, self.length)
        ax = np.interp(ahead, sd, xd[:, 0])
        ay = np.interp(ahead, sd, xd[:, 1])
        d = np.column_stack([ax - self.positions[:, 0], ay - self.positions[:, 1]])
        # Past the end of an open path: keep the last segment's direction.
        last = xy[-1] - xy[-2]
        norm = np.hypot(d[:, 0], d[:, 1])
        d[norm < 1e-6] = last
        d /= np.hypot(d[:, 0], d[:, 1])[:, None]
        c, s_ = math.cos(math.radians(path.look_yaw)), math.sin(math.radians(path.look_yaw))
        d = np.column_stack([c * d[:, 0] - s_ * d[:, 1], s_ * d[:, 0] + c * d[:, 1]])
        p = math.radians(pitch_deg)
        dist = max(0.1 * self.length, 100.0)
        self.focal = np.column_stack([
            self.positions[:, 0] + dist * math.cos(p) * d[:, 0],
            self.positions[:, 1] + dist * math.cos(p) * d[:, 1],
            self.positions[:, 2] - dist * math.sin(p)])


def _fill_nan(values, fallback):
    """Nodata ground under the path: interpolate from finite neighbours along the path."""
    ok = np.isfinite(values)
    if ok.all():
        return values
    if not ok.any():
        return np.full_like(values, fallback)
    idx = np.arange(len(values))
    return np.interp(idx, idx[ok], values[ok])


def _smooth_envelope(ground, radius, closed):
    """Running max over +-2r, then moving average over +-r: smooth and >= ground."""
    mode = "wrap" if closed else "edge"
    big = 2 * radius
    padded = np.pad(ground, big, mode=mode)
    from numpy.lib.stride_tricks import sliding_window_view

    env = sliding_window_view(padded, 2 * big + 1).max(axis=1)
    padded = np.pad(env, radius, mode=mode)
    kernel = np.ones(2 * radius + 1) / (2 * radius + 1)
    return np.convolve(padded, kernel, mode="valid")
