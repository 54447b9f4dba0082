"""freecadcmd: bad selections give a SelectionError with a message, never another exception."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD
    import Part

    import solids
    from pierce_fc import overlap_check, shotline, thickness_map
    from pierce_fc.errors import SelectionError, UserError
    from pierce_fc.overlap_check import OverlapOptions
    from pierce_fc.selection import collect_solids
    from pierce_fc.shotline import ShotOptions
    from pierce_fc.thickness_map import ThicknessOptions

    doc = FreeCAD.newDocument("PierceSelection")
    box = solids.box(doc, "Box")
    faces = box.Shape.Faces
    open_shell = solids.add(doc, "OpenShell", Part.Shell(faces[:5]))
    closed_shell = solids.add(doc, "ClosedShell", Part.Shell(faces))
    wire = solids.add(doc, "Wire", Part.makePolygon([FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1, 0, 0),
                                                      FreeCAD.Vector(1, 1, 0)]))
    face = solids.add(doc, "Face", faces[0])
    empty = doc.addObject("Part::Feature", "Empty")
    group = doc.addObject("App::DocumentObjectGroup", "Group")
    group.addObject(box)

    commands = [
        ("thickness", lambda objs: thickness_map.run(objs, ThicknessOptions(), doc=doc)),
        ("overlaps", lambda objs: overlap_check.run(objs, OverlapOptions(grid=4), doc=doc)),
        ("shotline", lambda objs: shotline.run(objs, [(5, 5, -1)], [(0, 0, 1)], ShotOptions(), doc=doc)),
    ]
    for name, cmd in commands:
        c.raises(SelectionError, lambda: cmd([]), "%s with nothing selected" % name, contains="nothing is selected")
        c.raises(SelectionError, lambda: cmd([open_shell]), "%s on an open shell" % name, contains="open shell")
        c.raises(SelectionError, lambda: cmd([wire]), "%s on a wire" % name, contains="no solid")
        c.raises(SelectionError, lambda: cmd([face]), "%s on a face" % name, contains="faces but no solid")
        c.raises(SelectionError, lambda: cmd([empty]), "%s on an empty object" % name, contains="no shape")

    refs, warnings = collect_solids([closed_shell, open_shell, box])
    c.check([r.obj.Name for r in refs] == ["ClosedShell", "Box"], "closed shell and box are analysed")
    c.check(any("open shell" in w for w in warnings), "the open shell is a warning: %s" % warnings)
    refs, _ = collect_solids([group, box])
    c.check([r.obj.Name for r in refs] == ["Box"], "a group expands to its contents, each object once")
    c.check(issubclass(SelectionError, UserError), "selection errors are user errors")
    c.raises(UserError, lambda: thickness_map.run([box], ThicknessOptions(method="laser")), "unknown method")
    c.raises(UserError, lambda: thickness_map.run([box], ThicknessOptions(deflection=-1)), "negative deflection")
    c.raises(UserError, lambda: thickness_map.run([box], ThicknessOptions(color_min=5, color_max=1)),
             "empty legend range")
    c.check(doc.getObject("PierceThickness") is None, "failed runs create no objects")


fc_check.run("selection", body)
