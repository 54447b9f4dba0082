"""freecadcmd: shotlines through stacked, interpenetrating and separated solids; face grids; CSG."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD

    import solids
    from pierce_fc import shotline
    from pierce_fc.errors import UserError
    from pierce_fc.shotline import ShotOptions

    doc = FreeCAD.newDocument("PierceShot")
    # Three touching plates along z: 1, 2 and 3 mm thick.
    p1 = solids.box(doc, "P1", (10, 10, 1))
    p2 = solids.box(doc, "P2", (10, 10, 2), at=(0, 0, 1))
    p3 = solids.box(doc, "P3", (10, 10, 3), at=(0, 0, 3))
    plates = [p1, p2, p3]
    run = shotline.run(plates, [(5, 5, -5)], [(0, 0, 1)], ShotOptions(), doc=doc)
    kinds = [r["kind"] for r in run.rows]
    c.check(kinds == ["solid"] * 3, "touching plates: three solid intervals, no gap or overlap (%s)" % kinds)
    c.check([r["labels"][0] for r in run.rows] == ["P1", "P2", "P3"], "in order P1, P2, P3")
    for r, want in zip(run.rows, (1.0, 2.0, 3.0)):
        c.near(r["los"], want, 1e-9, "%s line of sight" % r["labels"][0])
        c.near(r["obliquity_in"], 0.0, 1e-6, "%s obliquity" % r["labels"][0])
    c.near(run.rows[0]["in_point"][2], 0.0, 1e-9, "enters P1 at z = 0")
    c.near(run.rows[-1]["out_point"][2], 6.0, 1e-9, "leaves P3 at z = 6")
    c.check(run.group is not None and len(run.group.Group) == 3, "one line object per solid")
    c.near(sum(o.LineOfSight for o in run.group.Group), 6.0, 1e-9, "segments cover the 6 mm stack")

    # Oblique ray at 45 degrees through P1: LOS sqrt(2), normal thickness 1.
    run = shotline.run([p1], [(0, 5, -1)], [(1, 0, 1)], ShotOptions(create_objects=False))
    r = run.rows[0]
    c.near(r["los"], math.sqrt(2), 1e-9, "oblique LOS")
    c.near(r["obliquity_in"], 45.0, 1e-6, "oblique obliquity")
    c.near(r["normal_thickness"], 1.0, 1e-9, "oblique normal thickness")

    # Interpenetration and gap along one ray.
    a = solids.box(doc, "A", (10, 10, 10), at=(0, 50, 0))
    b = solids.box(doc, "B", (10, 10, 10), at=(7.5, 50, 0))
    g = solids.box(doc, "G", (2, 10, 10), at=(20, 50, 0))
    run = shotline.run([a, b, g], [(-5, 55, 5)], [(1, 0, 0)], ShotOptions(), doc=doc)
    rows = [(r["kind"], r["labels"], round(r["los"], 9)) for r in run.rows]
    c.check(rows == [("solid", ("A",), 7.5), ("overlap", ("A", "B"), 2.5), ("solid", ("B",), 7.5),
                     ("gap", ("B", "G"), 2.5), ("solid", ("G",), 2.0)], "rows %s" % rows)
    labels = sorted(o.Label for o in run.group.Group)
    c.check("Shot overlaps" in labels and "Shot gaps" in labels, "overlap and gap objects: %s" % labels)
    c.check(len(run.table()) == 5 and run.table()[1][1] == "overlap", "table rows")

    # Grid on P3's top face (Face6, normal +z): every ray crosses the whole stack downwards.
    top = p3.Shape.Faces[5]
    c.check(top.normalAt(0.5, 0.5).z > 0.99, "P3.Face6 faces up")
    run = shotline.run_face_grid(plates, top, 4, ShotOptions(create_objects=False))
    c.check(len(run.rays[0]) == 16, "4 x 4 grid rays (%d)" % len(run.rays[0]))
    per = run.per_solid()
    c.near(per.get("P3", 0), 16 * 3.0, 1e-6, "grid: P3 total LOS")
    c.near(per.get("P1", 0), 16 * 1.0, 1e-6, "grid: P1 total LOS")

    # CSG: A minus B along the same ray is A's part outside B.
    run = shotline.run([a, b], [(-5, 55, 5)], [(1, 0, 0)], ShotOptions(csg="difference(A, B)", create_objects=False))
    regions = [r for r in run.rows if r["kind"] == "region"]
    c.check(len(regions) == 1 and abs(regions[0]["los"] - 7.5) < 1e-9, "difference(A, B) region 7.5 mm")

    c.raises(UserError, lambda: shotline.run([a], [(0, 0, 0)], [(0, 0, 0)], ShotOptions()), "zero direction")
    c.raises(UserError, lambda: shotline.run([a, b], [(0, 0, 0)], [(1, 0, 0)], ShotOptions(csg="union(A, C)")),
             "unknown CSG solid", contains="unknown solid")


fc_check.run("shotline", body)
