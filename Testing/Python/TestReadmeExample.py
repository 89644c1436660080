"""Runs the README's Python example verbatim, so the documented API cannot rot; then checks
what it drew independently of the engine's own bound.

The block is executed as written (readmeblock.run_readme_block: in this process, with
sys.argv = [script, DEM] and a scratch working directory), its printed statistics are
parsed, and the frame it rendered is measured (gmmtestutil.check_drawn_within_tau:
vtkGeoMipMapFilter's copy of the drawn triangles against the full-resolution DEM through
vtkGeoMipMapScreenError, with the camera's own projection): the measured screen error must
be within the example's tau.
"""
import os
import re

from gmmdata import data_file
from gmmtestutil import check_drawn_within_tau
from readmeblock import run_readme_block

dem = data_file("N42E001.hgt")
with run_readme_block("## Python API", [dem]) as (example, printed, tmp):
    m = re.search(r"(\d+) triangles, error <= ([0-9.e+-]+) px", printed)
    assert m, "README example printed no statistics"
    triangles = int(m.group(1))
    assert 0 < triangles < 2 * 1200 * 1200, triangles   # LOD: fewer than full resolution
    size = os.path.getsize(os.path.join(tmp, "terrain.png"))
    assert size > 10000, "terrain.png looks empty (%d bytes)" % size
    # N42E001 has voids: in-view samples next to them are not covered, by design.
    check_drawn_within_tau(example["reader"].GetOutput(), example["ren"], example["actor"],
                           example["mapper"], "README example", uncovered_ok=True)
print("ok: README example ran, and what it drew measures within its tau")
