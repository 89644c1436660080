"""Rendering for the geomipmap tools: window, LOD mapper, colouring, lights, timed frames.

Why: keeps every VTK rendering detail (off-screen vs. window, sky, sun, colour map or
texture, how a frame's render time is measured, PNG output) away from the command lines
and the path code, and the same in every tool. Render time is the wall time of Render() plus WaitForCompletion() (a glFinish), so
the GPU/llvmpipe work is counted, not just the command submission.
"""

import os
import time

from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkColorTransferFunction,
    vtkLight,
    vtkRenderer,
    vtkRenderWindow,
    vtkTexture,
    vtkWindowToImageFilter,
)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (OpenGL factory overrides)

from . import command
from .errors import AppError, VTKMessages

# Hypsometric tints: fraction of the height range -> RGB (lowland green .. snow).
TERRAIN_COLOURS = (
    (0.00, (0.20, 0.42, 0.22)),
    (0.15, (0.33, 0.55, 0.27)),
    (0.35, (0.62, 0.64, 0.38)),
    (0.55, (0.60, 0.48, 0.33)),
    (0.75, (0.52, 0.45, 0.42)),
    (0.90, (0.85, 0.85, 0.85)),
    (1.00, (1.00, 1.00, 1.00)),
)


class Scene:
    """One renderer with the terrain actor, driven frame by frame.

    image, heights: the terrain (terrain.load_terrain). block_size, tau: the mapper's
    block size (quads) and pixel error. color: "elevation" (hypsometric tints) or
    "texture:FILE.png" (stretched over the extent). drape: a georeferenced image
    (orthophoto) laid over that colouring by its coordinates (vtkGeoMipMapImageDrape),
    resampled to at most drape_size pixels a side. normals: the mapper's NormalMode by
    name ("auto", "vertex" or "fragment": command.NORMAL_MODES). geomorphing: the mapper's
    Geomorphing (smooth level changes, on by default). size: the window's (width, height).
    on_screen: a window on the display instead of off-screen rendering. title: the
    window's name. messages: VTKMessages for errors (texture reading). window: a render
    window to add the terrain renderer to (one that showed loading progress), else a new
    one. The camera is the renderer's active one; a geomipmap.flight path drives it
    (apply(renderer, frame)).
    """

    def __init__(self, image, heights, block_size=None, tau=1.0, color="elevation",
                 lighting=True, size=(1280, 720), on_screen=False, title="geomipmap",
                 messages=None, window=None, drape=None, drape_size=8192, normals="auto",
                 geomorphing=True):
        import geomipmap

        self.messages = messages or VTKMessages()
        self.mapper = geomipmap.vtkGeoMipMapMapper()
        self.mapper.SetInputData(image)
        if block_size is not None:  # None: the mapper's default (GetDefaultBlockSize)
            self.mapper.SetBlockSize(block_size)
        self.mapper.SetPixelError(tau)
        command.set_normal_mode(self.mapper, normals)
        self.mapper.SetGeomorphing(geomorphing)
        self.actor = vtkActor()
        self.actor.SetMapper(self.mapper)
        self._colour(heights, color)
        if drape:
            self._drape(image, drape, drape_size)
        prop = self.actor.GetProperty()
        if not lighting:
            prop.LightingOff()
        else:
            prop.SetAmbient(0.25)
            prop.SetDiffuse(0.8)
            prop.SetSpecular(0.0)

        self.renderer = vtkRenderer()
        self.renderer.AddActor(self.actor)
        self.renderer.GradientBackgroundOn()  # sky: hazy horizon below, deeper blue above
        self.renderer.SetBackground(0.78, 0.86, 0.95)
        self.renderer.SetBackground2(0.30, 0.50, 0.80)
        self.renderer.SetNearClippingPlaneTolerance(0.0005)  # low flights: near plane close
        if lighting:
            self._sun()

        self.window = window or vtkRenderWindow()
        self.window.SetSize(*size)
        self.window.AddRenderer(self.renderer)
        self.window.SetWindowName(title)
        self.window.SetMultiSamples(0)
        self.window.SetOffScreenRendering(0 if on_screen else 1)
        self.grab = None

    @classmethod
    def from_args(cls, image, heights, args, **kw):
        """A Scene with the rendering options of command.add_rendering_options."""
        return cls(image, heights, block_size=args.block_size, tau=args.tau, color=args.color,
                   lighting=not args.no_lighting, size=args.size, drape=args.texture,
                   drape_size=args.texture_size, normals=args.normals,
                   geomorphing=not args.no_geomorphing, **kw)

    def _colour(self, heights, spec):
        if spec == "elevation":
            ctf = vtkColorTransferFunction()
            lo, hi = heights.zmin, max(heights.zmax, heights.zmin + 1e-3)
            for frac, rgb in TERRAIN_COLOURS:
                ctf.AddRGBPoint(lo + frac * (hi - lo), *rgb)
            self.mapper.SetLookupTable(ctf)
            self.mapper.SetScalarRange(lo, hi)
            self.mapper.SetColorModeToMapScalars()
            self.mapper.ScalarVisibilityOn()
            return
        path = spec.split(":", 1)[1]
        if not os.path.isfile(path):
            raise AppError(f"texture image not found: {path}")
        reader = vtkPNGReader()
        if not reader.CanReadFile(path):
            raise AppError(f"texture is not a PNG image: {path}")
        self.messages.observe(reader)
        reader.SetFileName(path)
        reader.Update()
        dims = reader.GetOutput().GetDimensions()
        if self.messages.first_error() or dims[0] < 1 or dims[1] < 1:
            raise AppError(f"cannot read texture {path}: {self.messages.first_error()}")
        tex = vtkTexture()
        tex.SetInputConnection(reader.GetOutputPort())
        tex.InterpolateOn()
        tex.MipmapOn()
        self.texture_reader = reader
        self.actor.SetTexture(tex)
        self.mapper.ScalarVisibilityOff()

    def _drape(self, image, path, size):
        """Lay the georeferenced image at `path` over the terrain (AppError naming it when
        it cannot be placed: no georeference, a terrain without CRS, ...)."""
        import geomipmap

        if not os.path.isfile(path):
            raise AppError(f"texture image not found: {path}")
        drape = geomipmap.vtkGeoMipMapImageDrape()
        self.messages.observe(drape)
        drape.SetFileName(path)
        drape.SetTerrain(image)
        drape.SetMaximumSize(size)
        ok = drape.GetExecutive().Update()
        err = self.messages.first_error()
        if not ok or err:
            raise AppError(err or f"cannot drape {path}")
        self.drape = drape  # its output is the mapper's drape image
        self.mapper.SetDrapeImage(drape.GetOutput())

    def _sun(self):
        """A sun from the north-west, 40 degrees up (relief reads as in a shaded map)."""
        self.renderer.AutomaticLightCreationOff()
        sun = vtkLight()
        sun.SetLightTypeToSceneLight()
        sun.SetPositional(False)
        sun.SetPosition(-0.55, 0.55, 0.63)
        sun.SetFocalPoint(0.0, 0.0, 0.0)
        sun.SetIntensity(1.0)
        self.renderer.AddLight(sun)

    def render(self):
        """Render one frame; return (render_ms, lod_ms, stats dict)."""
        t0 = time.perf_counter()
        self.window.Render()
        self.window.WaitForCompletion()
        render_ms = (time.perf_counter() - t0) * 1000.0
        m = self.mapper
        stats = {
            "lod_ms": m.GetLastUpdateTime() * 1000.0,
            "render_ms": render_ms,
            "triangles": int(m.GetNumberOfRenderedTriangles()),
            "visible_blocks": int(m.GetNumberOfVisibleBlocks()),
            "culled_blocks": int(m.GetNumberOfCulledBlocks()),
            "certified_error_px": float(m.GetMaximumScreenSpaceError()),
            "reused": bool(m.GetIndicesReused()),
        }
        return stats

    def capture(self):
        """Grab the frame rendered last; returns the vtkImageData (RGB, bottom row first).
        Once a frame: write_png and a video both use this grab."""
        if self.grab is None:
            self.grab = vtkWindowToImageFilter()
            self.grab.SetInput(self.window)
            self.grab.ReadFrontBufferOff()
            self.grab.ShouldRerenderOff()
            self.png = vtkPNGWriter()
            self.png.SetInputConnection(self.grab.GetOutputPort())
        self.grab.Modified()
        self.grab.Update()
        return self.grab.GetOutput()

    def write_png(self, filename):
        """Write the frame captured last (capture()) as PNG."""
        self.png.SetFileName(filename)
        self.png.Write()
