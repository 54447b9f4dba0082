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
