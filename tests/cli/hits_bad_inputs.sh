#!/usr/bin/env bash
# Bad models, ray specs, kernels and arguments: non-zero exit and a message naming the problem.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
PLATES="$SAMPLES/plates.obj"
GRID="grid:axis=z,n=4"

expect_error "missing model" "$WORK/nosuch.obj: cannot open" -- "$PIERCE" hits "$WORK/nosuch.obj" --rays "$GRID" --kernel restart
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >"$WORK/bad.obj"
expect_error "bad OBJ index" "$WORK/bad.obj:4: vertex index 9 out of range" -- "$PIERCE" hits "$WORK/bad.obj" --rays "$GRID" --kernel restart
printf 'solid x\n' >"$WORK/cut.stl"
expect_error "truncated STL" "$WORK/cut.stl:1: unexpected end of file" -- "$PIERCE" hits "$WORK/cut.stl" --rays "$GRID" --kernel restart
: >"$WORK/empty.ply"
expect_error "empty model" "$WORK/empty.ply: file is empty" -- "$PIERCE" hits "$WORK/empty.ply" --rays "$GRID" --kernel restart
printf 'x' >"$WORK/model.3ds"
expect_error "unknown format" "unknown model format '.3ds'" -- "$PIERCE" hits "$WORK/model.3ds" --rays "$GRID" --kernel restart
# A good model after a bad one still fails: nothing runs on a partial scene.
expect_error "bad second model" "$WORK/bad.obj:4:" -- "$PIERCE" hits "$PLATES" "$WORK/bad.obj" --rays "$GRID" --kernel restart

expect_error "n=0" "n must be positive" -- "$PIERCE" hits "$PLATES" --rays grid:axis=z,n=0 --kernel restart
expect_error "unknown key" "unknown key 'step'" -- "$PIERCE" hits "$PLATES" --rays grid:n=4,step=2 --kernel restart
expect_error "missing n" "missing n" -- "$PIERCE" hits "$PLATES" --rays random:seed=2 --kernel restart
expect_error "unknown generator" "unknown ray generator 'cone'" -- "$PIERCE" hits "$PLATES" --rays cone:n=3 --kernel restart
expect_error "missing ray file" "$WORK/rays.csv: cannot open" -- "$PIERCE" hits "$PLATES" --rays "$WORK/rays.csv" --kernel restart
printf '0,0,-1,0,0,1\n0,0,-1,0,0\n' >"$WORK/short.csv"
expect_error "short ray line" "$WORK/short.csv:2: expected 6 or 8" -- "$PIERCE" hits "$PLATES" --rays "$WORK/short.csv" --kernel restart

expect_error "unknown kernel" "unknown kernel 'warp'" -- "$PIERCE" hits "$PLATES" --rays "$GRID" --kernel warp
expect_error "missing --rays" "--rays" -- "$PIERCE" hits "$PLATES" --kernel restart
expect_error "missing --kernel" "--kernel" -- "$PIERCE" hits "$PLATES" --rays "$GRID"
expect_error "missing model argument" "models" -- "$PIERCE" hits --rays "$GRID" --kernel restart
expect_error "negative --max-hits" "max-hits" -- "$PIERCE" hits "$PLATES" --rays "$GRID" --kernel restart --max-hits -1

# Input errors exit with 2 and leave no output file.
rc=0
"$PIERCE" hits "$WORK/bad.obj" --rays "$GRID" --kernel restart --out "$WORK/out.csv" 2>/dev/null || rc=$?
[ "$rc" -eq 2 ] || fail "input error exit code $rc, expected 2"
[ ! -e "$WORK/out.csv" ] || fail "an output file was left after an input error"

finish
