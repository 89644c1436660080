"""Terrain input for the geomipmap tools: load a DEM (or the synthetic terrain).

Why a separate module: every tool opens its terrain the same way, the reader or the
fractal source, and fails with one line naming the file; the heights under a flight are
then the flight API's (geomipmap.flight.Heights).
"""

import os

import numpy as np
from vtkmodules.vtkCommonCore import vtkCommand

from . import command
from .errors import AppError, VTKMessages

FILL_DISTANCE = 100.0  # samples: vtkGeoMipMapTerrainReader's (and gdal_fillnodata's) default


def add_fill_arguments(group):
    """The void-filling options every tool that reads a DEM offers (--fill-voids ...)."""
    group.add_argument("--fill-voids", action="store_true",
                       help="fill nodata voids of the DEM from the samples around them "
                       "(GDAL's GDALFillNodata; the filled samples are marked in the image's "
                       "FilledNodata array)")
    group.add_argument("--fill-distance", type=command.positive(float), default=None,
                       metavar="SAMPLES", help="with --fill-voids: how far to look for valid "
                       f"samples, in samples (default {FILL_DISTANCE:g}); farther voids stay holes")
    group.add_argument("--fill-smoothing", type=command.positive(int, 0, strict=False),
                       default=None, metavar="N", help="with --fill-voids: 3x3 smoothing "
                       "passes over the filled samples, 0..1000 (default 0)")


def fill_options(args):
    """load_terrain's `fill` from the options of add_fill_arguments: None (no filling) or
    (distance, smoothing iterations). Raises AppError for a fill option without --fill-voids."""
    if not args.fill_voids:
        for name in ("fill_distance", "fill_smoothing"):
            if getattr(args, name) is not None:
                raise AppError(f"--{name.replace('_', '-')} needs --fill-voids")
        return None
    smoothing = args.fill_smoothing or 0
    if smoothing > 1000:
        raise AppError(f"--fill-smoothing must be in 0..1000, got {smoothing}")
    distance = args.fill_distance if args.fill_distance is not None else FILL_DISTANCE
    return (distance, smoothing)


def load_terrain(dem=None, height_scale=1.0, spacing=None, terrain_rgb=False,
                 synthetic_size=1025, seed=1, messages=None, progress=None, fill=None):
    """Run the reader on `dem`, or the fractal source when dem is None; return
    (vtkImageData, geomipmap.flight.Heights).

    spacing: metres between samples for images without georeference (synthetic terrain:
    default 30). synthetic_size, seed: the fractal source's samples per side and seed.
    messages: the VTKMessages that capture VTK's errors (a new one when None).
    progress: called as progress(fraction) with the reader's (or source's) progress events.
    fill: None, or (search distance in samples, smoothing iterations) to fill the DEM's
    voids (the reader's FillNodata; the synthetic terrain has none).
    Raises AppError with one line for a missing / unreadable file or an empty image.
    """
    import geomipmap  # noqa: deferred so that --help works without the compiled package
    from geomipmap.flight import Heights

    messages = messages or VTKMessages()
    if dem:
        if not os.path.isfile(dem):
            raise AppError(f"DEM file not found: {dem}")
        if not os.access(dem, os.R_OK):
            raise AppError(f"DEM file not readable: {dem}")
        algo = geomipmap.vtkGeoMipMapTerrainReader()
        algo.SetFileName(dem)
        algo.SetHeightScale(height_scale)
        if spacing is not None:
            algo.SetSpacing(spacing)
        algo.SetTerrainRGB(1 if terrain_rgb else 0)
        if fill is not None:
            algo.SetFillNodata(1)
            algo.SetFillSearchDistance(fill[0])
            algo.SetFillSmoothingIterations(fill[1])
        what = f"cannot read DEM {dem}"
    else:
        algo = geomipmap.vtkGeoMipMapFractalSource()
        algo.SetDimensions(synthetic_size, synthetic_size)
        algo.SetSpacing(spacing if spacing is not None else 30.0)
        algo.SetSeed(seed)
        what = "synthetic terrain failed"
    messages.observe(algo)
    if progress is not None:
        algo.AddObserver(vtkCommand.ProgressEvent,
                         lambda obj, _event: progress(obj.GetProgress()))
    ok = algo.GetExecutive().Update()
    image = algo.GetOutput()
    err = messages.first_error()
    dims = image.GetDimensions() if image is not None else (0, 0, 0)
    if not ok or err or dims[0] < 2 or dims[1] < 2:
        if err and dem and dem in err:
            raise AppError(err)  # the reader's message names the file already
        raise AppError(f"{what}: {err or 'no elevation samples in the output'}")
    image = image.NewInstance()
    image.ShallowCopy(algo.GetOutput())
    heights = Heights(image)
    if not np.isfinite(heights.z).any():
        raise AppError(f"{what}: every sample is nodata")
    return image, heights


def load_terrain_for(args, messages=None, progress=None):
    """load_terrain with the terrain options of command.add_terrain_options."""
    return load_terrain(dem=args.dem, height_scale=args.height_scale, spacing=args.spacing,
                        terrain_rgb=args.terrain_rgb, synthetic_size=args.synthetic_size,
                        seed=args.seed, messages=messages, progress=progress,
                        fill=fill_options(args))
