"""DEM files written by the tests themselves (GDAL's Python bindings are not a dependency).

tiff(): a minimal little-endian, one-strip, uncompressed TIFF, optionally a GeoTIFF
(ModelPixelScale + ModelTiepoint + a UTM zone 10N GeoKeyDirectory) with a GDAL_NODATA
tag. Every header field can be forged (width, height, sample format, compression) so the
same writer makes the malformed files. esri_ascii() and hgt() write the text and SRTM
formats, png16() a 16-bit greyscale PNG (through VTK's writer).
"""
import struct

import numpy as np

# TIFF field types: code -> struct format
_TYPES = {"SHORT": (3, "H"), "LONG": (4, "I"), "DOUBLE": (12, "d"), "ASCII": (2, "s")}
# numpy dtype -> (BitsPerSample, SampleFormat)
_SAMPLE = {"uint8": (8, 1), "int16": (16, 2), "uint16": (16, 1), "int32": (32, 2),
           "float32": (32, 3), "float64": (64, 3), "complex64": (64, 6)}


def tiff(path, z, georef=(500000.0, 4000000.0, 30.0), nodata=None, width=None, height=None,
         compression=1, rgb=False, geographic=False):
    """Writes z (ny x nx array, row 0 = north; ny x nx x 3 uint8 when rgb, or ny x nx x 4
    for RGB + an (unassociated) alpha channel) as a TIFF.

    georef: (west, north, pixel size) of the upper-left corner, or None for a plain TIFF;
    in UTM zone 10N metres, or in WGS 84 lon/lat degrees (EPSG:4326) when geographic.
    width/height forge the header's ImageWidth/ImageLength; compression forges the tag.
    """
    z = np.ascontiguousarray(z)
    ny, nx = z.shape[:2]
    spp = (z.shape[2] if z.ndim == 3 else 3) if rgb else 1
    bits, fmt = _SAMPLE[z.dtype.name]
    pixels = z.astype(z.dtype.newbyteorder("<")).tobytes()
    entries = [
        (256, "LONG", [width if width is not None else nx]),
        (257, "LONG", [height if height is not None else ny]),
        (258, "SHORT", [bits] * spp),
        (259, "SHORT", [compression]),
        (262, "SHORT", [2 if rgb else 1]),
        (273, "LONG", [0]),  # strip offset, patched below
        (277, "SHORT", [spp]),
        (278, "LONG", [ny]),
        (279, "LONG", [len(pixels)]),
        (284, "SHORT", [1]),
        (339, "SHORT", [fmt] * spp),
    ]
    if spp == 4:
        entries.insert(-1, (338, "SHORT", [2]))  # ExtraSamples: unassociated alpha
    if georef is not None:
        west, north, size = georef
        entries += [
            (33550, "DOUBLE", [size, size, 0.0]),
            (33922, "DOUBLE", [0.0, 0.0, 0.0, west, north, 0.0]),
            # version 1.1.0, 3 keys: projected model, pixel-is-area, EPSG:32610; or
            # geographic model, pixel-is-area, EPSG:4326
            (34735, "SHORT", [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326]
             if geographic else
             [1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32610]),
        ]
    if nodata is not None:
        entries.append((42113, "ASCII", (str(nodata) + "\0").encode()))
    ifd_size = 2 + 12 * len(entries) + 4
    extra = bytearray()
    data_start = 8 + ifd_size
    ifd = struct.pack("<H", len(entries))
    packed = []
    for tag, tname, values in entries:
        code, f = _TYPES[tname]
        raw = values if tname == "ASCII" else struct.pack("<%d%s" % (len(values), f), *values)
        packed.append((tag, code, len(values), raw))
    pixel_offset = data_start + sum(len(r) + (len(r) & 1) for _, _, _, r in packed if len(r) > 4)
    for tag, code, count, raw in packed:
        if tag == 273:
            raw = struct.pack("<I", pixel_offset)
        if len(raw) <= 4:
            ifd += struct.pack("<HHI", tag, code, count) + raw.ljust(4, b"\0")
        else:
            ifd += struct.pack("<HHII", tag, code, count, data_start + len(extra))
            extra += raw + (b"\0" if len(raw) & 1 else b"")
    ifd += struct.pack("<I", 0)
    with open(path, "wb") as f:
        f.write(b"II*\0" + struct.pack("<I", 8) + ifd + bytes(extra) + pixels)
    return path


def esri_ascii(path, z, nodata=-9999, x0=500000.0, y0=4000000.0, cell=30.0, header=None):
    """ESRI ASCII grid of z (row 0 = north); header replaces the computed header lines."""
    ny, nx = z.shape
    head = header or ("ncols %d\nnrows %d\nxllcorner %r\nyllcorner %r\ncellsize %r\n"
                      "NODATA_value %r\n" % (nx, ny, x0, y0, cell, nodata))
    with open(path, "w") as f:
        f.write(head)
        for row in z:
            f.write(" ".join(repr(float(v)) if np.isfinite(v) else str(nodata) for v in row))
            f.write("\n")
    return path


def hgt(path, z):
    """SRTM .hgt: big-endian int16, row 0 = north, -32768 = void."""
    with open(path, "wb") as f:
        f.write(np.asarray(z, dtype=">i2").tobytes())
    return path


def png16(path, z):
    """z (ny x nx, uint16, row 0 south, as vtkImageData holds it) as a 16-bit greyscale PNG
    (zlib level 1: the tests write large ones)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter
    z = np.asarray(z, dtype=np.uint16)
    img = vtkImageData()
    img.SetDimensions(z.shape[1], z.shape[0], 1)
    img.GetPointData().SetScalars(numpy_to_vtk(z.ravel(), deep=True))
    w = vtkPNGWriter()
    w.SetCompressionLevel(1)
    w.SetInputData(img)
    w.SetFileName(path)
    w.Write()
    return path
