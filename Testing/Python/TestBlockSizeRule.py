"""One minimum block size, refused at every entry point (issue #16, item 4).

Regression: SetBlockSize(2) or (3) on the mapper and the filter, and geomipmap-fly
--block-size 2 (whose help said "a power of two 2..1024"), were accepted, then every
render logged "below the minimum of 4 quads" and drew nothing. The rule now lives in one
place (gmm::kMinBlockQuads, 4): the setters refuse smaller values with an error and keep
the previous value, geomipmap-fly refuses them with its one-line error and exit 2, and
the help texts say 4.
The default block size is one value too (gmm::kDefaultBlockQuads, 32, chosen by
measurement): a new mapper and filter start with it and the tools' --block-size defaults
to it (the help says so).
Usage: TestBlockSizeRule.py [geomipmap-fly]
"""
import subprocess
import sys

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer

import geomipmap
import refscene

check = refscene.Checks()


class Errors:
    def __init__(self, obj):
        self.count = 0
        obj.AddObserver(vtkCommand.ErrorEvent, self)

    def __call__(self, caller, event):
        self.count += 1


src = geomipmap.vtkGeoMipMapFractalSource()
src.SetDimensions(129, 129)
src.SetSpacing(30.0)

mapper = geomipmap.vtkGeoMipMapMapper()
mapper.SetInputConnection(src.GetOutputPort())
filt = geomipmap.vtkGeoMipMapFilter()
filt.SetInputConnection(src.GetOutputPort())
default = geomipmap.vtkGeoMipMapMapper.GetDefaultBlockSize()
check(default == 32, f"the default block size is 32 (got {default})")
check(mapper.GetBlockSize() == default and filt.GetBlockSize() == default,
      f"a new mapper and filter start at the default (mapper {mapper.GetBlockSize()}, "
      f"filter {filt.GetBlockSize()})")
for obj, name in ((mapper, "mapper"), (filt, "filter")):
    errors = Errors(obj)
    obj.SetBlockSize(32)
    for bad in (3, 2, 1, 0, -4):
        before = errors.count
        obj.SetBlockSize(bad)
        check(obj.GetBlockSize() == 32 and errors.count == before + 1,
              f"{name}: SetBlockSize({bad}) refused with an error, 32 kept "
              f"(now {obj.GetBlockSize()})")
    obj.SetBlockSize(4)
    check(obj.GetBlockSize() == 4, f"{name}: SetBlockSize(4) accepted")

filt.Update()
check(filt.GetOutput().GetNumberOfCells() > 0,
      f"filter at block size 4: {filt.GetOutput().GetNumberOfCells()} triangles")

actor = vtkActor()
actor.SetMapper(mapper)
ren = vtkRenderer()
ren.AddActor(actor)
win = refscene.window(200, 150, ren)
ren.ResetCamera()
ren.GetActiveCamera().Elevation(-40)
ren.ResetCameraClippingRange()
mapper.SetBlockSize(2)  # refused: the 4 set above stays
merr = Errors(mapper)
win.Render()
check(mapper.GetNumberOfRenderedTriangles() > 0 and merr.count == 0,
      f"mapper draws {mapper.GetNumberOfRenderedTriangles()} triangles at block size "
      f"{mapper.GetBlockSize()} with {merr.count} errors")

if len(sys.argv) > 1:
    fly = sys.argv[1]
    for bad in ("2", "3", "6"):
        p = subprocess.run([fly, "--block-size", bad, "--frames", "1", "--synthetic-size",
                            "65", "--no-frames", "--out", "/tmp/gmm-blocksize"],
                           capture_output=True, text=True, timeout=120)
        lines = p.stderr.strip().splitlines()
        check(p.returncode == 2 and len(lines) == 1 and "4" in lines[0],
              f"geomipmap-fly --block-size {bad}: exit {p.returncode}, stderr {lines}")
    p = subprocess.run([fly, "--help"], capture_output=True, text=True, timeout=60)
    text = " ".join(p.stdout.split())
    check("4..1024" in text and "2..1024" not in text,
          "geomipmap-fly --help states the block size range 4..1024")
    check("(default 32)" in text, "geomipmap-fly --help states the default block size 32")

check.exit()
