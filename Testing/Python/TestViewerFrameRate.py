"""geomipmap-view --fps (issue #14): VTK's frame-rate contract in the viewer.

While a mouse button moves the camera the interactor styles put the interactor's
DesiredUpdateRate on the window (VTK's orbit style itself; fly mode's look drag through
Viewer.start_motion), and with --fps the mapper follows the allocated render time: each
moving frame is drawn within a triangle budget. The frame on release is a still one,
drawn at --tau. Played with recorded events, as TestViewerInteraction does:
- with --fps 4, orbit and fly drags: every frame during a drag is interactive, allocated
  what the rest of the frame leaves of 1/4 s (one prop: the whole frame's time, less the
  median over the moving frames before it of their time outside the mapper's draw; the
  first gets 1/4 s), drawn within the budget in force; the frame
  on release is not interactive and measures within tau with the independent
  vtkGeoMipMapScreenError (gmmtestutil.check_drawn_within_tau); the overlay says which;
- without --fps the same drag draws no frame within a budget.
No timing threshold: what is checked is which frames are budgeted, and their counts.
"""
import sys

import refscene
from gmmtestutil import check_within_tau
from viewtestutil import drag, key, open_viewer_recording, stream

from geomipmap_apps.view import cli

W, H = 480, 270
check = refscene.Checks()


def frames_during(v, parts):
    """Plays the events; returns the per-frame figures of every frame they drew, taken
    when the window's frame ends (after the viewer's own observer: its frame time)."""
    seen = []
    tag = v.window.AddObserver("EndEvent", lambda *_: seen.append(v.stats()), -10.0)
    cli.play(v, stream(*parts))
    v.window.RemoveObserver(tag)
    return seen


rests = []  # every moving frame's time outside the mapper's draw, in order


def expected_allocations(moving):
    """What each moving frame should be allocated (ms), from the frames before it: 1/4 s
    less the median of the last 15 moving frames' time outside the mapper's draw, never
    below a quarter of it."""
    out = []
    for s in moving:
        last = sorted(rests[-15:])
        rest = 0.0 if not last else (last[len(last) // 2] if len(last) % 2 else
                                     0.5 * (last[len(last) // 2 - 1] + last[len(last) // 2]))
        out.append(max(250.0 - rest, 62.5))
        rests.append(max(s["frame_ms"] - s["draw_ms"], 0.0))
    return out


v, _, _ = open_viewer_recording(["--synthetic-size", "513", "--size", f"{W}x{H}", "--fps", "4"])
m = v.mapper
check(m.GetFollowAllocatedRenderTime(), "--fps turns on the mapper's FollowAllocatedRenderTime")
first = v.stats()
check(not first["interactive"], "the first frame is a still one (tau)")

for mode, parts in (("orbit", [drag(240, 135, 300, 150, steps=6)]),
                    ("fly", [key("f"), drag(240, 135, 200, 120, steps=6)])):
    seen = frames_during(v, parts)
    moving = [s for s in seen if s["interactive"]]
    check(len(moving) >= 6, f"{mode}: the drag's frames are moving ones ({len(moving)} of "
          f"{len(seen)} frames)")
    want = expected_allocations(moving)
    check(all(abs(s["allocated_ms"] - a) < 1e-3 for s, a in zip(moving, want)),
          f"{mode}: each moving frame was allocated 1/4 s less the rest of the frame "
          f"({[(round(s['allocated_ms'], 3), round(a, 3)) for s, a in zip(moving, want)]} ms)")
    check(mode != "orbit" or abs(moving[0]["allocated_ms"] - 250.0) < 1e-6,
          "the first moving frame is allocated the whole 1/4 s")
    check(all(0 < s["triangles"] <= s["budget"] for s in moving),
          f"{mode}: each moving frame draws within its budget "
          f"({[(s['triangles'], s['budget']) for s in moving]})")
    last = seen[-1] if seen else None
    check(last is not None and not last["interactive"] and last["budget"] == 0,
          f"{mode}: the frame on release is a still one, no budget")
    check_within_tau(check, v.image, v.renderer, v.actor, m, f"{mode}: the still frame after the drag")
    text = v.overlay.stats.GetInput()
    check("4 fps while moving; still: tau" in text, f"{mode}: the overlay says the frame is still ({text!r})")

# The overlay during a moving frame: the budget and the allocated time.
overlay = []
tag = v.renderer.AddObserver("EndEvent", lambda *_: overlay.append(v.stats_text()))
cli.play(v, stream(drag(240, 135, 260, 140, steps=2)))
v.renderer.RemoveObserver(tag)
check(any("4 fps: moving, budget" in t and " triangles in " in t and " ms\n" in t for t in overlay),
      f"the overlay shows the budget of a moving frame ({overlay[:1]!r})")
v.window.Finalize()

# Without --fps the same drag is drawn at tau.
w, _, _ = open_viewer_recording(["--synthetic-size", "513", "--size", f"{W}x{H}"])
seen = frames_during(w, [drag(240, 135, 300, 150, steps=6)])
check(len(seen) >= 6 and not any(s["interactive"] or s["budget"] for s in seen),
      f"without --fps no frame of a drag is budgeted ({len(seen)} frames)")
w.window.Finalize()
check.exit()
