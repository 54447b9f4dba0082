#!/usr/bin/env bash
# Compares `pierce thickness` outputs (JSON and CSV, per vertex and per face, ray and cone) of two
# builds on CAD parts: identical files, or the differing rows. For changes that must keep CAD
# thickness results as they are.
# Usage: compare_cad_thickness.sh OLD_PIERCE NEW_PIERCE PART...   (OLD_LIBDIR: the old build's
# libpierce directory, if it is not found through the binary's RUNPATH)
set -uo pipefail
old=$1 new=$2
shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
status=0
for part in "$@"; do
  for args in "--per vertex" "--per face" "--per face --method cone --cone-rays 8"; do
    tag=$(basename "$part")_$(echo "$args" | tr -d ' -')
    for ext in json csv; do
      LD_LIBRARY_PATH=${OLD_LIBDIR:-} "$old" thickness $args "$part" -o "$out/old_$tag.$ext" > "$out/old_$tag.$ext.log" 2>&1
      "$new" thickness $args "$part" -o "$out/new_$tag.$ext" > "$out/new_$tag.$ext.log" 2>&1
      if cmp -s "$out/old_$tag.$ext" "$out/new_$tag.$ext"; then
        echo "same      $tag.$ext"
      else
        echo "DIFFERENT $tag.$ext"
        diff "$out/old_$tag.$ext" "$out/new_$tag.$ext" | head -n 6
        status=1
      fi
    done
  done
done
exit $status
