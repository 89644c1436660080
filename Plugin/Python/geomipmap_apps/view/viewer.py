"""geomipmap-view's window: the terrain scene under an interactor, two camera modes, keys,
and an overlay with the live LOD statistics.

Why one class over scene.Scene: the scene (window, LOD mapper, colours, sun) is the one
every tool renders; what is interactive lives here: the camera modes (orbit: VTK's
vtkInteractorStyleTerrain; fly: FlyStyle below, which keeps the camera above the ground),
the keys (KEYS, also the help text and the user guide's table), the overlay (a second
renderer on layer 1, filled after the terrain renderer drew, so its figures are those of
the frame it is drawn on) and screenshots. Nothing here blocks until start(): a test
plays a recorded event stream (vtkInteractorEventRecorder) after Viewer(...) and
initialize().
"""

import math
import os
import time

from vtkmodules.vtkCommonCore import reference, vtkCommand
from vtkmodules.vtkInteractionStyle import vtkInteractorStyleTerrain
from vtkmodules.vtkRenderingCore import (
    vtkInteractorStyle,
    vtkRenderer,
    vtkRenderWindowInteractor,
    vtkTextActor,
)
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (text rendering)

from .motion_rate import MotionRate

TAU_MIN, TAU_MAX = 1.0 / 16.0, 256.0

# (key symbols, action, what it does): dispatch, the help overlay and the user guide's
# key table (TestViewerInteraction checks the guide lists every one).
KEYS = (
    (("plus", "equal", "KP_Add"), "tau_up", "+  double tau (coarser, fewer triangles)"),
    (("minus", "underscore", "KP_Subtract"), "tau_down", "-  halve tau (finer)"),
    (("w", "W"), "wireframe", "w  wireframe on / off"),
    (("l", "L"), "freeze", "l  freeze the LOD on / off (inspect it from elsewhere)"),
    (("f", "F"), "mode_switch", "f  fly mode / orbit mode"),
    (("g", "G"), "geomorph", "g  geomorphing on / off (smooth level changes)"),
    (("n", "N"), "normals", "n  shading normals automatic / per vertex / per pixel"),
    (("s", "S"), "screenshot", "s  save a screenshot (PNG, the window's size)"),
    (("r", "R"), "reset", "r  reset the camera"),
    (("o", "O"), "overlay_toggle", "o  overlay on / off"),
    (("h", "H", "question"), "help", "h  this help"),
    (("q", "Q", "Escape"), "quit", "q  quit"),
)
FLY_HELP = ("fly mode: Up / Down arrows or mouse wheel: forward / back; Left / Right: turn;\n"
            "          Page Up / Down: climb / descend; left drag: look; Shift: 5x faster")
ORBIT_HELP = "orbit mode: left drag: rotate; middle drag: pan; right drag: zoom"


class Overlay:
    """Text over the terrain: statistics (top left), status line (bottom left) and the
    loading text (centre), in their own renderer. Alone in `window` while the terrain
    loads (layer 0: it clears the window); over_scene() puts it on layer 1, above the
    terrain renderer, transparent."""

    def __init__(self, window, font_size=16):
        self.renderer = vtkRenderer()
        self.renderer.InteractiveOff()
        self.renderer.SetBackground(0.1, 0.1, 0.12)
        window.AddRenderer(self.renderer)
        self.window = window
        self.stats = self._text(font_size, 0.01, 0.99, "left", "top")
        self.status = self._text(font_size, 0.01, 0.01, "left", "bottom")
        self.loading = self._text(int(font_size * 1.5), 0.5, 0.5, "centered", "centered")

    def _text(self, size, x, y, justify, vjustify):
        actor = vtkTextActor()
        actor.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
        actor.SetPosition(x, y)
        prop = actor.GetTextProperty()
        prop.SetFontFamilyToCourier()
        prop.SetFontSize(size)
        prop.SetColor(1.0, 1.0, 1.0)
        prop.SetBackgroundColor(0.0, 0.0, 0.0)
        prop.SetBackgroundOpacity(0.55)
        getattr(prop, "SetJustificationTo" + justify.capitalize())()
        getattr(prop, "SetVerticalJustificationTo" + vjustify.capitalize())()
        actor.SetInput("")
        self.renderer.AddActor2D(actor)
        return actor

    def show_loading(self, text):
        """Shows `text` in the centre and renders the window now (LoadProgress's show)."""
        self.loading.SetInput(text)
        self.loading.VisibilityOn()
        self.window.Render()

    def over_scene(self):
        """Moves the overlay above the terrain renderer (layer 1) and hides the loading text."""
        self.window.SetNumberOfLayers(max(self.window.GetNumberOfLayers(), 2))
        self.renderer.SetLayer(1)
        self.loading.VisibilityOff()

    def set_visible(self, on):
        self.renderer.SetDraw(1 if on else 0)

    def visible(self):
        return bool(self.renderer.GetDraw())


class FlyStyle:
    """First-person flight over the terrain, one step per key press or wheel notch (no
    timers: every motion is an event, so a recorded event stream replays exactly).

    Left drag turns the view (0.2 degrees a pixel; the pitch stays within +-85 degrees,
    the view up is z). Motion moves the eye and the focal point together; after each one
    the eye is kept `clearance` above the full-resolution ground (the mapper's
    GetHeightAt; off the terrain or over nodata, its lowest point: Viewer.floor). A step
    is a tenth of the height above that floor, at least half the clearance, so flying low
    is slow and flying high is fast.
    """

    LOOK_DEG_PER_PIXEL = 0.2
    TURN_DEG = 5.0
    MAX_PITCH = 85.0

    def __init__(self, viewer):
        self.viewer = viewer
        self.style = vtkInteractorStyle()
        self.looking = None
        for event, handler in (("LeftButtonPressEvent", self._press),
                               ("LeftButtonReleaseEvent", self._release),
                               ("MouseMoveEvent", self._move),
                               ("MouseWheelForwardEvent", lambda *_: self.step(1.0)),
                               ("MouseWheelBackwardEvent", lambda *_: self.step(-1.0))):
            self.style.AddObserver(event, handler)

    def _press(self, *_):
        self.looking = self.viewer.interactor.GetEventPosition()
        self.viewer.start_motion()

    def _release(self, *_):
        self.looking = None
        self.viewer.end_motion()

    def _move(self, *_):
        if self.looking is None:
            return
        x, y = self.viewer.interactor.GetEventPosition()
        dx, dy = x - self.looking[0], y - self.looking[1]
        self.looking = (x, y)
        self.look(-dx * self.LOOK_DEG_PER_PIXEL, dy * self.LOOK_DEG_PER_PIXEL)

    def _direction(self):
        """(azimuth, pitch) of the view direction in degrees, and the focal distance."""
        cam = self.viewer.camera
        p, f = cam.GetPosition(), cam.GetFocalPoint()
        d = [f[k] - p[k] for k in range(3)]
        dist = math.sqrt(sum(v * v for v in d))
        return (math.degrees(math.atan2(d[1], d[0])),
                math.degrees(math.asin(max(-1.0, min(1.0, d[2] / dist)))), dist)

    def _aim(self, azimuth, pitch, dist, position=None):
        cam = self.viewer.camera
        p = position or cam.GetPosition()
        a, e = math.radians(azimuth), math.radians(pitch)
        d = (math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e))
        cam.SetPosition(*p)
        cam.SetFocalPoint(*(p[k] + dist * d[k] for k in range(3)))
        cam.SetViewUp(0.0, 0.0, 1.0)

    def look(self, yaw_deg, pitch_deg):
        """Turns the view by yaw (left, degrees) and pitch (up), the eye fixed."""
        azimuth, pitch, dist = self._direction()
        pitch = max(-self.MAX_PITCH, min(self.MAX_PITCH, pitch + pitch_deg))
        self._aim(azimuth + yaw_deg, pitch, dist)
        self.viewer.camera_moved()

    def level(self):
        """Makes the view up z and the pitch within +-MAX_PITCH (entering fly mode)."""
        self.look(0.0, 0.0)

    def step(self, amount, vertical=False):
        """Moves `amount` steps along the view direction, or up when vertical."""
        cam = self.viewer.camera
        if self.viewer.interactor.GetShiftKey():
            amount *= 5.0
        p = list(cam.GetPosition())
        size = max(0.1 * abs(p[2] - self.viewer.floor(p[0], p[1])), 0.5 * self.viewer.clearance)
        azimuth, pitch, dist = self._direction()
        if vertical:
            d = (0.0, 0.0, 1.0)
        else:
            a, e = math.radians(azimuth), math.radians(pitch)
            d = (math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e))
        p = [p[k] + amount * size * d[k] for k in range(3)]
        p[2] = max(p[2], self.viewer.floor(p[0], p[1]) + self.viewer.clearance)
        self._aim(azimuth, pitch, dist, p)
        self.viewer.camera_moved()

    def on_key(self, sym):
        """Handles a fly-mode motion key; True when it was one."""
        moves = {"Up": lambda: self.step(1.0), "Down": lambda: self.step(-1.0),
                 "Left": lambda: self.look(self.TURN_DEG, 0.0),
                 "Right": lambda: self.look(-self.TURN_DEG, 0.0),
                 "Prior": lambda: self.step(1.0, vertical=True),
                 "Next": lambda: self.step(-1.0, vertical=True)}
        if sym not in moves:
            return False
        moves[sym]()
        return True


class Viewer:
    """The interactive terrain viewer over a scene.Scene (on-screen window).

    scene: the Scene (its window already holds `overlay`'s renderer; tau, block size and
    colours are the scene's). image: the terrain image the mapper draws. screenshot_dir:
    where 's' writes geomipmap-view-NNNN.png. fly: start in fly mode. prog: the name
    messages start with. say(text): where status messages go besides the overlay
    (default: print). fps: the frame rate to hold while a mouse button moves the camera
    (VTK's frame-rate contract: the interactor's DesiredUpdateRate, which the interactor
    styles put on the window during a drag, and the mapper's FollowAllocatedRenderTime);
    None: tau alone.
    """

    def __init__(self, scene, image, overlay, screenshot_dir=".", fly=False,
                 prog="geomipmap-view", say=None, fps=None):
        self.scene = scene
        self.image = image
        self.mapper = scene.mapper
        self.actor = scene.actor
        self.renderer = scene.renderer
        self.window = scene.window
        self.overlay = overlay
        self.screenshot_dir = screenshot_dir
        self.prog = prog
        self.say = say or (lambda text: print(f"{prog}: {text}", flush=True))
        self.camera = self.renderer.GetActiveCamera()
        self.screenshots = []
        self.frame_ms = None
        self.show_help = False
        self.message = ""
        spacing = image.GetSpacing()
        self.clearance = 2.0 * max(abs(spacing[0]), abs(spacing[1]))

        self.interactor = vtkRenderWindowInteractor()
        self.interactor.SetRenderWindow(self.window)
        self.fps = fps
        self.motion_rate = None
        if fps:
            # The terrain gets what the rest of the frame leaves of 1 / fps (MotionRate).
            self.motion_rate = MotionRate(fps, self.window.GetRenderers().GetNumberOfItems())
            self.interactor.SetDesiredUpdateRate(self.motion_rate.desired_update_rate())
            self.mapper.FollowAllocatedRenderTimeOn()
        self.orbit_style = vtkInteractorStyleTerrain()
        self.fly_style = FlyStyle(self)
        for style in (self.orbit_style, self.fly_style.style):
            # Our keys replace VTK's default ones ('w' for all actors, 'e' exit, '3' stereo...).
            style.AddObserver("CharEvent", lambda *_: None)
        self.interactor.AddObserver("KeyPressEvent", self._on_key)
        self.mode = "fly" if fly else "orbit"
        self.interactor.SetInteractorStyle(
            self.fly_style.style if fly else self.orbit_style)

        self._t0 = None
        self.window.AddObserver(vtkCommand.StartEvent, self._frame_start)
        self.window.AddObserver(vtkCommand.EndEvent, self._frame_end)
        self.renderer.AddObserver(vtkCommand.EndEvent, self._update_stats)
        self.actions = {action: getattr(self, action) for _, action, _ in KEYS}
        self.keymap = {sym: action for syms, action, _ in KEYS for sym in syms}

        self.home_camera()
        if fly:
            self.fly_style.level()
        self.overlay.over_scene()
        self._status(ORBIT_HELP if not fly else FLY_HELP)

    # -- camera -----------------------------------------------------------------------
    def home_camera(self):
        """The starting view: from the south, 35 degrees down, the whole terrain in view."""
        x0, x1, y0, y1, z0, z1 = self.mapper.GetBounds()
        centre = (0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1))
        e = math.radians(35.0)
        cam = self.camera
        cam.SetFocalPoint(*centre)
        cam.SetPosition(centre[0], centre[1] - math.cos(e), centre[2] + math.sin(e))
        cam.SetViewUp(0.0, 0.0, 1.0)
        cam.SetViewAngle(40.0)
        self.renderer.ResetCamera()  # fits the bounding sphere: the terrain looks small
        cam.Dolly(1.7)
        self.renderer.ResetCameraClippingRange()

    def ground_height(self, x, y):
        """The full-resolution ground height at (x, y), NaN off the terrain or on nodata."""
        return self.mapper.GetHeightAt(x, y)

    def floor(self, x, y):
        """The height fly mode keeps `clearance` above: the ground at (x, y), or the
        terrain's lowest point off the terrain and over nodata."""
        ground = self.ground_height(x, y)
        return ground if math.isfinite(ground) else self.mapper.GetBounds()[4]

    def camera_moved(self):
        self.renderer.ResetCameraClippingRange()
        self.interactor.Render()

    def _focus_on_ground(self):
        """Orbit mode pivots about the focal point: put it on the terrain in the middle of
        the view (exact ray hit), so that leaving fly mode orbits what is looked at."""
        cam = self.camera
        p, f = cam.GetPosition(), cam.GetFocalPoint()
        x0, x1, y0, y1, z0, z1 = self.mapper.GetBounds()
        reach = 4.0 * math.dist((x0, y0, z0), (x1, y1, z1))
        d = [f[k] - p[k] for k in range(3)]
        n = math.sqrt(sum(v * v for v in d))
        far = [p[k] + reach * d[k] / n for k in range(3)]
        t, pid, cid = reference(0.0), reference(0), reference(0)
        x, normal = [0.0] * 3, [0.0] * 3
        if self.mapper.IntersectWithLine(p, far, t, x, normal, pid, cid):
            cam.SetFocalPoint(*x)

    # -- keys ---------------------------------------------------------------------------
    def _on_key(self, *_):
        sym = self.interactor.GetKeySym() or ""
        if self.mode == "fly" and self.fly_style.on_key(sym):
            return
        action = self.keymap.get(sym)
        if action:
            self.actions[action]()

    def _status(self, text, render=False):
        self.message = text
        self._refresh_status()
        if render:
            self.interactor.Render()

    def _refresh_status(self):
        if self.show_help:
            lines = [doc for _, _, doc in KEYS] + [ORBIT_HELP if self.mode == "orbit"
                                                   else FLY_HELP]
            self.overlay.status.SetInput("\n".join(lines))
        else:
            self.overlay.status.SetInput(f"{self.message}\n[h: help]")

    def tau_up(self):
        self.set_tau(self.mapper.GetPixelError() * 2.0)

    def tau_down(self):
        self.set_tau(self.mapper.GetPixelError() / 2.0)

    def set_tau(self, tau):
        tau = min(max(tau, TAU_MIN), TAU_MAX)
        self.mapper.SetPixelError(tau)
        frozen = " (applies when the LOD is unfrozen)" if self.frozen() else ""
        self._status(f"tau = {tau:g} px{frozen}", render=True)

    def wireframe(self):
        prop = self.actor.GetProperty()
        if prop.GetRepresentation() == 1:  # VTK_WIREFRAME
            prop.SetRepresentationToSurface()
        else:
            prop.SetRepresentationToWireframe()
        self._status("wireframe " + ("on" if self.wireframe_on() else "off"), render=True)

    def wireframe_on(self):
        return self.actor.GetProperty().GetRepresentation() == 1

    def frozen(self):
        return bool(self.mapper.GetFreezeLevelOfDetail())

    def freeze(self):
        self.mapper.SetFreezeLevelOfDetail(not self.frozen())
        self._status("LOD frozen: move the camera to inspect it" if self.frozen()
                     else "LOD live", render=True)

    def mode_switch(self):
        if self.mode == "orbit":
            self.mode = "fly"
            self.interactor.SetInteractorStyle(self.fly_style.style)
            self.fly_style.level()
            self._status(FLY_HELP, render=True)
        else:
            self.mode = "orbit"
            self._focus_on_ground()
            self.interactor.SetInteractorStyle(self.orbit_style)
            self._status(ORBIT_HELP, render=True)

    def geomorph(self):
        self.mapper.SetGeomorphing(not self.mapper.GetGeomorphing())
        self._status("geomorphing on: levels change smoothly" if self.mapper.GetGeomorphing()
                     else "geomorphing off: levels switch at once", render=True)

    def normals(self):
        """Cycles the mapper's NormalMode: automatic -> per vertex -> per pixel."""
        m = self.mapper
        mode = m.GetNormalMode()
        if mode == m.NORMALS_AUTOMATIC:
            m.SetNormalModeToPerVertex()
            text = "normals per vertex: faster frames, less shading detail in coarse triangles"
        elif mode == m.NORMALS_PER_VERTEX:
            m.SetNormalModeToPerFragment()
            text = "normals per pixel: full-resolution shading"
        else:
            m.SetNormalModeToAutomatic()
            text = ("normals automatic: per vertex while the certified error is at most "
                    f"{m.GetAutomaticVertexNormalsPixels():g} px, per pixel above")
        self._status(text, render=True)

    def screenshot(self):
        """Writes the current frame, overlay included, at the window's size; returns the
        file name. The frame is rendered again without a buffer swap and read from the
        back buffer (what is on screen after a swap is undefined in OpenGL)."""
        try:
            os.makedirs(self.screenshot_dir, exist_ok=True)
        except OSError as e:
            self._status(f"screenshot failed: cannot make {self.screenshot_dir}: {e.strerror}",
                         render=True)
            return None
        n = len(self.screenshots) + 1
        while True:
            name = os.path.join(self.screenshot_dir, f"geomipmap-view-{n:04d}.png")
            if not os.path.exists(name):
                break
            n += 1
        swap = self.window.GetSwapBuffers()
        self.window.SwapBuffersOff()
        try:
            self.window.Render()
            self.scene.capture()
        finally:
            self.window.SetSwapBuffers(swap)
        self.scene.write_png(name)
        if not os.path.isfile(name):
            self._status(f"screenshot failed: cannot write {name}", render=True)
            return None
        self.screenshots.append(name)
        w, h = self.window.GetSize()
        self.say(f"screenshot {name} ({w} x {h})")
        self._status(f"screenshot: {name} ({w} x {h})", render=True)
        return name

    def reset(self):
        self.home_camera()
        if self.mode == "fly":
            self.fly_style.level()
        self._status("camera reset", render=True)

    def overlay_toggle(self):
        self.overlay.set_visible(not self.overlay.visible())
        self.interactor.Render()

    def help(self):
        self.show_help = not self.show_help
        self._refresh_status()
        self.interactor.Render()

    def quit(self):
        self.interactor.ExitCallback()

    # -- frame rate while moving ---------------------------------------------------------
    def start_motion(self):
        """A drag starts (fly mode's look; VTK's orbit style does the same itself): frames
        are interactive until end_motion, rendered at the interactor's DesiredUpdateRate."""
        self.window.SetDesiredUpdateRate(self.interactor.GetDesiredUpdateRate())

    def end_motion(self):
        """The drag ends: back to the still rate, and with --fps a still frame (tau) of
        where it ended."""
        self.window.SetDesiredUpdateRate(self.interactor.GetStillUpdateRate())
        if self.fps:
            self.interactor.Render()

    # -- statistics ---------------------------------------------------------------------
    def _frame_start(self, *_):
        self._t0 = time.perf_counter()

    def _frame_end(self, *_):
        if self._t0 is not None:
            self.window.WaitForCompletion()
            self.frame_ms = (time.perf_counter() - self._t0) * 1000.0
            self._t0 = None
            if self.motion_rate and self.mapper.GetLastFrameInteractive():
                # A moving frame: what the rest of it took moves the terrain's share of
                # the next ones, this drag's and the next drags'.
                self.motion_rate.record(self.frame_ms / 1000.0, self.mapper.GetLastRenderTime())
                rate = self.motion_rate.desired_update_rate()
                self.interactor.SetDesiredUpdateRate(rate)
                if self.window.GetDesiredUpdateRate() != self.interactor.GetStillUpdateRate():
                    self.window.SetDesiredUpdateRate(rate)

    def stats(self):
        """The figures the overlay shows, of the frame rendered last."""
        m = self.mapper
        # VTK skips the mapper when the actor's bounds are out of view; its figures would
        # then be the last drawn frame's.
        drawn = self.renderer.GetNumberOfPropsRendered() > 0
        visible, culled = m.GetNumberOfVisibleBlocks(), m.GetNumberOfCulledBlocks()
        return {"tau": m.GetPixelError(), "in_view": drawn,
                "triangles": int(m.GetNumberOfRenderedTriangles()) if drawn else 0,
                "visible_blocks": visible if drawn else 0, "blocks": visible + culled,
                "certified_error_px": m.GetMaximumScreenSpaceError() if drawn else 0.0,
                "lod_ms": m.GetLastUpdateTime() * 1000.0 if drawn else 0.0,
                "frame_ms": self.frame_ms, "frozen": self.frozen(),
                "draw_ms": m.GetLastRenderTime() * 1000.0 if drawn else 0.0,
                # --fps: whether the frame was a moving one, drawn within a triangle budget
                # for its allocated time, and that budget.
                "interactive": bool(drawn and m.GetLastFrameInteractive()),
                "budget": int(m.GetTriangleBudgetInForce()) if drawn else 0,
                "allocated_ms": m.GetLastAllocatedRenderTime() * 1000.0 if drawn else 0.0}

    def stats_text(self):
        s = self.stats()
        frame = "-" if s["frame_ms"] is None else f"{s['frame_ms']:.1f} ms"
        lod = "FROZEN (figures of the frozen view)" if s["frozen"] else "live"
        if not s["in_view"]:
            lod += "   (terrain out of view)"
        rate = ""
        if self.fps:
            rate = (f"{self.fps:g} fps: moving, budget {s['budget']:,} triangles in "
                    f"{s['allocated_ms']:.0f} ms\n" if s["interactive"]
                    else f"{self.fps:g} fps while moving; still: tau\n")
        return (f"tau {s['tau']:g} px   certified error {s['certified_error_px']:.3f} px\n"
                + rate +
                f"triangles {s['triangles']:,}   visible blocks {s['visible_blocks']} "
                f"of {s['blocks']}\n"
                f"last frame {frame}   LOD update {s['lod_ms']:.2f} ms\n"
                f"{self.mode}   LOD {lod}   "
                f"{'wireframe' if self.wireframe_on() else 'surface'}")

    def _update_stats(self, *_):
        self.overlay.stats.SetInput(self.stats_text())

    # -- running --------------------------------------------------------------------------
    def initialize(self):
        """Makes the interactor ready (events can be played) and draws the first frame."""
        self.interactor.Initialize()
        self.interactor.Render()

    def start(self):
        """Hands the window to the user until 'q' or the window is closed."""
        self.interactor.Start()
