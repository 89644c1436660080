"""geomipmap_fly: the `geomipmap-fly` command (a camera flight over a GeoMipMapped DEM).

Modules: cli (options, main), terrain (DEM loading, height sampling, lon/lat -> local
metres), paths (orbit / line / waypoints at constant speed, terrain following), scene
(VTK rendering and timing), report (CSV, progress bar, summary), errors (one-line errors).
"""

from .cli import main  # noqa: F401
