"""geomipmap_apps.bench, the `geomipmap-bench` command: frame time against measured
screen-space error, GeoMipMapping versus the mesh reductions VTK already offers, on the
same flight, window and machine.

Modules: cli (options, the run per DEM), meshes (the competing meshes), measure (timed
frames, measured error, depth check), report (CSV, Markdown summary, plot). They are the
benchmark's alone: no other tool, and nothing in the geomipmap package, imports them
(Testing/Python/TestAppsPackage.py checks it). Terrain, paths and scene are the apps
package's.
"""
