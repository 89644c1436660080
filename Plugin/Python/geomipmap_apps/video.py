"""Videos of a flight: the render window's frames into an .mp4 or .ogv file.

Why two encoders: ffmpeg (the Debian package Scripts/setup.sh installs) writes H.264 in
MP4, which every player and browser plays, and Ogg Theora; where it is missing, VTK's own
vtkOggTheoraWriter still writes Ogg Theora, so a video never depends on a package VTK
does not bring. Every frame handed over becomes one video frame at the given rate (no
frame is dropped or repeated), at the window's size.

Every problem that can be known before rendering (format, encoder, size, rate) is found
by check(), so that a flight never renders for minutes and then fails to write.
"""

import os
import shutil
import subprocess
import tempfile

from vtkmodules.util.numpy_support import vtk_to_numpy

from .errors import AppError, VTKMessages

ENCODERS = ("auto", "ffmpeg", "vtk")
FORMATS = {".mp4": "H.264 (MP4)", ".ogv": "Ogg Theora", ".ogg": "Ogg Theora"}
# ffmpeg's output options per format: H.264 in the 4:2:0 layout players expect, the MP4
# index at the front (playback starts before the whole file is read); Theora at quality
# 7 of 10.
FFMPEG_CODECS = {
    ".mp4": ["-c:v", "libx264", "-preset", "fast", "-crf", "18", "-pix_fmt", "yuv420p",
             "-movflags", "+faststart"],
    ".ogv": ["-c:v", "libtheora", "-q:v", "7", "-pix_fmt", "yuv420p"],
}
FFMPEG_CODECS[".ogg"] = FFMPEG_CODECS[".ogv"]


def ffmpeg_program():
    """The ffmpeg executable on PATH, or None."""
    return shutil.which("ffmpeg")


def check(filename, size, fps, encoder="auto"):
    """The encoder that will write `filename` ("ffmpeg" or "vtk"), or AppError saying why
    none can: an unknown format, MP4 without ffmpeg or with an odd width or height (H.264
    4:2:0), for VTK's writer a width that is not a multiple of 16 or a fractional rate."""
    ext = os.path.splitext(filename)[1].lower()
    if ext not in FORMATS:
        raise AppError(f"--video {filename}: unknown format {ext or '(no extension)'}; "
                       "use .mp4 (H.264, written by ffmpeg) or .ogv (Ogg Theora)")
    if encoder not in ENCODERS:
        raise AppError(f"video encoder must be one of {', '.join(ENCODERS)}, got {encoder!r}")
    if encoder == "auto":
        encoder = "ffmpeg" if ffmpeg_program() else "vtk"
    if encoder == "ffmpeg" and not ffmpeg_program():
        raise AppError(f"--video {filename}: ffmpeg not found on PATH (Scripts/setup.sh "
                       "installs it); without it, write .ogv (VTK's Ogg Theora writer)")
    if encoder == "vtk" and ext == ".mp4":
        why = "ffmpeg is not on PATH" if ffmpeg_program() is None else "--video-encoder vtk"
        raise AppError(f"--video {filename}: MP4 needs ffmpeg ({why}); VTK's own writer "
                       "writes Ogg Theora: use .ogv")
    w, h = size
    if ext == ".mp4" and (w % 2 or h % 2):
        raise AppError(f"--video {filename}: H.264 needs an even width and height, got "
                       f"{w}x{h}")
    if encoder == "vtk" and w % 16:
        # vtkOggTheoraWriter centres other widths in a frame padded to 16: ffmpeg (and the
        # players built on it) then decode them up to 4 columns too wide (measured: 200
        # and 202 as 204, 330 as 332).
        raise AppError(f"--video {filename}: VTK's Theora writer needs a width that is a "
                       f"multiple of 16 (e.g. 1280), got {w}; ffmpeg takes any")
    if encoder == "vtk" and fps != round(fps):
        raise AppError(f"--video {filename}: VTK's Theora writer takes whole frame rates, "
                       f"got --fps {fps:g} (ffmpeg takes any)")
    return encoder


class VideoWriter:
    """Writes the frames of a render window's grab into one video file.

    filename: .mp4 or .ogv (.ogg). size: the frames' (width, height). fps: frames per
    second. encoder: "auto" (ffmpeg when on PATH, else VTK), "ffmpeg" or "vtk"; check()
    says which and refuses what cannot work. add(image) appends a vtkImageData of RGB
    bytes (a vtkWindowToImageFilter's output, bottom row first as VTK stores it); close()
    finishes the file. Failures raise AppError with one line.
    """

    def __init__(self, filename, size, fps, encoder="auto"):
        self.filename = filename
        self.size = tuple(size)
        self.fps = fps
        self.encoder = check(filename, size, fps, encoder)
        self.frames = 0
        self.process = None
        self.writer = None
        if self.encoder == "ffmpeg":
            self._start_ffmpeg()

    def describe(self):
        """E.g. "video: /abs/out.mp4 (300 frames, 1280x720, 30 fps, H.264 (MP4) by ffmpeg)"."""
        ext = os.path.splitext(self.filename)[1].lower()
        by = "ffmpeg" if self.encoder == "ffmpeg" else "vtkOggTheoraWriter"
        return (f"video: {os.path.abspath(self.filename)} ({self.frames} frames, "
                f"{self.size[0]}x{self.size[1]}, {self.fps:g} fps, {FORMATS[ext]} by {by})")

    def _start_ffmpeg(self):
        w, h = self.size
        ext = os.path.splitext(self.filename)[1].lower()
        self.errors = tempfile.TemporaryFile()  # ffmpeg's messages; a pipe could fill up
        command = [ffmpeg_program(), "-hide_banner", "-loglevel", "error", "-nostdin", "-y",
                   "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", f"{w}x{h}",
                   "-framerate", f"{self.fps:g}", "-i", "pipe:0", *FFMPEG_CODECS[ext],
                   self.filename]
        try:
            self.process = subprocess.Popen(command, stdin=subprocess.PIPE,
                                            stdout=subprocess.DEVNULL, stderr=self.errors)
        except OSError as e:
            raise AppError(f"cannot start ffmpeg: {e.strerror}") from None

    def _start_vtk(self, image):
        from vtkmodules.vtkIOOggTheora import vtkOggTheoraWriter

        self.messages = VTKMessages()
        self.writer = vtkOggTheoraWriter()
        self.messages.observe(self.writer)
        self.writer.SetInputData(image)
        self.writer.SetFileName(self.filename)
        self.writer.SetRate(int(round(self.fps)))
        self.writer.SetQuality(2)  # the best of 0..2
        self.writer.SubsamplingOn()  # 4:2:0, what players expect
        self.writer.Start()
        self._vtk_check()

    def _vtk_check(self):
        err = self.messages.first_error()
        if self.writer.GetError() or err:
            raise AppError(f"cannot write video {self.filename}: "
                           f"{err or 'vtkOggTheoraWriter failed'}")

    def add(self, image):
        """Append one frame: a vtkImageData of self.size with RGB unsigned char pixels."""
        w, h, _ = image.GetDimensions()
        if (w, h) != self.size:
            raise AppError(f"video frame {self.frames} is {w}x{h}, the video "
                           f"{self.size[0]}x{self.size[1]}")
        if self.encoder == "ffmpeg":
            rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)[:, :, :3]
            try:
                self.process.stdin.write(rgb[::-1].tobytes())  # VTK's rows run bottom-up
            except (BrokenPipeError, OSError):
                raise AppError(self._ffmpeg_failure()) from None
        else:
            if self.writer is None:
                self._start_vtk(image)
            self.writer.Write()
            self._vtk_check()
        self.frames += 1

    def close(self, quiet=False):
        """Finish the file (with the frames so far: an interrupted flight still leaves a
        playable video); AppError when the encoder failed, unless quiet (used while
        another error is on its way out)."""
        failure = None
        if self.process is not None:
            process, self.process = self.process, None
            try:
                process.stdin.close()
            except (BrokenPipeError, OSError):
                pass
            if process.wait() != 0:
                failure = self._ffmpeg_failure(process.returncode)
        elif self.writer is not None:
            writer, self.writer = self.writer, None
            writer.End()
            if writer.GetError():
                failure = (f"cannot write video {self.filename}: vtkOggTheoraWriter failed "
                           "to finish the file")
        if failure and not quiet:
            raise AppError(failure)

    def _ffmpeg_failure(self, status=None):
        if status is None and self.process is not None:
            status = self.process.wait()
        self.errors.seek(0)
        lines = [ln for ln in self.errors.read().decode("utf-8", "replace").splitlines()
                 if ln.strip()]
        said = " ".join(lines[-1].split())[:300] if lines else f"exit status {status}"
        return f"ffmpeg failed writing {self.filename}: {said}"

