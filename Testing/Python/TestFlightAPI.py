"""geomipmap.flight, the Python flight API, in-process: what each promise means, measured.

- frames and camera poses: len(), camera_at() and apply() to a vtkCamera and to a
  vtkRenderer (whose clipping range is then reset to take in the terrain);
- constant ground speed: equal chords frame to frame on a line and on an orbit, and
  speed= (metres per second at fps) giving the nearest whole number of frames;
- terrain following: every camera at least the clearance above the ground under it, and
  close to it: on average far lower above the ground than a flat flight clearing the
  same ground, its height following the ground's;
- absolute altitude kept exactly; the default altitude above the highest summit;
- smooth look-ahead: through a 90 degree corner the view turns by 90 degrees, spread
  over the look-ahead distance at the rate its geometry allows (2 / L radians a metre at
  most), and looks along each leg away from the corner;
- lon/lat waypoints land where the reader's frame (GeoFrame) puts them;
- a reader or source is taken as terrain (updated first);
- bad input: FlightError (one line), TypeError for what is not a camera, IndexError past
  the last frame.
No window is opened.
"""

import math
import sys

import geomipmap
import numpy as np
from geomipmap import flight
from vtkmodules.vtkRenderingCore import vtkActor, vtkCamera, vtkRenderer

from waypointcases import make_terrain

failures = []


def check(cond, msg):
    if not cond:
        print(f"FAIL: {msg}")
        failures.append(msg)


def expect(error, fn, words=()):
    try:
        fn()
    except error as e:
        text = str(e)
        check(all(w in text for w in words) and "\n" not in text,
              f"{error.__name__} {text!r} lacks {words} or is not one line")
        return
    except Exception as e:  # noqa: BLE001: the point of the check
        check(False, f"expected {error.__name__}, got {type(e).__name__}: {e}")
        return
    check(False, f"expected {error.__name__}, nothing raised")


source = geomipmap.vtkGeoMipMapFractalSource()
source.SetDimensions(257, 257)
source.SetSpacing(30.0)
source.SetSeed(3)
orbit = flight.Orbit(source, frames=90, clearance=200.0, view_angle=40.0)
heights = orbit.heights
relief = heights.zmax - heights.zmin
print(f"terrain: {heights.nx} x {heights.ny} at 30 m, heights {heights.zmin:.0f} .. "
      f"{heights.zmax:.0f} m")
check(isinstance(heights, flight.Heights) and heights.nx == 257, "a source is taken as terrain")

# Frames and poses.
check(len(orbit) == 90, f"len(orbit) = {len(orbit)}, expected 90")
pose = orbit.camera_at(7)
check(np.allclose(pose.position, orbit.positions[7]) and
      np.allclose(pose.focal_point, orbit.focal_points[7]) and pose.view_up == (0, 0, 1),
      f"camera_at(7) = {pose}")
cam = vtkCamera()
orbit.apply(cam, 7)
check(np.allclose(cam.GetPosition(), pose.position) and
      np.allclose(cam.GetFocalPoint(), pose.focal_point) and cam.GetViewAngle() == 40.0,
      "apply(camera) sets position, focal point and view angle")
ren = vtkRenderer()
mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputConnection(source.GetOutputPort())
actor = vtkActor()
actor.SetMapper(mapper)
ren.AddActor(actor)
ren.GetActiveCamera().SetClippingRange(1.0, 2.0)
orbit.apply(ren, 30)
near, far = ren.GetActiveCamera().GetClippingRange()
check(np.allclose(ren.GetActiveCamera().GetPosition(), orbit.positions[30]),
      "apply(renderer) moves the renderer's active camera")
# The orbit looks inwards: the terrain's centre lies ahead, between the clipping planes.
xmin, xmax, ymin, ymax = heights.bounds
ahead = np.subtract(orbit.focal_points[30], orbit.positions[30])
centre = np.array([0.5 * (xmin + xmax), 0.5 * (ymin + ymax), 0.5 * (heights.zmin + heights.zmax)])
depth = np.dot(centre - orbit.positions[30], ahead / np.linalg.norm(ahead))
check(near < depth < far, f"apply(renderer): clipping range {near:.1f} .. {far:.1f} m does "
      f"not take in the terrain's centre {depth:.1f} m ahead")
expect(IndexError, lambda: orbit.camera_at(90))
expect(TypeError, lambda: orbit.apply("camera", 0), ("vtkCamera",))

# Terrain following at a clearance: never below it, and close to the ground: a flat flight
# that clears the same ground by as much is on average far higher above it.
low = flight.Orbit(heights, frames=90, clearance=50.0)
ground = heights.sample(low.positions[:, 0], low.positions[:, 1])
agl = low.positions[:, 2] - ground
flat_agl = ground.max() + 50.0 - ground
print(f"orbit at 50 m clearance: {agl.min():.1f} .. {agl.max():.1f} m above ground (mean "
      f"{agl.mean():.1f}; a flat flight clearing it by 50 m: mean {flat_agl.mean():.1f}); "
      f"ground under the path {ground.min():.0f} .. {ground.max():.0f} m")
check(agl.min() >= 50.0 - 1e-6, f"camera {agl.min():.2f} m above ground, clearance 50")
check(agl.mean() - 50.0 < 0.5 * (flat_agl.mean() - 50.0),
      f"mean height above ground {agl.mean():.1f} m: not following the terrain")
check(np.corrcoef(low.positions[:, 2], ground)[0, 1] > 0.8,
      "camera height does not follow the ground's")
# Flight.ground comes from the path's profile, sampled every quarter sample spacing.
check(np.abs(low.ground - ground).max() < 1.0,
      f"Flight.ground is {np.abs(low.ground - ground).max():.2f} m off the ground")
flat = flight.Orbit(heights, frames=90, altitude=heights.zmax + 300.0)
check(np.allclose(flat.positions[:, 2], heights.zmax + 300.0), "absolute altitude kept")
high = flight.Orbit(heights, frames=10)
check(high.positions[:, 2].min() > heights.zmax, "default altitude above the summit")

# Constant ground speed.
line = flight.Line(heights, frames=41, clearance=150.0)
chords = np.hypot(*np.diff(line.positions[:, :2], axis=0).T)
check(np.allclose(chords, line.step, rtol=1e-9) and
      abs(line.step * 40 - line.length) < 1e-6 * line.length,
      f"line: chords {chords.min():.4f} .. {chords.max():.4f} m, step {line.step:.4f} m")
chords = np.hypot(*np.diff(orbit.positions[:, :2], axis=0).T)
check(np.ptp(chords) < 1e-3 * chords.mean(),
      f"orbit: chords {chords.min():.4f} .. {chords.max():.4f} m vary")
fast = flight.Line(heights, speed=250.0, fps=25.0, clearance=150.0)
want = line.length * 25.0 / 250.0 + 1
check(len(fast) == round(want) and abs(fast.speed - 250.0) <= 250.0 / (len(fast) - 1),
      f"speed 250 m/s at 25 fps over {line.length:.0f} m: {len(fast)} frames "
      f"({fast.speed:.2f} m/s), expected {want:.1f}")
print(f"line of {line.length:.0f} m at 250 m/s, 25 fps: {len(fast)} frames, "
      f"{fast.speed:.3f} m/s")

# Smooth look-ahead through a 90 degree corner (x, y in metres; heights absolute). The
# camera looks at the point L metres further along the path: at distance a before the
# corner the view is atan2(L - a, a) off the first leg, so it turns by 90 degrees over
# the last L metres before the corner, at most 2 / L radians a metre (at a = L / 2).
for look in (None, 1500.0):
    corner = flight.Waypoints(heights, [(1000, 1000, 2000), (6000, 1000, 2000),
                                        (6000, 6000, 2000)], frames=200, look_ahead=look)
    ell = look or min(0.05 * corner.length, 2000.0)
    view = corner.focal_points[:, :2] - corner.positions[:, :2]
    yaw = np.degrees(np.unwrap(np.arctan2(view[:, 1], view[:, 0])))
    turn = np.abs(np.diff(yaw))
    bound = math.degrees(2.0 * corner.step / ell)
    print(f"corner, look-ahead {ell:.0f} m: the view turns {yaw[-1] - yaw[0]:.1f} degrees, at "
          f"most {turn.max():.2f} a frame (bound {bound:.2f})")
    check(abs(yaw[0]) < 1e-6 and abs(yaw[-1] - 90.0) < 1e-6,
          f"looks along each leg: first {yaw[0]:.3f}, last {yaw[-1]:.3f} degrees")
    check(turn.max() <= bound * 1.001,
          f"the view turns {turn.max():.2f} degrees in one frame, more than {bound:.2f}")
    check(np.count_nonzero(turn > 1e-9) * corner.step >= 0.9 * ell,
          "the turn is not spread over the look-ahead distance")
    check(np.allclose(corner.positions[:, 2], 2000.0), "waypoint heights kept (absolute)")

# lon/lat waypoints through the reader's frame (test terrain with a geographic origin).
geo = make_terrain(True)
frame = flight.GeoFrame(geo)
pts = [(1.0, 42.0, 100.0), (1.01, 42.012, 100.0)]
wp = flight.Waypoints(geo, pts, lonlat=True, above_ground=True, frames=5)
for p, i in ((pts[0], 0), (pts[1], -1)):
    x, y = frame.to_local(p[0], p[1])
    check(np.allclose(wp.positions[i, :2], (x, y), atol=1e-6),
          f"waypoint {p[:2]} at {wp.positions[i, :2]}, the reader's frame says {(x, y)}")

# Bad input.
expect(flight.FlightError, lambda: flight.Orbit(heights, frames=0), ("frames",))
expect(flight.FlightError, lambda: flight.Orbit(heights, frames=3, speed=5.0), ("not both",))
expect(flight.FlightError, lambda: flight.Line(heights, pitch=100.0), ("pitch",))
expect(flight.FlightError, lambda: flight.Line(heights, clearance=-5.0), ("clearance",))
expect(flight.FlightError, lambda: flight.Line(heights, speed=math.nan), ("speed",))
expect(flight.FlightError, lambda: flight.Waypoints(heights, [(100, 100, 50)]),
       ("at least 2",))
expect(flight.FlightError, lambda: flight.Waypoints(heights, [(100, 100, 5), (1e7, 0, 5)]),
       ("waypoint 2", "outside the terrain"))
expect(flight.FlightError, lambda: flight.Waypoints(heights, [(1, 42, 5), (1.1, 42, 5)],
                                                    lonlat=True), ("geographic",))
expect(flight.FlightError, lambda: flight.Waypoints(heights, [(100, 100), (200, 200)]),
       ("(x, y, h)",))
expect(flight.FlightError, lambda: flight.Waypoints(heights, [(100, 100, "high"), (2, 2, 2)]),
       ("waypoint 1", "numbers"))
expect(flight.FlightError, lambda: flight.Waypoints(heights, [(100, math.inf, 5), (2, 2, 2)]),
       ("waypoint 1", "finite"))
xy = flight.Waypoints(heights, [(100, 100), (2000, 900)], clearance=80.0, frames=3)
check(np.allclose(xy.positions[[0, -1], :2], [(100, 100), (2000, 900)]),
      "(x, y) waypoints with a clearance")
expect(flight.FlightError, lambda: flight.Line(heights, start=(500, 500), end=(500, 500)),
       ("zero length",))
expect(TypeError, lambda: flight.Orbit("dem.tif"), ("vtkImageData",))

if failures:
    print(f"TestFlightAPI: {len(failures)} failure(s)")
    sys.exit(1)
print("TestFlightAPI: passed")
