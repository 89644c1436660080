"""Waypoint files for the geomipmap-fly tests: malformed ones, valid ones, a test terrain.

Why one module: TestFlyBadInput (through the command), TestFlyWaypointFiles (in-process,
every case) and TestFlyWaypointFuzz (the cases as mutation seeds) use the same files.
Coordinates fit a 65 x 65 terrain at 30 m with origin (0, 0), i.e. 0..1920 m: the
command's --synthetic-size 65 and make_terrain() below; lon/lat fit make_terrain(True).
"""

# name -> (file name, content (str: written as UTF-8; bytes: as is), words the one-line
# error must hold besides the file name). Issue #16 item 6 and its neighbours.
BAD = {
    "extra field in a data row": ("extra.csv", "x,y,agl\n100,100,50\n200,200,50,7\n",
                                  ["line 3", "4 fields", "header has 3"]),
    "missing field in a data row": ("short.csv", "x,y,agl\n100,100,50\n200,200\n",
                                    ["line 3", "2 fields", "header has 3"]),
    "empty header": ("emptyheader.csv", ",,\n100,100,50\n200,200,50\n", ["need columns x,y"]),
    "header only": ("headeronly.csv", "x,y,agl\n", ["at least 2 waypoints, found 0"]),
    # A byte order mark (as Excel writes) is not part of the first column's name, so the
    # error is the bad value in line 3, not "no column x".
    "BOM, bad value": ("bom.csv", "\ufeffx,y,agl\n100,100,50\n200,200,abc\n",
                       ["line 3", "agl", "abc"]),
    "BOM JSON, outside": ("bom.json", '\ufeff[{"x": 100, "y": 100, "agl": 5}, '
                          '{"x": 1e7, "y": 100, "agl": 5}]', ["waypoint 2", "outside"]),
    "duplicate column": ("dup.csv", "x,y,x,agl\n100,100,5,50\n200,200,6,50\n",
                         ["line 1", "column 'x'", "twice"]),
    "duplicate column, other case": ("dupcase.csv", "x,y,X,agl\n100,100,5,50\n200,200,6,50\n",
                                     ["column 'x'", "twice"]),
    "duplicate JSON key": ("dup.json", '[{"x": 100, "y": 100, "x": 5, "agl": 5}, '
                           '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "'x'", "twice"]),
    "non-object JSON row": ("list.json", '[{"x": 100, "y": 100, "agl": 5}, [200, 200, 5]]',
                            ["waypoint 2", "not an object"]),
    "JSON not a list": ("scalar.json", '{"waypoints": 5}', ["list of waypoint objects"]),
    "nested JSON value": ("nested.json", '[{"x": {"v": 100}, "y": 100, "agl": 5}, '
                          '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "x", "not a number"]),
    "JSON list value": ("listvalue.json", '[{"x": 100, "y": [100], "agl": 5}, '
                        '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "y", "not a number"]),
    "JSON boolean value": ("bool.json", '[{"x": 100, "y": 100, "agl": true}, '
                           '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "agl", "not a number"]),
    "JSON row without y": ("noy.json", '[{"x": 100, "y": 100, "agl": 5}, {"x": 200, "agl": 5}]',
                           ["waypoint 2", "no y"]),
    "NaN string": ("nan.csv", "x,y,agl\n100,100,nan\n200,200,50\n", ["line 2", "non-finite"]),
    "Inf string": ("inf.csv", "x,y,agl\n100,100,50\n-Infinity,200,50\n", ["line 3", "non-finite"]),
    "JSON NaN": ("nan.json", '[{"x": NaN, "y": 100, "agl": 5}, {"x": 200, "y": 200, "agl": 5}]',
                 ["waypoint 1", "non-finite"]),
    "huge number": ("huge.csv", "x,y,agl\n100,100,1e400\n200,200,50\n", ["line 2", "non-finite"]),
    "huge JSON integer": ("hugeint.json", '[{"x": 1' + "0" * 400 + ', "y": 100, "agl": 5}, '
                          '{"x": 200, "y": 200, "agl": 5}]', ["waypoint 1", "x", "out of range"]),
    # Python refuses int() of more than 4300 digits (ValueError, not a JSON error).
    "JSON integer of 5000 digits": ("digits.json", '[{"x": 1' + "0" * 5000 + ', "y": 100, '
                                    '"agl": 5}, {"x": 200, "y": 200, "agl": 5}]',
                                    ["waypoint 1", "x", "out of range"]),
    "JSON nested 100000 deep": ("deep.json", "[" * 100000, ["cannot read waypoint file",
                                                          "nested"]),
    "huge coordinate": ("far.csv", "x,y,agl\n100,100,50\n1e300,200,50\n",
                        ["line 3", "outside the terrain"]),
    "non-UTF-8 bytes": ("latin1.csv", b"x,y,agl\n100,100,50\n200,200,50\xb0\n",
                        ["cannot read waypoint file", "UTF-8", "line 3"]),
    "NUL byte": ("nul.csv", "x,y,agl\n100,100,50\n200,200\x0050\n", ["line 3"]),
    "field spans lines": ("quoted.csv", 'x,y,agl\n100,100,50\n"200\nabc",200,50\n',
                          ["line 3", "x", "not a number"]),
    "JSON lon/lat on a local terrain": ("geo.json", '[{"lon": 1.01, "lat": 42.01}, '
                                        '{"lon": 1.02, "lat": 42.01}]', ["geographic"]),
}

# The cases TestFlyBadInput also runs through the command: the case and those that
# used to end in an internal error (exit 1) rather than a bad-input error.
THROUGH_COMMAND = ("extra field in a data row", "huge JSON integer",
                   "JSON integer of 5000 digits", "JSON nested 100000 deep")

# name -> (file name, content, geographic terrain?, clearance, expected (x, y) in metres,
# expected heights, above ground?). Valid files in the forms users write them.
GOOD = {
    "plain CSV": ("plain.csv", "x,y,agl\n100,100,50\n200,250,60\n", False, None,
                  [(100, 100), (200, 250)], [50, 60], True),
    "CRLF, comments, blanks, spaces, upper case": (
        "messy.csv", "# route\r\n\r\n X , Y ,Z\r\n100, 100, 500\r\n# mid\r\n\r\n200,200,600\r\n",
        False, None, [(100, 100), (200, 200)], [500, 600], False),
    "BOM CSV": ("bom.csv", "\ufeffx,y,alt\n100,100,900\n300,300,950\n", False, None,
                [(100, 100), (300, 300)], [900, 950], False),
    "unnamed trailing column": ("trailing.csv", "x,y,agl,\n100,100,50,\n200,200,50,\n", False,
                                None, [(100, 100), (200, 200)], [50, 50], True),
    "quoted fields and a name column": (
        "named.csv", 'name,x,y,agl\n"Summit, north",100,100,50\n"say ""hi""",200,200,70\n',
        False, None, [(100, 100), (200, 200)], [50, 70], True),
    "no height with --clearance": ("noheight.csv", "x,y\n100,100\n200,200\n", False, 120.0,
                                   [(100, 100), (200, 200)], [120, 120], True),
    "JSON list": ("list.json", '[{"x": 100, "y": 100, "z": 900}, {"x": 1900, "y": 1800, '
                  '"z": 950.5}]', False, None, [(100, 100), (1900, 1800)], [900, 950.5], False),
    "JSON object, strings, extra keys": (
        "obj.json", '{"name": "r", "waypoints": [{"X": "100", "y": 100, "agl": 5, "note": [1]},'
        ' {"x": 200, "y": " 200 ", "agl": 6}]}', False, None, [(100, 100), (200, 200)], [5, 6],
        True),
    "BOM JSON": ("bom.json", '\ufeff[{"x": 100, "y": 100, "agl": 5}, {"x": 200, "y": 200, '
                 '"agl": 5}]', False, None, [(100, 100), (200, 200)], [5, 5], True),
    "lon/lat CSV on a geographic terrain": (
        "geo.csv", "lon,lat,agl\n1.0,42.0,100\n1.02,42.015,100\n", True, None,
        [(0.0, 0.0), None], [100, 100], True),
}


def make_terrain(geographic=False):
    """geomipmap.flight.Heights of a test image: 65 x 65 samples at 30 m from (0, 0).

    geographic: the reader's fields "GeographicOrigin" = lon 1, lat 42 at sample (0, 0) and
    "CentralMeridian" = 1 (its local frame, see vtkGeoMipMapTerrainReader.h).
    Needs vtkmodules and the geomipmap package on sys.path; renders nothing.
    """
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from geomipmap.flight import Heights

    n = 65
    j, i = np.mgrid[0:n, 0:n]
    z = (100.0 + 40.0 * np.sin(i / 7.0) * np.cos(j / 5.0)).astype(np.float32).ravel()
    image = vtkImageData()
    image.SetDimensions(n, n, 1)
    image.SetSpacing(30.0, 30.0, 1.0)
    arr = numpy_to_vtk(z, deep=True)
    arr.SetName("Elevation")
    image.GetPointData().SetScalars(arr)
    if geographic:
        origin = vtkDoubleArray()
        origin.SetName("GeographicOrigin")
        origin.SetNumberOfComponents(2)
        origin.InsertNextTuple2(1.0, 42.0)
        image.GetFieldData().AddArray(origin)
        meridian = vtkDoubleArray()
        meridian.SetName("CentralMeridian")
        meridian.InsertNextValue(1.0)
        image.GetFieldData().AddArray(meridian)
    return Heights(image)


def write(folder, filename, content):
    """Write a case's content (str as UTF-8, bytes as is) into folder; return the path."""
    import os

    path = os.path.join(folder, filename)
    with open(path, "wb") as f:
        f.write(content.encode("utf-8") if isinstance(content, str) else content)
    return path
