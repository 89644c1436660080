"""geomipmap-bench --quick: the harness runs end to end and its error measure is sane.

Usage: TestBenchQuick.py <path to geomipmap-bench> <scratch folder>. Checks:
- a missing --dem file: exit status 2 and one line naming it;
- exit status 0; frames.csv, summary.md and bench.png written, every method present;
- brute force (the full-resolution mesh) measures 0 px on every frame;
- ours measures at most its tau on every frame, and so does ours-vn-nomorph;
- ours-vn-nomorph has geomorphing off: it draws fewer triangles than ours (whose level path
  holds blocks finer than tau needs);
- --fill-voids on a DEM with holes: ours draws another mesh (the voids' surfaces are drawn);
  a fill option without it is bad input;
- --geomorph-range 3 draws more triangles than the default range (2) on the synthetic
  terrain, within tau both; 0 is bad input;
- the fill floor (ours at its coarsest) draws fewer triangles than ours at any tau, frame by
  frame, and summary.md reports every method against it ('x floor');
- a deliberately coarse mesh (every 16th sample) measures more than tau = 1 px on the
  same flight, through the same measure (vtkGeoMipMapScreenError) and camera set-up.
"""

import csv
import os
import shutil
import subprocess
import sys

if len(sys.argv) != 3:
    sys.exit("usage: TestBenchQuick.py GEOMIPMAP_BENCH SCRATCH_DIR")
exe, scratch = sys.argv[1], sys.argv[2]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
p = subprocess.run([exe, "--quick", "--out", scratch], capture_output=True, text=True,
                   timeout=240)
failures = []
bad = subprocess.run([exe, "--dem", os.path.join(scratch, "missing.tif"),
                      "--out", os.path.join(scratch, "bad")],
                     capture_output=True, text=True, timeout=60)
if bad.returncode != 2 or "missing.tif" not in bad.stderr or "Traceback" in bad.stderr:
    failures.append(f"a missing DEM: exit {bad.returncode}, stderr {bad.stderr!r}")
if p.returncode != 0:
    sys.exit(f"FAIL: exit status {p.returncode}\n{p.stdout}\n{p.stderr}")

# --fill-voids reaches the benchmark's terrain: on a smooth DEM with holes (ESRI ASCII,
# written here) ours draws another number of triangles with the voids filled (the filled
# surfaces are drawn; since blocks with voids coarsen around them, HoleCells.h, the voids
# no longer cost more than their filling, so the count may go either way); a fill option
# without --fill-voids is bad input (exit 2, one line).
import numpy as np  # noqa: E402

ys, xs = np.mgrid[0:257, 0:257]
z = 1000.0 + 300.0 * np.sin(xs / 40.0) * np.cos(ys / 55.0)
for cx, cy, r in ((60, 60, 4), (150, 90, 9), (200, 200, 6), (90, 210, 3)):
    z[np.hypot(xs - cx, ys - cy) <= r] = -9999.0
holes = os.path.join(scratch, "holes.asc")
with open(holes, "w") as f:
    f.write("ncols 257\nnrows 257\nxllcorner 500000\nyllcorner 4000000\ncellsize 30\n"
            "NODATA_value -9999\n")
    for row in z:
        f.write(" ".join("%.3f" % v for v in row) + "\n")
mean_tri = {}
for fill in (False, True):
    folder = os.path.join(scratch, "filled" if fill else "voids")
    q = subprocess.run([exe, "--dem", holes, "--synthetic", "", "--data-dir", "", "--methods",
                        "ours", "--tau", "1", "--frames", "3", "--size", "320x180", "--out",
                        folder] + (["--fill-voids"] if fill else []),
                       capture_output=True, text=True, timeout=240)
    if q.returncode != 0:
        sys.exit(f"FAIL: --dem holes.asc{' --fill-voids' if fill else ''}: exit "
                 f"{q.returncode}\n{q.stderr}")
    with open(os.path.join(folder, "frames.csv"), newline="") as f:
        tri = [int(r["triangles"]) for r in csv.DictReader(f) if r["method"] == "ours"]
    mean_tri[fill] = sum(tri) / max(len(tri), 1)
print(f"holes.asc, tau 1: ours draws {mean_tri[False]:.0f} triangles a frame with voids, "
      f"{mean_tri[True]:.0f} filled")
if not (0 < mean_tri[True] and 0 < mean_tri[False] and mean_tri[True] != mean_tri[False]):
    failures.append(f"--fill-voids: {mean_tri[True]:.0f} triangles a frame, the same as "
                    f"{mean_tri[False]:.0f} with voids (or none)")
# --geomorph-range reaches ours' mapper and filters: a range of 3 lags the certificate more
# than the default 2 on the synthetic terrain, whose errors about double a level (design.md,
# "The level path"), so ours draws more triangles, still within tau; 0 is bad input.
from geomipmap_apps import command  # noqa: E402

default_range = command.default_geomorph_range()
range_tri = {}
for r in (None, 3):
    folder = os.path.join(scratch, f"range{r or 'default'}")
    q = subprocess.run([exe, "--synthetic", "513", "--data-dir", "", "--methods", "ours", "--tau",
                        "1", "--frames", "3", "--size", "320x180", "--out", folder]
                       + (["--geomorph-range", str(r)] if r else []),
                       capture_output=True, text=True, timeout=240)
    if q.returncode != 0:
        sys.exit(f"FAIL: --geomorph-range {r}: exit {q.returncode}\n{q.stderr}")
    with open(os.path.join(folder, "frames.csv"), newline="") as f:
        ours = [row for row in csv.DictReader(f) if row["method"] == "ours"]
    range_tri[r] = sum(int(row["triangles"]) for row in ours)
    with open(os.path.join(folder, "summary.md")) as f:
        if f"GeomorphRange {r or default_range:g}" not in f.read():  # the mapper's, as noted
            failures.append(f"--geomorph-range {r}: the mapper's range is not {r or default_range:g}")
    worst = max(float(row["err_max_px"]) for row in ours)
    if not worst <= 1.0:
        failures.append(f"--geomorph-range {r}: ours measures {worst} px at tau 1")
print(f"513^2, tau 1, 3 frames: ours draws {range_tri[None]} triangles at the default range "
      f"{default_range:g}, {range_tri[3]} at 3")
if not 0 < range_tri[None] < range_tri[3]:
    failures.append(f"--geomorph-range 3: {range_tri[3]} triangles over the flight, not more "
                    f"than the default's {range_tri[None]}")
# --geomorph-measure-samples reaches them too: at 1 sample a frame nearly every part after
# the first frame waits for later frames, which changes no triangle (the selection does not
# depend on it), and ours still measures within tau (vtkGeoMipMapScreenError); -1 is bad input.
folder = os.path.join(scratch, "measure1")
q = subprocess.run([exe, "--synthetic", "513", "--data-dir", "", "--methods", "ours", "--tau", "1",
                    "--frames", "3", "--size", "320x180", "--out", folder, "--geomorph-measure-samples", "1"],
                   capture_output=True, text=True, timeout=240)
if q.returncode != 0:
    sys.exit(f"FAIL: --geomorph-measure-samples 1: exit {q.returncode}\n{q.stderr}")
with open(os.path.join(folder, "frames.csv"), newline="") as f:
    ours = [row for row in csv.DictReader(f) if row["method"] == "ours"]
with open(os.path.join(folder, "summary.md")) as f:
    if "GeomorphMeasureSamples 1\n" not in f.read():
        failures.append("--geomorph-measure-samples 1: the mapper's limit is not 1")
if sum(int(row["triangles"]) for row in ours) != range_tri[None]:
    failures.append("--geomorph-measure-samples 1 changed the triangles")
if not max(float(row["err_max_px"]) for row in ours) <= 1.0:
    failures.append("--geomorph-measure-samples 1: ours measures above tau 1")
bad = subprocess.run([exe, "--geomorph-measure-samples", "-1", "--out", os.path.join(scratch, "bad")],
                     capture_output=True, text=True, timeout=60)
if bad.returncode != 2 or "--geomorph-measure-samples" not in bad.stderr or "Traceback" in bad.stderr:
    failures.append(f"--geomorph-measure-samples -1: exit {bad.returncode}, stderr {bad.stderr!r}")
bad = subprocess.run([exe, "--geomorph-range", "0", "--out", os.path.join(scratch, "bad")],
                     capture_output=True, text=True, timeout=60)
if bad.returncode != 2 or "--geomorph-range" not in bad.stderr or "Traceback" in bad.stderr:
    failures.append(f"--geomorph-range 0: exit {bad.returncode}, stderr {bad.stderr!r}")
bad = subprocess.run([exe, "--fill-smoothing", "3", "--out", os.path.join(scratch, "bad")],
                     capture_output=True, text=True, timeout=60)
if bad.returncode != 2 or "--fill-smoothing needs --fill-voids" not in bad.stderr \
        or len(bad.stderr.strip().splitlines()) != 1:
    failures.append(f"--fill-smoothing alone: exit {bad.returncode}, stderr {bad.stderr!r}")
for name in ("frames.csv", "summary.md", "bench.png"):
    path = os.path.join(scratch, name)
    if not os.path.isfile(path) or os.path.getsize(path) == 0:
        failures.append(f"{name} missing or empty")
with open(os.path.join(scratch, "bench.png"), "rb") as f:
    if f.read(8) != b"\x89PNG\r\n\x1a\n":
        failures.append("bench.png is not a PNG")
with open(os.path.join(scratch, "frames.csv"), newline="") as f:
    rows = list(csv.DictReader(f))
methods = {r["method"] for r in rows}
for m in ("brute", "ours", "ours-fn", "ours-vn", "ours-vn-nomorph", "floor", "greedy", "uniform", "quadric"):
    if m not in methods:
        failures.append(f"method {m} missing from frames.csv")
for r in rows:
    err = float(r["err_max_px"])
    if r["method"] == "brute" and not err < 1e-6:
        failures.append(f"brute force frame {r['frame']} measures {err} px, expected 0")
    if r["method"] in ("ours", "ours-vn-nomorph") and not err <= float(r["tau"]):
        failures.append(f"{r['method']} tau {r['tau']} frame {r['frame']} measures {err} px > tau")
    if int(r["samples_in_view"]) <= 0:
        failures.append(f"{r['method']} frame {r['frame']}: no samples in view")
# Geomorphing's level path holds blocks finer than tau needs (design.md, "The level path"),
# so the same flight without it draws fewer triangles at each tau.
for tau in sorted({r["tau"] for r in rows if r["method"] == "ours"}):
    count = {m: sum(int(r["triangles"]) for r in rows if r["method"] == m and r["tau"] == tau)
             for m in ("ours", "ours-vn-nomorph")}
    print(f"tau {tau}: ours {count['ours']} triangles over the flight, ours-vn-nomorph "
          f"{count['ours-vn-nomorph']}")
    if not 0 < count["ours-vn-nomorph"] < count["ours"]:
        failures.append(f"tau {tau}: ours-vn-nomorph draws {count['ours-vn-nomorph']} "
                        f"triangles over the flight, not fewer than ours' {count['ours']}: "
                        f"is geomorphing off?")
# The floor is ours at its coarsest: on every frame it draws fewer triangles than ours at
# the finest tau (1), and no more than at any other.
floor = {r["frame"]: int(r["triangles"]) for r in rows if r["method"] == "floor"}
for r in (r for r in rows if r["method"] == "ours"):
    f_tri, o_tri = floor.get(r["frame"], -1), int(r["triangles"])
    if not (0 < f_tri < o_tri if float(r["tau"]) == 1.0 else 0 < f_tri <= o_tri):
        failures.append(f"frame {r['frame']}: the floor draws {f_tri} triangles, ours at tau "
                        f"{r['tau']} {o_tri}")
with open(os.path.join(scratch, "summary.md")) as f:
    if "| x floor |" not in f.read():
        failures.append("summary.md has no 'x floor' column")

# The coarse mesh, through the bench's own pieces (same terrain, flight and camera).
import geomipmap  # noqa: E402
from geomipmap import flight  # noqa: E402
from geomipmap_apps.bench import meshes  # noqa: E402
from geomipmap_apps.terrain import load_terrain  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkRenderer  # noqa: E402

image, heights = load_terrain(synthetic_size=513, seed=1)
orbit = flight.Orbit(heights, frames=3, pitch=15.0, view_angle=50.0)
coarse = meshes.grid_mesh(heights, 16)
ren = vtkRenderer()
cam = ren.GetActiveCamera()
measure = geomipmap.vtkGeoMipMapScreenError()
measure.SetHeightfield(image)
measure.SetMesh(coarse)
measure.SetViewportSize(1280, 720)
xmin, xmax, ymin, ymax = heights.bounds
for f in range(3):
    orbit.apply(cam, f)
    ren.ResetCameraClippingRange(xmin, xmax, ymin, ymax, heights.zmin, heights.zmax)
    measure.SetProjectionMatrix(cam.GetCompositeProjectionTransformMatrix(1280 / 720, -1, 1))
    if not measure.Compute() or not measure.GetMaximumError() > 1.0:
        failures.append(f"coarse mesh (stride 16) frame {f} measures "
                        f"{measure.GetMaximumError()} px, expected > tau = 1 px")

if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print(f"ok: {len(rows)} frames; brute 0 px, ours <= tau, stride-16 mesh > 1 px")
