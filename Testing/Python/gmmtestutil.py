"""Helpers of the geomipmap Python tests: data folder, skipping, error capture, memory."""
import resource

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

from gmmdata import SKIP, data_dir_or_skip, data_file  # noqa: F401 (the one data rule)


class ErrorCatcher:
    """Collects the ErrorEvent texts of one algorithm (and keeps them off stderr).

    The executive's follow-up "returned failure" error is swallowed too: it names the
    request, not the file, and would only clutter the log.
    """

    def __init__(self, alg):
        self.messages = []

        @calldata_type(VTK_STRING)
        def on_error(caller, event, text):
            self.messages.append(text)

        @calldata_type(VTK_STRING)
        def on_executive_error(caller, event, text):
            pass

        self._callbacks = (on_error, on_executive_error)  # keep them alive
        alg.AddObserver(vtkCommand.ErrorEvent, on_error)
        alg.GetExecutive().AddObserver(vtkCommand.ErrorEvent, on_executive_error)

    def clear(self):
        self.messages = []


def update(alg):
    """Runs the pipeline; returns True when every request succeeded."""
    return alg.GetExecutive().Update() == 1


def max_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def check(cond, what):
    if not cond:
        raise AssertionError(what)
    print("ok:", what)
