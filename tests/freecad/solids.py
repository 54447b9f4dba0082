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
