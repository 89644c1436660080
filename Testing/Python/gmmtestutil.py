"""Helpers of the geomipmap Python tests: data folder, skipping, error capture, memory."""
import resource

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

from gmmdata import SKIP, data_dir_or_skip, data_file  # noqa: F401 (the one data rule)


class ErrorCatcher:
    """Collects the ErrorEvent texts of one algorithm (and keeps them off stderr).

    The executive's follow-up "returned failure" error is swallowed too: it names the
    request, not the file, and would only clutter the log.
    """

    def __init__(self, alg):
        self.messages = []

        @calldata_type(VTK_STRING)
        def on_error(caller, event, text):
            self.messages.append(text)

        @calldata_type(VTK_STRING)
        def on_executive_error(caller, event, text):
            pass

        self._callbacks = (on_error, on_executive_error)  # keep them alive
        alg.AddObserver(vtkCommand.ErrorEvent, on_error)
        alg.GetExecutive().AddObserver(vtkCommand.ErrorEvent, on_executive_error)

    def clear(self):
        self.messages = []


def update(alg):
    """Runs the pipeline; returns True when every request succeeded."""
    return alg.GetExecutive().Update() == 1


def read_dem(path, **options):
    """Runs a vtkGeoMipMapTerrainReader on `path` with Set<Name>(value) for each option;
    checks (check()) that it reads without an error; returns (reader, output image)."""
    from geomipmap import vtkGeoMipMapTerrainReader

    r = vtkGeoMipMapTerrainReader()
    r.SetFileName(path)
    for key, value in options.items():
        getattr(r, "Set" + key)(value)
    errors = ErrorCatcher(r)
    check(update(r), "%s %s reads (errors: %s)" % (path, options or "", errors.messages))
    return r, r.GetOutput()


def max_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def check(cond, what):
    if not cond:
        raise AssertionError(what)
    print("ok:", what)


# ---------------------------------------------------------------------------------------
# The measured screen-space error of what vtkGeoMipMapMapper drew, independent of the
# engine's own bound: vtkGeoMipMapFilter with the same camera, viewport, tau and block
# size gives the mapper's triangles (TestGeoMipMapFilterAgreement; the triangle counts are
# compared on every use), and vtkGeoMipMapScreenError (no engine code) measures them
# against the full-resolution heightfield, projecting with the camera's own composite
# matrix times the actor's: data -> world -> clip.

class Measured:
    """What measure_drawn found: triangles (the filter's), error_px (the maximum over the
    in-view samples), p99_px, in_view, uncovered (in-view samples no triangle covers)."""

    def __init__(self, **kw):
        self.__dict__.update(kw)

    def __repr__(self):
        return ("%d triangles, measured error %.4f px (p99 %.4f), %d samples in view, "
                "%d uncovered" % (self.triangles, self.error_px, self.p99_px, self.in_view,
                                  self.uncovered))


def lod_mesh(image, camera, size, tau, block_size, matrix=None, height_scale=1.0,
             geomorphing=True, geomorph_merges=None):
    """vtkGeoMipMapFilter's triangles for this camera, viewport size (w, h), tau, block
    size, actor matrix (None: identity), height scale, geomorphing and geomorph merges (None:
    the filter's default, the mapper's): what the mapper draws with them."""
    import geomipmap

    filt = geomipmap.vtkGeoMipMapFilter()
    filt.SetInputData(image)
    filt.SetCamera(camera)
    filt.SetModelMatrix(matrix)
    filt.SetViewportSize(*size)
    filt.SetPixelError(tau)
    filt.SetBlockSize(block_size)
    filt.SetHeightScale(height_scale)
    filt.SetGeomorphing(geomorphing)
    if geomorph_merges is not None:
        filt.SetGeomorphMerges(geomorph_merges)
    filt.Update()
    return filt.GetOutput()


def data_matrix(actor):
    """The actor's data -> world matrix, or None when it is the identity."""
    matrix = actor.GetMatrix()  # also brings GetIsIdentity up to date
    return None if actor.GetIsIdentity() else matrix


def measure_mesh(image, ren, actor, mesh):
    """vtkGeoMipMapScreenError of `mesh` (world coordinates of `actor`'s data) against the
    full-resolution `image`, with `ren`'s camera and size: a Measured."""
    import geomipmap
    from vtkmodules.vtkCommonMath import vtkMatrix4x4

    matrix = data_matrix(actor)
    w, h = ren.GetSize()
    clip = vtkMatrix4x4()
    clip.DeepCopy(ren.GetActiveCamera().GetCompositeProjectionTransformMatrix(
        ren.GetTiledAspectRatio(), -1, 1))
    if matrix is not None:
        vtkMatrix4x4.Multiply4x4(clip, matrix, clip)  # data -> world -> clip
    err = geomipmap.vtkGeoMipMapScreenError()
    err.SetHeightfield(image)
    err.SetHeightScale(actor.GetMapper().GetHeightScale())
    err.SetMesh(mesh)
    err.SetViewportSize(w, h)
    err.SetProjectionMatrix(clip)
    if not err.Compute():
        raise AssertionError("vtkGeoMipMapScreenError failed")
    return Measured(triangles=mesh.GetNumberOfPolys(), error_px=err.GetMaximumError(),
                    p99_px=err.GetPercentile99Error(), in_view=err.GetNumberOfSamplesInView(),
                    uncovered=err.GetNumberOfUncoveredSamples())


def measure_drawn(image, ren, actor, tau, block_size):
    """Measures the last frame `ren` drew of `actor` (a vtkGeoMipMapMapper over `image` with
    this tau and block size): see the comment above. Call it right after the render."""
    mapper = actor.GetMapper()
    mesh = lod_mesh(image, ren.GetActiveCamera(), ren.GetSize(), tau, block_size, data_matrix(actor),
                    mapper.GetHeightScale(), mapper.GetGeomorphing(), mapper.GetGeomorphMerges())
    return measure_mesh(image, ren, actor, mesh)


def full_resolution_uncovered(image, ren, actor):
    """In-view samples of `image` that its full-resolution mesh (vtkGeoMipMapFilter at a
    maximum geometric error of 0, the mapper's block size) leaves uncovered in `ren`'s
    view: valid samples whose every full-resolution triangle touches nodata."""
    import geomipmap

    filt = geomipmap.vtkGeoMipMapFilter()
    filt.SetInputData(image)
    filt.SetBlockSize(actor.GetMapper().GetBlockSize())
    filt.SetHeightScale(actor.GetMapper().GetHeightScale())
    filt.SetMaximumGeometricError(0.0)
    filt.Update()
    return measure_mesh(image, ren, actor, filt.GetOutput()).uncovered


def check_drawn_within_tau(image, ren, actor, mapper, what="", uncovered_ok=False):
    """Asserts (AssertionError) that the mapper's last frame measures within its tau and
    that the measured mesh is the drawn one (same triangle count); returns the Measured.
    uncovered_ok: False, no in-view sample may be left uncovered; True, any may (holes);
    "as full resolution", no more than the full-resolution mesh leaves (a valid sample
    between nodata samples can have no full-resolution triangle, and which ones depends on
    the diagonals of the quads beside it)."""
    tau = mapper.GetPixelError()
    m = measure_drawn(image, ren, actor, tau, mapper.GetBlockSize())
    drawn = mapper.GetNumberOfRenderedTriangles()
    print("%s: mapper %d triangles; %r; tau %g" % (what, drawn, m, tau))
    if m.triangles != drawn:
        raise AssertionError("%s: the filter gives %d triangles, the mapper drew %d: not the "
                             "drawn mesh" % (what, m.triangles, drawn))
    if m.in_view <= 0 or drawn <= 0:
        raise AssertionError("%s: nothing in view (%d samples, %d triangles)"
                             % (what, m.in_view, drawn))
    if not m.error_px <= tau + 1e-6:
        raise AssertionError("%s: measured screen error %.4f px > tau %g px"
                             % (what, m.error_px, tau))
    if uncovered_ok == "as full resolution" and m.uncovered:
        full = full_resolution_uncovered(image, ren, actor)
        print("%s: %d in-view samples uncovered, %d at full resolution" % (what, m.uncovered, full))
        if m.uncovered > full:
            raise AssertionError("%s: %d in-view samples not covered, %d at full resolution"
                                 % (what, m.uncovered, full))
    elif not uncovered_ok and m.uncovered:
        raise AssertionError("%s: %d in-view samples not covered" % (what, m.uncovered))
    return m


def check_within_tau(check, image, ren, actor, mapper, what, uncovered_ok=False):
    """check_drawn_within_tau reported through `check` (a refscene.Checks): one line, ok or
    FAIL with the reason, instead of an exception."""
    try:
        check_drawn_within_tau(image, ren, actor, mapper, what, uncovered_ok)
        check(True, f"{what}: measured within tau")
    except AssertionError as e:
        check(False, str(e))


def resampling_mismatch(img, src, lon0, lat0, step_deg, nodes=20000, seed=5):
    """How far a lon/lat raster read by vtkGeoMipMapTerrainReader is from its source.

    src: the source heights (ny x nx, row 0 = south, NaN = nodata) on the lattice lon0 +
    i * step_deg, lat0 + j * step_deg. At `nodes` random valid-or-void nodes inside the
    lattice, the node's lon/lat (vtkGeoMipMapTerrainReader.LocalToGeographic) gives the
    expected height, recomputed here from the source: bilinear in the 4 samples around it,
    or the nearest sample when one of the 4 is nodata (the reader's documented rule).
    Returns (nodes whose nodata-ness differs, largest height difference, nodes compared)."""
    import random

    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from geomipmap import vtkGeoMipMapTerrainReader as R

    z = vtk_to_numpy(img.GetPointData().GetScalars())
    gx = img.GetDimensions()[0]
    (ox, oy), (dx, dy) = img.GetOrigin()[:2], img.GetSpacing()[:2]
    sy, sx = src.shape
    rng = random.Random(seed)
    bad, worst, done, ll = 0, 0.0, 0, [0.0, 0.0]
    while done < nodes:
        k = rng.randrange(z.size)
        R.LocalToGeographic(img, ox + k % gx * dx, oy + k // gx * dy, ll)
        u, v = (ll[0] - lon0) / step_deg, (ll[1] - lat0) / step_deg
        if not (1e-6 < u < sx - 1 - 1e-6 and 1e-6 < v < sy - 1 - 1e-6):
            continue  # outside the lattice or on its edge
        i, j = int(u), int(v)
        tu, tv = u - i, v - j
        q = src[j:j + 2, i:i + 2]
        if np.isfinite(q).all():
            want = (1 - tv) * ((1 - tu) * q[0, 0] + tu * q[0, 1]) + \
                tv * ((1 - tu) * q[1, 0] + tu * q[1, 1])
        else:
            want = q[int(tv >= 0.5), int(tu >= 0.5)]
        got = z[k]
        if np.isnan(want) != np.isnan(got):
            bad += 1
        elif not np.isnan(want):
            worst = max(worst, abs(float(got) - float(want)))
        done += 1
    return bad, worst, done
