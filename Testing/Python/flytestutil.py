"""Shared helpers for the geomipmap-fly tests (TestFly*.py).

Why: each test runs the installed-style launcher as a subprocess, exactly as a user would,
and checks its exit status, stdout/stderr and output files without importing VTK itself.
Usage of every test: TestFlyX.py <path to geomipmap-fly> <scratch folder>.
"""

import csv
import os
import shutil
import subprocess
import sys

from gmmdata import SKIP  # noqa: F401 (CTest SKIP_RETURN_CODE)


def setup():
    if len(sys.argv) != 3:
        sys.exit(f"usage: {os.path.basename(sys.argv[0])} GEOMIPMAP_FLY SCRATCH_DIR")
    exe, scratch = sys.argv[1], sys.argv[2]
    if not os.path.isfile(exe):
        sys.exit(f"FAIL: {exe} not found")
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    return exe, scratch


def bad_dem_files(folder):
    """Writes two DEM files no reader takes into `folder`: (garbage.tif, empty.hgt)."""
    garbage = os.path.join(folder, "garbage.tif")
    with open(garbage, "wb") as f:
        f.write(b"this is not a raster\n" * 10)
    empty = os.path.join(folder, "empty.hgt")
    open(empty, "wb").close()
    return garbage, empty


def run(exe, *args, timeout=240):
    """Run geomipmap-fly; return (rc, stdout, stderr)."""
    p = subprocess.run([exe, *args], capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def read_csv(filename):
    with open(filename, newline="") as f:
        return list(csv.DictReader(f))


def png_pixels(filename):
    """(width, height, pixels): the PNG's pixels as a float numpy array, one row per pixel,
    read with VTK's PNG reader."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy

    r = vtkPNGReader()
    r.SetFileName(filename)
    r.Update()
    w, h, _ = r.GetOutput().GetDimensions()
    return w, h, vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)


def png_stats(filename):
    """(width, height, variance of the grey values, fraction of terrain-coloured pixels).

    Terrain colours (green, brown, grey, snow) have blue <= max(red, green) + 8; the sky
    background is clearly blue.
    """
    import numpy as np

    w, h, a = png_pixels(filename)
    if a.ndim == 1 or a.shape[1] < 3:
        return w, h, float(a.var()), 0.0
    rgb = a[:, :3]
    terrain = rgb[:, 2] <= np.maximum(rgb[:, 0], rgb[:, 1]) + 8
    return w, h, float(rgb.mean(axis=1).var()), float(terrain.mean())


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)


def measured_flight(argv, every=1):
    """Runs geomipmap-fly in this process (cli.main(argv): the command's own code, flight,
    cameras, CSV and PNG output; only the launcher script is left out) and measures every
    `every`-th frame it renders, independently of the engine's bound
    (gmmtestutil.measure_drawn). Returns (exit status, stdout, stderr, [(frame, stats,
    Measured or None)]), stats being the values the frame's CSV row was written from."""
    import contextlib
    import io

    from geomipmap_apps import scene
    from geomipmap_apps.fly import cli
    from gmmtestutil import measure_drawn

    frames = []
    render = scene.Scene.render

    def measuring_render(self):
        stats = render(self)
        m = None
        if len(frames) % every == 0:
            image = self.mapper.GetInputDataObject(0, 0)
            m = measure_drawn(image, self.renderer, self.actor, self.mapper.GetPixelError(),
                              self.mapper.GetBlockSize())
        frames.append((len(frames), stats, m))
        return stats

    so, se = io.StringIO(), io.StringIO()
    scene.Scene.render = measuring_render
    try:
        with contextlib.redirect_stdout(so), contextlib.redirect_stderr(se):
            rc = cli.main(list(argv))
    finally:
        scene.Scene.render = render
    return rc, so.getvalue(), se.getvalue(), frames


def check_measured(frames, rows, tau):
    """For frames from measured_flight and the CSV rows that flight wrote: one row per
    frame with the frame's triangle count, and on every measured frame the filter's copy is
    the drawn mesh, something is in view and the measured screen error is within tau."""
    check(len(frames) == len(rows), f"{len(frames)} frames rendered, {len(rows)} CSV rows")
    worst, measured = 0.0, 0
    for (f, stats, m), row in zip(frames, rows):
        check(stats["triangles"] == int(row["triangles"]),
              f"frame {f}: {stats['triangles']} triangles drawn, CSV says {row['triangles']}")
        if m is None:
            continue
        print(f"frame {f}: {m!r}")
        check(m.triangles == stats["triangles"], f"frame {f}: filter {m.triangles} triangles, "
              f"mapper {stats['triangles']}: not the drawn mesh")
        check(m.in_view > 0, f"frame {f}: nothing in view")
        check(m.error_px <= tau + 1e-6,
              f"frame {f}: measured screen error {m.error_px:.4f} px > tau {tau}")
        worst, measured = max(worst, m.error_px), measured + 1
    check(measured > 0, "no frame measured")
    print(f"measured screen error over {measured} frames: at most {worst:.4f} px (tau {tau})")
    return worst
