"""freecadcmd: the thickness panel's caliper (thickness_map.caliper): a point picked on a face reads
the wall there on the exact B-rep; counts of excluded samples in the report."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD
    import Part

    import solids
    from pierce_fc import thickness_map
    from pierce_fc.errors import UserError

    doc = FreeCAD.newDocument("PierceCaliper")
    # A 10 x 20 x 30 box, placed away from the origin: each face reads the box's extent across it.
    box = solids.box(doc, "Box", (10, 20, 30), at=(5, -3, 2))
    doc.recompute()
    shape = box.Shape
    for i, face in enumerate(shape.Faces):
        name = "Face%d" % (i + 1)
        u0, u1, v0, v1 = face.ParameterRange
        p = face.valueAt(0.3 * u0 + 0.7 * u1, 0.6 * v0 + 0.4 * v1)
        n = face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
        extent = abs(n.x) * 10 + abs(n.y) * 20 + abs(n.z) * 30
        r = thickness_map.caliper(box, name, p)
        c.check(r.status == "ok", "%s: status %s" % (name, r.status))
        c.near(r.thickness, extent, 1e-9, "%s: wall" % name)
        c.near(math.dist(r.point, (p.x, p.y, p.z)), 0.0, 1e-9, "%s: reading at the picked point" % name)
        c.check("wall %.6g mm" % extent in r.text(), "%s: text '%s'" % (name, r.text()))

    # A cylinder of radius 4: picked on its curved face slightly off the surface (a pick is never
    # exactly on it), the point is projected and the wall read along the exact normal: 8.
    cyl = doc.addObject("Part::Cylinder", "Cyl")
    cyl.Radius = 4
    cyl.Height = 10
    doc.recompute()
    side = [i for i, f in enumerate(cyl.Shape.Faces) if f.Surface.__class__.__name__ == "Cylinder"][0]
    p = FreeCAD.Vector(4.001 * math.cos(0.7), 4.001 * math.sin(0.7), 3)
    r = thickness_map.caliper(cyl, "Face%d" % (side + 1), p)
    c.check(r.status == "ok", "cylinder: status %s" % r.status)
    c.near(r.thickness, 8.0, 1e-9, "cylinder: diameter through the axis")
    c.near(math.hypot(r.point[0], r.point[1]), 4.0, 1e-9, "cylinder: reading on the exact surface")

    # Clicks on one solid load it once; moved, it is loaded again and read where it now is.
    solid = box.Shape.Solids[0]
    first = thickness_map._caliper_scene(thickness_map._pierce(), solid)
    c.check(thickness_map._caliper_scene(thickness_map._pierce(), solid) is first, "the same solid: its scene reused")
    box.Placement.Base = box.Placement.Base + FreeCAD.Vector(100, 0, 0)
    doc.recompute()
    c.check(thickness_map._caliper_scene(thickness_map._pierce(), box.Shape.Solids[0]) is not first,
            "the solid moved: loaded again")
    top = [i for i, f in enumerate(box.Shape.Faces) if abs(f.normalAt(0, 0).z - 1) < 1e-12][0]
    centre = box.Shape.Faces[top].CenterOfMass
    r = thickness_map.caliper(box, "Face%d" % (top + 1), centre)
    c.near(r.thickness, 30.0, 1e-9, "moved box: wall read where it now is")
    c.near(r.point[0], centre.x, 1e-9, "moved box: reading at the new place")
    c.check(centre.x > 100, "moved box: its top's centre at x = %g" % centre.x)

    c.raises(UserError, lambda: thickness_map.caliper(box, "Edge1", shape.Vertexes[0].Point), "an edge pick",
             contains="face")
    c.raises(UserError, lambda: thickness_map.caliper(box, "Face99", shape.Vertexes[0].Point), "no such face")
    shell = doc.addObject("Part::Feature", "Sheet")
    shell.Shape = Part.makePlane(5, 5)
    doc.recompute()
    c.raises(UserError, lambda: thickness_map.caliper(shell, "Face1", FreeCAD.Vector(1, 1, 0)), "a face on no solid",
             contains="not on a solid")


fc_check.run("caliper", body)
