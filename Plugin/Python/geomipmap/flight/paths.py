"""Camera paths: orbit, line, waypoints; constant ground speed; terrain following; look-ahead.

Why: the LOD statistics of a flight are only comparable between runs if the camera
position depends on the frame number alone (as in the NDL paper's test flight), so a path
is a dense polyline parametrised by arc length, sampled at equal distances per frame.
Heights either come from the path (absolute) or follow the terrain with a clearance; the
ground profile is smoothed so that the camera does not jitter, and never dips below the
clearance at the sampled points (running maximum, then a moving average narrower than it).
"""

import collections
import math

import numpy as np
from vtkmodules.vtkRenderingCore import vtkCamera, vtkRenderer

from .heights import FlightError, GeoFrame, as_heights


class Path:
    """A polyline over the terrain; heights absolute or above ground, per vertex.

    xy: (n, 2) vertices in the terrain's metres. height: n heights, metres above the
    ground under the camera when above_ground, else absolute (the DEM's datum). closed: the
    last vertex joins the first (an orbit). look_yaw: degrees the camera looks to the left
    of straight ahead.
    """

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


def orbit_path(heights, clearance=None, altitude=None, center=None, radius=None):
    """A counter-clockwise circle, by default around the centre with a radius of 35 % of
    the smaller extent."""
    xmin, xmax, ymin, ymax = heights.bounds
    cx, cy = center if center is not None else (0.5 * (xmin + xmax), 0.5 * (ymin + ymax))
    r = radius if radius is not None else 0.35 * min(xmax - xmin, ymax - ymin)
    if not (math.isfinite(cx) and math.isfinite(cy) and math.isfinite(r) and r > 0):
        raise FlightError(f"orbit: centre ({cx:g}, {cy:g}) and radius {r:g} must be finite, "
                          "the radius > 0")
    t = np.linspace(0.0, 2 * math.pi, 721)  # counter-clockwise; last == first
    xy = np.column_stack([cx + r * np.cos(t), cy + r * np.sin(t)])
    path = _flat(xy, heights, clearance, altitude, closed=True)
    path.look_yaw = 20.0  # counter-clockwise: a little inwards keeps the DEM's edge out of view
    return path


def line_path(heights, clearance=None, altitude=None, start=None, end=None):
    """A straight line, by default across from south-west to north-east, 10 % in from the
    edges."""
    xmin, xmax, ymin, ymax = heights.bounds
    wx, wy = xmax - xmin, ymax - ymin
    start = start if start is not None else (xmin + 0.1 * wx, ymin + 0.1 * wy)
    end = end if end is not None else (xmax - 0.1 * wx, ymax - 0.1 * wy)
    return _flat([start, end], heights, clearance, altitude, closed=False)


def _flat(xy, heights, clearance, altitude, closed):
    if clearance is not None:
        _check_height("clearance", clearance)
        return Path(xy, np.full(len(xy), clearance), True, closed)
    if altitude is not None:
        _check_height("altitude", altitude)
        return Path(xy, np.full(len(xy), altitude), False, closed)
    return Path(xy, np.full(len(xy), default_altitude(heights)), False, closed)


def _check_height(name, value):
    if not math.isfinite(value) or (name == "clearance" and value <= 0):
        raise FlightError(f"{name} must be finite{' and > 0' if name == 'clearance' else ''}, "
                          f"got {value:g}")


def points_path(points, heights, frame=None, above_ground=False, clearance=None,
                context=""):
    """Waypoints -> Path in the terrain's metres.

    points: an iterable of (where, a, b, h): a, b are x, y metres, or lon, lat degrees
    when frame (a GeoFrame) is given; h is metres above ground (above_ground) or absolute;
    where names the point in messages ("waypoint 3 (line 5)"). clearance, when given,
    replaces every h. FlightError (its text starting with context) for a point off the
    terrain, or fewer than 2 points.
    """
    xy, hs = [], []
    for where, a, b, h in points:
        x, y = frame.to_local(a, b) if frame else (a, b)
        if not heights.contains(x, y):
            at = f"lon {a:g} lat {b:g}" if frame else f"x {a:g} y {b:g}"
            raise FlightError(f"{context}{where} at {at} is outside the terrain")
        xy.append((x, y))
        hs.append(h)
    if len(xy) < 2:
        raise FlightError(f"{context}need at least 2 waypoints, found {len(xy)}")
    if clearance is not None:
        _check_height("clearance", clearance)
        return Path(xy, np.full(len(xy), clearance), True)
    return Path(xy, hs, above_ground)


Pose = collections.namedtuple("Pose", "position focal_point view_up")
Pose.__doc__ = """A camera pose: position, focal_point and view_up as (x, y, z) tuples."""


class Flight:
    """A Path flown over the terrain: one camera pose per frame, at constant ground speed.

    The camera moves the same distance along the path every frame; its height follows the
    path (absolute heights, kept at least 2 m above the smoothed ground) or the terrain
    at the path's clearance (terrain following: the ground profile under the path is
    smoothed over a few clearances, never below the ground at the sampled points). It
    looks towards the point `look_ahead` metres further along the path (smooth through
    corners), turned by the path's look_yaw, `pitch` degrees down.

    path: a Path. terrain: Heights, a vtkImageData or an algorithm producing one
    (as_heights). frames: the number of frames (default 300), or speed: ground speed in
    metres per second at fps frames per second (frames then follow from the path's
    length: the nearest whole number, at least 1). pitch: look-down angle in degrees,
    -89..89. look_ahead: metres (default 5 % of the path, at most 2 km). view_angle:
    vertical field of view in degrees that apply() sets, or None to leave the camera's.

    Attributes: positions and focal_points, (frames, 3) arrays; ground, the terrain
    height under each position; length, the path's length in metres; step, metres of
    path per frame. A closed path does not repeat its first frame at the end.
    """

    def __init__(self, path, terrain, frames=None, speed=None, fps=30.0, pitch=15.0,
                 look_ahead=None, view_angle=None):
        heights = as_heights(terrain)
        self.heights = heights
        self.view_angle = _check_flight_options(frames, speed, fps, pitch, look_ahead,
                                                view_angle)
        xy = path.xy
        seg = np.hypot(*np.diff(xy, axis=0).T)
        keep = np.concatenate([[True], seg > 1e-9])
        xy, hgt = xy[keep], path.height[keep]
        if len(xy) < 2:
            raise FlightError("the flight path has zero length")
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])
        self.length = float(s[-1])
        n = int(frames) if frames is not None else 300
        if speed is not None:
            n = max(int(round(self.length * fps / speed)) + (0 if path.closed else 1), 1)
        self.fps = fps
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
        window = min(0.04 * self.length, max(5.0 * typical, 10.0 * spacing))
        smooth = _smooth_envelope(ground, max(int(window / (sd[1] - sd[0])), 1), path.closed)
        zd = smooth + hd if path.above_ground else np.maximum(hd, smooth + 2.0)
        # Frame stations: a closed path does not repeat its first point at the end.
        if path.closed:
            fs = np.arange(n) * self.length / n
            self.step = self.length / n
        else:
            fs = np.linspace(0.0, self.length, n) if n > 1 else np.zeros(1)
            self.step = self.length / (n - 1) if n > 1 else 0.0
        self.positions = np.column_stack(
            [np.interp(fs, sd, xd[:, 0]), np.interp(fs, sd, xd[:, 1]), np.interp(fs, sd, zd)])
        self.ground = np.interp(fs, sd, ground)
        # Look ahead along the path (smooths corners): direction to the point L metres on.
        look = look_ahead if look_ahead is not None else min(0.05 * self.length, 2000.0)
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
        p = math.radians(pitch)
        dist = max(0.1 * self.length, 100.0)
        self.focal_points = np.column_stack([
            self.positions[:, 0] + dist * math.cos(p) * d[:, 0],
            self.positions[:, 1] + dist * math.cos(p) * d[:, 1],
            self.positions[:, 2] - dist * math.sin(p)])

    def __len__(self):
        """The number of frames."""
        return len(self.positions)

    @property
    def speed(self):
        """Ground speed along the path in metres per second at self.fps frames a second."""
        return self.step * self.fps

    def camera_at(self, frame):
        """The Pose of frame `frame` (0 <= frame < len(self)); IndexError outside."""
        if not 0 <= frame < len(self):
            raise IndexError(f"frame {frame} out of range: the flight has {len(self)} frames")
        return Pose(tuple(map(float, self.positions[frame])),
                    tuple(map(float, self.focal_points[frame])), (0.0, 0.0, 1.0))

    def apply(self, target, frame):
        """Put a camera at frame `frame`'s pose (and view angle, when the flight has one).

        target: a vtkCamera, or a vtkRenderer: then its active camera, and the renderer's
        clipping range is reset to the visible props afterwards, as a renderer does for
        its own camera moves.
        """
        renderer = target if isinstance(target, vtkRenderer) else None
        camera = renderer.GetActiveCamera() if renderer else target
        if not isinstance(camera, vtkCamera):
            raise TypeError(f"apply() needs a vtkCamera or vtkRenderer, got "
                            f"{type(target).__name__}")
        pose = self.camera_at(frame)
        camera.SetPosition(*pose.position)
        camera.SetFocalPoint(*pose.focal_point)
        camera.SetViewUp(*pose.view_up)
        if self.view_angle is not None:
            camera.SetViewAngle(self.view_angle)
        if renderer:
            renderer.ResetCameraClippingRange()


def _check_flight_options(frames, speed, fps, pitch, look_ahead, view_angle):
    """FlightError for an option outside its range; returns view_angle (as a float)."""
    if frames is not None and speed is not None:
        raise FlightError("give frames or speed, not both")
    if frames is not None and (isinstance(frames, bool) or int(frames) != frames or frames < 1):
        raise FlightError(f"frames must be a whole number >= 1, got {frames!r}")
    for name, v in (("speed", speed), ("fps", fps), ("look_ahead", look_ahead)):
        if v is not None and not (math.isfinite(v) and v > 0):
            raise FlightError(f"{name} must be finite and > 0, got {v!r}")
    if not (math.isfinite(pitch) and -89.0 <= pitch <= 89.0):
        raise FlightError(f"pitch must be in -89..89 degrees, got {pitch!r}")
    if view_angle is not None and not (math.isfinite(view_angle) and 1.0 <= view_angle <= 170.0):
        raise FlightError(f"view_angle must be in 1..170 degrees, got {view_angle!r}")
    return None if view_angle is None else float(view_angle)


class Orbit(Flight):
    """A circle flown counter-clockwise, looking a little inwards (20 degrees).

    terrain: Heights, a vtkImageData or an algorithm producing one (a reader). center:
    (x, y) in metres (default: the terrain's centre); radius: metres (default 35 % of the
    smaller extent). clearance: follow the terrain this many metres above the ground; or
    altitude: absolute metres; neither: a constant altitude above the highest summit.
    Other keywords (frames or speed and fps, pitch, look_ahead, view_angle): Flight's.
    """

    def __init__(self, terrain, clearance=None, altitude=None, center=None, radius=None,
                 **flight):
        heights = as_heights(terrain)
        super().__init__(orbit_path(heights, clearance, altitude, center, radius), heights,
                         **flight)


class Line(Flight):
    """A straight flight from start to end ((x, y) metres; default: across the terrain
    from south-west to north-east, 10 % in from the edges). clearance, altitude and the
    other keywords as for Orbit."""

    def __init__(self, terrain, clearance=None, altitude=None, start=None, end=None,
                 **flight):
        heights = as_heights(terrain)
        super().__init__(line_path(heights, clearance, altitude, start, end), heights,
                         **flight)


class Waypoints(Flight):
    """A flight through waypoints, straight between them (corners are rounded by the
    look-ahead, not by the path).

    points: a sequence of (x, y, h): metres in the terrain's frame, or (lon, lat, h) in
    degrees WGS 84 when lonlat is true, converted through the reader's georeference
    (GeoFrame; FlightError when the DEM has none). h: metres above the ground under the
    camera when above_ground is true (terrain following), else absolute metres (the
    DEM's datum). clearance, when given, replaces every h (and points may be (x, y)
    pairs). FlightError for fewer than 2 points, a non-finite value or a point off the
    terrain. Other keywords: Flight's. Waypoint files: Waypoints.from_file.
    """

    def __init__(self, terrain, points, lonlat=False, above_ground=False, clearance=None,
                 **flight):
        heights = as_heights(terrain)
        frame = GeoFrame(heights) if lonlat else None
        rows = []
        for n, p in enumerate(points, start=1):
            try:
                values = tuple(float(v) for v in p)
            except (TypeError, ValueError):
                raise FlightError(f"waypoint {n}: expected numbers, got {p!r:.60}") from None
            if len(values) != 3 and not (len(values) == 2 and clearance is not None):
                raise FlightError(f"waypoint {n}: expected (x, y, h), or (x, y) with a "
                                  f"clearance, got {len(values)} values")
            if not all(math.isfinite(v) for v in values):
                raise FlightError(f"waypoint {n}: values must be finite, got {values}")
            rows.append((f"waypoint {n}",) + values[:2] + (values[2:] or (0.0,)))
        super().__init__(points_path(rows, heights, frame, above_ground, clearance), heights,
                         **flight)

    @classmethod
    def from_file(cls, filename, terrain, clearance=None, **flight):
        """A flight through the waypoints of a CSV or JSON file (format:
        waypoints.parse_waypoints); FlightError naming the file, line or waypoint for a
        malformed one. clearance replaces the file's heights; other keywords: Flight's."""
        from .waypoints import read_waypoints

        heights = as_heights(terrain)
        self = cls.__new__(cls)
        Flight.__init__(self, read_waypoints(filename, heights, clearance), heights, **flight)
        return self


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
