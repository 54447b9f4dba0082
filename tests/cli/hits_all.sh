#!/usr/bin/env bash
# `--kernel all` on the touching plates: every exact kernel reports zero disagreements, the epsilon
# baseline reports missed hits, and the exit code is 0. With --out the consensus CSV is written.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
PLATES="$SAMPLES/plates.obj"
N=32
PLATE_COUNT=$(grep -c '^o ' "$PLATES")
EXACT="embree-restart embree-filter embree-nodecull restart queue nodecull filter buffered"

rc=0
"$PIERCE" hits "$PLATES" --rays "grid:axis=z,n=$N" --kernel all >"$WORK/table.txt" 2>"$WORK/stderr" || rc=$?
cat "$WORK/table.txt"
[ "$rc" -eq 0 ] || fail "exit code $rc, expected 0: $(cat "$WORK/stderr")"

# Row layout: kernel exact time Mrays/s hits rays-differ missing extra duplicated out-of-order t-differs
row() { awk -v k="$1" '$1 == k' "$WORK/table.txt"; }
for k in $EXACT; do
  r=$(row "$k")
  [ -n "$r" ] || { fail "no row for $k"; continue; }
  set -- $r
  [ "$2" = yes ] || fail "$k not marked exact"
  [ "$5" -eq $((N * N * 2 * PLATE_COUNT)) ] || fail "$k: $5 hits, expected $((N * N * 2 * PLATE_COUNT))"
  for col in 6 7 8 9 10 11; do
    [ "${!col}" -eq 0 ] || fail "$k: column $col is ${!col}, expected 0 ($r)"
  done
done
r=$(row epsilon)
[ -n "$r" ] || fail "no row for epsilon"
set -- $r
[ "$2" = no ] || fail "epsilon marked exact"
[ "$7" -gt 0 ] || fail "epsilon reports no missed hits on touching plates ($r)"
[ "$6" -gt 0 ] || fail "epsilon reports no differing rays ($r)"
grep -q "^all 8 exact kernels agree" "$WORK/table.txt" || fail "no agreement line"

# --out writes the consensus hits, which are what each exact kernel prints.
"$PIERCE" hits "$PLATES" --rays "grid:axis=z,n=$N" --kernel all --out "$WORK/consensus.csv" >/dev/null ||
  fail "--kernel all --out failed"
"$PIERCE" hits "$PLATES" --rays "grid:axis=z,n=$N" --kernel queue >"$WORK/queue.csv" || fail "queue run failed"
cmp -s "$WORK/consensus.csv" "$WORK/queue.csv" || fail "consensus CSV differs from the queue kernel's"

finish
