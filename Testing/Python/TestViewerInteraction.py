"""geomipmap-view driven by recorded event streams (issue #15, part 1), the way VTK tests
interaction: vtkInteractorEventRecorder plays events on the viewer's window interactor
(under Xvfb), and after each part of the stream the viewer's state is checked.

The viewer runs in this process (cli.open_viewer: the command's own loading and window)
over the synthetic terrain, 513^2 at 640 x 360:
- loading progress: the source's and the error-table build's progress events reach the
  window (the texts it rendered while loading) and the terminal; the window's redraw
  throttle, under a fake clock;
- orbit drag: the camera turns about its focal point;
- '+' / '-': tau doubles / halves, clamped to 1/16 .. 256;
- 'w': the actor's representation toggles wireframe / surface;
- 'l': the LOD freezes: while the camera orbits, the triangle count stays and no index is
  uploaded; unfrozen, the new view's LOD is drawn (another count), measured within tau;
- overlay: its text holds the mapper's live figures of the frame it is drawn on, and it
  is drawn (the top left differs with the overlay off);
- 's': a PNG of the window's size is written, showing the terrain;
- 'f': fly mode: Up moves along the view direction, a drag turns the view by 0.2 degrees a
  pixel with the eye fixed, Page Down stops at the clearance above the ground; 'f' again:
  orbit about the terrain point in the middle of the view;
- 'g' toggles geomorphing (the mapper's Geomorphing, on at start); 'n' toggles the shading
  normals automatic / per vertex / per pixel (NormalMode; per pixel changes the picture); 'h' shows every key,
  and Documentation/user-guide.md's key table lists every one;
- looking away from the terrain (VTK then skips the mapper), the overlay says so and shows
  no stale figures;
- a recorded session (cli.record) played back gives the same camera;
- the final frame matches Data/Baseline/TestViewerInteraction.png (threshold 10, as the
  other image tests) and measures within tau (gmmtestutil.check_drawn_within_tau);
- the launcher: --play a stream file with a screenshot; exit 0, the PNG written (into a
  --screenshot-dir the viewer makes).
GEOMIPMAP_WRITE_BASELINE=1 writes the baseline instead (look at it before committing it).
Usage: TestViewerInteraction.py GEOMIPMAP_VIEW SCRATCH_DIR
"""
import math
import os
import shutil
import subprocess
import sys

import numpy as np
from vtkmodules.test import Testing
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

import refscene
from gmmtestutil import check_within_tau
from viewtestutil import (check_progress_throttle, drag, key, keys, open_viewer_recording,
                          stream)

from geomipmap_apps.view import cli, viewer as viewer_module

exe, scratch = sys.argv[1], sys.argv[2]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
here = os.path.dirname(os.path.abspath(__file__))
baseline = os.path.join(here, "..", "..", "Data", "Baseline", "TestViewerInteraction.png")
W, H = 640, 360
check = refscene.Checks()


def read_png(name):
    r = vtkPNGReader()
    r.SetFileName(name)
    r.Update()
    img = r.GetOutput()
    w, h, _ = img.GetDimensions()
    return w, h, vtk_to_numpy(img.GetPointData().GetScalars()).reshape(h, w, -1)


# --- Loading, with what the window showed recorded -------------------------------------
said = []
v, shown, terminal = open_viewer_recording(
    ["--synthetic-size", "513", "--size", f"{W}x{H}", "--block-size", "32",
     "--screenshot-dir", scratch], say=said.append)
for stage in ("generating terrain", "error tables"):
    texts = [t for t in shown if stage in t]
    check(len(texts) >= 2 and texts[-1].endswith("100 %"),
          f"the window showed the {stage} stage from its start to 100 % ({texts})")
    check(f"geomipmap-view: {stage} 100 %" in terminal,
          f"the terminal got the {stage} stage's progress")
check(not v.overlay.loading.GetVisibility(), "the loading text is gone once loaded")
check_progress_throttle(check)
mapper, cam = v.mapper, v.camera


def play(*parts):
    cli.play(v, stream(*parts))


def stats_in_overlay(what):
    text = v.overlay.stats.GetInput()
    s = v.stats()
    want = [f"tau {s['tau']:g} px", f"certified error {s['certified_error_px']:.3f} px",
            f"triangles {s['triangles']:,}",
            f"visible blocks {s['visible_blocks']} of {s['blocks']}", "last frame "]
    missing = [w for w in want if w not in text]
    check(not missing and s["triangles"] > 0 and s["frame_ms"] is not None
          and s["triangles"] == mapper.GetNumberOfRenderedTriangles(),
          f"{what}: the overlay shows the frame's figures ({text!r}; missing {missing})")


stats_in_overlay("first frame")

# --- Orbit drag ------------------------------------------------------------------------
p0, f0 = cam.GetPosition(), cam.GetFocalPoint()
play(drag(320, 180, 400, 200))
p1, f1 = cam.GetPosition(), cam.GetFocalPoint()
check(math.dist(p0, p1) > 100.0 and math.dist(f0, f1) < 1e-6
      and abs(math.dist(p0, f0) - math.dist(p1, f1)) < 1e-6 * math.dist(p0, f0),
      f"orbit drag: the camera moved {math.dist(p0, p1):.0f} m about a fixed focal point")
stats_in_overlay("after the orbit drag")

# --- tau keys --------------------------------------------------------------------------
for sym, want in (("plus", 2.0), ("plus", 4.0), ("minus", 2.0), ("minus", 1.0),
                  ("minus", 0.5)):
    play(key(sym))
    check(mapper.GetPixelError() == want and f"tau = {want:g} px" in v.message,
          f"'{sym}': tau {mapper.GetPixelError():g} (want {want:g})")
stats_in_overlay("after the tau keys")
play(keys(*["minus"] * 8))
check(mapper.GetPixelError() == 1.0 / 16.0, f"tau stops at 1/16 ({mapper.GetPixelError()})")
play(keys(*["plus"] * 16))
check(mapper.GetPixelError() == 256.0, f"tau stops at 256 ({mapper.GetPixelError()})")
play(keys(*["minus"] * 8))
check(mapper.GetPixelError() == 1.0, f"tau back to 1 ({mapper.GetPixelError()})")

# --- Wireframe -------------------------------------------------------------------------
prop = v.actor.GetProperty()
play(key("w"))
check(prop.GetRepresentation() == 1 and "wireframe" in v.overlay.stats.GetInput(),
      f"'w': wireframe (representation {prop.GetRepresentation()})")
play(key("w"))
check(prop.GetRepresentation() == 2 and "surface" in v.overlay.stats.GetInput(),
      f"'w' again: surface (representation {prop.GetRepresentation()})")

# --- Freeze ----------------------------------------------------------------------------
play(key("l"))
tri0, uploads0 = mapper.GetNumberOfRenderedTriangles(), mapper.GetNumberOfIndexUploads()
p0 = cam.GetPosition()
play(drag(320, 180, 200, 160), drag(320, 180, 260, 120))
check(mapper.GetFreezeLevelOfDetail() and "FROZEN" in v.overlay.stats.GetInput(),
      "'l': the LOD is frozen, and the overlay says so")
check(math.dist(p0, cam.GetPosition()) > 100.0, "frozen: the camera moved")
check(mapper.GetNumberOfRenderedTriangles() == tri0 and mapper.GetIndicesReused()
      and mapper.GetNumberOfIndexUploads() == uploads0,
      f"frozen: {mapper.GetNumberOfRenderedTriangles()} triangles (were {tri0}), "
      f"{mapper.GetNumberOfIndexUploads() - uploads0} index uploads")
play(key("l"))
check(not mapper.GetFreezeLevelOfDetail() and mapper.GetNumberOfRenderedTriangles() != tri0,
      f"'l' again: live, this view's LOD ({mapper.GetNumberOfRenderedTriangles()} "
      f"triangles, frozen had {tri0})")
check_within_tau(check, v.image, v.renderer, v.actor, mapper, "unfrozen")
stats_in_overlay("after unfreezing")

# --- Overlay drawn, and the 'o' key ----------------------------------------------------
with_overlay = refscene.grab(v.window)[H - 40:, :200].astype(int)
play(key("o"))
without = refscene.grab(v.window)[H - 40:, :200].astype(int)
check(not v.overlay.visible() and np.abs(with_overlay - without).max() > 60,
      "'o': the overlay was drawn top left, and is hidden now")
play(key("o"))
check(v.overlay.visible(), "'o' again: overlay shown")

# --- Screenshot ------------------------------------------------------------------------
play(key("s"))
shot = os.path.join(scratch, "geomipmap-view-0001.png")
check(os.path.isfile(shot) and any(shot in s for s in said),
      f"'s': {shot} written and announced ({said})")
if os.path.isfile(shot):
    w, h, pixels = read_png(shot)
    rgb = pixels[:, :, :3].astype(float)
    terrain = (rgb[:, :, 2] <= np.maximum(rgb[:, :, 0], rgb[:, :, 1]) + 8).mean()
    check((w, h) == (W, H) and 0.1 < terrain < 0.95,
          f"screenshot {w} x {h}, terrain covers {terrain:.0%} of it")

# --- Fly mode --------------------------------------------------------------------------
play(key("r"), key("f"))
check(v.mode == "fly" and v.interactor.GetInteractorStyle() is v.fly_style.style,
      "'f': fly mode, fly style on the interactor")


def direction():
    p, f = cam.GetPosition(), cam.GetFocalPoint()
    d = np.subtract(f, p)
    return np.array(p), d / np.linalg.norm(d)


p0, d0 = direction()
play(keys("Up", "Up", "Up"))
p1, d1 = direction()
moved = p1 - p0
check(np.linalg.norm(moved) > 10.0 and np.dot(moved, d0) / np.linalg.norm(moved) > 0.9999
      and np.allclose(d0, d1), f"fly Up x3: {np.linalg.norm(moved):.0f} m along the view")
az0 = math.degrees(math.atan2(d1[1], d1[0]))
play(drag(320, 180, 280, 180))
p2, d2 = direction()
az1 = math.degrees(math.atan2(d2[1], d2[0]))
check(np.allclose(p1, p2) and abs((az1 - az0) - 8.0) < 1e-6,
      f"fly drag 40 px left: the view turned {az1 - az0:.6f} degrees left, eye fixed")
for n in range(1, 11):
    play(key("Up", shift=True))
    x, y, z = cam.GetPosition()
    if math.isfinite(mapper.GetHeightAt(x, y)):
        break
check(math.isfinite(mapper.GetHeightAt(x, y)), f"fly Shift+Up x{n}: over the terrain "
      f"({x:.0f}, {y:.0f}, {z:.0f})")
play(keys(*["Next"] * 30, shift=True))
x, y, z = cam.GetPosition()
ground = mapper.GetHeightAt(x, y)
check(abs(z - ground - v.clearance) < 1e-6 * max(1.0, abs(z)),
      f"fly Shift+Page Down x30: stopped {z - ground:.3f} m above the ground "
      f"(clearance {v.clearance:g})")
play(keys("Up", "Up"))
x, y, z = cam.GetPosition()
check(z - mapper.GetHeightAt(x, y) >= v.clearance - 1e-6,
      f"fly low: still {z - mapper.GetHeightAt(x, y):.3f} m above the ground")
play(key("f"))
fx, fy, fz = cam.GetFocalPoint()
check(v.mode == "orbit" and v.interactor.GetInteractorStyle() is v.orbit_style
      and abs(fz - mapper.GetHeightAt(fx, fy)) < 1e-3,
      f"'f' again: orbit about the ground point in view ({fz - mapper.GetHeightAt(fx, fy):.2e})")

# --- Geomorphing: 'g' toggles the mapper's Geomorphing (on at start) ---------------------
check(mapper.GetGeomorphing(), "geomorphing is on at start")
tau_before = mapper.GetPixelError()
play(key("g"))
check(not mapper.GetGeomorphing() and "geomorphing off" in v.message
      and mapper.GetPixelError() == tau_before, f"'g': off ({v.message!r})")
play(key("g"))
check(mapper.GetGeomorphing() and "geomorphing on" in v.message, f"'g' again: on ({v.message!r})")
# --- Shading normals: 'n' cycles the mapper's NormalMode (automatic at start) -------------
check(mapper.GetNormalMode() == mapper.NORMALS_AUTOMATIC, "normals automatic at start")
# Automatic: per vertex where OpenGL runs on the CPU and the frame is certified within 1 px,
# which a still frame at tau <= 1 is (its certificate is at most tau).
software = refscene.renders_on_cpu(v.window)
auto_vertex = software and mapper.GetPixelError() <= 1.0
check(mapper.GetLastFrameVertexNormals() == auto_vertex,
      f"automatic normals: per vertex {mapper.GetLastFrameVertexNormals()} at tau "
      f"{mapper.GetPixelError():g} (renderer on the CPU: {software})")
automatic = refscene.grab(v.window)[60:H - 80].astype(int)  # between the status line and statistics
play(key("n"))
per_vertex = refscene.grab(v.window)[60:H - 80].astype(int)
check(mapper.GetNormalMode() == mapper.NORMALS_PER_VERTEX and mapper.GetLastFrameVertexNormals()
      and "per vertex" in v.message, f"'n': normals per vertex ({v.message!r})")
play(key("n"))
per_pixel = refscene.grab(v.window)[60:H - 80].astype(int)
changed = float((np.abs(per_pixel - per_vertex).max(axis=2) > 0).mean())
check(mapper.GetNormalMode() == mapper.NORMALS_PER_FRAGMENT and not mapper.GetLastFrameVertexNormals()
      and "per pixel" in v.message and changed > 0.01,
      f"'n' again: per pixel ({v.message!r}; {100 * changed:.1f} % of the pixels changed)")
# Automatic draws what its choice draws: the same pixels as that mode.
same = per_vertex if auto_vertex else per_pixel
check(float((np.abs(automatic - same).max(axis=2) > 0).mean()) == 0.0,
      "automatic normals draw the same picture as the mode they chose")
play(key("n"))
check(mapper.GetNormalMode() == mapper.NORMALS_AUTOMATIC and "automatic" in v.message,
      f"'n' a third time: automatic ({v.message!r})")
play(key("h"))
check(all(doc in v.overlay.status.GetInput() for _, _, doc in viewer_module.KEYS),
      "'h': the help lists every key")
with open(os.path.join(here, "..", "..", "Documentation", "user-guide.md")) as f:
    guide = f.read()
missing = [doc.split()[0] for _, _, doc in viewer_module.KEYS
           if f"| `{doc.split()[0]}`" not in guide]
check(not missing, f"the user guide's key table lists every key (missing {missing})")
play(key("h"))

# --- Terrain out of view: VTK skips the mapper, the overlay must not show stale figures ---
x0, x1, y0, y1, z0, z1 = mapper.GetBounds()
cam.SetPosition(0.5 * (x0 + x1), y0 - 50000.0, z1)
cam.SetFocalPoint(0.5 * (x0 + x1), y0 - 60000.0, z1)
v.camera_moved()
check("terrain out of view" in v.overlay.stats.GetInput() and "triangles 0 " in
      v.overlay.stats.GetInput(), f"looking away: {v.overlay.stats.GetInput()!r}")

# --- A recorded session plays back the same ---------------------------------------------
play(key("r"))
start = (cam.GetPosition(), cam.GetFocalPoint())
log = os.path.join(scratch, "session.log")
recorder = cli.record(v, log)
play(drag(300, 200, 360, 150), key("plus"), drag(320, 180, 330, 240))
recorder.Stop()
recorder.Off()
after = (cam.GetPosition(), cam.GetFocalPoint(), mapper.GetPixelError())
with open(log) as f:
    recorded = f.read()
play(key("r"), key("minus"))
check(cam.GetPosition() == start[0], "'r': the camera is back home")
cli.play(v, recorded)
again = (cam.GetPosition(), cam.GetFocalPoint(), mapper.GetPixelError())
check("KeyPressEvent" in recorded and "LeftButtonPressEvent" in recorded and
      np.allclose(np.hstack(again[:2]), np.hstack(after[:2])) and again[2] == after[2],
      f"the recorded session ({recorded.count(chr(10))} lines) plays back to the same camera")

# --- Final frame: regression image and the independent measure --------------------------
play(key("r"), key("minus"), drag(320, 180, 300, 150), key("o"))
v.window.SwapBuffersOff()  # read the frame back before any swap (see Viewer.screenshot)
v.window.Render()
v.scene.capture()
v.window.SwapBuffersOn()
check_within_tau(check, v.image, v.renderer, v.actor, mapper, "final frame")
if os.environ.get("GEOMIPMAP_WRITE_BASELINE"):
    v.scene.write_png(baseline)
    print("wrote", baseline)
else:
    try:
        Testing.compareImageWithSavedImage(v.scene.grab, baseline, threshold=10)
        check(True, "final frame matches " + os.path.basename(baseline))
    except RuntimeError as e:
        check(False, f"final frame: {' '.join(str(e).split())}")

# --- The launcher, as a user runs it -----------------------------------------------------
events = os.path.join(scratch, "events.log")
with open(events, "w") as f:
    f.write(stream(drag(160, 100, 200, 110), key("s"), key("q")))
shots = os.path.join(scratch, "launcher", "shots")  # made by the first screenshot
p = subprocess.run([exe, "--synthetic-size", "129", "--size", "320x200", "--screenshot-dir",
                    shots, "--play", events], capture_output=True, text=True, timeout=120)
out = os.path.join(shots, "geomipmap-view-0001.png")
check(p.returncode == 0 and os.path.isfile(out) and read_png(out)[:2] == (320, 200)
      and "error tables 100 %" in p.stderr and "Traceback" not in p.stderr,
      f"geomipmap-view --play: exit {p.returncode}, screenshot 320 x 200; "
      f"stderr {p.stderr.strip()!r}")
check.exit()
