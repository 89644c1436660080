"""geomipmap_apps.view: the `geomipmap-view` command, an interactive window over a DEM.

Modules: cli (options, loading, main), viewer (camera modes, keys, overlay, screenshots),
progress (loading progress in the terminal and the window). Terrain loading, the scene
and errors are the apps package's (geomipmap_apps).
"""

from .cli import main  # noqa: F401
