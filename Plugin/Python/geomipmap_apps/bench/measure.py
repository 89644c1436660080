"""Timed frames, measured screen-space error and the depth-buffer check.

Why here and not in the engine: the measured error must not share code with the bound it
checks. geomipmap.vtkGeoMipMapScreenError (C++, no gmm code) rasterises any mesh over the
full-resolution grid and projects true and drawn points with the camera's own matrix.

Shading check: the fraction of terrain pixels whose colour differs from the
full-resolution rendering (brute force, lit with the same central-difference normals and
coloured per fragment) by more than 24 grey levels in some channel.

Depth check: a pixel "differs by more than one depth step" from the full-resolution
rendering when |z - z_ref| exceeds the largest |z_ref(p) - z_ref(q)| over its 8
neighbours q (what shifting the reference image by one pixel could cause) plus one 24-bit
depth quantum, or when exactly one of the two shows terrain (the other background).
"""

import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkUnsignedCharArray
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

DEPTH_QUANTUM = 2.0 ** -24


class Bench:
    """One window and renderer (geomipmap_apps.scene.Scene); one actor shown at a time."""

    def __init__(self, scene, image, heights, flight, size):
        import geomipmap

        self.scene, self.image, self.heights, self.flight = scene, image, heights, flight
        self.size = size
        xmin, xmax, ymin, ymax = heights.bounds
        self.bounds = (min(xmin, xmax), max(xmin, xmax), min(ymin, ymax), max(ymin, ymax),
                       heights.zmin, heights.zmax)
        self.error = geomipmap.vtkGeoMipMapScreenError()
        self.error.SetHeightfield(image)
        self.error.SetViewportSize(*size)
        # The mapper's triangles (and morphed heights) per frame, one filter per
        # geomorphing setting: each keeps its own morph history, as the mapper does.
        self.filters = {}
        for geomorphing in (True, False):
            self.filters[geomorphing] = self._filter()
            self.filters[geomorphing].SetGeomorphing(geomorphing)

    def _filter(self):
        """A vtkGeoMipMapFilter of the terrain for the scene's camera and viewport, at the
        scene mapper's block size."""
        import geomipmap

        f = geomipmap.vtkGeoMipMapFilter()
        f.SetInputData(self.image)
        f.SetCamera(self.scene.renderer.GetActiveCamera())
        f.SetViewportSize(*self.size)
        f.SetBlockSize(self.scene.mapper.GetBlockSize())
        return f

    def _add_actor(self, mapper):
        """An actor in the scene for `mapper`, coloured through ours' lookup table and
        scalar range and lit with ours' actor's property."""
        ours = self.scene.mapper
        mapper.SetLookupTable(ours.GetLookupTable())
        mapper.SetScalarRange(ours.GetScalarRange())
        mapper.SetColorModeToMapScalars()
        mapper.ScalarVisibilityOn()
        a = vtkActor()
        a.SetMapper(mapper)
        a.SetProperty(self.scene.actor.GetProperty())
        self.scene.renderer.AddActor(a)
        return a

    def camera(self, frame):
        """Frame's camera; one clipping range for every method (from the terrain's bounds),
        so that depth buffers are comparable."""
        self.flight.apply(self.scene.renderer.GetActiveCamera(), frame)
        self.scene.renderer.ResetCameraClippingRange(*self.bounds)

    def show(self, actor):
        for a in self.all_actors():
            a.SetVisibility(a is actor)

    def all_actors(self):
        acts = self.scene.renderer.GetActors()
        acts.InitTraversal()
        return [acts.GetNextActor() for _ in range(acts.GetNumberOfItems())]

    def add_mesh(self, mesh):
        """A stock vtkPolyDataMapper actor for a mesh, coloured and lit like ours."""
        m = vtkPolyDataMapper()
        m.SetInputData(mesh)
        # Map each fragment's interpolated height, as the GeoMipMap mapper does.
        m.InterpolateScalarsBeforeMappingOn()
        return self._add_actor(m)

    def add_floor(self, tau):
        """The fill floor: a second LOD mapper as the scene's is configured (block size,
        geomorphing settings, colouring, the actor's property) with its cheapest shading
        (normals per vertex) at pixel error `tau`, with its own actor and its own filter for
        the measured error. Its own, so that it keeps its own levels and morph history: the
        scene's mapper, shared by ours' methods, would otherwise follow a frame at the
        coarsest. Returns (actor, mapper, mesh_for_frame)."""
        import geomipmap

        ours = self.scene.mapper
        m = geomipmap.vtkGeoMipMapMapper()
        m.SetInputData(self.image)
        m.SetBlockSize(ours.GetBlockSize())
        m.SetGeomorphRange(ours.GetGeomorphRange())
        m.SetGeomorphMeasureSamples(ours.GetGeomorphMeasureSamples())
        m.SetPixelError(tau)
        m.SetNormalModeToPerVertex()
        a = self._add_actor(m)
        f = self._filter()
        f.SetGeomorphRange(ours.GetGeomorphRange())
        f.SetGeomorphMeasureSamples(ours.GetGeomorphMeasureSamples())
        f.SetPixelError(tau)

        def mesh(frame):
            f.Modified()
            f.Update()
            return f.GetOutput()
        return a, m, mesh

    def depth(self):
        w, h = self.size
        buf = vtkFloatArray()
        self.scene.window.GetZbufferData(0, 0, w - 1, h - 1, buf)
        return vtk_to_numpy(buf).reshape(h, w).copy()

    def pixels(self):
        w, h = self.size
        buf = vtkUnsignedCharArray()
        self.scene.window.GetPixelData(0, 0, w - 1, h - 1, 0, buf, 0)
        return vtk_to_numpy(buf).reshape(h, w, 3).copy()

    def render(self):
        """Render() then WaitForCompletion() (glFinish): milliseconds of wall time."""
        w = self.scene.window
        t0 = time.perf_counter()
        w.Render()
        w.WaitForCompletion()
        return (time.perf_counter() - t0) * 1000.0

    def frame(self, actor, mesh_for_frame, f, reference, extra=None):
        """Render frame f with only `actor` shown; return (row, (depth buffer, pixels)).

        mesh_for_frame(f) -> the vtkPolyData drawn (for the measured error); extra(row)
        adds method-specific columns (ours: LOD and index upload times); reference: the
        full-resolution (depth buffer, pixels) of this frame, or None.
        """
        self.show(actor)
        self.camera(f)
        total = self.render()
        row = {"frame": f, "total_ms": total, "lod_ms": 0.0, "upload_ms": 0.0,
               "render_ms": total}
        if extra:
            extra(row)
        z, rgb = self.depth(), self.pixels()
        row["depth_bad_frac"] = (depth_mismatch(reference[0], z) if reference is not None
                                 else float("nan"))
        row["shade_diff_frac"] = (shading_mismatch(reference, z, rgb) if reference is not None
                                  else float("nan"))
        row.update(self.measure(mesh_for_frame(f)))
        return row, (z, rgb)

    def measure(self, mesh):
        cam = self.scene.renderer.GetActiveCamera()
        w, h = self.size
        self.error.SetProjectionMatrix(cam.GetCompositeProjectionTransformMatrix(w / h, -1, 1))
        self.error.SetMesh(mesh)
        if not self.error.Compute():
            raise RuntimeError("screen error measure failed")
        e = self.error
        return {"err_max_px": e.GetMaximumError(), "err_p99_px": e.GetPercentile99Error(),
                "err_mean_px": e.GetMeanError(), "samples_in_view": e.GetNumberOfSamplesInView(),
                "uncovered": e.GetNumberOfUncoveredSamples(),
                "triangles": mesh.GetNumberOfPolys()}

    def ours_mesh(self, tau, geomorphing=True):
        """The mapper's triangles for the current camera (vtkGeoMipMapFilter, same engine
        call, same camera and viewport), with geomorphing on (the default) or off."""
        f = self.filters[geomorphing]
        f.SetPixelError(tau)
        f.Modified()
        f.Update()
        return f.GetOutput()


SHADE_TOLERANCE = 24  # grey levels, largest channel difference


def shading_mismatch(reference, z, rgb):
    """Fraction of the terrain's pixels (terrain in either picture) whose colour differs
    from the full-resolution rendering by more than SHADE_TOLERANCE in some channel."""
    ref_z, ref_rgb = reference
    terrain = (ref_z < 1.0) | (z < 1.0)
    if not terrain.any():
        return 0.0
    diff = np.abs(rgb.astype(np.int16) - ref_rgb.astype(np.int16)).max(axis=2)
    return float((diff[terrain] > SHADE_TOLERANCE).mean())


def depth_mismatch(ref, z):
    """Fraction of pixels whose depth differs from the reference by more than one step."""
    pad = np.pad(ref, 1, mode="edge")
    h, w = ref.shape
    step = np.zeros_like(ref)
    for dj in (-1, 0, 1):
        for di in (-1, 0, 1):
            if di or dj:
                step = np.maximum(step, np.abs(pad[1 + dj:1 + dj + h, 1 + di:1 + di + w] - ref))
    ref_bg, bg = ref >= 1.0, z >= 1.0
    bad = (ref_bg != bg) | (~ref_bg & ~bg & (np.abs(z - ref) > step + DEPTH_QUANTUM))
    return float(bad.mean())
