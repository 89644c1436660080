"""Where the tests find the real DEMs, and what they do when they are missing: one rule.

The folder is $GEOMIPMAP_DATA_DIR when set (non-empty), else ../shared/data beside the
source tree (the layout of CI and every developer machine). A test whose data is missing
skips (exit 77, CTest's SKIP_RETURN_CODE), except when GEOMIPMAP_REQUIRE_DATA=1 (CI sets
it: the data is always there, so a skip would hide a broken path): then it fails (exit 1).
Used by every Python test (gmmtestutil, flytestutil and the tests themselves); the C++
tests follow the same rule in Testing/Cxx/GeoMipMapTestUtilities.h.
"""
import os
import sys

SKIP = 77  # CTest SKIP_RETURN_CODE
_here = os.path.dirname(os.path.abspath(__file__))
DEFAULT_DIR = os.path.normpath(os.path.join(_here, "..", "..", "..", "shared", "data"))


def data_dir():
    """$GEOMIPMAP_DATA_DIR, else ../shared/data beside the source tree (may not exist)."""
    return os.environ.get("GEOMIPMAP_DATA_DIR") or DEFAULT_DIR


def required():
    """True when missing data must fail the test (GEOMIPMAP_REQUIRE_DATA set, not 0)."""
    return os.environ.get("GEOMIPMAP_REQUIRE_DATA", "") not in ("", "0")


def missing(what):
    """Ends the test for missing data: skip (77), or fail (1) when data is required."""
    if required():
        print(f"FAIL: {what}; GEOMIPMAP_REQUIRE_DATA is set, so missing data fails the test")
        sys.exit(1)
    print(f"SKIP: {what} (set GEOMIPMAP_DATA_DIR to the shared data folder)")
    sys.exit(SKIP)


def data_dir_or_skip():
    """The data folder; ends the test (see missing) when it does not exist."""
    d = data_dir()
    if not os.path.isdir(d):
        missing(f"data folder {d} is absent")
    return d


def data_file(name):
    """Path of one data file; ends the test (see missing) when it does not exist."""
    path = os.path.join(data_dir(), name)
    if not os.path.isfile(path):
        missing(f"{path} not found")
    return path


def optional_data_file(name):
    """For tests where real data only adds cases: the path, or None when absent (and the
    test goes on without those cases); fails the test when data is required."""
    path = os.path.join(data_dir(), name)
    if os.path.isfile(path):
        return path
    if required():
        missing(f"{path} not found")
    print(f"note: {path} not found, its cases are left out")
    return None
