#!/usr/bin/env bash
# `pierce hits` on a STEP assembly (tessellated through OpenCASCADE): samples/plate_assembly.step
# holds a 10 x 10 x 2 plate, two 2 mm cubes standing on it at (1,1) and (6,1) (touching its top
# face, z 2..4) and a 2 mm cube sunk 0.5 into it at (6,6) (z 1.5..3.5). All faces are planar, so
# tessellation is exact and every t below follows from those dimensions.
source "$(dirname "$0")/lib.sh"
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
STEP="$SAMPLES/plate_assembly.step"

# Rays up from z = -1: through plate and the cube at (1,1); through plate and the sunk cube;
# through the plate alone.
printf 'ox,oy,oz,dx,dy,dz\n2,2,-1,0,0,1\n7,7,-1,0,0,1\n5,5,-1,0,0,1\n' >"$WORK/rays.csv"
for kernel in queue filter embree-filter; do
  if ! "$PIERCE" hits "$STEP" --rays "$WORK/rays.csv" --kernel "$kernel" >"$WORK/$kernel.csv" 2>"$WORK/err"; then
    fail "$kernel: pierce hits on STEP failed: $(cat "$WORK/err")"
    continue
  fi
  # Per ray: "t:enter:geom" in hit order.
  for r in 0 1 2; do
    got[$r]=$(awk -F, -v r=$r 'NR > 1 && $1 == r { printf "%s%g:%s:%s", sep, $2, $7, $3; sep = " " }' "$WORK/$kernel.csv")
  done
  # Ray 0: enter plate at 1, leave plate and enter cube at 3 (either order: equal t), leave cube at 5.
  read -r -a h <<<"${got[0]}"
  if [ "${#h[@]}" -ne 4 ]; then
    fail "$kernel: ray through plate and cube: ${#h[@]} hits (${got[0]}), expected 4"
  else
    plate=${h[0]##*:} cube=${h[3]##*:}
    [ "${h[0]%:*}" = "1:1" ] || fail "$kernel: ray 0 first hit ${h[0]}, expected entering at t=1"
    [ "${h[3]%:*}" = "5:0" ] || fail "$kernel: ray 0 last hit ${h[3]}, expected leaving at t=5"
    [ "$plate" != "$cube" ] || fail "$kernel: ray 0 enters and leaves the same solid ${plate}"
    mid=$(printf '%s\n' "${h[1]}" "${h[2]}" | sort | tr '\n' ' ')
    want=$(printf '%s\n' "3:0:$plate" "3:1:$cube" | sort | tr '\n' ' ')
    [ "$mid" = "$want" ] || fail "$kernel: ray 0 middle hits '$mid', expected '$want' (plate left, cube entered at t=3)"
  fi
  # Ray 1: enter plate 1, enter sunk cube 2.5, leave plate 3, leave cube 4.5 (0.5 of interference).
  read -r -a h <<<"${got[1]}"
  if [ "${#h[@]}" -ne 4 ]; then
    fail "$kernel: ray through plate and sunk cube: ${#h[@]} hits (${got[1]}), expected 4"
  else
    plate=${h[0]##*:} clash=${h[1]##*:}
    want="1:1:$plate 2.5:1:$clash 3:0:$plate 4.5:0:$clash"
    [ "${got[1]}" = "$want" ] || fail "$kernel: ray 1 hits '${got[1]}', expected '$want'"
    [ "$plate" != "$clash" ] || fail "$kernel: ray 1 plate and sunk cube are the same solid"
  fi
  # Ray 2: the plate only.
  [ "$(echo "${got[2]}" | sed 's/:[0-9]*$//; s/:[0-9]* / /')" = "1:1 3:0" ] ||
    fail "$kernel: ray through the plate alone: '${got[2]}', expected t=1 enter, t=3 leave"
done

# A 10 x 10 grid of rays along z through cell centres (0.5 .. 9.5): 4 rays meet each of the
# three cubes (4 hits each), the other 88 only the plate (2 hits): 224 hits.
"$PIERCE" hits "$STEP" --rays grid:axis=z,n=10 --kernel queue --deflection 0.05 >"$WORK/grid.csv" 2>"$WORK/err" ||
  fail "grid run failed: $(cat "$WORK/err")"
counts=$(awk -F, 'NR > 1 { c[$1]++ } END { for (r in c) n[c[r]]++; printf "%d %d %d", n[2], n[4], NR - 1 }' "$WORK/grid.csv")
[ "$counts" = "88 12 224" ] || fail "grid: rays with 2 hits, with 4 hits, total hits = '$counts', expected '88 12 224'"

# Bad tessellation options are refused with a clear message.
expect_error "negative deflection" "deflection" -- "$PIERCE" hits "$STEP" --rays grid:axis=z,n=2 --kernel queue --deflection -1

finish
