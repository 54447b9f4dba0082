#!/usr/bin/env bash
# `pierce hits MODEL --heatmap cost.png --kernel K [--max-hits N]`: Gribble's heat map of traversal
# work, one ray per pixel; a PNG of the asked size that shows something, its statistics printed,
# more work for more hits, and the same refusals as every other output.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
PLATES="$SAMPLES/plates.obj"

# mean_of OUTPUT: the mean count per pixel from the printed statistics.
mean_of() { sed -n 's/.* per ray: mean \([0-9.]*\) .*/\1/p' "$1"; }

"$PIERCE" hits "$PLATES" --heatmap "$WORK/one.png" --kernel queue --max-hits 1 --png-size 120x90 \
  --heatmap-count prim-tests >"$WORK/one.txt" 2>"$WORK/err" || fail "heat map failed: $(cat "$WORK/err")"
[ "$(png_size "$WORK/one.png")" = "120 90" ] || fail "heat map size '$(png_size "$WORK/one.png")', expected 120 90"
grep -q "heat map .*120x90, kernel queue, up to 1 hits per ray; prim-tests per ray: mean" "$WORK/one.txt" ||
  fail "statistics missing: $(cat "$WORK/one.txt")"
distinct=$(od -An -tu1 -v -j64 "$WORK/one.png" | tr -s ' ' '\n' | sort -u | wc -l)
[ "$distinct" -gt 20 ] || fail "heat map looks blank ($distinct distinct byte values)"

"$PIERCE" hits "$PLATES" --heatmap "$WORK/all.png" --kernel queue --png-size 120x90 --heatmap-count prim-tests \
  >"$WORK/all.txt" 2>"$WORK/err" || fail "all-hits heat map failed: $(cat "$WORK/err")"
awk -v a="$(mean_of "$WORK/one.txt")" -v b="$(mean_of "$WORK/all.txt")" 'BEGIN { exit !(a > 0 && b > a) }' ||
  fail "all hits should cost more than the first: $(mean_of "$WORK/one.txt") vs $(mean_of "$WORK/all.txt")"

cp "$WORK/one.png" "$WORK/keep.png"
expect_error "exists" "not overwriting it without --force" -- "$PIERCE" hits "$PLATES" --heatmap "$WORK/one.png" --kernel queue
cmp -s "$WORK/one.png" "$WORK/keep.png" || fail "existing heat map changed without --force"
expect_error "with --rays" "drop --rays" -- "$PIERCE" hits "$PLATES" --heatmap "$WORK/x.png" --rays grid:n=4 --kernel queue
expect_error "no rays" "--rays is required" -- "$PIERCE" hits "$PLATES" --kernel queue
expect_error "all kernels" "not all" -- "$PIERCE" hits "$PLATES" --heatmap "$WORK/x.png" --kernel all
expect_error "bad count" "expected one of steps, node-tests, prim-tests" -- \
  "$PIERCE" hits "$PLATES" --heatmap "$WORK/x.png" --kernel queue --heatmap-count nodes
expect_error "bad size" "--png-size" -- "$PIERCE" hits "$PLATES" --heatmap "$WORK/x.png" --kernel queue --png-size 3x3
[ ! -e "$WORK/x.png" ] || fail "a heat map was written despite bad options"
finish
