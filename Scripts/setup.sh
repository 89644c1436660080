#!/usr/bin/env bash
# Installs the Debian 12 packages geomipmap needs (only those missing), then configures
# and builds into ${GEOMIPMAP_BUILD_DIR:-build}. Used by demo.sh, test.sh and CI.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${GEOMIPMAP_BUILD_DIR:-$here/build}

packages=(cmake ninja-build g++ pkg-config
  libvtk9-dev python3-vtk9 libgdal-dev libgeographiclib-dev libglm-dev libopenimageio-dev
  libgtest-dev libbenchmark-dev python3-numpy python3-matplotlib python3-geographiclib
  xvfb xauth ffmpeg)  # ffmpeg: geomipmap-fly --video (H.264 / Theora); ffprobe in its tests
# Callers add packages they need on top (sanitize.sh, fuzz.sh: GEOMIPMAP_EXTRA_PACKAGES,
# space-separated) and may stop after installing (GEOMIPMAP_SETUP_ONLY=1: no build here).
read -r -a extra <<<"${GEOMIPMAP_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "geomipmap: installing ${missing[*]}"
  sudo_=""
  [ "$(id -u)" = 0 ] || sudo_=sudo
  $sudo_ apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_ apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

[ -z "${GEOMIPMAP_SETUP_ONLY:-}" ] || exit 0

cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build "$build" -j"$(nproc)"
