#!/usr/bin/env bash
# Ctrl-C (SIGINT) during tracing: "cancelled", exit 130, no output file and no temporary file.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
# Big enough to take seconds on any machine (the signal arrives right after the first progress
# report), small in memory: 1.5 M rays, at most one hit each.
"$PIERCE" hits "$SAMPLES/blob.stl" --rays random:n=1500000,seed=3 --kernel restart --max-hits 1 --progress \
  --out "$WORK/out.csv" >"$WORK/stdout" 2>"$WORK/stderr" &
expect_clean_interrupt $! rays "$WORK/out.csv"
finish
