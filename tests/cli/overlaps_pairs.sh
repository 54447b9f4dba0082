#!/usr/bin/env bash
# `pierce overlaps --clearance D` on assemblies of axis-aligned blocks written here as OBJ and STL:
# the JSON `pairs` (contact, clash, clearance, with their exact gaps and depths), the text summary,
# the VTP `Clearance` array, and that blocks farther apart than D are not reported.
source "$(dirname "$0")/lib.sh"

# a-b touch on x = 1; b-c 0.3 apart (x = 2 .. 2.3); c-d clash over a 0.5 x 10 x 10 slab
# (x = 2.8 .. 3.3 across d's whole 10 x 10 face); e is 5 from d.
{
  box_obj a 0 0 0 1 1 1 0
  box_obj b 1 0 0 2 1 1 8
  box_obj c 2.3 -1 -1 3.3 11 11 16
  box_obj d 2.8 0 0 12.8 10 10 24
  box_obj e 17.8 0 0 18.8 1 1 32
} >"$WORK/blocks.obj"

run "overlaps --clearance" "$PIERCE" overlaps "$WORK/blocks.obj" --clearance 0.5 --rays axes:n=64 -o "$WORK/o.json"
grep -q "^pairs within clearance 0.5: 1 clash, 1 contact, 1 clearance$" "$WORK/stdout" ||
  fail "text: counts line missing: $(cat "$WORK/stdout")"
grep -Eq "^clash +c +d " "$WORK/stdout" || fail "text: no clash row for c, d"
$PY - "$WORK/o.json" <<'PYEOF' || fail "json pairs"
import json, math, sys
j = json.load(open(sys.argv[1]))
names = [s["name"] for s in j["solids"]]
pairs = [(p["kind"], names[p["solid_a"]], names[p["solid_b"]]) for p in j["pairs"]]
assert pairs == [("clash", "c", "d"), ("contact", "a", "b"), ("clearance", "b", "c")], pairs
clash, contact, gap = j["pairs"]
assert abs(clash["depth"] - 0.5) <= 0.005, clash
assert abs(clash["overlap_length"] - 10) <= 1e-6, clash
assert clash["gap"] is None and clash["volume"] > 0, clash
assert contact["gap"] == 0 and contact["depth"] is None and contact["point_b"] is None, contact
assert abs(contact["point"][0] - 1) <= 1e-12, contact
assert abs(gap["gap"] - 0.3) <= 1e-9, gap
assert gap["point"][0] == 2 and gap["point_b"][0] == 2.3, gap
assert gap["depth"] is None and gap["overlap_length"] is None and gap["volume"] is None, gap
assert j["clearance"] == 0.5
# The outputs that were there before the pairs are still there.
for key in ("interferences", "contacts", "coplanar", "coplanar_triangle_pairs", "interference_intervals"):
    assert key in j, key
PYEOF

# Default clearance 0: clash and contact only.
run "overlaps default" "$PIERCE" overlaps "$WORK/blocks.obj" --rays axes:n=64 -o "$WORK/d.json"
$PY -c 'import json, sys; k = [p["kind"] for p in json.load(open(sys.argv[1]))["pairs"]]; sys.exit(k != ["clash", "contact"])' \
  "$WORK/d.json" || fail "clearance 0: expected clash and contact only"

# Other rays than an axis grid: the pairs come from a grid of their own, the same answer.
run "overlaps random rays" "$PIERCE" overlaps "$WORK/blocks.obj" --clearance 0.5 --rays random:n=100 -o "$WORK/r.json"
$PY -c 'import json, sys; k = [p["kind"] for p in json.load(open(sys.argv[1]))["pairs"]]; sys.exit(k != ["clash", "contact", "clearance"])' \
  "$WORK/r.json" || fail "random rays: pairs differ"

# VTP: a Clearance value per triangle, D for e's (nothing within D), below D elsewhere.
run "overlaps vtp" "$PIERCE" overlaps "$WORK/blocks.obj" --clearance 0.5 --rays axes:n=16 -o "$WORK/o.vtp"
$PY - "$WORK/o.vtp" <<'PYEOF' || fail "vtp Clearance"
import base64, struct, sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
arrays = {a.get("Name"): a for a in root.iter("DataArray")}
for name in ("Clearance", "OverlapCount", "SolidId"):
    assert name in arrays, name
def values(name, code):
    # Inline binary: base64 of the UInt64 byte count and the data.
    raw = base64.b64decode(arrays[name].text.strip())
    (n,) = struct.unpack_from("<Q", raw)
    return struct.unpack_from("<%d%s" % (n // struct.calcsize(code), code), raw, 8)
assert arrays["Clearance"].get("type") == "Float64", arrays["Clearance"].get("type")
clearance, solid = values("Clearance", "d"), values("SolidId", "i")
assert len(clearance) == len(solid) == 60, len(clearance)
assert all(c == 0.5 for c, s in zip(clearance, solid) if s == 4), "e"
assert min(clearance) == 0 and all(0 <= c <= 0.5 for c in clearance)
PYEOF

# Touching blocks whose shared face x = 1 is 2 triangles on one side and a 4 x 4 grid of 32 on
# the other (STL, so nothing is welded): contact.
$PY - "$WORK/grid.stl" <<'PYEOF'
import sys
def quad_grid(axis, side, lo, hi, k):
    u, v = (axis + 1) % 3, (axis + 2) % 3
    def at(i, j):
        p = [0.0] * 3
        p[axis] = hi[axis] if side else lo[axis]
        p[u] = lo[u] + (hi[u] - lo[u]) * i / k
        p[v] = lo[v] + (hi[v] - lo[v]) * j / k
        return p
    for i in range(k):
        for j in range(k):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            yield from ([a, b, c], [a, c, d]) if side else ([a, c, b], [a, d, c])
with open(sys.argv[1], "w") as f:
    f.write("solid gridded\n")
    for axis in range(3):
        for side in range(2):
            for tri in quad_grid(axis, side, [1, 0, 0], [2, 1, 1], 4):
                f.write("facet normal 0 0 0\nouter loop\n")
                for p in tri:
                    f.write("vertex %r %r %r\n" % tuple(p))
                f.write("endloop\nendfacet\n")
    f.write("endsolid gridded\n")
PYEOF
box_obj plain 0 0 0 1 1 1 0 >"$WORK/plain.obj"
run "overlaps tessellated" "$PIERCE" overlaps "$WORK/plain.obj" "$WORK/grid.stl" --clearance 0.1 --rays axes:n=32 \
  -o "$WORK/t.json"
$PY -c 'import json, sys; p = json.load(open(sys.argv[1]))["pairs"]; sys.exit(not (len(p) == 1 and p[0]["kind"] == "contact" and p[0]["gap"] == 0))' \
  "$WORK/t.json" || fail "differently tessellated shared face: expected one contact"

expect_error "negative clearance" "--clearance" -- "$PIERCE" overlaps "$WORK/blocks.obj" --clearance -1

finish
