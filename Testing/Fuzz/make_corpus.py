#!/usr/bin/env python3
"""Writes the fuzzers' seed corpora (small files made here, no real DEM): usage
make_corpus.py OUTDIR -> OUTDIR/reader/*, OUTDIR/engine/*.

Reader seeds start with the selector byte FuzzTerrainReader.cpp reads (bits 0-2: file name,
bit 3: terrain-RGB, bits 4-6: scale / offset / spacing options), then the file bytes:
a GeoTIFF (int16 and float32 with nodata and a negative-height pixel), ESRI ASCII grids,
an XYZ grid, a GRASS ASCII grid, a 16-bit grey PNG, an 8-bit RGB terrain-RGB PNG and a PGM.
Standard library only."""
import os
import random
import struct
import sys
import zlib

# file-name indices in FuzzTerrainReader.cpp's kNames
TIF, ASC, HGT, TERRAIN_PNG, PNG, PGM, DEM, BIN = range(8)
RGB_FLAG = 8


def tiff(nx, ny, values, float32, nodata=None, geo=True):
    """Little-endian single-strip TIFF; GeoTIFF tags (pixel scale, tie point, geokeys)."""
    fmt = "<%d%s" % (nx * ny, "f" if float32 else "h")
    data = struct.pack(fmt, *values)
    entries = []  # (tag, type, count, payload bytes)

    def short(tag, v):
        entries.append((tag, 3, 1, struct.pack("<HH", v, 0)))

    def long_(tag, v):
        entries.append((tag, 4, 1, struct.pack("<I", v)))

    short(256, nx)
    short(257, ny)
    short(258, 32 if float32 else 16)
    short(259, 1)  # no compression
    short(262, 1)  # min-is-black
    long_(273, 0)  # strip offset, patched below
    short(277, 1)
    short(278, ny)
    long_(279, len(data))
    short(284, 1)
    short(339, 3 if float32 else 2)  # sample format: IEEE float / signed int
    if geo:
        entries.append((33550, 12, 3, struct.pack("<3d", 30.0, 30.0, 0.0)))
        entries.append((33922, 12, 6, struct.pack("<6d", 0, 0, 0, 500000.0, 4000000.0, 0)))
        keys = [1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32610]  # UTM 10N
        entries.append((34735, 3, len(keys), struct.pack("<%dH" % len(keys), *keys)))
    if nodata is not None:
        s = (str(nodata) + "\0").encode()
        entries.append((42113, 2, len(s), s))
    entries.sort()
    header = 8
    ifd_size = 2 + 12 * len(entries) + 4
    extra_at = header + ifd_size
    extra = b""
    ifd = struct.pack("<H", len(entries))
    fixups = []
    for tag, typ, count, payload in entries:
        if len(payload) <= 4:
            ifd += struct.pack("<HHI", tag, typ, count) + payload.ljust(4, b"\0")
        else:
            off = extra_at + len(extra)
            ifd += struct.pack("<HHII", tag, typ, count, off)
            extra += payload + (b"\0" if len(payload) % 2 else b"")
        if tag == 273:
            fixups.append(len(ifd) - 4)
    ifd += struct.pack("<I", 0)
    data_at = extra_at + len(extra)
    ifd = bytearray(ifd)
    for pos in fixups:
        ifd[pos:pos + 4] = struct.pack("<I", data_at)
    return b"II*\0" + struct.pack("<I", header) + bytes(ifd) + extra + data


def png(nx, ny, rows, bit_depth, colour_type):
    def chunk(kind, body):
        c = kind + body
        return struct.pack(">I", len(body)) + c + struct.pack(">I", zlib.crc32(c) & 0xFFFFFFFF)

    raw = b"".join(b"\0" + r for r in rows)
    ihdr = struct.pack(">IIBBBBB", nx, ny, bit_depth, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw))
            + chunk(b"IEND", b""))


def asc(nx, ny, values, nodata=-9999):
    lines = ["ncols %d" % nx, "nrows %d" % ny, "xllcorner 1000.0", "yllcorner 2000.0",
             "cellsize 10.0", "NODATA_value %d" % nodata]
    for j in range(ny):
        lines.append(" ".join("%g" % v for v in values[j * nx:(j + 1) * nx]))
    return ("\n".join(lines) + "\n").encode()


def xyz(nx, ny, values):
    """GDAL XYZ grid: "x y z" lines, rows top (north) first, x increasing."""
    lines = ["%g %g %g" % (1000.0 + 10.0 * i, 2000.0 - 10.0 * j, values[j * nx + i])
             for j in range(ny) for i in range(nx)]
    return ("\n".join(lines) + "\n").encode()


def grass(nx, ny, values):
    """GRASS ASCII grid: header (bounds, rows, cols, null value), then rows north first."""
    lines = ["north: 2050", "south: 2000", "east: 1070", "west: 1000", "rows: %d" % ny,
             "cols: %d" % nx, "null: -9999"]
    for j in range(ny):
        lines.append(" ".join("%g" % v for v in values[j * nx:(j + 1) * nx]))
    return ("\n".join(lines) + "\n").encode()


def main():
    out = sys.argv[1]
    rng = random.Random(6)
    reader = os.path.join(out, "reader")
    engine = os.path.join(out, "engine")
    os.makedirs(reader, exist_ok=True)
    os.makedirs(engine, exist_ok=True)
    nx, ny = 7, 5
    heights = [rng.randint(-20, 300) for _ in range(nx * ny)]
    heights[3] = -32768  # nodata below
    seeds = {
        "geotiff-int16": bytes([TIF]) + tiff(nx, ny, heights, False, nodata=-32768),
        "geotiff-float": bytes([TIF | 0x10]) + tiff(nx, ny, [h * 0.5 for h in heights], True,
                                                    nodata=-32768),
        "tiff-plain": bytes([TIF | 0x40]) + tiff(3, 2, [1, 2, 3, 4, 5, 6], False, geo=False),
        "asc": bytes([ASC]) + asc(nx, ny, heights, -32768),
        "asc-as-hgt": bytes([HGT]) + asc(2, 2, [1, 2, 3, 4]),
        "asc-as-dem": bytes([DEM | 0x20]) + asc(3, 3, [float(i) for i in range(9)]),
        "xyz": bytes([BIN]) + xyz(4, 3, heights[:12]),
        "grass": bytes([ASC | 0x40]) + grass(nx, ny, heights),
        "png16": bytes([PNG]) + png(4, 3, [struct.pack(">4H", *(rng.randint(0, 65535)
                                                             for _ in range(4)))
                                          for _ in range(3)], 16, 0),
        "png-terrain-rgb": bytes([TERRAIN_PNG | RGB_FLAG]) + png(
            4, 4, [bytes(rng.randint(0, 255) for _ in range(12)) for _ in range(4)], 8, 2),
        "pgm": bytes([PGM]) + b"P5\n3 2\n255\n" + bytes([0, 50, 100, 150, 200, 250]),
        "bin": bytes([BIN]) + bytes(rng.randint(0, 255) for _ in range(64)),
    }
    for name, data in seeds.items():
        with open(os.path.join(reader, name), "wb") as f:
            f.write(data)
    # engine seeds: byte strings of a few lengths (FuzzedDataProvider reads any bytes)
    for k, n in enumerate((16, 64, 200, 600, 1500)):
        with open(os.path.join(engine, "seed%d" % k), "wb") as f:
            f.write(bytes(rng.randint(0, 255) for _ in range(n)))


if __name__ == "__main__":
    main()
