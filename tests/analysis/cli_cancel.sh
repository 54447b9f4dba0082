#!/usr/bin/env bash
# Ctrl-C (SIGINT) during a thickness run: "cancelled", exit 130, no output file left.
source "$(dirname "$0")/../cli/lib.sh"
MAKE_MODELS=${2:?usage: $0 PIERCE_BINARY MAKE_MODELS_BINARY}
"$MAKE_MODELS" "$WORK" || { echo "FAIL: make_models"; exit 1; }
# Tens of seconds of work uninterrupted: a finely tessellated sphere, 10000 cone rays per vertex.
"$PIERCE" thickness "$WORK/hollow.brep" --deflection 0.002 --method cone --cone-rays 10000 --progress \
  -o "$WORK/t.vtp" >"$WORK/stdout" 2>"$WORK/stderr" &
expect_clean_interrupt $! thickness "$WORK/t.vtp"
finish
