"""geomipmap-bench: frame time against measured screen-space error, GeoMipMapping versus
the mesh reductions VTK already offers, on the same flight, window and machine.

Modules: cli (options, the run per DEM), meshes (the competing meshes), measure (timed
frames, measured error, depth check), report (CSV, Markdown summary, plot).
"""
