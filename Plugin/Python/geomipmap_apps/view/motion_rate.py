"""The frame rate asked of VTK while the camera moves with --fps (issue #14).

VTK hands each renderer 1 / (DesiredUpdateRate x renderers) of a frame, and the terrain
mapper (FollowAllocatedRenderTime) fits its own draw, timed from RenderPiece to a
glFinish, in its share. The rest of the window's frame comes on top: clearing, the
overlay, the buffer swap. On llvmpipe at 960 x 540 over Rainier that was about 11 ms
(10 - 33 ms) a frame, so with the whole 1 / fps for the terrain the frames at 20 fps took
57 - 59 ms instead of 50 (benchmarks-core.md, session 13). MotionRate asks VTK for the
rate that leaves the terrain what the rest of the frame leaves of 1 / fps: the median,
over the last moving frames, of the window's frame time less the mapper's draw. It never
leaves the terrain less than a quarter of the frame (a stall outside the mapper would
otherwise starve it).
"""

import statistics
from collections import deque


class MotionRate:
    """fps: the frame rate to hold (> 0). renderers: the window's renderers (VTK splits a
    frame's time evenly among them; the overlay's text costs next to nothing, so the
    terrain's renderer is given the others' shares too). window: how many moving frames
    the rest of the frame is the median of."""

    MIN_SHARE = 0.25

    def __init__(self, fps, renderers, window=15):
        self.frame = 1.0 / fps
        self.renderers = max(int(renderers), 1)
        self.rest = deque(maxlen=window)

    def record(self, frame_seconds, mapper_seconds):
        """A moving frame took frame_seconds in the window, mapper_seconds of it in the
        terrain mapper's timed draw."""
        if frame_seconds > 0.0 and mapper_seconds > 0.0:
            self.rest.append(max(frame_seconds - mapper_seconds, 0.0))

    def terrain_seconds(self):
        """The time the terrain is allocated of a moving frame."""
        rest = statistics.median(self.rest) if self.rest else 0.0
        return max(self.frame - rest, self.MIN_SHARE * self.frame)

    def desired_update_rate(self):
        """The DesiredUpdateRate that gives the terrain's renderer terrain_seconds()."""
        return 1.0 / (self.terrain_seconds() * self.renderers)
