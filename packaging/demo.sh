#!/usr/bin/env bash
# Installs dependencies, builds, and runs the main job on the bundled sample model:
# every kernel on 10 stacked touching plates, with the exactness table.
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/install-deps.sh
bash packaging/build.sh
./build/bin/pierce hits samples/plates.obj --rays grid:axis=z,n=128 --kernel all
