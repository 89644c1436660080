#!/usr/bin/env bash
# The main job: sets up and builds, then flies over the built-in synthetic terrain,
# rendering off-screen (under xvfb-run when there is no display), and writes PNG frames,
# a video of the flight next to them (flight.mp4; flight.ogv by VTK's writer where
# ffmpeg is missing), a per-frame CSV and a summary. Extra arguments go to geomipmap-fly.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${GEOMIPMAP_BUILD_DIR:-$here/build}
bash "$here/Scripts/setup.sh"
source "$here/Scripts/display.sh" # run=(): xvfb-run where there is no display
out=${GEOMIPMAP_DEMO_OUT:-$PWD/geomipmap-flight}
video=flight.mp4
command -v ffmpeg >/dev/null || video=flight.ogv
"${run[@]}" "$build/bin/geomipmap-fly" --out "$out" --video "$out/$video" "$@"
