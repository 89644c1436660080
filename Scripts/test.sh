#!/usr/bin/env bash
# Sets up, builds and runs every test (what CI runs). Rendering tests need an X server:
# without DISPLAY the whole ctest runs under xvfb-run (Mesa llvmpipe).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${GEOMIPMAP_BUILD_DIR:-$here/build}
bash "$here/Scripts/setup.sh"
cd "$build"
run=()
[ -n "${DISPLAY:-}" ] || run=(xvfb-run -a -s "-screen 0 1920x1080x24")
"${run[@]}" ctest --output-on-failure -j2 "$@"
