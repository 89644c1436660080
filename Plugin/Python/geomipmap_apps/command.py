"""What every geomipmap tool's command line shares: argument types, one-line errors and
exit statuses.

Why: a tool must fail with one readable line, never a traceback or argparse's usage dump,
and the same failure must end the same way in every tool: "PROG: error: ..." on stderr
with exit status 2 for bad input, 1 (one line too) for an unexpected internal error,
130 when interrupted.
"""

import argparse
import math
import os
import sys

from .errors import AppError


class ArgumentParser(argparse.ArgumentParser):
    """argparse, but a bad option raises AppError (one line) instead of printing usage."""

    def error(self, message):
        raise AppError(message)


def positive(kind, minimum=0.0, strict=True):
    """Argument type: a finite `kind` (int, float) > minimum (>= when not strict)."""
    def check(text):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
        if not math.isfinite(v) or (v <= minimum if strict else v < minimum):
            rel = ">" if strict else ">="
            raise argparse.ArgumentTypeError(f"must be {rel} {minimum:g}, got {text}")
        return v
    return check


def window_size(text):
    """Argument type: WxH, each 16..16384 -> (width, height)."""
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected WxH, e.g. 1280x720, got {text!r}") from None
    if not (16 <= w <= 16384 and 16 <= h <= 16384):
        raise argparse.ArgumentTypeError(f"width and height must be 16..16384, got {text}")
    return (w, h)


def _bad_input():
    """The exceptions that mean bad input: AppError, and the flight API's FlightError once
    geomipmap.flight is loaded (the tools import it late, so that --help works without
    the compiled package)."""
    flight = sys.modules.get("geomipmap.flight")
    return (AppError, flight.FlightError) if flight else (AppError,)


def run(prog, body):
    """Call body() (the whole tool after its imports) and return the exit status: body's,
    or 2 after one line on stderr for bad input (AppError, geomipmap.flight.FlightError),
    a missing geomipmap package or memory, 130 when interrupted, 1 for anything else
    (GEOMIPMAP_DEBUG=1 re-raises it for a traceback)."""
    try:
        return body()
    except _bad_input() as e:
        print(f"{prog}: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return 130
    except ImportError as e:
        print(f"{prog}: error: cannot import the geomipmap package ({e}); "
              "is it built / installed next to this command?", file=sys.stderr)
        return 2
    except MemoryError:
        print(f"{prog}: error: out of memory", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001: last resort, still one line
        msg = " ".join(str(e).split())[:300]
        print(f"{prog}: internal error: {type(e).__name__}: {msg} "
              "(set GEOMIPMAP_DEBUG=1 for a traceback)", file=sys.stderr)
        if os.environ.get("GEOMIPMAP_DEBUG"):
            raise
        return 1
