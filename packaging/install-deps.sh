#!/usr/bin/env bash
# Installs every Debian 12 package Pierce needs (core, tests, bench, VTK/ParaView, FreeCAD).
# Idempotent: when everything is already installed it returns in about a second.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libocct-data-exchange-dev
  libgtest-dev libgmock-dev libcli11-dev nlohmann-json3-dev libspng-dev
  qtbase5-dev paraview-dev python3-paraview
  libqt5svg5-dev qttools5-dev libqt5opengl5-dev qtxmlpatterns5-dev-tools
  libxml2-dev libexpat1-dev libavcodec-dev libavformat-dev libavutil-dev libswscale-dev libswresample-dev
  libfreetype-dev libgdal-dev libgl2ps-dev libglew-dev libhdf5-mpi-dev libjpeg-dev liblz4-dev liblzma-dev
  mpi-default-dev libnetcdf-dev libgl-dev libpng-dev libtheora-dev libtiff-dev libx11-dev zlib1g-dev
  libdouble-conversion-dev libutfcpp-dev libboost-dev
  freecad pybind11-dev python3-dev python3-numpy xvfb xauth
  help2man man-db
  libgmp-dev clang libclang-rt-14-dev
  python3-matplotlib
  libjs-three chromium
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${#missing[@]} missing packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y --no-install-recommends "${PACKAGES[@]}"
