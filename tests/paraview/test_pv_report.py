"""pierce_vtk.report under pvpython: the report of the active pipeline object, from the file its
reader reads (the four-block assembly as STL files through a Group Datasets) and from a source
without a file (a Box), each checked through the page's data (tests/report/report_models.py).
Needs PIERCE_BINARY (the `pierce` program) and PYTHONPATH at the built packages."""
import os
import sys
import tempfile

from paraview import simple

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "report"))
from report_models import report_data  # noqa: E402
from pierce_vtk import report  # noqa: E402

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


with tempfile.TemporaryDirectory() as work:
    # Two touching boxes, each an STL file read by ParaView's STL reader, grouped.
    stls = []
    for name, x0 in (("left", 0.0), ("right", 1.0)):
        box = simple.Box(XLength=1, YLength=1, ZLength=0.5, Center=[x0 + 0.5, 0.5, 0.25])
        path = os.path.join(work, name + ".stl")
        simple.SaveData(path, proxy=simple.Triangulate(Input=box))
        stls.append(path)
    readers = [simple.OpenDataFile(p) for p in stls]
    group = simple.GroupDatasets(Input=readers)
    simple.SetActiveSource(group)
    html = report(os.path.join(work, "files.html"), min_thickness=0.6, per="face")
    with open(html, encoding="utf-8") as f:
        data = report_data(f.read())
    check([i["path"] for i in data["provenance"]["inputs"]] == stls, "the readers' files: %s" % data["provenance"])
    thin = [f for f in data["findings"] if f["kind"] == "thin"]
    check(len(thin) == 2 and all(abs(f["thickness"] - 0.5) < 1e-6 for f in thin), "two thin plates: %s" % thin)
    kinds = [f["kind"] for f in data["findings"] if "solid_b" in f]
    check(kinds == ["contact"], "the plates touch: %s" % kinds)

    # A source without a file: its output surface.
    box = simple.Box(XLength=2, YLength=3, ZLength=0.25)
    simple.SetActiveSource(box)
    html = report(os.path.join(work, "data.html"), min_thickness=0.5, per="face")
    with open(html, encoding="utf-8") as f:
        data = report_data(f.read())
    thin = [f for f in data["findings"] if f["kind"] == "thin"]
    check(len(thin) == 1 and abs(thin[0]["thickness"] - 0.25) < 1e-6, "the box is 0.25 thick: %s" % thin)

print("%d failures" % len(failures) if failures else "report ok")
sys.exit(1 if failures else 0)
