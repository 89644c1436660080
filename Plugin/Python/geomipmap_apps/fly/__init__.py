"""geomipmap_apps.fly: the `geomipmap-fly` command (a camera flight over a GeoMipMapped DEM).

Modules: cli (options, main), report (CSV, progress bar, summary). Terrain loading, the
scene and errors are the apps package's (geomipmap_apps); the camera paths are
geomipmap_apps.paths.
"""

from .cli import main  # noqa: F401
