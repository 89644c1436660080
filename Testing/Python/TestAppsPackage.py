"""The apps package's boundaries (issue #15, part 6), each in a fresh interpreter:

- the product, `import geomipmap, geomipmap.flight`, loads nothing of the tools
  (geomipmap_apps) nor argparse or matplotlib;
- a whole geomipmap-fly flight, run in-process, loads none of the benchmark's modules
  (geomipmap_apps.bench: its measurement code) nor matplotlib;
- a geomipmap-view session (loading, a played event stream) loads none of them either;
- every launcher answers --help with its own name.
Usage: TestAppsPackage.py GEOMIPMAP_FLY GEOMIPMAP_BENCH GEOMIPMAP_VIEW SCRATCH_DIR
"""

import json
import os
import shutil
import subprocess
import sys

fly_exe, bench_exe, view_exe, scratch = sys.argv[1:5]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
failures = []


def modules_after(code):
    """The module names loaded after running `code` in a fresh interpreter."""
    script = code + "\nimport json, sys\nprint(json.dumps(sorted(sys.modules)))\n"
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                       timeout=120)
    if p.returncode != 0:
        failures.append(f"{code!r} failed ({p.returncode}): {p.stderr.strip()[-500:]}")
        return []
    return json.loads(p.stdout.strip().splitlines()[-1])


def loaded(modules, prefixes):
    return [m for m in modules if m.split(".")[0] in prefixes or m in prefixes
            or any(m.startswith(p + ".") for p in prefixes)]


def boundary(what, modules, ran, forbidden):
    """Records a failure when `what` did not run (ran False) or loaded a `forbidden` module."""
    bad = loaded(modules, forbidden)
    if not ran:
        failures.append(f"{what} did not run")
    if bad:
        failures.append(f"{what} loads {bad}")
    print(f"{what}: {len(modules)} modules, none of {', '.join(forbidden)}")


product = modules_after("import geomipmap, geomipmap.flight")
boundary("import geomipmap.flight", product, "geomipmap.flight" in product,
         ("geomipmap_apps", "argparse", "matplotlib"))

out = os.path.join(scratch, "flight")
fly = modules_after(
    "import sys\nfrom geomipmap_apps.fly import cli\n"
    f"rc = cli.main(['--synthetic-size', '65', '--frames', '2', '--size', '64x64', "
    f"'--out', {out!r}])\n"
    "if rc: sys.exit(rc)")
boundary("a geomipmap-fly flight", fly, "geomipmap_apps.fly.cli" in fly and
         os.path.isfile(os.path.join(out, "flight.csv")), ("geomipmap_apps.bench", "matplotlib"))

events = os.path.join(scratch, "events.log")
with open(events, "w") as f:
    f.write("# StreamVersion 1.1\nKeyPressEvent 10 10 0 43 1 plus\n")
view = modules_after(
    "import sys\nfrom geomipmap_apps.view import cli\n"
    f"rc = cli.main(['--synthetic-size', '65', '--size', '64x64', '--play', {events!r}])\n"
    "if rc: sys.exit(rc)")
boundary("a geomipmap-view session", view, "geomipmap_apps.view.viewer" in view,
         ("geomipmap_apps.bench", "geomipmap_apps.fly", "matplotlib"))

for exe, name in ((fly_exe, "geomipmap-fly"), (bench_exe, "geomipmap-bench"),
                  (view_exe, "geomipmap-view")):
    p = subprocess.run([exe, "--help"], capture_output=True, text=True, timeout=60)
    if p.returncode != 0 or not p.stdout.startswith(f"usage: {name}"):
        failures.append(f"{name} --help: exit {p.returncode}, {p.stdout[:80]!r} {p.stderr!r}")

if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("TestAppsPackage: passed")
