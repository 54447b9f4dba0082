#!/usr/bin/env bash
# Installs the Pierce workbench into FreeCAD's user add-on directory and records where the
# `pierce` Python module is, so the add-on can import it.
#
#   bash packaging/install-freecad-addon.sh [--link] [--force] [--dest DIR] [--module-dir DIR]
#
#   --link        symlink DIR to the checkout's freecad_addon/ (development: edits take effect
#                 on FreeCAD's next start) instead of copying it
#   --force       replace an existing, different install without asking
#   --dest DIR    install as DIR (default: $FREECAD_USER_HOME/Mod/Pierce when that variable is
#                 set, else ~/.local/share/FreeCAD/Mod/Pierce)
#   --module-dir  directory holding the built `pierce` package (default: build/python, or
#                 $PIERCE_BUILD_DIR/python)
#
# Copy mode writes the module directory to pierce_path.txt inside the installed add-on. A linked
# add-on finds the module in the checkout's build*/python by itself; PIERCE_PYTHONPATH overrides
# both.
set -euo pipefail
SCRIPT=$(readlink -f "$0")
cd "$(dirname "$0")/.."
REPO=$(pwd)

link=0 force=0 dest="" module_dir=""
while [ $# -gt 0 ]; do
  case "$1" in
    --link) link=1 ;;
    --force) force=1 ;;
    --dest) dest=${2:?--dest needs a directory}; shift ;;
    --module-dir) module_dir=${2:?--module-dir needs a directory}; shift ;;
    -h|--help) sed -n '2,/^set -e/p' "$SCRIPT" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-freecad-addon: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

if [ -z "$dest" ]; then
  if [ -n "${FREECAD_USER_HOME:-}" ]; then dest="$FREECAD_USER_HOME/Mod/Pierce"
  else dest="$HOME/.local/share/FreeCAD/Mod/Pierce"; fi
fi
module_given=1
[ -n "$module_dir" ] || { module_dir="$REPO/${PIERCE_BUILD_DIR:-build}/python"; module_given=0; }
if [ -f "$module_dir/pierce/__init__.py" ]; then
  module_dir=$(cd "$module_dir" && pwd)
elif [ $link -eq 0 ] || [ $module_given -eq 1 ]; then
  echo "install-freecad-addon: no built 'pierce' package in $module_dir: build Pierce first (bash packaging/build.sh)" >&2
  exit 1
fi
src="$REPO/freecad_addon"

# Is what is there already the same install? (same link target, or same files)
same_install() {
  if [ -L "$dest" ]; then
    [ $link -eq 1 ] && [ "$(readlink -f "$dest")" = "$(readlink -f "$src")" ]
  elif [ -d "$dest" ]; then
    [ $link -eq 0 ] && diff -rq -x pierce_path.txt -x __pycache__ "$src" "$dest" >/dev/null 2>&1
  else
    return 1
  fi
}

if [ -e "$dest" ] || [ -L "$dest" ]; then
  if ! same_install && [ $force -eq 0 ]; then
    what="a different install"
    [ -L "$dest" ] && what="a link to $(readlink "$dest")"
    if [ -t 0 ]; then
      read -r -p "$dest already holds $what. Replace it? [y/N] " answer
      case "$answer" in y|Y|yes|YES) ;; *) echo "install-freecad-addon: left $dest as it was"; exit 1 ;; esac
    else
      echo "install-freecad-addon: $dest already holds $what; rerun with --force to replace it" >&2
      exit 1
    fi
  fi
  rm -rf "$dest"
fi

mkdir -p "$(dirname "$dest")"
if [ $link -eq 1 ]; then
  ln -s "$src" "$dest"
  echo "install-freecad-addon: linked $dest -> $src"
  echo "install-freecad-addon: the add-on finds the module in $REPO/build*/python; elsewhere set PIERCE_PYTHONPATH=$module_dir"
else
  mkdir -p "$dest"
  (cd "$src" && tar --exclude=__pycache__ --exclude=pierce_path.txt -cf - .) | (cd "$dest" && tar -xf -)
  printf '# Written by packaging/install-freecad-addon.sh: where the pierce module is.\n%s\n' "$module_dir" \
    > "$dest/pierce_path.txt"
  echo "install-freecad-addon: installed into $dest (module: $module_dir)"
fi
echo "install-freecad-addon: restart FreeCAD and pick the Pierce workbench"
