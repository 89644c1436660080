"""Regression images of real DEMs through vtkGeoMipMapTerrainReader + vtkGeoMipMapMapper.

Cases: Puget Sound (16-bit PNG, 0.1 m units, 160 m spacing) and Mt Rainier (GeoTIFF, lon/lat,
9033 voids that must render as holes). Each renders off-screen at tau = 1 px with an elevation
lookup table, lighting and a 2x vertical exaggeration (actor scale (1, 1, 2)), measures the
screen error of what was drawn independently of the engine (gmmtestutil.check_drawn_within_tau:
vtkGeoMipMapFilter's copy of the drawn triangles against the full-resolution DEM through
vtkGeoMipMapScreenError, projected data -> clip with the camera's matrix times the actor's),
requires it within tau, and compares the picture with Data/Baseline/TestRender<Case>.png
(VTK's image comparison). GEOMIPMAP_WRITE_BASELINE=1 writes the baseline instead (look at it
before committing it). Both DEMs are required: a missing one skips the whole test (or fails
it under GEOMIPMAP_REQUIRE_DATA=1).
"""
import os
import sys

import geomipmap
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkRenderer, vtkRenderWindow,
                                         vtkWindowToImageFilter)
from vtkmodules.test import Testing

from gmmdata import data_file
from gmmtestutil import check_drawn_within_tau

here = os.path.dirname(os.path.abspath(__file__))
baselines = os.path.join(here, "..", "..", "Data", "Baseline")
CASES = {
    "Puget": ("ps_height_1k.png", dict(HeightScale=0.1, Spacing=160.0), (0.0, 4379.8)),
    "Rainier": ("mt_rainier_90m.tif", {}, (263.0, 4371.0)),
}


def render(case):
    name, options, (zmin, zmax) = CASES[case]
    path = data_file(name)
    reader = geomipmap.vtkGeoMipMapTerrainReader()
    reader.SetFileName(path)
    for key, value in options.items():
        getattr(reader, "Set" + key)(value)
    mapper = geomipmap.vtkGeoMipMapMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.SetPixelError(1.0)
    lut = vtkLookupTable()
    lut.SetHueRange(0.33, 0.0)
    lut.SetSaturationRange(0.6, 0.0)
    lut.SetValueRange(0.45, 1.0)
    lut.Build()
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(zmin, zmax)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.SetScale(1.0, 1.0, 2.0)  # vertical exaggeration, as users do for relief
    ren = vtkRenderer()
    ren.AddActor(actor)
    ren.SetBackground(0.1, 0.1, 0.2)
    win = vtkRenderWindow()
    win.AddRenderer(ren)
    win.SetOffScreenRendering(1)
    win.SetSize(400, 300)
    ren.ResetCamera()
    cam = ren.GetActiveCamera()
    cam.Elevation(-60)
    cam.Zoom(1.4)
    ren.ResetCameraClippingRange()
    win.Render()
    print("%s: engine's own bound %.3f px (not checked: the measure below is)"
          % (case, mapper.GetMaximumScreenSpaceError()))
    try:
        check_drawn_within_tau(reader.GetOutput(), ren, actor, mapper, case,
                               uncovered_ok=case == "Rainier")  # Rainier's voids
    except AssertionError as e:
        print("FAIL:", e)
        return win, False
    return win, True


def main():
    for name, _, _ in CASES.values():
        data_file(name)  # every DEM, before anything renders: none may be missing
    failed = []
    for case in CASES:
        win, ok = render(case)
        if not ok:
            failed.append(case)
        baseline = os.path.join(baselines, "TestRender%s.png" % case)
        if os.environ.get("GEOMIPMAP_WRITE_BASELINE"):
            shot = vtkWindowToImageFilter()
            shot.SetInput(win)
            writer = vtkPNGWriter()
            writer.SetInputConnection(shot.GetOutputPort())
            writer.SetFileName(baseline)
            writer.Write()
            continue
        Testing.compareImage(win, baseline, threshold=10)
    if failed:
        print("FAIL: measured screen error above tau in", ", ".join(failed))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
