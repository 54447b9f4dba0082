#!/usr/bin/env bash
# Errors of the analysis commands: clear message, non-zero exit, no output file touched.
source "$(dirname "$0")/../cli/lib.sh"
MAKE_MODELS=${2:?usage: $0 PIERCE_BINARY MAKE_MODELS_BINARY}
box_obj a 0 0 0 1 1 1 0 >"$WORK/box.obj"

expect_error "missing model" "no such file" -- "$PIERCE" thickness "$WORK/nope.stl" -o "$WORK/x.csv"
expect_error "unknown model format" "unknown model format" -- "$PIERCE" info "$WORK/box.xyz"
printf 'ISO-10303-21;\nthis is not STEP\n' >"$WORK/bad.step"
expect_error "malformed STEP" "bad.step" -- "$PIERCE" info "$WORK/bad.step"
expect_error "malformed STEP" "not a readable STEP file" -- "$PIERCE" overlaps "$WORK/bad.step"
printf 'solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nope\n' >"$WORK/bad.stl"
expect_error "malformed STL" "bad.stl" -- "$PIERCE" thickness "$WORK/bad.stl"
expect_error "unknown output format" "unknown output format" -- "$PIERCE" thickness "$WORK/box.obj" -o "$WORK/t.txt"
expect_error "bad method" "method" -- "$PIERCE" thickness "$WORK/box.obj" --method laser
expect_error "bad per" "per" -- "$PIERCE" thickness "$WORK/box.obj" --per edge
expect_error "unknown solid" "no solid with that name" -- "$PIERCE" thickness "$WORK/box.obj" --solid wheel
expect_error "inexact kernel" "not an exact kernel" -- "$PIERCE" thickness "$WORK/box.obj" --kernel epsilon
expect_error "negative tolerance" "--tol" -- "$PIERCE" overlaps "$WORK/box.obj" --tol -1
expect_error "bad ray spec" "axes:n=" -- "$PIERCE" overlaps "$WORK/box.obj" --rays axes:n=zero

# Never overwrite without --force, and leave the file as it was.
echo "precious" >"$WORK/keep.csv"
expect_error "existing output" "--force" -- "$PIERCE" thickness "$WORK/box.obj" -o "$WORK/keep.csv"
[ "$(cat "$WORK/keep.csv")" = "precious" ] || fail "existing output was modified"
expect_error "existing output" "--force" -- "$PIERCE" overlaps "$WORK/box.obj" -o "$WORK/keep.csv"
[ "$(cat "$WORK/keep.csv")" = "precious" ] || fail "existing output was modified"
run "with --force" "$PIERCE" thickness "$WORK/box.obj" -o "$WORK/keep.csv" --force
head -1 "$WORK/keep.csv" | grep -q "^id,solid," || fail "--force did not write the CSV"
finish
