"""Helpers of the robustness tests (issue #6): every VTK message, small render scenes,
and the checks made on vtkGeoMipMapFilter output."""
import re

import numpy as np
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
from vtkmodules.util.numpy_support import vtk_to_numpy
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL factory overrides)


class VtkMessages:
    """Routes every VTK error and warning (any object) into a string, read per case."""

    def __init__(self):
        self.window = vtkStringOutputWindow()
        vtkOutputWindow.SetInstance(self.window)
        self.seen = 0

    def take(self):
        """Messages since the last call: (errors, warnings), each "class (ptr): text"."""
        text = self.window.GetOutput()[self.seen:]
        self.seen += len(text)
        errors, warnings = [], []
        for kind, message in re.findall(r"^(ERROR|Generic Error|Warning|Generic Warning)"
                                        r": In [^\n]*\n([^\n]*)", text, re.M):
            (errors if "error" in kind.lower() else warnings).append(message)
        return errors, warnings


class Scene:
    """An off-screen window with one actor; the mapper is swapped per case."""

    def __init__(self, width=160, height=120):
        self.actor = vtkActor()
        self.ren = vtkRenderer()
        self.ren.AddActor(self.actor)
        self.win = vtkRenderWindow()
        self.win.SetOffScreenRendering(1)
        self.win.SetMultiSamples(0)
        self.win.SetSize(width, height)
        self.win.AddRenderer(self.ren)
        self.cam = self.ren.GetActiveCamera()


def filter_points(filt):
    """(points as an n x 3 array, number of triangles) of a vtkGeoMipMapFilter output."""
    out = filt.GetOutput()
    pts = out.GetPoints()
    xyz = vtk_to_numpy(pts.GetData()) if pts is not None and pts.GetNumberOfPoints() else \
        np.zeros((0, 3))
    return xyz, out.GetNumberOfPolys()
