#!/usr/bin/env bash
# Installs the Debian 12 packages geomipmap needs (only those missing), then configures
# and builds into ${GEOMIPMAP_BUILD_DIR:-build}. Used by demo.sh, test.sh and CI.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${GEOMIPMAP_BUILD_DIR:-$here/build}

packages=(cmake ninja-build g++ pkg-config
  libvtk9-dev python3-vtk9 libgdal-dev libgeographiclib-dev libglm-dev libopenimageio-dev
  libgtest-dev libbenchmark-dev python3-numpy python3-matplotlib python3-geographiclib
  xvfb xauth)
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

cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build "$build" -j"$(nproc)"
