"""measure_popping.py --quick: geomorphing removes popping on a slow flight (issue #13).

A 24-frame flight over a 257^2 fractal terrain at tau = 2 px, 0.02 block per frame
(vtkGeoMipMapFilter's output per frame, vtkGeoMipMapScreenError with the previous frame's
mesh as the reference: the screen displacement the camera motion does not explain). Checks,
all measured by the independent measure:
- morphing off pops (some frame > 0.5 px), so the flight can see popping at all;
- morphing on: the worst displacement between frames is <= 0.5 px (the issue's target) and
  at least 5 times below morphing off;
- both modes measure within tau against the true surface on every frame.
"""

import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
p = subprocess.run([sys.executable, os.path.join(here, "measure_popping.py"), "--quick",
                    "--no-render"], capture_output=True, text=True, timeout=240)
if p.returncode != 0:
    sys.exit(f"FAIL: measure_popping.py exit {p.returncode}\n{p.stdout}\n{p.stderr}")
r = json.loads(p.stdout)
off, on = r["off"], r["on"]
print(f"popping max: off {off['pop_max_px']:.4f} px, on {on['pop_max_px']:.4f} px; screen error "
      f"max: off {off['screen_error_max_px']:.4f}, on {on['screen_error_max_px']:.4f} (tau {r['tau']})")
failures = []
if not off["pop_max_px"] > 0.5:
    failures.append(f"morphing off pops only {off['pop_max_px']:.4f} px: the flight shows nothing")
if not on["pop_max_px"] <= 0.5:
    failures.append(f"morphing on: {on['pop_max_px']:.4f} px > 0.5 px between frames")
if not on["pop_max_px"] * 5 <= off["pop_max_px"]:
    failures.append(f"morphing on ({on['pop_max_px']:.4f} px) is not 5x below off "
                    f"({off['pop_max_px']:.4f} px)")
for mode in ("off", "on"):
    if not r[mode]["screen_error_max_px"] <= r["tau"] + 1e-4:
        failures.append(f"morphing {mode}: measured {r[mode]['screen_error_max_px']:.4f} px > tau")
if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("ok")
