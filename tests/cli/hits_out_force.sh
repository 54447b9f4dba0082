#!/usr/bin/env bash
# --out never overwrites an existing file without --force, and leaves no temporary files.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
PLATES="$SAMPLES/plates.obj"
RUN=("$PIERCE" hits "$PLATES" --rays grid:axis=z,n=4 --kernel filter)

"${RUN[@]}" >"$WORK/stdout.csv" || fail "run to stdout failed"
"${RUN[@]}" --out "$WORK/new.csv" >"$WORK/new_stdout" || fail "run to a new --out file failed"
cmp -s "$WORK/stdout.csv" "$WORK/new.csv" || fail "--out file differs from stdout output"
[ ! -s "$WORK/new_stdout" ] || fail "CSV also went to stdout with --out"

echo precious >"$WORK/existing.csv"
expect_error "existing --out" "not overwriting it without --force" -- "${RUN[@]}" --out "$WORK/existing.csv"
[ "$(cat "$WORK/existing.csv")" = precious ] || fail "existing file was modified without --force"

"${RUN[@]}" --out "$WORK/existing.csv" --force || fail "--force run failed"
cmp -s "$WORK/stdout.csv" "$WORK/existing.csv" || fail "--force did not write the hits"

expect_error "--out into a missing directory" "does not exist" -- "${RUN[@]}" --out "$WORK/no/such/dir/x.csv"
expect_error "--out is a directory" "is a directory" -- "${RUN[@]}" --out "$WORK"
"${RUN[@]}" --out /dev/null || fail "--out /dev/null failed"

leftovers=$(find "$WORK" -name '*pierce-tmp*' | wc -l)
[ "$leftovers" -eq 0 ] || fail "temporary files left behind"
finish
