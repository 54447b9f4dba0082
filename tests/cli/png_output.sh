#!/usr/bin/env bash
# `pierce thickness --png` and `pierce overlaps --png` on the STEP sample: a PNG of the asked size
# that shows something, never written over an existing file without --force.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
STEP="$SAMPLES/plate_assembly.step"


"$PIERCE" thickness "$STEP" --per face --png "$WORK/t.png" --png-size 160x120 >"$WORK/out" 2>"$WORK/err" ||
  fail "thickness --png failed: $(cat "$WORK/err")"
[ "$(png_size "$WORK/t.png")" = "160 120" ] || fail "thickness picture: '$(png_size "$WORK/t.png")', expected 160 120"
grep -q "picture .*160x120" "$WORK/out" || fail "thickness --png does not report the picture: $(cat "$WORK/out")"
# Uncompressed 8-bit RGB: the image's bytes are in the file. A white picture would be all 0xff;
# count distinct byte values as a cheap "something was drawn" check.
distinct=$(od -An -tu1 -v -j64 "$WORK/t.png" | tr -s ' ' '\n' | sort -u | wc -l)
[ "$distinct" -gt 20 ] || fail "thickness picture looks blank ($distinct distinct byte values)"

# An existing file is kept unless --force; the refusal comes before the analysis.
cp "$WORK/t.png" "$WORK/keep.png"
expect_error "png exists" "not overwriting it without --force" -- "$PIERCE" thickness "$STEP" --png "$WORK/t.png"
cmp -s "$WORK/t.png" "$WORK/keep.png" || fail "existing PNG was changed without --force"
"$PIERCE" thickness "$STEP" --png "$WORK/t.png" --png-size 100x80 --png-view 0,0,-1 --force >/dev/null 2>&1 ||
  fail "thickness --png --force failed"
[ "$(png_size "$WORK/t.png")" = "100 80" ] || fail "--force did not replace the picture"

expect_error "bad size" "--png-size" -- "$PIERCE" thickness "$STEP" --png "$WORK/x.png" --png-size 100
expect_error "bad view" "--png-view" -- "$PIERCE" thickness "$STEP" --png "$WORK/x.png" --png-view 0,0,0
[ ! -e "$WORK/x.png" ] || fail "a picture was written despite bad options"

"$PIERCE" overlaps "$STEP" --rays axes:n=16 --png "$WORK/o.png" --png-size 128x96 >"$WORK/out" 2>"$WORK/err" ||
  fail "overlaps --png failed: $(cat "$WORK/err")"
[ "$(png_size "$WORK/o.png")" = "128 96" ] || fail "overlaps picture: '$(png_size "$WORK/o.png")', expected 128 96"
expect_error "overlaps png exists" "not overwriting it without --force" -- "$PIERCE" overlaps "$STEP" --png "$WORK/o.png"

finish
