#!/usr/bin/env bash
# Thickness true to the CAD model from the CLI: `pierce info` reports the tessellation checked
# against the B-rep (a fold found, remeshed or flagged), `pierce thickness` samples the B-rep and
# counts tessellation artefacts apart from the statistics, `--at points.csv` measures chosen
# points (one output row per input row) and names the file and line of a bad row.
source "$(dirname "$0")/../cli/lib.sh"
MAKE_MODELS=${2:?usage: $0 PIERCE_BINARY MAKE_MODELS_BINARY}
"$MAKE_MODELS" "$WORK" || { echo "FAIL: make_models"; exit 1; }
FOLDED=$WORK/folded.brep
SHEET=$WORK/sheet.brep

# The folded triangle is found, the solid meshed again, no fold left.
run "info folded" "$PIERCE" info "$FOLDED" --deflection 0.05
grep -q "tessellation against the B-rep (26 faces): 0 folded triangles" "$WORK/stdout" ||
  fail "info: no fold expected after remeshing: $(cat "$WORK/stdout")"
grep -qE "first mesh had 1 folded triangles on 1 faces, [1-9][0-9]* faces remeshed" "$WORK/stdout" ||
  fail "info: the fold found and the faces remeshed: $(cat "$WORK/stdout")"
grep -q "folded triangles on 1 faces, meshed again" "$WORK/stderr" || fail "info: warning about the fold"
grep -q "closed, oriented: 0 boundary edges" "$WORK/stdout" || fail "info: the mesh stays closed: $(cat "$WORK/stdout")"
run "info folded json" "$PIERCE" info "$FOLDED" --deflection 0.05 --fold-remesh-rounds 0 --json
$PY - "$WORK/stdout" <<'PYEOF' || fail "info --json tessellation"
import json, sys
t = json.load(open(sys.argv[1]))["solids"][0]["tessellation"]
assert t["brep_faces"] == 26 and t["folded_triangles"] == 1 and t["folded_found"] == 1, t
assert t["faces_remeshed"] == 0 and t["remesh_rounds"] == 0 and t["sliver_triangles"] == 0, t
PYEOF
# Meshes have no tessellation check.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >"$WORK/tet.obj"
run "info mesh" "$PIERCE" info "$WORK/tet.obj" --json
$PY -c "import json; s=json.load(open('$WORK/stdout'))['solids'][0]; assert 'tessellation' not in s" ||
  fail "info: a mesh has no tessellation report"

# Fold left in place: its samples are excluded and counted, the minimum is the wall (1, the blends).
run "thickness folded" "$PIERCE" thickness "$FOLDED" --deflection 0.05 --fold-remesh-rounds 0 --per face -o "$WORK/f.json"
grep -q "excluded as tessellation artefacts" "$WORK/stdout" || fail "thickness: the summary names the exclusions"
$PY - "$WORK/f.json" <<'PYEOF' || fail "thickness folded json"
import json, sys
j = json.load(open(sys.argv[1]))
s = j["solids"][0]
tess = [e for e in j["elements"] if e["status"] == "tessellation"]
assert s["tessellation"] == len(tess) >= 1, (s, len(tess))
assert all(e["thickness"] is None and not e["thin"] for e in tess)
assert s["valid"] == s["elements"] - s["tessellation"] - s["no_exit"] - s["no_normal"], s
assert s["exact"] and s["min"] >= 1 - 1e-6, s
PYEOF

# The bent sheet: every face sample on the two big faces reads the 0.5 wall, B-rep true.
run "thickness sheet" "$PIERCE" thickness "$SHEET" --per face -o "$WORK/s.csv"
head -n 1 "$WORK/s.csv" | grep -qx "id,solid,element,x,y,z,thickness,thin,status,name,region" || fail "thickness csv header"
grep -q "sampled on the exact B-rep" "$WORK/stdout" || fail "thickness: says it sampled the B-rep"

# Per vertex: a vertex on an edge between B-rep faces is sampled per face, the smallest kept, and
# says so (JSON brep_faces per element, edge_samples per solid; VTP array BrepFaces).
run "thickness sheet per vertex" "$PIERCE" thickness "$SHEET" -o "$WORK/v.json"
grep -q "vertices on B-rep edges show the smaller of their per-face samples" "$WORK/stdout" ||
  fail "thickness per vertex: says edge vertices show the smaller sample"
$PY - "$WORK/v.json" <<'PYEOF' || fail "per-vertex json brep_faces"
import json, sys
j = json.load(open(sys.argv[1]))
e, s = j["elements"], j["solids"][0]
assert s["edge_samples"] == sum(x["brep_faces"] >= 2 for x in e) > 0, s
assert all(abs(x["thickness"] - 0.5) < 1e-9 for x in e), [x for x in e if abs(x["thickness"] - 0.5) >= 1e-9]
PYEOF
run "thickness sheet vtp" "$PIERCE" thickness "$SHEET" -o "$WORK/v.vtp"
grep -q 'Name="BrepFaces"' "$WORK/v.vtp" || fail "vtp: BrepFaces array"

# --at: points (header, optional normals) -> one row per input row, in order, id = input row.
cat >"$WORK/pts.csv" <<'CSV'
solid,x,y,z,nx,ny,nz
0,6,4,-0.01,0,0,-1
sheet,0.5,3,6,1,0,0
# a comment line is not a row

0,6,4,0.2,0,0,-1
CSV
run "--at" "$PIERCE" thickness "$SHEET" --at "$WORK/pts.csv" -o "$WORK/at.csv"
$PY - "$WORK/at.csv" <<'PYEOF' || fail "--at csv"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["id"] for r in rows] == ["0", "1", "2"], rows
assert all(r["status"] == "ok" and abs(float(r["thickness"]) - 0.5) < 1e-9 for r in rows), rows
assert abs(float(rows[0]["z"])) < 1e-12 and abs(float(rows[1]["x"]) - 0.5) < 1e-12, rows
PYEOF
printf 'x,y,z,solid\n6,4,0,0\n' >"$WORK/pts2.csv"
run "--at without normals, columns in any order" "$PIERCE" thickness "$SHEET" --at "$WORK/pts2.csv" -o "$WORK/at.json"
$PY -c "
import json; j=json.load(open('$WORK/at.json')); e=j['elements']
assert j['per']=='point' and len(e)==1 and abs(e[0]['thickness']-0.5)<1e-9, j" || fail "--at json"

# Solids by assembly name (quoted or not); the block touching the plate reads its own 2 mm.
printf 'solid,x,y,z\nplate_assy/block#2,7,2,4\n"plate_assy/plate",5,5,0\n  plate_assy/clash , 7 , 7 , 3.5\n' >"$WORK/pts3.csv"
run "--at by name" "$PIERCE" thickness "$WORK/assembly.step" --at "$WORK/pts3.csv" -o "$WORK/at3.csv"
$PY - "$WORK/at3.csv" <<'PYEOF' || fail "--at by name"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["name"] for r in rows] == ["plate_assy/block#2", "plate_assy/plate", "plate_assy/clash"], rows
assert all(abs(float(r["thickness"]) - 2) < 1e-9 and r["status"] == "ok" for r in rows), rows
PYEOF

printf 'solid,x,y,z\n0,1,2,3\n0,1,oops,3\n' >"$WORK/bad1.csv"
expect_error "--at bad number" "bad1.csv, line 3: y 'oops' is not a finite number" -- \
  "$PIERCE" thickness "$SHEET" --at "$WORK/bad1.csv"
printf 'solid,x,y,z\n0,1,2\n' >"$WORK/bad2.csv"
expect_error "--at short row" "bad2.csv, line 2: 3 fields, the header has 4" -- "$PIERCE" thickness "$SHEET" --at "$WORK/bad2.csv"
printf 'solid,x,y,z\nnope,1,2,3\n' >"$WORK/bad3.csv"
expect_error "--at unknown solid" "bad3.csv, line 2: no solid 'nope'" -- "$PIERCE" thickness "$SHEET" --at "$WORK/bad3.csv"
printf 'a,b,c\n1,2,3\n' >"$WORK/bad4.csv"
expect_error "--at header" "bad4.csv, line 1: header needs the columns solid,x,y,z" -- \
  "$PIERCE" thickness "$SHEET" --at "$WORK/bad4.csv"
printf 'solid,x,y,z,nx\n0,1,2,3,1\n' >"$WORK/bad5.csv"
expect_error "--at partial normal" "give all of nx,ny,nz or none" -- "$PIERCE" thickness "$SHEET" --at "$WORK/bad5.csv"
printf 'solid,x,y,z,nx,ny,nz\n0,1,2,3,0,0,0\n' >"$WORK/bad6.csv"
expect_error "--at zero normal" "bad6.csv, line 2: the normal nx,ny,nz is zero" -- \
  "$PIERCE" thickness "$SHEET" --at "$WORK/bad6.csv"
printf 'solid,x,y,z\n' >"$WORK/bad7.csv"
expect_error "--at no rows" "no points after the header" -- "$PIERCE" thickness "$SHEET" --at "$WORK/bad7.csv"
expect_error "--at missing file" "cannot open the points file" -- "$PIERCE" thickness "$SHEET" --at "$WORK/none.csv"
expect_error "--at vtp" "not .vtp" -- "$PIERCE" thickness "$SHEET" --at "$WORK/pts.csv" -o "$WORK/x.vtp"
[ ! -e "$WORK/x.vtp" ] || fail "--at vtp: no file expected"

# Meshes: --at works on the mesh itself (no B-rep), the sample's status and value as for faces.
run "--at mesh" "$PIERCE" thickness "$WORK/tet.obj" --at "$WORK/pts2.csv" -o "$WORK/m.csv"
$PY -c "
import csv; r=list(csv.DictReader(open('$WORK/m.csv')))
assert len(r)==1 and r[0]['status'] in ('ok','no_exit'), r" || fail "--at mesh"
finish
