#!/usr/bin/env bash
# Makes docs/images/paraview_thickness.png: the ParaView GUI, under Xvfb, with the Pierce plugin,
# after a user's clicks (first_screen.py): open samples/blob.stl, Apply, Filters ▸ Pierce ▸
# Pierce Thickness, Apply with the default properties. Nothing is set by hand: the colours are
# what the plugin's GUI behaviour gives a new Pierce Thickness display.
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
model=$root/samples/blob.stl
[ -f "$plugin" ] || { echo "make_screenshot: no plugin at $plugin (build first)" >&2; exit 1; }
[ -f "$model" ] || { echo "make_screenshot: no model at $model" >&2; exit 1; }
if [ -e "$out" ] && [ "$force" != "--force" ]; then
  echo "make_screenshot: $out exists; pass --force as third argument to overwrite" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# -noreset: see tests/paraview/CMakeLists.txt.
xvfb-run -a -s "-screen 0 1280x800x24 -noreset" /usr/bin/python3 "$here/first_screen.py" \
  --plugin-dir "$(dirname "$plugin")" --model "$model" --state "$work/state.pvsm" --shot "$work/shot.png"

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
