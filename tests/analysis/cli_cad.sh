#!/usr/bin/env bash
# `pierce info`, `thickness` and `overlaps` on a STEP assembly (plate, two touching blocks, a
# clash sunk 0.5 mm into the plate) and a BREP hollow sphere, both written with OpenCASCADE.
source "$(dirname "$0")/../cli/lib.sh"
MAKE_MODELS=${2:?usage: $0 PIERCE_BINARY MAKE_MODELS_BINARY}
"$MAKE_MODELS" "$WORK" || { echo "FAIL: make_models"; exit 1; }
STEP=$WORK/assembly.step

run "info" "$PIERCE" info "$STEP"
for name in plate_assy/plate plate_assy/block plate_assy/block#2 plate_assy/clash; do
  grep -qF "$name" "$WORK/stdout" || fail "info: no solid $name"
done
[ "$(grep -c "closed, oriented" "$WORK/stdout")" -eq 4 ] || fail "info: expected 4 closed oriented solids"
grep -q "units mm" "$WORK/stdout" || fail "info: units"
run "info json" "$PIERCE" info "$STEP" --json
$PY -c "import json,sys; j=json.load(open('$WORK/stdout')); assert len(j['solids'])==4 and all(s['closed'] for s in j['solids'])" ||
  fail "info --json"

run "overlaps" "$PIERCE" overlaps "$STEP" --rays axes:n=64 -o "$WORK/o.csv"
$PY - "$WORK/o.csv" <<'PYEOF' || fail "overlaps csv"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
inter = [r for r in rows if r["kind"] == "interference"]
assert len(inter) == 1 and {inter[0]["name_a"], inter[0]["name_b"]} == {"plate_assy/plate", "plate_assy/clash"}, inter
assert abs(float(inter[0]["penetration"]) - 0.5) < 1e-4, inter
contacts = sorted(r["name_b"] for r in rows if r["kind"] == "contact")
assert contacts == ["plate_assy/block", "plate_assy/block#2"], contacts
cop = [r for r in rows if r["kind"] == "coplanar"]
assert len(cop) == 2 and all(abs(float(r["area"]) - 4) < 1e-9 and r["same_facing"] == "0" for r in cop), cop
PYEOF
grep -q "INTERFERENCE plate_assy/plate <-> plate_assy/clash" "$WORK/stdout" || fail "overlaps: summary"
run "overlaps json" "$PIERCE" overlaps "$STEP" --rays axes:n=32 -o "$WORK/o.json"
run "overlaps vtp" "$PIERCE" overlaps "$STEP" --rays axes:n=32 -o "$WORK/o.vtp"
grep -q 'Name="OverlapCount"' "$WORK/o.vtp" && grep -q 'Name="CoplanarPartner"' "$WORK/o.vtp" ||
  fail "overlaps vtp: arrays missing"

run "thickness" "$PIERCE" thickness "$STEP" --per face -o "$WORK/t.json"
$PY - "$WORK/t.json" <<'PYEOF' || fail "thickness of the assembly"
import json, sys
s = {x["name"]: x for x in json.load(open(sys.argv[1]))["solids"]}
assert abs(s["plate_assy/plate"]["min"] - 2) < 1e-6 and abs(s["plate_assy/plate"]["max"] - 10) < 1e-6
for n in ("plate_assy/block", "plate_assy/block#2", "plate_assy/clash"):
    assert abs(s[n]["min"] - 2) < 1e-6 and abs(s[n]["max"] - 2) < 1e-6, s[n]
PYEOF
run "thickness --solid" "$PIERCE" thickness "$STEP" --per face --solid plate_assy/clash -o "$WORK/c.csv"
[ "$(($(wc -l <"$WORK/c.csv") - 1))" -eq 12 ] || fail "--solid: expected the clash's 12 faces only"
# The same solid by id, as #N (the CSG form) and as a bare N: one syntax for solids everywhere.
run "thickness --solid #3" "$PIERCE" thickness "$STEP" --per face --solid '#3' -o "$WORK/c_hash.csv"
run "thickness --solid 3" "$PIERCE" thickness "$STEP" --per face --solid 3 -o "$WORK/c_id.csv"
cmp -s "$WORK/c.csv" "$WORK/c_hash.csv" || fail "--solid '#3' is not the clash (solid 3)"
cmp -s "$WORK/c.csv" "$WORK/c_id.csv" || fail "--solid 3 is not the clash (solid 3)"

run "hollow sphere" "$PIERCE" thickness "$WORK/hollow.brep" --deflection 0.002 -o "$WORK/h.csv"
$PY - "$WORK/h.csv" <<'PYEOF' || fail "hollow sphere wall"
import csv, sys
t = [float(r["thickness"]) for r in csv.DictReader(open(sys.argv[1]))]
ok = sum(abs(v - 0.05) <= 0.004 for v in t)
assert ok >= 0.99 * len(t), (ok, len(t))
PYEOF
finish
