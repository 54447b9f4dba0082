#!/usr/bin/env bash
# `pierce thickness --origin-offsets on|off|auto`: identical maps, bad values rejected.
# Usage: cli_offsets.sh PIERCE_BINARY SAMPLES_DIR
set -euo pipefail
pierce=$1
samples=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for method in ray cone; do
  for mode in on off auto; do
    "$pierce" thickness "$samples/blob.stl" --per face --method "$method" --cone-rays 7 \
      --origin-offsets "$mode" --offset-set median+center -o "$tmp/$method-$mode.csv" > "$tmp/$method-$mode.txt"
  done
  cmp "$tmp/$method-on.csv" "$tmp/$method-off.csv"
  cmp "$tmp/$method-auto.csv" "$tmp/$method-off.csv"
  [ "$(wc -l < "$tmp/$method-on.csv")" -gt 1000 ] || { echo "too few rows"; exit 1; }
done
if "$pierce" thickness "$samples/blob.stl" --origin-offsets maybe > "$tmp/bad.txt" 2>&1; then
  echo "accepted --origin-offsets maybe"; exit 1
fi
grep -q "origin-offsets" "$tmp/bad.txt" || { cat "$tmp/bad.txt"; exit 1; }
echo "cli_offsets: ok"
