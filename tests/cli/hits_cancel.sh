#!/usr/bin/env bash
# Ctrl-C (SIGINT) during tracing: "cancelled", exit 130, no output file and no temporary file.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
# Big enough to take seconds on any machine (the signal arrives right after the first progress
# report), small in memory: 1.5 M rays, at most one hit each.
"$PIERCE" hits "$SAMPLES/blob.stl" --rays random:n=1500000,seed=3 --kernel restart --max-hits 1 --progress \
  --out "$WORK/out.csv" >"$WORK/stdout" 2>"$WORK/stderr" &
pid=$!
# Wait for the progress bar: tracing has started.
for _ in $(seq 1 600); do
  grep -q 'rays' "$WORK/stderr" 2>/dev/null && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.05
done
kill -INT "$pid" 2>/dev/null || fail "pierce finished before it could be interrupted"
rc=0
wait "$pid" || rc=$?
[ "$rc" -eq 130 ] || fail "exit code $rc, expected 130"
grep -q cancelled "$WORK/stderr" || fail "no 'cancelled' message: $(cat "$WORK/stderr")"
[ ! -e "$WORK/out.csv" ] || fail "a partial output file was left"
[ "$(find "$WORK" -name '*pierce-tmp*' | wc -l)" -eq 0 ] || fail "temporary file left behind"
finish
