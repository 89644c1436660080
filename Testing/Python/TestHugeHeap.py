"""The tools' restart with glibc's heap on huge pages (geomipmap_apps/hugeheap.py).

- the environment it restarts with: the tunable added (after any others), not twice, and
  none with GEOMIPMAP_HUGE_HEAP=0;
- a restart runs the same program with the same arguments (a fake execv);
- in a fresh interpreter that restarts, the child has the tunable and, where the kernel
  has transparent huge pages, a 64 MiB allocation is backed by huge pages
  (AnonHugePages in /proc/self/smaps_rollup), and none with GEOMIPMAP_HUGE_HEAP=0;
- every launcher still runs (--help) through its restart.
Usage: TestHugeHeap.py GEOMIPMAP_FLY GEOMIPMAP_BENCH GEOMIPMAP_VIEW
"""
import os
import platform
import subprocess
import sys

from geomipmap_apps import hugeheap

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


env = hugeheap.environment_with_huge_heap({"PATH": "/bin"})
check(env == {"PATH": "/bin", "GLIBC_TUNABLES": "glibc.malloc.hugetlb=1"}, f"added: {env}")
env = hugeheap.environment_with_huge_heap({"GLIBC_TUNABLES": "glibc.malloc.arena_max=2"})
check(env["GLIBC_TUNABLES"] == "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1",
      f"after the others: {env['GLIBC_TUNABLES']}")
check(hugeheap.environment_with_huge_heap({"GLIBC_TUNABLES": "glibc.malloc.hugetlb=0"}) is None,
      "a tunable the user set is left alone")
check(hugeheap.environment_with_huge_heap({"GEOMIPMAP_HUGE_HEAP": "0"}) is None, "off switch")

calls = []
hugeheap.restart_with_huge_heap(["prog.py", "--x", "1"], execv=lambda *a: calls.append(a))
glibc = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"
if glibc:
    check(len(calls) == 1 and calls[0][0] == sys.executable and
          calls[0][1] == [sys.executable, "prog.py", "--x", "1"] and
          "glibc.malloc.hugetlb=1" in calls[0][2].get("GLIBC_TUNABLES", ""),
          f"restart with the same program and arguments: {calls[:1]!r:.200}")
else:
    check(calls == [], "no restart without glibc")

CHILD = r"""
import os
data = bytearray(64 << 20)
data[::4096] = b'x' * len(data[::4096])
huge = 0
for line in open('/proc/self/smaps_rollup'):
    if line.startswith('AnonHugePages:'):
        huge = int(line.split()[1])
if 'libasan' in open('/proc/self/maps').read():
    huge = -2  # malloc is the sanitizer's (LD_PRELOAD): glibc's tunable does not apply
print(os.environ.get('GLIBC_TUNABLES', ''), huge)
"""
PARENT = ("from geomipmap_apps.hugeheap import restart_with_huge_heap\n"
          f"restart_with_huge_heap(['-c', {CHILD!r}])\n" + CHILD)
try:
    thp = open("/sys/kernel/mm/transparent_hugepage/enabled").read()
except OSError:
    thp = "[never]"


def child_says(extra):
    e = dict(os.environ, **extra)
    e.pop("GLIBC_TUNABLES", None)
    p = subprocess.run([sys.executable, "-c", PARENT], env=e, capture_output=True, text=True,
                       timeout=60)
    tunables, _, huge = p.stdout.strip().rpartition(" ")
    return p.returncode, tunables, int(huge or -1)


if glibc:
    rc, tunables, huge = child_says({})
    check(rc == 0 and "glibc.malloc.hugetlb=1" in tunables, f"restarted child: {tunables!r}")
    rc0, tunables0, huge0 = child_says({"GEOMIPMAP_HUGE_HEAP": "0"})
    check(rc0 == 0 and tunables0 == "", f"not restarted with GEOMIPMAP_HUGE_HEAP=0: {tunables0!r}")
    if "[never]" in thp:
        print(f"skip: no transparent huge pages here ({thp.strip()}): backing not checked")
    elif huge == -2:
        print("skip: malloc is AddressSanitizer's here (LD_PRELOAD): backing not checked")
    else:
        check(huge >= 32 << 10, f"64 MiB on huge pages after the restart: AnonHugePages {huge} kB")
        if "[madvise]" in thp:
            check(huge0 < 32 << 10, f"and not without it: {huge0} kB")

    for exe in sys.argv[1:4]:
        p = subprocess.run([sys.executable, exe, "--help"], capture_output=True, text=True,
                           timeout=120, env=dict(os.environ, GEOMIPMAP_HUGE_HEAP="1"))
        name = os.path.basename(exe)
        check(p.returncode == 0 and name in p.stdout, f"{name} --help after its restart")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
