"""vtkGeoMipMapMapper frame budgets (issue #14): SetTriangleBudget, the
FollowAllocatedRenderTime mode, and front-to-back drawing.

A 257^2 fractal seen low across a corner at tau 0.5 px. Each check is against something
the mapper does not report about itself:
- with a triangle budget, the drawn count is within it, and the budgeted mesh (the same
  engine run by vtkGeoMipMapFilter with the same budget; same triangle count as drawn)
  measures with vtkGeoMipMapScreenError within the error the mapper reports;
- in FollowAllocatedRenderTime mode the budget moves the right way: down when each frame
  is allocated 1 ms (no frame fits), up to the tau-driven frame when allocated 100 s, and
  a still render (the interactor's StillUpdateRate) draws the tau-driven frame. No
  timing threshold: only directions and the endpoints are checked;
- front to back draws the very same pixels as block order, with fewer depth-passing
  fragments (GL_SAMPLES_PASSED) where block order is back to front.
"""

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindowInteractor

import vtkmodules.vtkInteractionStyle  # noqa: F401 (the interactor's default style)
import geomipmap
import refscene
from gmmtestutil import ErrorCatcher

W, H = 400, 300
TAU, BLOCK = 0.5, 32
check = refscene.Checks()

image = refscene.fractal_image(257, 257, seed=3)

mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputData(image)
mapper.SetPixelError(TAU)
mapper.SetBlockSize(BLOCK)
actor = vtkActor()
actor.SetMapper(mapper)
ren = vtkRenderer()
ren.AddActor(actor)
win = refscene.window(W, H, ren)
x0, x1, y0, y1, z0, z1 = mapper.GetBounds()
cam = ren.GetActiveCamera()
cam.SetPosition(x0 - 300.0, y0 - 300.0, z1 + 200.0)
cam.SetFocalPoint(0.5 * (x0 + x1), 0.5 * (y0 + y1), z0)
cam.SetViewUp(0.0, 0.0, 1.0)
cam.SetViewAngle(40.0)
ren.ResetCameraClippingRange(x0, x1, y0, y1, z0, z1)


def budget_mesh(budget):
    """vtkGeoMipMapFilter's triangles for the current camera with this budget."""
    f = geomipmap.vtkGeoMipMapFilter()
    f.SetInputData(image)
    f.SetCamera(cam)
    f.SetViewportSize(W, H)
    f.SetPixelError(TAU)
    f.SetBlockSize(BLOCK)
    f.SetTriangleBudget(budget)
    # Where the mapper's budgeted search started (its previous budgeted frame's tau).
    f.SetBudgetStartTau(mapper.GetLastBudgetStartTau())
    f.Update()
    return f.GetOutput()


def measured_error(mesh):
    from vtkmodules.vtkCommonMath import vtkMatrix4x4

    clip = vtkMatrix4x4()
    clip.DeepCopy(cam.GetCompositeProjectionTransformMatrix(ren.GetTiledAspectRatio(), -1, 1))
    e = geomipmap.vtkGeoMipMapScreenError()
    e.SetHeightfield(image)
    e.SetMesh(mesh)
    e.SetViewportSize(W, H)
    e.SetProjectionMatrix(clip)
    check(e.Compute(), "vtkGeoMipMapScreenError computes")
    return e.GetMaximumError(), e.GetNumberOfUncoveredSamples()


# --- tau alone: the reference frame
win.Render()
full = mapper.GetNumberOfRenderedTriangles()
check(mapper.GetTriangleBudgetInForce() == 0, "no budget by default")
check(full > 20000, f"tau-driven frame draws {full} triangles")
# A budgeted frame follows no geomorphing level path (its levels are the coarsest within its
# error): the tau-driven frame it reduces to when tau stops first is the one without the path.
mapper.SetGeomorphRange(1.0)
win.Render()
coarsest = mapper.GetNumberOfRenderedTriangles()
mapper.SetGeomorphRange(geomipmap.vtkGeoMipMapMapper().GetGeomorphRange())
check(0 < coarsest <= full, f"without the level path tau draws {coarsest} triangles")

# --- a fixed budget
for budget in (full // 3, full // 10, 2000):
    mapper.SetTriangleBudget(budget)
    win.Render()
    drawn = mapper.GetNumberOfRenderedTriangles()
    reported = mapper.GetMaximumScreenSpaceError()
    check(mapper.GetTriangleBudgetInForce() == budget, f"budget {budget} in force")
    check(0 < drawn <= budget, f"budget {budget}: {drawn} triangles drawn")
    check(mapper.GetTriangleBudgetReached(), f"budget {budget} binds (tau would draw {full})")
    mesh = budget_mesh(budget)
    check(mesh.GetNumberOfPolys() == drawn,
          f"budget {budget}: the filter's mesh is the drawn one ({mesh.GetNumberOfPolys()} vs {drawn})")
    err, uncovered = measured_error(mesh)
    check(uncovered == 0, f"budget {budget}: every in-view sample covered")
    check(err <= reported + 1e-6,
          f"budget {budget}: measured {err:.4f} px <= reported {reported:.4f} px")
    check(reported > TAU, f"budget {budget}: coarser than tau ({reported:.3f} px)")

mapper.SetTriangleBudget(1)
win.Render()
check(mapper.GetOverTriangleBudget(), "budget 1: even the coarsest selection is over it")
check(mapper.GetNumberOfRenderedTriangles() == 2 * mapper.GetNumberOfVisibleBlocks(),
      "budget 1: every visible block drawn as one quad")

check(mapper.GetLastBudgetStartTau() > 0.0,
      "a budgeted frame after another starts its search at that frame's tau")
f = geomipmap.vtkGeoMipMapFilter()
ferrors = ErrorCatcher(f)
f.SetBudgetStartTau(float("nan"))
f.SetBudgetStartTau(-1.0)
check(f.GetBudgetStartTau() == 0.0 and len(ferrors.messages) == 2
      and all("BudgetStartTau must be a finite number >= 0" in e for e in ferrors.messages),
      f"the filter refuses a start tau that is not finite and >= 0 ({ferrors.messages})")

errors = ErrorCatcher(mapper)
mapper.SetTriangleBudget(-5)
check(mapper.GetTriangleBudget() == 1 and len(errors.messages) == 1,
      f"a negative budget is refused with an error ({errors.messages})")
mapper.SetTriangleBudget(0)
win.Render()
check(mapper.GetNumberOfRenderedTriangles() == full and mapper.GetTriangleBudgetInForce() == 0,
      "budget 0 is the tau-driven frame again")

# --- following the allocated render time
mapper.FollowAllocatedRenderTimeOn()
win.SetDesiredUpdateRate(1000.0)  # 1 ms a frame: nothing fits, the budget must fall
budgets = []
for _ in range(8):
    win.Render()
    check(mapper.GetLastFrameInteractive(), "a 1000 Hz render is interactive")
    budgets.append(mapper.GetTriangleBudgetInForce())
    check(mapper.GetNumberOfRenderedTriangles() <= budgets[-1] or mapper.GetOverTriangleBudget(),
          f"interactive frame within its budget {budgets[-1]}")
print("budgets at 1 ms:", budgets)
check(abs(actor.GetAllocatedRenderTime() - 0.001) < 1e-9, "the actor was allocated 1 ms")
check(all(b <= a for a, b in zip(budgets[1:], budgets[2:])) and budgets[-1] < budgets[0],
      "allocated 1 ms: the budget only falls")
check(mapper.GetNumberOfRenderedTriangles() < full, "allocated 1 ms: fewer triangles than tau")

win.SetDesiredUpdateRate(0.01)  # 100 s a frame: the budget may grow up to the tau frame
budgets = []
for _ in range(16):
    win.Render()
    budgets.append(mapper.GetTriangleBudgetInForce())
print("budgets at 100 s:", budgets)
check(all(b >= a for a, b in zip(budgets, budgets[1:])), "allocated 100 s: the budget only grows")
check(all(b <= 2 * a for a, b in zip(budgets, budgets[1:])), "it grows at most x2 a frame")
check(mapper.GetNumberOfRenderedTriangles() == coarsest and not mapper.GetTriangleBudgetReached(),
      "allocated 100 s: tau stops first, the tau-driven frame (without the level path) is drawn")
check(budgets[-1] <= 2 * full, "the budget stays within x2 of what tau draws")

# Still and interactive as an interactor defines them.
iren = vtkRenderWindowInteractor()
iren.SetRenderWindow(win)
iren.SetStillUpdateRate(0.5)
win.SetDesiredUpdateRate(1000.0)
win.Render()
check(mapper.GetLastFrameInteractive() and mapper.GetTriangleBudgetInForce() > 0,
      "above the interactor's still rate: interactive, budgeted")
win.SetDesiredUpdateRate(0.5)
win.Render()
check(not mapper.GetLastFrameInteractive() and mapper.GetTriangleBudgetInForce() == 0
      and mapper.GetNumberOfRenderedTriangles() == full,
      "at the still rate: tau alone, the full frame")
mapper.FollowAllocatedRenderTimeOff()

# --- front to back, seen from the north-east corner: there block order (rows from the
# south) is back to front, the worst case for the depth test.
cam.SetPosition(x1 + 300.0, y1 + 300.0, z1 + 100.0)
ren.ResetCameraClippingRange(x0, x1, y0, y1, z0, z1)
mapper.SetCountFragments(True)
shots, passed = {}, {}
for order in (False, True):
    mapper.SetFrontToBack(order)
    win.Render()
    shots[order] = refscene.grab(win)
    passed[order] = mapper.GetLastFragmentsPassed()
print("samples passed: block order %d, front to back %d" % (passed[False], passed[True]))
check(np.array_equal(shots[False], shots[True]), "front to back draws the same pixels")
check(0 < passed[True] < passed[False], "front to back: fewer fragments pass the depth test")

check.exit()
