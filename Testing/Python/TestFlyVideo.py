"""geomipmap-fly --video: the file holds every frame of the flight, at the render size and
rate, in order and the right way up, with ffmpeg and with VTK's vtkOggTheoraWriter.

Read back two ways: ffprobe (decodes and counts every frame) and, for Ogg Theora, this
test's own reading of the Ogg pages (theora_stream: the identification header's picture
size and rate, one packet per frame), which needs no ffmpeg. Cases:
- .mp4 through ffmpeg (H.264): frame count, size, rate; frames 0, 6 and 11 decoded by
  ffmpeg match the PNGs the same flight wrote (and not the neighbouring ones, nor the
  image upside down);
- .ogv forced through VTK's writer (--video-encoder vtk), at an odd height: the same;
- no ffmpeg on PATH: .ogv falls back to VTK's writer by itself, .mp4 is refused;
- .ogv through ffmpeg (libtheora), odd size, --no-frames;
- bad requests (unknown format, odd size for H.264, MP4 or a width off the 16 grid or a
  fractional rate for VTK's writer): exit 2 and one line, before anything is written.
Without ffmpeg the VTK parts still run; the rest skips (exit 77), or fails when
GEOMIPMAP_REQUIRE_DATA=1 (CI, whose set-up installs ffmpeg).
"""

import os
import shutil
import struct
import subprocess

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from flytestutil import SKIP, check, run, setup
from gmmdata import required

exe, out = setup()
ffmpeg, ffprobe = shutil.which("ffmpeg"), shutil.which("ffprobe")
synthetic = ["--synthetic-size", "129", "--tau", "2"]


def fly(*args, env=None):
    """Run the command; check it succeeded; return its stdout."""
    p = subprocess.run([exe, *synthetic, *args], capture_output=True, text=True, timeout=240,
                       env=env)
    check(p.returncode == 0, f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()}")
    return p.stdout


def probe(filename):
    """ffprobe's view of the first video stream, every frame decoded and counted."""
    p = subprocess.run([ffprobe, "-v", "error", "-count_frames", "-select_streams", "v:0",
                        "-show_entries", "stream=codec_name,width,height,r_frame_rate,"
                        "nb_read_frames", "-of", "default=noprint_wrappers=1", filename],
                       capture_output=True, text=True, timeout=120)
    check(p.returncode == 0, f"ffprobe {filename}: {p.stderr.strip()}")
    info = dict(line.split("=", 1) for line in p.stdout.split())
    return (info["codec_name"], int(info["width"]), int(info["height"]),
            int(info["nb_read_frames"]), info["r_frame_rate"])


def theora_stream(filename):
    """(width, height, frames, 'num/den' frame rate) of the Ogg Theora stream in a file,
    read from its pages: the identification header (0x80 'theora') holds the picture
    size and rate; every later non-header packet is one frame (an empty one repeats the
    previous frame, and counts)."""
    data = open(filename, "rb").read()
    packets, partial, pos, serial = {}, {}, 0, None
    while pos < len(data):
        check(data[pos:pos + 4] == b"OggS", f"{filename}: no Ogg page at byte {pos}")
        sid, nseg = struct.unpack_from("<I", data, pos + 14)[0], data[pos + 26]
        lacing = data[pos + 27:pos + 27 + nseg]
        body = pos + 27 + nseg
        for n in lacing:
            partial[sid] = partial.get(sid, b"") + data[body:body + n]
            body += n
            if n < 255:  # a packet ends with a lacing value below 255
                packets.setdefault(sid, []).append(partial.pop(sid))
        pos = body
    for sid, ps in packets.items():
        if ps and ps[0][:7] == b"\x80theora":
            serial = sid
    check(serial is not None, f"{filename}: no Theora stream")
    ident = packets[serial][0]
    width = int.from_bytes(ident[14:17], "big")
    height = int.from_bytes(ident[17:20], "big")
    num, den = struct.unpack_from(">II", ident, 22)
    frames = [p for p in packets[serial] if not (p and p[0] & 0x80)]  # headers: 0x80..0x82
    return width, height, len(frames), f"{num}/{den}"


def png_rgb(filename):
    r = vtkPNGReader()
    r.SetFileName(filename)
    r.Update()
    w, h, _ = r.GetOutput().GetDimensions()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).reshape(h, w, -1)[:, :, :3]


def decoded(filename, n, size):
    """Frame n of a video as ffmpeg decodes it, top row first like the PNGs as read here
    (VTK's reader also gives the bottom row first, so both are compared as stored)."""
    w, h = size
    p = subprocess.run([ffmpeg, "-v", "error", "-i", filename, "-vf", f"select=eq(n\\,{n})",
                        "-frames:v", "1", "-f", "rawvideo", "-pix_fmt", "rgb24", "-"],
                       capture_output=True, timeout=120)
    check(p.returncode == 0 and len(p.stdout) == w * h * 3,
          f"ffmpeg decoding frame {n} of {filename}: {len(p.stdout)} bytes, "
          f"{p.stderr.decode(errors='replace').strip()}")
    return np.frombuffer(p.stdout, np.uint8).reshape(h, w, 3)[::-1]


def check_frames(video, folder, frames, size):
    """Decoded frames match the flight's PNGs of the same number: closer to them than to
    the neighbouring frames' PNGs and than to the PNG upside down."""
    for n in frames:
        got = decoded(video, n, size).astype(float)
        diffs = {k: np.abs(got - png_rgb(os.path.join(folder, f"frame_{k:05d}.png"))).mean()
                 for k in (n - 1, n, n + 1) if os.path.isfile(
                     os.path.join(folder, f"frame_{k:05d}.png"))}
        own = png_rgb(os.path.join(folder, f"frame_{n:05d}.png"))
        flipped = np.abs(got - own[::-1]).mean()
        print(f"{os.path.basename(video)} frame {n}: mean difference to the PNGs "
              + ", ".join(f"{k}: {d:.1f}" for k, d in diffs.items()) + f"; upside down {flipped:.1f}")
        check(diffs[n] < 10.0 and diffs[n] == min(diffs.values()) and flipped > 2 * diffs[n],
              f"{video}: frame {n} is not the flight's frame {n}")


def refused(args, words, env=None):
    rc, so, se = run(exe, *synthetic, "--frames", "2", *args)
    lines = se.strip().splitlines()
    check(rc == 2 and len(lines) == 1 and all(w in lines[0] for w in words)
          and "Traceback" not in se, f"{args}: exit {rc}, stderr {se!r}, expected {words}")
    print(f"refused {' '.join(args)}: {lines[0] if lines else ''}")


# VTK's writer, forced (also where ffmpeg is installed), at an odd height.
d = os.path.join(out, "vtk")
video = os.path.join(d, "flight.ogv")
so = fly("--frames", "9", "--fps", "24", "--size", "320x181", "--video", video,
         "--video-encoder", "vtk", "--out", d)
check("Ogg Theora by vtkOggTheoraWriter" in so and "(9 frames, 320x181, 24 fps" in so,
      f"summary does not name the video:\n{so}")
got = theora_stream(video)
print(f"{video}: own read-back {got}, {os.path.getsize(video)} bytes")
check(got == (320, 181, 9, "24/1"), f"{video}: {got}, expected (320, 181, 9, '24/1')")

# No ffmpeg on PATH: .ogv falls back to VTK's writer by itself; .mp4 cannot be written.
bare = dict(os.environ, PATH="/nonexistent")
video = os.path.join(out, "fallback", "flight.ogv")
so = fly("--frames", "5", "--size", "160x90", "--no-frames", "--video", video, "--out",
         os.path.join(out, "fallback"), env=bare)
check("by vtkOggTheoraWriter" in so, f"no ffmpeg: not VTK's writer:\n{so}")
got = theora_stream(video)
check(got == (160, 90, 5, "30/1"), f"{video}: {got}, expected (160, 90, 5, '30/1')")
print(f"{video} (no ffmpeg on PATH): own read-back {got}")
p = subprocess.run([exe, *synthetic, "--frames", "2", "--video",
                    os.path.join(out, "x.mp4"), "--out", os.path.join(out, "x")],
                   capture_output=True, text=True, timeout=120, env=bare)
check(p.returncode == 2 and "ffmpeg" in p.stderr and len(p.stderr.strip().splitlines()) == 1,
      f"no ffmpeg, .mp4: exit {p.returncode}, {p.stderr!r}")

refused(["--video", os.path.join(out, "v.avi")], ["unknown format .avi", ".mp4", ".ogv"])
refused(["--video", os.path.join(out, "v.ogv"), "--video-encoder", "vtk", "--size",
         "200x120"], ["multiple of 16", "200"])
refused(["--video", os.path.join(out, "v.ogv"), "--video-encoder", "vtk", "--fps", "29.97"],
        ["whole frame rates", "29.97"])
refused(["--video", os.path.join(out, "v.mp4"), "--video-encoder", "vtk"], ["use .ogv"])
check(not os.path.exists(os.path.join(out, "v.ogv")), "a refused video was written")

if not ffmpeg or not ffprobe:
    print("ffmpeg / ffprobe not on PATH: the ffmpeg parts are not run "
          "(Scripts/setup.sh installs ffmpeg)")
    raise SystemExit(1 if required() else SKIP)

refused(["--video", os.path.join(out, "v.mp4"), "--size", "201x120"],
        ["even width and height", "201x120"])
# The forced VTK video, decoded by ffmpeg.
got = probe(os.path.join(out, "vtk", "flight.ogv"))
check(got == ("theora", 320, 181, 9, "24/1"), f"ffprobe of VTK's video: {got}")
check_frames(os.path.join(out, "vtk", "flight.ogv"), os.path.join(out, "vtk"), (0, 4, 8),
             (320, 181))

# MP4 through ffmpeg (auto).
d = os.path.join(out, "mp4")
video = os.path.join(d, "flight.mp4")
so = fly("--frames", "12", "--size", "320x180", "--video", video, "--out", d)
check("(12 frames, 320x180, 30 fps, H.264 (MP4) by ffmpeg)" in so, f"summary:\n{so}")
got = probe(video)
print(f"{video}: ffprobe {got}, {os.path.getsize(video)} bytes")
check(got == ("h264", 320, 180, 12, "30/1"), f"{video}: {got}")
check_frames(video, d, (0, 6, 11), (320, 180))

# Ogg Theora through ffmpeg, odd size, no PNG frames.
d = os.path.join(out, "ogv")
video = os.path.join(d, "flight.ogv")
so = fly("--frames", "7", "--size", "201x121", "--no-frames", "--video", video, "--out", d)
check("Ogg Theora by ffmpeg" in so, f"summary:\n{so}")
got, own = probe(video), theora_stream(video)
print(f"{video}: ffprobe {got}, own read-back {own}")
check(got == ("theora", 201, 121, 7, "30/1") and own == (201, 121, 7, "30/1"),
      f"{video}: ffprobe {got}, own {own}")
check(not any(f.endswith(".png") for f in os.listdir(d)), "--no-frames wrote PNGs")
print("TestFlyVideo: passed")
