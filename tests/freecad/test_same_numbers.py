"""freecadcmd: the same part through every front end, default options: the same samples and
statistics.

Each test part (the heatsink-like sheet part, flat faces; the bracket, with cylinders) is written as
BREP; the CLI (`pierce thickness`,
$PIERCE_CLI), Python (pierce.load + pierce.thickness) and, when $PIERCE_PVBATCH and
$PIERCE_PARAVIEW_PLUGIN are set, ParaView (the plugin's CAD reader and Thickness filter under
pvbatch) read that file; FreeCAD's thickness map runs on the Part object with default options. All
must give the same sample count, minimum, median and P95.
"""
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402

OUT = os.environ.get("PIERCE_TEST_OUT", os.getcwd())

PVBATCH_SCRIPT = """
import json, sys
from paraview.simple import LoadPlugin, OpenDataFile, UpdatePipeline
from paraview import servermanager
import numpy as np
from vtk.numpy_interface import dataset_adapter as dsa
LoadPlugin(sys.argv[1], ns=globals())
reader = OpenDataFile(sys.argv[2])
thickness = PierceThickness(Input=reader)
data = servermanager.Fetch(thickness)
values = []
for i in range(data.GetNumberOfBlocks()):
    block = data.GetBlock(i)
    arr = block.GetPointData().GetArray("Thickness")
    if arr is None:
        arr = block.GetCellData().GetArray("Thickness")
    values.extend(dsa.vtkDataArrayToVTKArray(arr).tolist())
print("PIERCE_VALUES " + json.dumps(values))
"""


def stats(values):
    """(count of valid samples, min, median, P95) as Pierce summarises them (linear percentiles)."""
    import numpy as np
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    return len(v), float(v.min()), float(np.percentile(v, 50)), float(np.percentile(v, 95))


def body(c):
    import FreeCAD

    import solids
    from pierce_fc.locate import import_pierce
    pierce = import_pierce()

    doc = FreeCAD.newDocument("PierceSameNumbers")
    for make in (solids.heatsink, solids.bracket):
        part = make(doc)
        doc.recompute()
        compare(c, pierce, part)


def compare(c, pierce, part):
    import numpy as np
    from pierce_fc import thickness_map
    from pierce_fc.thickness_map import ThicknessOptions
    path = os.path.join(OUT, "same_numbers_%s.brep" % part.Name)
    part.Shape.exportBrep(path)
    results = {}
    run = thickness_map.run([part], ThicknessOptions(create_objects=False))
    s = run.solids[0]
    c.check(run.options.per == pierce.thickness_defaults()["per"] and run.model.max_edge == 0,
            "FreeCAD uses Pierce's defaults: per %s, max_edge %g" % (run.options.per, run.model.max_edge))
    st = s.stats.summary
    results["FreeCAD"] = (len(s.values), st.min, s.percentile(50), s.percentile(95))
    freecad_values = np.sort(s.valid)

    scene = pierce.load(path)
    res = pierce.thickness(scene)
    py = res.solids[0].summary
    pct = dict(py.percentiles)
    results["Python"] = (len(res.thickness), py.min, pct[50], pct[95])
    python_values = np.sort(np.asarray(res.thickness)[np.isfinite(res.thickness)])

    cli = os.environ.get("PIERCE_CLI")
    c.check(bool(cli) and os.path.exists(cli), "the CLI is given: %r" % cli)
    if cli:
        out = os.path.join(OUT, "same_numbers_%s.json" % part.Name)
        p = subprocess.run([cli, "thickness", path, "-o", out, "--force"], capture_output=True, text=True)
        c.check(p.returncode == 0, "pierce thickness ran: %s" % p.stderr.strip())
        if p.returncode == 0:
            j = json.load(open(out))
            solid = j["solids"][0]
            results["CLI"] = (solid["elements"], solid["min"], solid["percentiles"]["p50"],
                              solid["percentiles"]["p95"])

    pvbatch, plugin = os.environ.get("PIERCE_PVBATCH"), os.environ.get("PIERCE_PARAVIEW_PLUGIN")
    if pvbatch and plugin and os.path.exists(plugin):
        script = os.path.join(OUT, "same_numbers_pvbatch.py")
        open(script, "w").write(PVBATCH_SCRIPT)
        p = subprocess.run([pvbatch, script, plugin, path], capture_output=True, text=True)
        line = [x for x in p.stdout.splitlines() if x.startswith("PIERCE_VALUES ")]
        c.check(p.returncode == 0 and bool(line), "pvbatch ran: %s" % (p.stderr.strip()[-500:]))
        if line:
            values = json.loads(line[0][len("PIERCE_VALUES "):])
            n, lo, med, p95 = stats([math.nan if v is None else v for v in values])
            results["ParaView"] = (len(values), lo, med, p95)
    else:
        print("ParaView not compared: PIERCE_PVBATCH / PIERCE_PARAVIEW_PLUGIN not set", flush=True)

    for name, r in sorted(results.items()):
        print("%s %-8s samples %d, min %.9g, median %.9g, P95 %.9g" % ((part.Label, name) + tuple(r)), flush=True)
    ref = results["Python"]
    for name, r in sorted(results.items()):
        c.check(r[0] == ref[0], "%s %s: %d samples, Python %d" % (part.Label, name, r[0], ref[0]))
        for k, what in ((1, "min"), (2, "median"), (3, "P95")):
            c.check(abs(r[k] - ref[k]) <= 1e-9 * max(1.0, abs(ref[k])), "%s %s %s %.12g, Python %.12g" % (
                part.Label, name, what, r[k], ref[k]))
    c.check(len(freecad_values) == len(python_values) and bool(np.allclose(freecad_values, python_values,
                                                                           rtol=1e-12, atol=0)),
            "FreeCAD and Python give the same sorted values")
    c.check("median %.4g" % ref[2] in run.summary(), "the panel's summary prints the same median: %s" %
            run.summary().splitlines()[0])


fc_check.run("same_numbers", body)
