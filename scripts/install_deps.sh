#!/usr/bin/env bash
# Installs the Debian packages the build needs, only those that are missing. Needs root (or sudo).
set -euo pipefail
packages=(cmake make g++ pkg-config nlohmann-json3-dev libcli11-dev catch2 libeigen3-dev libtinyobjloader-dev
          libglfw3-dev libglew-dev libimgui-dev libstb-dev xvfb xauth libgl1-mesa-dri python3-matplotlib
          clang libclang-rt-14-dev libopenvdb-dev libboost-iostreams-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "dependencies: all present"
  exit 0
fi
echo "dependencies: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "error: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
