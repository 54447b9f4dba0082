#!/usr/bin/env bash
# Makes docs/images/paraview_thickness.png: the ParaView GUI, under Xvfb, with the Pierce plugin
# loaded and Pierce Thickness applied to the sample STEP assembly.
#
#   plugins/paraview/screenshot/make_screenshot.sh [BUILD_DIR] [OUT.png] [--force]
#
# Needs xvfb-run, paraview and /usr/bin/python3 with Pillow (python3-pil, for the X11 grab).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/docs/images/paraview_thickness.png}
force=${3:-}
plugin=$build/lib/paraview-plugins/PierceParaView/PierceParaView.so
model=$root/samples/plate_assembly.step
[ -f "$plugin" ] || { echo "make_screenshot: no plugin at $plugin (build first)" >&2; exit 1; }
[ -f "$model" ] || { echo "make_screenshot: no model at $model" >&2; exit 1; }
if [ -e "$out" ] && [ "$force" != "--force" ]; then
  echo "make_screenshot: $out exists; pass --force as third argument to overwrite" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# -noreset: see tests/paraview/CMakeLists.txt.
PIERCE_PLUGIN=$plugin PIERCE_MODEL=$model PIERCE_MARKER=$work/ready PIERCE_SHOT=$work/shot.png \
PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}" \
xvfb-run -a -s "-screen 0 1280x800x24 -noreset" bash -c '
  paraview --dr --script="$0" &
  gui=$!
  for _ in $(seq 240); do [ -f "$PIERCE_MARKER" ] && break; sleep 0.5; done
  [ -f "$PIERCE_MARKER" ] || { kill $gui; echo "make_screenshot: ParaView did not get ready" >&2; exit 1; }
  sleep 8  # let the GUI finish laying out and painting
  /usr/bin/python3 -c "from PIL import ImageGrab; import os; ImageGrab.grab().save(os.environ[\"PIERCE_SHOT\"])"
  kill $gui
  wait $gui || true
' "$here/gui_thickness.py"

# Crop the black desktop around the window, keep the file small (palette PNG).
/usr/bin/python3 - "$work/shot.png" "$out" <<'PY'
import sys
from PIL import Image
im = Image.open(sys.argv[1]).convert("RGB")
box = im.point(lambda v: 255 if v > 0 else 0).convert("L").getbbox()
if box:
    im = im.crop(box)
im.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(sys.argv[2], optimize=True)
print("make_screenshot: wrote %s (%dx%d)" % (sys.argv[2], im.width, im.height))
PY
