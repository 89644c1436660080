"""Huge pages for the C heap on glibc: the tools restart themselves once with them.

On a CPU renderer (Mesa's llvmpipe) the "GPU" is this process, and what a frame renders
(vertex buffers, bins, the index list) comes from the C heap. Each new 4 KiB page costs a
page fault on its first touch, and on a virtual machine a fault is slow: over Puget Sound
in the frame-rate mode a frame that drew more triangles than any before took 2 000 - 6 000
faults and up to 1.5x its neighbours' time. glibc backs its heap with 2 MiB pages when the
tunable glibc.malloc.hugetlb=1 is set, which its dynamic loader reads only when the process
starts: hence a restart (os.execv) before anything else runs. Measured
(Documentation/benchmarks.md, session 24): faults after warm-up 9 473 - 16 741 -> 9 - 21 a
flight, frames within +-20 % of the frame-rate mode's budget 78 - 94 % -> 90 - 100 %
(Puget Sound), 74 - 78 % -> 92 - 98 % (4097^2); llvmpipe frames 1.2 - 1.7x faster.

Set GEOMIPMAP_HUGE_HEAP=0 to keep the heap as it is. Elsewhere than Linux with glibc, and
when GLIBC_TUNABLES already names the tunable, nothing happens. A glibc older than 2.35
ignores the tunable.
"""
import os
import platform
import sys

TUNABLE = "glibc.malloc.hugetlb"


def environment_with_huge_heap(environ):
    """The environment to restart with, or None when no restart is wanted."""
    if environ.get("GEOMIPMAP_HUGE_HEAP", "1") == "0":
        return None
    if TUNABLE in environ.get("GLIBC_TUNABLES", ""):
        return None  # set by the user, or by the restart already
    env = dict(environ)
    current = env.get("GLIBC_TUNABLES", "")
    env["GLIBC_TUNABLES"] = (current + ":" if current else "") + TUNABLE + "=1"
    return env


def restart_with_huge_heap(argv=None, execv=os.execve):
    """Restarts this Python program with the tunable set (does not return), where wanted.

    Call it first thing in a program's entry point, before modules that allocate much are
    imported: whatever ran before the restart is done again.
    """
    if not sys.platform.startswith("linux") or platform.libc_ver()[0] != "glibc":
        return
    env = environment_with_huge_heap(os.environ)
    if env is None:
        return
    args = list(sys.argv if argv is None else argv)
    execv(sys.executable, [sys.executable] + args, env)
