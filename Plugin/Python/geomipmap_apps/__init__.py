"""geomipmap_apps: the geomipmap command-line tools, one subpackage each.

    fly    geomipmap-fly: a camera flight over a DEM, PNG frames, per-frame CSV, video
    view   geomipmap-view: an interactive window over a DEM (orbit / fly, keys, overlay)
    bench  geomipmap-bench: frame time against measured screen-space error, ours against
           VTK's mesh reductions (its measurement code is imported by no other tool)

What the tools share lives here, written once: terrain (load a DEM or the synthetic
terrain with one-line errors), scene (window, LOD mapper, colours, sun, timed frames, PNG
grabs), video (frames into .mp4 / .ogv through ffmpeg or vtkOggTheoraWriter), command
(argument types, the terrain and rendering options, one-line errors, exit statuses),
errors (AppError, VTK message capture).
A new tool is a subpackage with a cli.main(argv) and a launcher
(Plugin/Python/geomipmapApps.cmake). The camera paths are the product's:
geomipmap.flight.

The product is the geomipmap package; nothing in it imports this one
(Testing/Python/TestAppsPackage.py).
"""
