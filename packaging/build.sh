#!/usr/bin/env bash
# Configures and builds Pierce (Release) into ${PIERCE_BUILD_DIR:-build}.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${PIERCE_BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 "$@"
cmake --build "$BUILD_DIR" -j "$(nproc)"
