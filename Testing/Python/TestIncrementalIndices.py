"""Incremental index uploads (issue #11): along a slow flight the mapper uploads only the
index ranges of the blocks that changed, and every frame is pixel-identical to a fresh
mapper that uploads everything; in wireframe too. The last frame is certified by the
independent screen-error measure.
"""
import math

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer

import geomipmap
import refscene
from gmmtestutil import check_drawn_within_tau

N = 513
ok = refscene.Checks()
image = refscene.fractal_image(N, N, seed=7)
ext = (N - 1) * 30.0


def scene():
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputData(image)
    mapper.SetPixelError(1.0)
    mapper.SetBlockSize(16)
    mapper.SetScalarRange(0.0, 1500.0)
    # Geomorphing off: how fast a morph factor may rise depends on the frames a mapper drew
    # before, so a fresh mapper morphs differently; the triangles, whose uploads are under
    # test, are the same either way.
    mapper.GeomorphingOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    ren = vtkRenderer()
    ren.AddActor(actor)
    win = refscene.window(400, 260, ren)
    ren._window = win
    return mapper, actor, ren, win


def place(ren, f):
    # A low flight along the diagonal, 15 m a frame (half a sample), turning slowly.
    x = 0.25 * ext + 15.0 * f
    a = math.radians(40.0 + 0.5 * f)
    cam = ren.GetActiveCamera()
    cam.SetPosition(x, x, 1900.0)
    cam.SetFocalPoint(x + 1000 * math.cos(a), x + 1000 * math.sin(a), 1500.0)
    cam.SetViewUp(0, 0, 1)
    cam.SetViewAngle(50.0)
    ren.ResetCameraClippingRange()


def fresh_frame(f, wireframe):
    mapper, actor, ren, win = scene()
    if wireframe:
        actor.GetProperty().SetRepresentationToWireframe()
    place(ren, f)
    win.Render()
    return refscene.grab(win), mapper


for wireframe in (False, True):
    what = "wireframe" if wireframe else "surface"
    mapper, actor, ren, win = scene()
    if wireframe:
        actor.GetProperty().SetRepresentationToWireframe()
    partial, fractions, same = 0, [], True
    for f in range(24):
        place(ren, f)
        win.Render()
        # (Before grabbing: the grab renders again, a reused frame that uploads nothing.)
        uploaded = mapper.GetLastIndexUploadBytes()
        whole = 4 * mapper.GetNumberOfRenderedTriangles() * 3
        got = refscene.grab(win)
        if 0 < uploaded < whole:
            partial += 1
        if f > 0:
            fractions.append(uploaded / whole)
        if f % 4 == 3:  # against a fresh mapper (one whole upload) at the same camera
            ref, fm = fresh_frame(f, wireframe)
            same = same and np.array_equal(got, ref)
            ok(fm.GetNumberOfRenderedTriangles() == mapper.GetNumberOfRenderedTriangles(),
               "%s frame %d: same triangle count as a fresh mapper" % (what, f))
    ok(same, "%s: every compared frame pixel-identical to a fresh mapper's" % what)
    if wireframe:
        ok(partial == 0, "wireframe uploads its line list whole (%d partial frames)" % partial)
    else:
        ok(partial >= 20, "surface: %d of 24 frames uploaded only changed ranges" % partial)
        ok(np.median(fractions) < 0.25, "surface: median upload %.1f %% of the whole index list"
           % (100 * np.median(fractions)))
        check_drawn_within_tau(image, ren, actor, mapper, "last incremental frame")

ok.exit()
