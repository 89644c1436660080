"""geomipmap.flight: camera flights over a DEM, for any vtkCamera, frame by frame.

A flight is a plain object: build it from the terrain (a reader, its vtkImageData, or
Heights), then put a camera at each frame's pose:

    import geomipmap, geomipmap.flight
    reader = geomipmap.vtkGeoMipMapTerrainReader(); reader.SetFileName("dem.tif")
    path = geomipmap.flight.Orbit(reader, frames=120, clearance=500)
    for i in range(len(path)):
        path.apply(renderer, i)      # a vtkCamera or vtkRenderer (clipping range reset)
        window.Render()

Paths: Orbit (a circle), Line (a straight flight), Waypoints (metres, or lon/lat through
the reader's georeference; Waypoints.from_file reads CSV or JSON), or Flight over any
Path. Each is flown at constant ground speed (frames, or speed and fps), either at
absolute heights or following the terrain at a clearance, looking ahead along the path
(smooth through corners) and down by a pitch. camera_at(frame) gives a Pose (position,
focal_point, view_up); positions, focal_points and ground hold every frame's.

Nothing here renders or needs a window; bad input raises FlightError (one line).
The geomipmap-fly command (geomipmap_apps.fly) is a command line over this module.
"""

from .heights import FlightError, GeoFrame, Heights, as_heights
from .paths import Flight, Line, Orbit, Path, Pose, Waypoints, default_altitude

__all__ = ["Flight", "FlightError", "GeoFrame", "Heights", "Line", "Orbit", "Path", "Pose",
           "Waypoints", "as_heights", "default_altitude"]
