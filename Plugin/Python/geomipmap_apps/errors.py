"""Errors and VTK message capture for the geomipmap tools.

Why: a command-line tool must fail with one readable line, not a traceback or a
multi-line VTK error dump. Every expected failure raises AppError; VTK's own messages
are routed into a string buffer (vtkStringOutputWindow) so the first error can be
quoted in that one line instead of being printed by VTK.
"""

import re

from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand, vtkOutputWindow, vtkStringOutputWindow


class AppError(Exception):
    """An expected failure (bad option, bad file, ...): reported as one line, exit 2."""


class VTKMessages:
    """Captures VTK error/warning text instead of letting VTK print it to the terminal."""

    def __init__(self):
        self.window = vtkStringOutputWindow()
        vtkOutputWindow.SetInstance(self.window)
        self.errors = []
        self.warnings = []

    def observe(self, algorithm):
        """Record ErrorEvents of `algorithm` (and of its executive) in self.errors, and its
        WarningEvents in self.warnings (unobserved, VTK's logger would print them)."""

        def on_error(_obj, _event, calldata=None):
            self.errors.append(calldata if calldata else "unknown VTK error")

        def on_warning(_obj, _event, calldata=None):
            line = one_line(calldata or "")
            if line and line not in self.warnings:
                self.warnings.append(line)

        on_error.CallDataType = VTK_STRING  # the message comes as calldata
        on_warning.CallDataType = VTK_STRING
        algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
        algorithm.AddObserver(vtkCommand.WarningEvent, on_warning)
        executive = algorithm.GetExecutive()
        if executive is not None:
            executive.AddObserver(vtkCommand.ErrorEvent, on_error)
        return on_error

    def first_error(self):
        """The first captured error as one short line, or None."""
        texts = list(self.errors)
        out = self.window.GetOutput() or ""
        texts += [blk for blk in re.split(r"\n\s*\n", out) if "ERROR" in blk]
        for text in texts:
            line = one_line(text)
            if line:
                return line
        return None


def one_line(text):
    """Squash a (possibly multi-line VTK) message into one line without the file/line header."""
    text = str(text)
    # VTK: "ERROR: In /path/file.cxx, line 123\nvtkClass (0x...): message"
    text = re.sub(r"(ERROR|Warning|WARNING): In [^\n]*, line \d+\s*", "", text)
    text = re.sub(r"\bvtk\w+ \(0x[0-9a-fA-F]+\):\s*", "", text)
    text = " ".join(text.split())
    return text[:500]
