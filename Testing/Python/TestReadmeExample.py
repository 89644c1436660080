"""Runs the README's Python example verbatim, so the documented API cannot rot."""
import os
import re
import subprocess
import sys
import tempfile

from gmmdata import data_file

here = os.path.dirname(os.path.abspath(__file__))
readme = open(os.path.join(here, "..", "..", "README.md")).read()
section = readme.split("## Python API", 1)[1]
code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
dem = data_file("N42E001.hgt")
with tempfile.TemporaryDirectory() as tmp:
    script = os.path.join(tmp, "example.py")
    open(script, "w").write(code)
    out = subprocess.run([sys.executable, script, dem], cwd=tmp, capture_output=True, text=True)
    print(out.stdout, out.stderr)
    assert out.returncode == 0, "README example failed"
    m = re.search(r"(\d+) triangles, error <= ([0-9.e+-]+) px", out.stdout)
    assert m, "README example printed no statistics"
    triangles, error = int(m.group(1)), float(m.group(2))
    assert 0 < triangles < 2 * 1200 * 1200, triangles   # LOD: fewer than full resolution
    assert error <= 1.0 + 1e-9, error
    size = os.path.getsize(os.path.join(tmp, "terrain.png"))
    assert size > 10000, "terrain.png looks empty (%d bytes)" % size
print("ok: README example ran")
