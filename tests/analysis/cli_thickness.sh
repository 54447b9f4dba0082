#!/usr/bin/env bash
# `pierce thickness` on meshes: CSV columns and values for two boxes sharing a face, the thin
# flag, an open box (nan where rays escape), per-vertex rows, JSON statistics, VTP arrays.
source "$(dirname "$0")/../cli/lib.sh"
MAKE_MODELS=${2:?usage: $0 PIERCE_BINARY MAKE_MODELS_BINARY}

{ box_obj a 0 0 0 1 1 1 0; box_obj b 1 0 0 3 1 1 8; } >"$WORK/boxes.obj"
run "thickness csv" "$PIERCE" thickness "$WORK/boxes.obj" --per face --min 1.5 -o "$WORK/t.csv"

# Columns by name, whatever their order.
$PY - "$WORK/t.csv" <<'PYEOF' || fail "boxes: CSV content"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
need = ["id", "solid", "x", "y", "z", "thickness", "thin"]
missing = [c for c in need if c not in rows[0]]
assert not missing, f"missing columns {missing}"
assert len(rows) == 24, len(rows)
for r in rows:
    solid, x, t = int(r["solid"]), float(r["x"]), float(r["thickness"])
    # b's faces at x = 1 and x = 3 measure its width 2; every other face 1.
    want = 2.0 if solid == 1 and x in (1.0, 3.0) else 1.0
    assert abs(t - want) < 1e-6, (r, want)
    assert r["thin"] == ("1" if t < 1.5 else "0"), r
assert [int(r["id"]) for r in rows] == list(range(24))
PYEOF

# Open box (no +z face): the -z face's rays escape -> nan, not thin.
box_obj open 0 0 0 1 1 1 0 | head -n -2 >"$WORK/open.obj"
run "open box" "$PIERCE" thickness "$WORK/open.obj" --per face --min 5 -o "$WORK/open.csv"
$PY - "$WORK/open.csv" <<'PYEOF' || fail "open box: nan rows"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 10, len(rows)
nan = [r for r in rows if r["thickness"] == "nan"]
assert len(nan) == 2 and all(float(r["z"]) == 0 and r["thin"] == "0" for r in nan), nan
assert all(abs(float(r["thickness"]) - 1) < 1e-6 and r["thin"] == "1" for r in rows if r not in nan)
PYEOF
grep -q "2 without exit" "$WORK/stdout" || fail "open box: summary lacks the no-exit count: $(cat "$WORK/stdout")"

# Per vertex: one row per vertex of the file.
run "per vertex" "$PIERCE" thickness "$WORK/boxes.obj" -o "$WORK/v.csv"
[ "$(($(wc -l <"$WORK/v.csv") - 1))" -eq 16 ] || fail "per vertex: expected 16 rows"

# STL stores three corners per facet; they are welded by exact position, so a box in STL (ASCII
# and binary) has 8 vertex rows, as ParaView shows it, each measuring the box along the averaged
# normal (the corner diagonal, sqrt 3 for the unit cube).
$PY - "$WORK" <<'PYEOF' || fail "writing the STL boxes"
import struct, sys
v = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
q = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
tris = [t for a, b, c, d in q for t in ((a, b, c), (a, c, d))]
with open(sys.argv[1] + "/box.stl", "w") as f:
    f.write("solid box\n")
    for t in tris:
        f.write(" facet normal 0 0 0\n  outer loop\n")
        for i in t: f.write("   vertex %g %g %g\n" % v[i])
        f.write("  endloop\n endfacet\n")
    f.write("endsolid box\n")
with open(sys.argv[1] + "/box_bin.stl", "wb") as f:
    f.write(b"\0" * 80 + struct.pack("<I", len(tris)))
    for t in tris: f.write(struct.pack("<12fH", 0, 0, 0, *[c for i in t for c in v[i]], 0))
PYEOF
for stl in box box_bin; do
  run "per vertex $stl.stl" "$PIERCE" thickness "$WORK/$stl.stl" -o "$WORK/$stl.csv"
  $PY - "$WORK/$stl.csv" <<'PYEOF' || fail "$stl.stl: one row per welded vertex"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 8, len(rows)
assert len({(r["x"], r["y"], r["z"]) for r in rows}) == 8
assert all(abs(float(r["thickness"]) - math.sqrt(3)) < 1e-6 for r in rows), rows
PYEOF
  "$PIERCE" info "$WORK/$stl.stl" | grep -q "triangles 12, vertices 8 (8 distinct positions)" ||
    fail "$stl.stl: info does not report 8 welded vertices"
done

# JSON: per-solid statistics and elements.
run "json" "$PIERCE" thickness "$WORK/boxes.obj" --per face -o "$WORK/t.json"
$PY - "$WORK/t.json" <<'PYEOF' || fail "json content"
import json, sys
j = json.load(open(sys.argv[1]))
s = {x["name"]: x for x in j["solids"]}
assert abs(s["a"]["min"] - 1) < 1e-6 and abs(s["a"]["max"] - 1) < 1e-6, s["a"]
assert abs(s["b"]["max"] - 2) < 1e-6 and abs(s["b"]["percentiles"]["p50"] - 1) < 1e-6, s["b"]
assert sum(s["b"]["histogram"]["counts"]) == 12
assert len(j["elements"]) == 24 and j["method"] == "ray"
PYEOF

# VTP: ParaView's reader sees the arrays (when VTK's Python module is there).
run "vtp" "$PIERCE" thickness "$WORK/boxes.obj" --per face --min 1.5 -o "$WORK/t.vtp"
if $PY -c "import vtkmodules.vtkIOXML" 2>/dev/null; then
  $PY - "$WORK/t.vtp" <<'PYEOF' || fail "vtp content"
import sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
r = vtkXMLPolyDataReader(); r.SetFileName(sys.argv[1]); r.Update()
d = r.GetOutput()
assert d.GetNumberOfCells() == 24 and d.GetNumberOfPoints() == 16, (d.GetNumberOfCells(), d.GetNumberOfPoints())
cd = d.GetCellData()
assert cd.GetArray("Thickness").GetRange() == (1.0, 2.0), cd.GetArray("Thickness").GetRange()
assert cd.GetArray("Thin").GetRange() == (0.0, 1.0)
assert cd.GetArray("SolidId").GetRange() == (0.0, 1.0)
PYEOF
else
  echo "note: VTK Python module missing, VTP content not checked"
fi

# The cone and sphere methods run and give per-box widths on faces (sphere: ball radius).
run "sphere" "$PIERCE" thickness "$WORK/boxes.obj" --per face --method sphere -o "$WORK/s.csv"
run "cone" "$PIERCE" thickness "$WORK/boxes.obj" --per face --method cone --cone-angle 10 -o "$WORK/c.csv"
$PY - "$WORK/c.csv" <<'PYEOF' || fail "cone values"
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    t = float(r["thickness"])
    assert 1 - 1e-6 <= t <= 2 / 0.99, r
PYEOF
finish
