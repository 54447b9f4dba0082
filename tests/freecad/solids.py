"""Part solids with known answers, shared by the FreeCAD tests."""
import FreeCAD
import Part


def add(doc, name, shape):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = shape
    return obj


def box(doc, name="Box", size=(10, 10, 10), at=(0, 0, 0)):
    return add(doc, name, Part.makeBox(size[0], size[1], size[2], FreeCAD.Vector(*at)))


def hollow_sphere(doc, name="Shell", outer=1.0, inner=0.95):
    shape = Part.makeSphere(outer).cut(Part.makeSphere(inner))
    return add(doc, name, shape.Solids[0])


def thin_blended_plate(doc, name="Plate"):
    """A 30 x 30 x 0.3 sheet whose edges are filleted with radius 0.01, with a through hole of
    radius 3.75 at its centre (the OCCT tests' thin_blended_plate): its mesh alone reads walls far
    under the sheet's 0.3 where rays start on the blends' chords; the B-rep's thinnest wall is 0.3."""
    plate = Part.makeBox(30, 30, 0.3)
    plate = plate.makeFillet(0.01, plate.Edges)
    hole = Part.makeCylinder(3.75, 0.9, FreeCAD.Vector(15, 15, -0.3))
    return add(doc, name, plate.cut(hole).Solids[0])


def heatsink(doc, name="Heatsink"):
    """A heatsink-like sheet part: a 40 x 30 x 1.5 base with five 0.8 mm fins 12 mm tall, a 1 x 1
    pocket under the base between two fins leaving a 0.1 mm floor (the one thin spot, about 2 mm^2
    both sides), and a knife edge: the base's front edge chamfered down to 0.05 mm."""
    base = Part.makeBox(40, 30, 1.5)
    fins = [Part.makeBox(0.8, 30, 12, FreeCAD.Vector(3 + 8 * k, 0, 1.5)) for k in range(5)]
    shape = base.fuse(fins)
    pocket = Part.makeBox(1, 1, 1.4, FreeCAD.Vector(7.5, 14.5, 0))
    # A wedge along the base's front (y = 0) edge: the base thins from 1.5 to 0.05 over 0.5 mm.
    wedge = Part.makePolygon([FreeCAD.Vector(0, -0.01, 0.05), FreeCAD.Vector(0, 0.5, 1.51),
                              FreeCAD.Vector(0, -0.01, 1.51), FreeCAD.Vector(0, -0.01, 0.05)])
    cutter = Part.Face(wedge).extrude(FreeCAD.Vector(3 - 0.01, 0, 0))
    shape = shape.cut([pocket, cutter]).removeSplitter()
    return add(doc, name, shape.Solids[0])


def bracket(doc, name="Bracket"):
    """A 60 x 40 x 6 plate with a boss (radius 9, 18 tall) around a through hole (radius 5) and a
    2 mm rib 12 tall: walls from 2 to 12 mm, curved and flat."""
    plate = Part.makeBox(60, 40, 6)
    boss = Part.makeCylinder(9, 18, FreeCAD.Vector(42, 20, 0))
    hole = Part.makeCylinder(5, 18, FreeCAD.Vector(42, 20, 0))
    rib = Part.makeBox(30, 2, 12, FreeCAD.Vector(4, 19, 0))
    return add(doc, name, plate.fuse([boss, rib]).cut(hole).removeSplitter())
