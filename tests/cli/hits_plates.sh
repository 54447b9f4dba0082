#!/usr/bin/env bash
# Every exact kernel on the bundled 10 stacked touching plates, grid rays along +z: each ray crosses
# each plate twice (enter at its bottom, leave at its top), so it has 2 x plates hits, all distinct
# (geom, prim), in the total order (t ascending, ties by geom then prim). The plate count comes
# from the file (one `o` group per plate), not from a stored answer.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
PLATES="$SAMPLES/plates.obj"
N=32
PLATE_COUNT=$(grep -c '^o ' "$PLATES")
[ "$PLATE_COUNT" -ge 2 ] || fail "expected several plates in $PLATES"

# check_plates CSV RAYS HITS_PER_RAY: every ray 0..RAYS-1 has HITS_PER_RAY hits, distinct (geom,
# prim), strictly increasing (t, geom, prim); each plate (geom) is entered (1) then left (0).
check_plates() {
  awk -F, -v rays="$2" -v want="$3" '
    NR == 1 { if ($0 != "ray,t,geom,prim,u,v,enter") { print "bad header: " $0; bad = 1 } next }
    {
      r = $1
      if (r != prev_ray) { prev_t = ""; }
      count[r]++
      key = r SUBSEP $3 SUBSEP $4
      if (key in seen) { print "ray " r ": repeated hit geom " $3 " prim " $4; bad = 1 }
      seen[key] = 1
      if (prev_t != "") {
        t = $2 + 0; pt = prev_t + 0
        if (t < pt || (t == pt && ($3 + 0 < prev_g || ($3 + 0 == prev_g && $4 + 0 <= prev_p)))) {
          print "ray " r ": hit " $2 "," $3 "," $4 " not after " prev_t "," prev_g "," prev_p; bad = 1
        }
      }
      # enter/leave per plate: first crossing of a geom enters, second leaves
      gk = r SUBSEP $3
      visits[gk]++
      if ((visits[gk] == 1 && $7 != 1) || (visits[gk] == 2 && $7 != 0)) { print "ray " r ": plate " $3 " crossing " visits[gk] " has enter=" $7; bad = 1 }
      if (r + 0 < last_ray) { print "rows not sorted by ray at line " NR; bad = 1 }
      last_ray = r + 0; prev_ray = r; prev_t = $2; prev_g = $3 + 0; prev_p = $4 + 0
    }
    END {
      for (i = 0; i < rays; i++) if (count[i] != want) { print "ray " i ": " count[i] + 0 " hits, expected " want; bad = 1; if (++shown > 5) break }
      for (r in count) if (r + 0 >= rays) { print "unexpected ray " r; bad = 1 }
      exit bad
    }' "$1"
}

for kernel in restart queue nodecull filter buffered embree-restart embree-filter embree-nodecull; do
  # Grid cell centres over the bounds' cross-section all lie inside the plates' common footprint.
  if ! "$PIERCE" hits "$PLATES" --rays "grid:axis=z,n=$N" --kernel "$kernel" >"$WORK/$kernel.csv"; then
    fail "$kernel: pierce hits failed"
    continue
  fi
  check_plates "$WORK/$kernel.csv" $((N * N)) $((2 * PLATE_COUNT)) || fail "$kernel: wrong hits"
  if [ "$kernel" != restart ] && ! cmp -s "$WORK/restart.csv" "$WORK/$kernel.csv"; then
    fail "$kernel: output differs from restart"
  fi
done

# Looking down (-z) gives the same count, each plate entered at its top.
"$PIERCE" hits "$PLATES" --rays "grid:axis=z,n=8,dir=-" --kernel queue >"$WORK/down.csv" || fail "dir=- run failed"
check_plates "$WORK/down.csv" 64 $((2 * PLATE_COUNT)) || fail "dir=-: wrong hits"

# --max-hits N keeps the first N hits of each ray.
"$PIERCE" hits "$PLATES" --rays "grid:axis=z,n=$N" --kernel nodecull --max-hits 5 >"$WORK/max5.csv" || fail "--max-hits run failed"
awk -F, 'NR == 1 { print; next } { if (++c[$1] <= 5) print }' "$WORK/restart.csv" >"$WORK/first5.csv"
cmp -s "$WORK/first5.csv" "$WORK/max5.csv" || fail "--max-hits 5 is not the first 5 hits of each ray"

# Rays from a CSV file: one through the stack, one beside it, one down through it.
printf 'ox,oy,oz,dx,dy,dz\n0.3,0.6,-1,0,0,1\n2,0.5,-1,0,0,1\n0.7,0.2,5,0,0,-2\n' >"$WORK/rays.csv"
"$PIERCE" hits "$PLATES" --rays "$WORK/rays.csv" --kernel buffered >"$WORK/csv_rays.csv" || fail "CSV rays run failed"
for r in 0 2; do
  got=$(awk -F, -v r=$r 'NR > 1 && $1 == r' "$WORK/csv_rays.csv" | wc -l)
  [ "$got" -eq $((2 * PLATE_COUNT)) ] || fail "CSV ray $r: $got hits, expected $((2 * PLATE_COUNT))"
done
got=$(awk -F, 'NR > 1 && $1 == 1' "$WORK/csv_rays.csv" | wc -l)
[ "$got" -eq 0 ] || fail "CSV ray 1 misses the plates but has $got hits"
# t is in units of |dir|: the down ray (|dir| = 2) reaches the top face z = 1 at t = 2.
first_t=$(awk -F, 'NR > 1 && $1 == 2 { print $2; exit }' "$WORK/csv_rays.csv")
[ "$first_t" = 2 ] || fail "CSV ray 2: first t is $first_t, expected 2"

finish
