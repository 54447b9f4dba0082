#!/usr/bin/env bash
# CI step after the test suite (packaging/test.sh): builds the .deb from the Release tree
# (packaging/build-deb.sh), installs it with apt, checks from a directory outside the checkout
# with no build tree on any path that everything is found where a user finds it (CLI, man page,
# CMake package, Python, ParaView plugin, FreeCAD workbench), then purges the package and checks
# that none of its files is left. The package is removed on failure too (trap). Uses sudo when
# not root. Refuses to run when a pierce package is already installed (it is not ours to replace).
#
#   bash packaging/test-deb.sh [DEB]     (DEB: test this package instead of building one)
set -euo pipefail
cd "$(dirname "$0")/.."
REPO=$(pwd)
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

fail() { echo "test-deb: FAIL: $*" >&2; exit 1; }
step() { echo "test-deb: $*"; }

if dpkg-query -W -f='${Status}' pierce 2>/dev/null | grep -q "installed"; then
  fail "a pierce package is already installed; remove it first (apt-get purge pierce)"
fi
if [ -e /usr/bin/paraview.conf ]; then
  fail "/usr/bin/paraview.conf exists (not from pierce); the package would refuse to replace it"
fi

if [ $# -ge 1 ]; then deb=$(readlink -f "$1"); else deb=$(bash packaging/build-deb.sh | tail -n 1); fi
[ -f "$deb" ] || fail "no package at '$deb'"
step "package $deb"
version=$(dpkg-deb -f "$deb" Version)
upstream=${version%-*}
project_version=$(sed -n 's/^project(Pierce VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
[ "$upstream" = "$project_version" ] || fail "package version $version is not the project version $project_version"

# Control fields: Depends only on runtime packages, licence and maintainer as in the sources.
depends=$(dpkg-deb -f "$deb" Depends)
step "Depends: $depends"
if tr ',|' '\n\n' <<<"$depends" | sed 's/(.*//; s/ //g' | grep -E -- '-dev(:|$)'; then
  fail "Depends names -dev packages"
fi
for p in libembree3-3 libtbb12 libspng0 paraview python3 python3-numpy; do
  tr ',|' '\n\n' <<<"$depends" | sed 's/(.*//; s/ //g' | grep -qx "$p" || fail "Depends lacks $p"
done
maint=$(dpkg-deb -f "$deb" Maintainer)   # "Name <email>"
maint_name=${maint% <*}
maint_email=${maint##*<}; maint_email=${maint_email%>}
grep -qF "<maintainer email=\"$maint_email\">$maint_name</maintainer>" freecad_addon/package.xml ||
  fail "Maintainer '$maint' is not package.xml's maintainer"
work=$(mktemp -d /tmp/pierce-deb-test.XXXXXX)
dpkg-deb -x "$deb" "$work/extract"
cmp -s "$work/extract/usr/share/doc/pierce/copyright" LICENSE || fail "usr/share/doc/pierce/copyright is not LICENSE"

installed=0
cleanup() {
  local rc=$?
  if [ $installed -eq 1 ]; then
    step "cleanup: purging the package"
    $SUDO apt-get purge -y -qq pierce >/dev/null 2>&1 || echo "test-deb: could not purge pierce" >&2
  fi
  rm -rf "$work"
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT TERM

step "apt-get install $deb"
installed=1
$SUDO apt-get install -y -qq "$deb" >"$work/apt-install.log" 2>&1 ||
  { cat "$work/apt-install.log" >&2; fail "apt-get install failed"; }
dpkg-query -L pierce | sort >"$work/files.txt"
step "$(wc -l <"$work/files.txt") paths installed"

# Every check below runs in a scratch directory with a scratch HOME (nothing read from or written
# to the user's configuration) and an environment without any Pierce, ParaView or Python paths.
mkdir -p "$work/run" "$work/home"
cp tests/install/pv_installed.py tests/install/pv_gui_plugins.py tests/install/fc_installed.py \
   tests/install/fc_gui_installed.py "$work/run/"
cd "$work/run"
clean_env=(env -i "PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin" "HOME=$work/home"
  "XDG_CONFIG_HOME=$work/home/.config" "XDG_DATA_HOME=$work/home/.local/share" "XDG_CACHE_HOME=$work/home/.cache"
  "XDG_RUNTIME_DIR=$work/home/run" "LANG=C.UTF-8" "QTWEBENGINE_DISABLE_SANDBOX=1")
mkdir -p "$work/home/run" && chmod 700 "$work/home/run"
run() { "${clean_env[@]}" "$@"; }

LIBDIR=/usr/lib/x86_64-linux-gnu
PYDIR=/usr/lib/python3/dist-packages
SAMPLES=/usr/share/doc/pierce/samples

# No installed ELF file may carry an RPATH into the checkout or any build tree.
while read -r f; do
  [ -f "$f" ] && [ ! -L "$f" ] || continue
  head -c 4 "$f" | grep -q $'\x7fELF' || continue
  rp=$(readelf -d "$f" | sed -n 's/.*(R\(UN\)\{0,1\}PATH).*\[\(.*\)\]/\2/p')
  case "$rp" in *"$REPO"*|*/build*) fail "$f has RPATH '$rp'";; esac
done <"$work/files.txt"

step "CLI"
[ "$(run which pierce)" = /usr/bin/pierce ] || fail "pierce on PATH is $(run which pierce)"
[ "$(run pierce --version)" = "pierce $project_version" ] || fail "pierce --version says '$(run pierce --version)'"
lib=$(run ldd /usr/bin/pierce | awk '$1 ~ /^libpierce\.so/ { print $3 }')   # /lib is /usr/lib (merged /usr)
[ -n "$lib" ] && [ "$(readlink -f "$lib")" = "$(readlink -f "$LIBDIR/$(basename "$lib")")" ] &&
  grep -qx "$LIBDIR/$(basename "$lib")" "$work/files.txt" || fail "pierce loads '$lib', not the installed libpierce"
run pierce hits "$SAMPLES/plates.obj" --rays grid:axis=z,n=8 --kernel queue --out hits.csv
rows=$(grep -vc '^ray,' hits.csv)
[ "$rows" -eq $((64 * 20)) ] || fail "pierce hits on plates.obj: $rows hits, expected 1280 (64 rays x 20 surfaces)"
set +e; run pierce hits /nonexistent.obj --rays grid:axis=z,n=2 --kernel queue >/dev/null 2>err.txt; rc=$?; set -e
[ $rc -eq 2 ] && grep -q nonexistent err.txt || fail "missing model: exit $rc, message '$(cat err.txt)'"
# The report carries its template and three.js in the binary: nothing of the build tree is needed.
run pierce report "$SAMPLES/plate_assembly.step" --min 3 -o report.html >/dev/null
grep -q 'id="pierce-data"' report.html && grep -q "THREE.OrbitControls" report.html ||
  fail "pierce report: report.html lacks its data or three.js"

step "man page"
man_file=$(run man -w pierce) || fail "man -w pierce found nothing"
[ "$man_file" = /usr/share/man/man1/pierce.1.gz ] || fail "man -w pierce: $man_file"
run man -P cat pierce 2>/dev/null | grep -q "exact multi-hit ray traversal" || fail "man pierce does not show the page"

step "CMake package (examples/consumer)"
cp -r /usr/share/doc/pierce/examples/consumer consumer
run cmake -S consumer -B consumer/build -G Ninja -DCMAKE_BUILD_TYPE=Release >consumer.log 2>&1 ||
  { cat consumer.log; fail "configuring the consumer example failed"; }
grep -q "^Pierce_DIR:PATH=$LIBDIR/cmake/Pierce$" consumer/build/CMakeCache.txt ||
  fail "find_package(Pierce) did not use $LIBDIR/cmake/Pierce: $(grep Pierce_DIR consumer/build/CMakeCache.txt)"
run cmake --build consumer/build >>consumer.log 2>&1 || { cat consumer.log; fail "building the consumer example failed"; }
run consumer/build/pierce_consumer "$SAMPLES/plates.obj" || fail "the consumer example failed"

step "Python"
run /usr/bin/python3 - "$PYDIR" "$SAMPLES/plates.obj" <<'PY' || fail "python checks"
import sys
import numpy as np
import pierce
import pierce_vtk
pydir, model = sys.argv[1:3]
for m in (pierce, pierce_vtk):
    assert m.__file__.startswith(pydir + "/"), m.__file__
scene = pierce.load(model)
hits = pierce.trace(scene, np.array([[0.37, 0.61, 2.0]]), np.array([[0.0, 0.0, -1.0]]), kernel="queue")
assert hits.total == 20, hits
assert hasattr(pierce_vtk, "vtkPierceThickness")
print("python ok:", pierce.__file__, hits)
PY

step "ParaView (pvbatch, plugin by name)"
run pvbatch pv_installed.py "$LIBDIR/paraview-5.11/plugins" "$project_version" "$SAMPLES/plate_assembly.step" ||
  fail "pvbatch checks"

step "ParaView GUI lists the plugin"
run env PIERCE_PV_PLUGIN_LIST="$work/run/pv_plugins.txt" timeout 300 xvfb-run -a -s "-screen 0 1024x768x24 -noreset" \
  paraview --script="$work/run/pv_gui_plugins.py" --exit >pv_gui.log 2>&1 || { cat pv_gui.log; fail "paraview GUI run failed"; }
pv_file=$(awk -F'\t' '$1 == "PierceParaView" { print $2 }' pv_plugins.txt)  # name, file, loaded
[ -n "$pv_file" ] && [ "$(readlink -f "$pv_file")" = "$LIBDIR/paraview-5.11/plugins/PierceParaView/PierceParaView.so" ] ||
  { cat pv_plugins.txt; fail "the ParaView GUI does not list the installed PierceParaView"; }

step "FreeCAD (freecadcmd)"
run env PIERCE_EXPECT_MOD=/usr/share/freecad/Mod/Pierce PIERCE_EXPECT_PYDIR=$PYDIR \
  timeout 300 freecadcmd fc_installed.py || fail "freecadcmd checks"

step "FreeCAD GUI lists the workbench"
run env PIERCE_EXPECT_MOD=/usr/share/freecad/Mod/Pierce PIERCE_TEST_REPORT="$work/run/fc_gui.txt" timeout 300 \
  xvfb-run -a -s "-screen 0 1280x1024x24" freecad fc_gui_installed.py >fc_gui.log 2>&1 ||
  { cat fc_gui.log fc_gui.txt; fail "FreeCAD GUI checks"; }
grep -qx "freecad GUI checks: 0 failures" fc_gui.txt || { cat fc_gui.log fc_gui.txt; fail "FreeCAD GUI checks"; }

step "apt-get remove pierce"
cd "$REPO"
$SUDO apt-get remove -y -qq pierce >"$work/apt-remove.log" 2>&1 || { cat "$work/apt-remove.log" >&2; fail "apt-get remove failed"; }
check_nothing_left() {
  local left=() f
  while read -r f; do
    if [ -e "$f" ] || [ -L "$f" ]; then
      # Directories shared with other packages (/usr/bin, ParaView's plugin directory, ...) stay.
      if [ -d "$f" ] && [ ! -L "$f" ] && dpkg-query -S "$f" >/dev/null 2>&1; then continue; fi
      left+=("$f")
    fi
  done <"$work/files.txt"
  [ ${#left[@]} -eq 0 ] || fail "left after apt-get $1: ${left[*]}"
}
check_nothing_left remove
# The package has no conffiles; dpkg only keeps its record (state rc, for postrm purge) until purged.
step "apt-get purge pierce"
$SUDO apt-get purge -y -qq pierce >"$work/apt-purge.log" 2>&1 || { cat "$work/apt-purge.log" >&2; fail "apt-get purge failed"; }
installed=0
status=$(dpkg-query -W -f='${db:Status-Abbrev}' pierce 2>/dev/null || true)
[ -z "$status" ] || [ "${status:0:2}" = "un" ] || fail "after apt-get purge, dpkg still has pierce as '$status'"
check_nothing_left purge
step "all checks passed; the package is removed, nothing of it is left"
