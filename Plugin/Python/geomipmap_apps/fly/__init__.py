"""geomipmap_apps.fly: the `geomipmap-fly` command (a camera flight over a GeoMipMapped DEM).

Modules: cli (options, main), report (CSV, progress bar, summary). Terrain loading, the
scene, videos and errors are the apps package's (geomipmap_apps); the camera paths are
the flight API's (geomipmap.flight): this command is a command line over it.
"""

from .cli import main  # noqa: F401
