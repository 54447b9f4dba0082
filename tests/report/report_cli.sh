#!/usr/bin/env bash
# `pierce report`: the data the page carries (findings, statistics, checks, exactness cost,
# provenance), that the tables do not change when the 3D view is decimated, that the file loads
# nothing from outside itself, and the command's errors. Usage: report_cli.sh PIERCE MAKE_MODELS.
source "$(dirname "$0")/../cli/lib.sh"
MAKE_MODELS=${2:?usage: $0 PIERCE MAKE_MODELS}
HERE=$(cd "$(dirname "$0")" && pwd)

"$MAKE_MODELS" "$WORK/models" >/dev/null || fail "writing the CAD models"
$PY "$HERE/report_models.py" blocks "$WORK/blocks.obj" || fail "writing the blocks"

run "report on the pocket part" "$PIERCE" report "$WORK/models/pocket_part.step" --per face --min 1 --max 30 \
  -o "$WORK/pocket.html"
grep -q "^report $WORK/pocket.html: .* 2 thin regions" "$WORK/stdout" || fail "pocket: summary line: $(cat "$WORK/stdout")"
run "report on the blocks" "$PIERCE" report "$WORK/blocks.obj" --per face --min 1.2 --clearance 0.5 -o "$WORK/blocks.html"
# The same model, its view limited to fewer triangles than it has (a finer tessellation).
run "decimated view" "$PIERCE" report "$WORK/models/pocket_part.step" --deflection 0.01 --angular-deflection 1 --per face --min 1 \
  --display-triangles 1000 -o "$WORK/fine_small.html"
run "full view" "$PIERCE" report "$WORK/models/pocket_part.step" --deflection 0.01 --angular-deflection 1 --per face --min 1 \
  -o "$WORK/fine_full.html"

# Markup in a solid's name and in the title stays text: it can neither end the data's <script> nor
# add elements.
{ echo 'o </script><b>x'; echo 'v 0 0 0'; echo 'v 1 0 0'; echo 'v 0 1 0'; echo 'v 0 0 1'
  echo 'f 1 3 2'; echo 'f 1 2 4'; echo 'f 1 4 3'; echo 'f 2 3 4'; } >"$WORK/markup.obj"
run "markup in names" "$PIERCE" report "$WORK/markup.obj" --title '<i>&"title"</i>' -o "$WORK/markup.html"
# Coordinates beyond Embree's range: the exact kernel measures, the epsilon baseline cannot.
{ echo 'v 0 0 0'; echo 'v 1e18 0 0'; echo 'v 0 1e18 0'; echo 'v 0 0 1e18'
  echo 'f 1 3 2'; echo 'f 1 2 4'; echo 'f 1 4 3'; echo 'f 2 3 4'; } >"$WORK/huge.obj"
run "beyond Embree's range" "$PIERCE" report "$WORK/huge.obj" -o "$WORK/huge.html"

PYTHONPATH="$HERE" $PY - "$WORK" "$WORK/models/pocket_part.step" <<'PYEOF' || fail "report content"
import os, re, sys
from report_models import report_data, network_references
work, step = sys.argv[1], sys.argv[2]
pages = {n: open(os.path.join(work, n + ".html"), encoding="utf-8").read()
         for n in ("pocket", "blocks", "fine_small", "fine_full", "markup")}
markup = pages["markup"]
assert report_data(markup)["solid_names"] == ["</script><b>x"], report_data(markup)["solid_names"]
huge = report_data(open(os.path.join(work, "huge.html"), encoding="utf-8").read())
assert "beyond what Embree" in huge["exactness"]["skipped"] and huge["exactness"]["rays"] == 0, huge["exactness"]
assert huge["solids"][0]["valid"] == 4, huge["solids"]
assert "<title>Pierce report: &lt;i&gt;&amp;&quot;title&quot;&lt;/i&gt;</title>" in markup
# Every "</script" is the end of one of the page's own five <script> elements.
assert markup.count("<script") == markup.count("</script") == 5, (markup.count("<script"), markup.count("</script"))
for name, html in pages.items():
    assert html.startswith("<!DOCTYPE html>"), name
    assert not network_references(html), (name, network_references(html)[:3])
    assert "THREE.OrbitControls" in html and "REVISION" in html, name + ": three.js not inlined"
    assert not re.search(r"\{\{\w+\}\}|/\*\{\{", html.split('id="pierce-data"')[0]), name + ": a template marker left"

# The pocket part: floors 0.6 and 0.8 are thin walls, measured on the B-rep; 1.5 is not.
d = report_data(pages["pocket"])
thin = [f for f in d["findings"] if f["kind"] == "thin"]
thick = [f for f in d["findings"] if f["kind"] == "thick"]
assert [round(f["thickness"], 9) for f in thin] == [0.6, 0.8], thin
assert [f["n"] for f in d["findings"]] == list(range(1, len(d["findings"]) + 1))
assert thick and all(f["thickness"] > 30 for f in thick), thick
# Each floor's extreme sample and its exit lie on the floor's two faces, one above the other.
assert all(abs(abs(f["point"][2] - f["point_b"][2]) - f["thickness"]) < 1e-9 for f in thin), thin
(s,) = d["solids"]
assert s["checks"]["closed"] and s["checks"]["non_manifold_edges"] == 0, s
assert "tessellation" in s["checks"], "CAD: the tessellation check is missing"
assert s["thickness"]["min"] == thin[0]["thickness"] and s["thin"] > 0, s
assert sum(s["histogram"]["counts"]) == s["valid"], s
assert s["elements"] == s["valid"] + s["no_exit"] + s["no_normal"] + s["tessellation"], s
x = d["exactness"]
assert x["exact_kernel"] == "queue" and 0 < x["rays"] <= x["budget"] == 20000, x
assert x["rays"] == s["elements"] and x["stride"] == 1, x
assert x["exact_ms"] > 0 and x["epsilon_ms"] > 0, x
assert x["wrong"] == x["missed"] + x["spurious"] + x["off"] <= x["rays"], x
assert (x["off"] > 0) == (x["max_error"] > x["tolerance"]), x
p = d["provenance"]
assert "report" in p["command"] and "--min 1" in p["command"], p
assert p["inputs"] == [{"path": step, "bytes": os.path.getsize(step)}], p
assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", p["date"]), p
assert set(p["dependencies"]) == {"Embree", "oneTBB", "OpenCASCADE", "three.js"}, p
assert all(p["dependencies"].values()), p
m = d["mesh"]
assert m["triangles_shown"] == m["triangles_model"] == s["checks"]["triangles"] and m["cell"] == 0, m

# The blocks: a, b and c are 1 thick (thin below 1.2); c-d clash 0.5 deep, a-b touch, b-c 0.3 apart.
d = report_data(pages["blocks"])
names = d["solid_names"]
thin = [f for f in d["findings"] if f["kind"] == "thin"]
assert sorted(names[f["solid"]] for f in thin) == ["a", "b", "c"], thin
assert all(abs(f["thickness"] - 1) < 1e-9 for f in thin), thin
pairs = [(f["kind"], names[f["solid"]], names[f["solid_b"]]) for f in d["findings"] if "solid_b" in f]
assert pairs == [("clash", "c", "d"), ("contact", "a", "b"), ("clearance", "b", "c")], pairs
clash, contact, gap = [f for f in d["findings"] if "solid_b" in f]
assert abs(clash["depth"] - 0.5) <= 0.005 and clash["gap"] is None and clash["volume"] > 0, clash
assert contact["gap"] == 0 and contact["depth"] is None, contact
assert abs(gap["gap"] - 0.3) <= 1e-9, gap
assert "pairs" in d["mesh"], "no clearance / clash map"
assert d["options"]["clearance"] == 0.5 and d["options"]["max_thickness"] is None

# Decimating the view leaves every table as it was.
small, full = report_data(pages["fine_small"]), report_data(pages["fine_full"])
assert full["mesh"]["triangles_model"] > 1000, full["mesh"]["triangles_model"]
assert small["mesh"]["triangles_shown"] <= 1000 < small["mesh"]["triangles_model"] and small["mesh"]["cell"] > 0, small["mesh"]
for key in ("findings", "solids", "thickness_range"):
    assert small[key] == full[key], key
PYEOF

# Errors: no -o, an existing report, a missing model, --max below --min.
expect_error "no -o" "--out is required" -- "$PIERCE" report "$WORK/blocks.obj"
expect_error "existing report" "pocket.html" -- "$PIERCE" report "$WORK/blocks.obj" -o "$WORK/pocket.html"
expect_error "missing model" "nowhere.step" -- "$PIERCE" report "$WORK/nowhere.step" -o "$WORK/x.html"
expect_error "max below min" "--max must not be below --min" -- "$PIERCE" report "$WORK/blocks.obj" --min 2 --max 1 -o "$WORK/x.html"
[ ! -e "$WORK/x.html" ] || fail "a failed report left a file"
run "--force replaces" "$PIERCE" report "$WORK/blocks.obj" -o "$WORK/pocket.html" --force
finish
