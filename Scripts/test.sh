#!/usr/bin/env bash
# Sets up, builds and runs every test (what CI runs). Rendering tests need an X server:
# without DISPLAY the whole ctest runs under xvfb-run (Mesa llvmpipe).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${GEOMIPMAP_BUILD_DIR:-$here/build}
bash "$here/Scripts/setup.sh"
cd "$build"
source "$here/Scripts/display.sh" # run=(): xvfb-run where there is no display
"${run[@]}" ctest --output-on-failure -j2 "$@"
