"""Camera paths for geomipmap-fly: orbit, line, waypoint files; constant speed; heights.

Why: the LOD statistics of a flight are only comparable between runs if the camera
position depends on the frame number alone (as in the NDL paper's test flight), so a path
is a dense polyline parametrised by arc length, sampled at equal distances per frame.
Heights either come from the path (absolute) or follow the terrain with a clearance; the
ground profile is smoothed so that the camera does not jitter, and never dips below the
clearance at the sampled points (running maximum, then a moving average narrower than it).
"""

import csv
import json
import math
import os

import numpy as np

from .errors import FlyError
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

    Columns / keys: x, y (local metres, the image's frame) or lon, lat (degrees WGS84,
    converted like the reader does, see terrain.GeoFrame); then one of agl (metres above
    the ground under the camera), z or alt (absolute metres, the DEM's height datum).
    --clearance overrides the heights with a constant clearance. JSON: a list of objects
    with those keys, or {"waypoints": [...]}.
    """
    if not os.path.isfile(filename):
        raise FlyError(f"waypoint file not found: {filename}")
    rows = _parse_rows(filename)
    if len(rows) < 2:
        raise FlyError(f"{filename}: need at least 2 waypoints, found {len(rows)}")
    keys = set(rows[0])
    if all(k in keys for k in GEO_KEYS):
        pos = GEO_KEYS
        frame = GeoFrame(image, heights)
    elif all(k in keys for k in LOCAL_KEYS):
        pos, frame = LOCAL_KEYS, None
    else:
        raise FlyError(f"{filename}: need columns x,y (metres) or lon,lat (degrees); "
                       f"found {','.join(sorted(keys)) or 'none'}")
    hkey = next((k for k in HEIGHT_KEYS if k in keys), None)
    if hkey is None and clearance is None:
        raise FlyError(f"{filename}: need a height column agl (above ground) or z/alt "
                       "(absolute metres), or give --clearance")
    xy, hs = [], []
    for n, row in enumerate(rows, start=1):
        try:
            a, b = float(row[pos[0]]), float(row[pos[1]])
            h = float(row[hkey]) if hkey else 0.0
        except (KeyError, TypeError, ValueError):
            raise FlyError(f"{filename}: waypoint {n} is not numeric: {row}") from None
        if not all(math.isfinite(v) for v in (a, b, h)):
            raise FlyError(f"{filename}: waypoint {n} has a non-finite value")
        x, y = frame.to_local(a, b) if frame else (a, b)
        if not heights.contains(x, y):
            where = f"lon {a:.6f} lat {b:.6f}" if frame else f"x {a:g} y {b:g}"
            raise FlyError(f"{filename}: waypoint {n} ({where}) is outside the terrain")
        xy.append((x, y))
        hs.append(h)
    if clearance is not None:
        return Path(xy, np.full(len(xy), clearance), True)
    return Path(xy, hs, hkey == "agl")


def _parse_rows(filename):
    try:
        if filename.lower().endswith(".json"):
            with open(filename, encoding="utf-8") as f:
                data = json.load(f)
            if isinstance(data, dict):
                data = data.get("waypoints")
            if not isinstance(data, list) or not all(isinstance(r, dict) for r in data):
                raise FlyError(f"{filename}: expected a list of waypoint objects "
                               "(or {\"waypoints\": [...]})")
            return [{str(k).strip().lower(): v for k, v in r.items()} for r in data]
        with open(filename, newline="", encoding="utf-8") as f:
            lines = [ln for ln in f if ln.strip() and not ln.lstrip().startswith("#")]
        reader = csv.DictReader(lines)
        return [{(k or "").strip().lower(): (v or "").strip() for k, v in r.items()}
                for r in reader]
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, csv.Error) as e:
        raise FlyError(f"cannot read waypoint file {filename}: {e}") from None


class Flight:
    """Camera positions and look-at points per frame, at constant speed along a Path."""

    def __init__(self, path, heights, frames, pitch_deg, clearance_smoothing=None):
        xy = path.xy
        seg = np.hypot(*np.diff(xy, axis=0).T)
        keep = np.concatenate([[True], seg > 1e-9])
        xy, hgt = xy[keep], path.height[keep]
        if len(xy) < 2:
            raise FlyError("the flight path has zero length")
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
