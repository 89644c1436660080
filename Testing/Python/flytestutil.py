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


def run(exe, *args, timeout=240):
    """Run geomipmap-fly; return (rc, stdout, stderr)."""
    p = subprocess.run([exe, *args], capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def read_csv(filename):
    with open(filename, newline="") as f:
        return list(csv.DictReader(f))


def png_stats(filename):
    """(width, height, variance of the grey values, fraction of terrain-coloured pixels).

    Terrain colours (green, brown, grey, snow) have blue <= max(red, green) + 8; the sky
    background is clearly blue. Read with VTK's PNG reader and numpy.
    """
    import numpy as np
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy

    r = vtkPNGReader()
    r.SetFileName(filename)
    r.Update()
    img = r.GetOutput()
    w, h, _ = img.GetDimensions()
    a = vtk_to_numpy(img.GetPointData().GetScalars()).astype(float)
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
