#!/usr/bin/env bash
# `pierce thickness --min/--max`: thin and thick regions in JSON, CSV, VTP and the summary table,
# on a 40 x 30 x 10 block with an 8 x 6 pocket leaving a floor of 0.5, meshed coarsely (the bottom
# two triangles), so the floor's area on both sides (96) is found by refinement.
source "$(dirname "$0")/../cli/lib.sh"

$PY - "$WORK/pocket.obj" <<'PYEOF' || fail "writing the pocket block"
import sys
X, Y, Z, x0, x1, y0, y1, d = 40, 30, 10, 4, 12, 4, 10, 0.5
v = [(0, 0, 0), (X, 0, 0), (X, Y, 0), (0, Y, 0), (0, 0, Z), (X, 0, Z), (X, Y, Z), (0, Y, Z),
     (x0, y0, Z), (x1, y0, Z), (x1, y1, Z), (x0, y1, Z), (x0, y0, d), (x1, y0, d), (x1, y1, d), (x0, y1, d)]
quads = [((0, 1, 2, 3), (0, 0, -1)), ((0, 1, 5, 4), (0, -1, 0)), ((1, 2, 6, 5), (1, 0, 0)),
         ((2, 3, 7, 6), (0, 1, 0)), ((3, 0, 4, 7), (-1, 0, 0)), ((4, 5, 9, 8), (0, 0, 1)),
         ((5, 6, 10, 9), (0, 0, 1)), ((6, 7, 11, 10), (0, 0, 1)), ((7, 4, 8, 11), (0, 0, 1)),
         ((8, 9, 13, 12), (0, 1, 0)), ((9, 10, 14, 13), (-1, 0, 0)), ((10, 11, 15, 14), (0, -1, 0)),
         ((11, 8, 12, 15), (1, 0, 0)), ((12, 13, 14, 15), (0, 0, 1))]
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
with open(sys.argv[1], "w") as f:
    for p in v:
        f.write("v %r %r %r\n" % p)
    for q, out in quads:
        n = cross(sub(v[q[1]], v[q[0]]), sub(v[q[2]], v[q[0]]))
        if sum(n[i] * out[i] for i in range(3)) < 0:
            q = (q[0], q[3], q[2], q[1])
        f.write("f %d %d %d\nf %d %d %d\n" % (q[0] + 1, q[1] + 1, q[2] + 1, q[0] + 1, q[2] + 1, q[3] + 1))
PYEOF

run "regions json" "$PIERCE" thickness "$WORK/pocket.obj" --per face --min 1.5 --max 5 -o "$WORK/r.json"
$PY - "$WORK/r.json" <<'PYEOF' || fail "regions: JSON content"
import json, sys
j = json.load(open(sys.argv[1]))
thin, thick = j["thin_regions"], j["thick_regions"]
assert len(thin) == 1, thin
g = thin[0]
assert list(g) == ["solid", "min_thickness", "area", "area_sides", "point", "exit", "samples", "faces"], list(g)
assert g["solid"] == 0 and abs(g["min_thickness"] - 0.5) < 1e-9, g
assert g["area_sides"] == "both" and abs(g["area"] - 96) <= 9.6, g
assert 4 <= g["point"][0] <= 12 and 4 <= g["point"][1] <= 10 and abs(g["point"][2] - 0.5) < 1e-9, g
assert abs(g["exit"][2]) < 1e-9 and g["samples"] == 2 and g["faces"] == [], g
assert thick and all(t["max_thickness"] > 5 for t in thick), thick
assert thick[0]["max_thickness"] == max(e["thickness"] for e in j["elements"] if e["thickness"] is not None)
assert j["max_thickness"] == 5
for e in j["elements"]:
    t, r = e["thickness"], e["region"]
    if t is not None and t < 1.5: assert r == 0, e
    elif t is not None and t > 5: assert r >= 1, e
    else: assert r == -1, e
PYEOF
grep -q "thin regions (thickness < 1.5): 1" "$WORK/stdout" || fail "summary lacks the region count: $(cat "$WORK/stdout")"
grep -Eq "^ +0 .* 0\.5 +[0-9.]+ +2 " "$WORK/stdout" || fail "summary lacks the region table: $(cat "$WORK/stdout")"

run "regions csv" "$PIERCE" thickness "$WORK/pocket.obj" --per face --min 1.5 -o "$WORK/r.csv"
$PY - "$WORK/r.csv" <<'PYEOF' || fail "regions: CSV region column"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert sorted(set(r["region"] for r in rows)) == ["-1", "0"], set(r["region"] for r in rows)
assert all((r["region"] == "0") == (r["thin"] == "1") for r in rows)
PYEOF

run "regions vtp" "$PIERCE" thickness "$WORK/pocket.obj" --min 1.5 -o "$WORK/r.vtp"
grep -q 'Name="Region"' "$WORK/r.vtp" || fail "VTP lacks the Region array"

"$PIERCE" thickness --help >"$WORK/help" 2>&1
grep -q "strictly below T" "$WORK/help" || fail "--help does not state the thin rule"
expect_error "--max below --min" "--max must not be below --min" -- "$PIERCE" thickness "$WORK/pocket.obj" --min 2 --max 1
finish
