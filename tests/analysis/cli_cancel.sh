#!/usr/bin/env bash
# Ctrl-C (SIGINT) during a thickness run: "cancelled", exit 130, no output file left.
source "$(dirname "$0")/../cli/lib.sh"
MAKE_MODELS=${2:?usage: $0 PIERCE_BINARY MAKE_MODELS_BINARY}
"$MAKE_MODELS" "$WORK" || { echo "FAIL: make_models"; exit 1; }
# Tens of seconds of work uninterrupted: a finely tessellated sphere, 10000 cone rays per vertex.
"$PIERCE" thickness "$WORK/hollow.brep" --deflection 0.002 --method cone --cone-rays 10000 --progress \
  -o "$WORK/t.vtp" >"$WORK/stdout" 2>"$WORK/stderr" &
pid=$!
for _ in $(seq 1 600); do
  grep -q 'thickness' "$WORK/stderr" 2>/dev/null && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.05
done
kill -INT "$pid" 2>/dev/null || fail "pierce finished before it could be interrupted"
rc=0
wait "$pid" || rc=$?
[ "$rc" -eq 130 ] || fail "exit code $rc, expected 130"
grep -q cancelled "$WORK/stderr" || fail "no 'cancelled' message: $(cat "$WORK/stderr")"
[ ! -e "$WORK/t.vtp" ] || fail "a partial output file was left"
[ "$(find "$WORK" -name '*pierce-tmp*' | wc -l)" -eq 0 ] || fail "temporary file left behind"
finish
