"""freecadcmd: Export report... (pierce_fc.html_report.export) on a pocketed box and a clashing
pair: the HTML report names the solids by their labels, lists the thin floor and the clash."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "report"))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD
    import Part

    import solids
    from report_models import report_data
    from pierce_fc import html_report
    from pierce_fc.errors import UserError

    doc = FreeCAD.newDocument("PierceReport")
    block = Part.makeBox(20, 10, 5).cut(Part.makeBox(10, 6, 5, FreeCAD.Vector(5, 2, 0.4)))
    pocketed = solids.add(doc, "Pocketed", block)
    a = solids.box(doc, "A", (10, 10, 10), at=(0, 30, 0))
    b = solids.box(doc, "B", (10, 10, 10), at=(7.5, 32, 3))
    path = os.path.join(os.environ.get("PIERCE_TEST_OUT", "."), "freecad_report.html")
    out = html_report.export([pocketed, a, b], path, min_thickness=1.0, clearance=0.5)
    c.check(out == path and os.path.exists(path), "the report was written")
    with open(path, encoding="utf-8") as f:
        data = report_data(f.read())
    c.check(data["solid_names"] == ["Pocketed", "A", "B"], "solids named by label: %s" % data["solid_names"])
    thin = [f for f in data["findings"] if f["kind"] == "thin"]
    c.check(len(thin) == 1, "one thin floor (got %d)" % len(thin))
    if thin:
        c.near(thin[0]["thickness"], 0.4, 1e-9, "the floor's thickness, on the B-rep")
    clash = [f for f in data["findings"] if f["kind"] == "clash"]
    c.check(len(clash) == 1 and abs(clash[0]["depth"] - 2.5) < 0.05, "A and B clash 2.5 deep: %s" % clash)
    c.raises(UserError, lambda: html_report.export([], path), "nothing selected", contains="Nothing is selected")


fc_check.run("report", body)
