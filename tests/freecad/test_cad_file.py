"""freecadcmd: the pierce module's STEP loader (OpenCASCADE) inside FreeCAD's own process, on a file
FreeCAD writes: both use the system OpenCASCADE, so they must coexist in one process."""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD
    import Import

    import solids
    from pierce_fc.locate import import_pierce
    pierce = import_pierce()
    if not c.check(pierce.HAS_CAD, "the pierce module was built with CAD loading"):
        return
    doc = FreeCAD.newDocument("PierceCad")
    a = solids.box(doc, "Base", (10, 10, 10))
    b = solids.box(doc, "Lid", (10, 10, 2), at=(0, 0, 10))
    doc.recompute()
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "stack.step")
        Import.export([a, b], path)
        scene = pierce.load(path, linear_deflection=0.01)
        c.check(len(scene) == 2, "two solids loaded (%d)" % len(scene))
        c.check(sorted(n.split("/")[-1] for n in scene.names) == ["Base", "Lid"], "names kept: %s" % scene.names)
        vols = sorted(r.volume for r in pierce.mesh_report(scene))
        c.near(vols[0], 200.0, 1e-6, "lid volume")
        c.near(vols[1], 1000.0, 1e-6, "base volume")
        r = pierce.ray_overlaps(scene, grid=8)
        c.check(not r.interferences and len(r.contacts) == 1, "the lid touches the base, no overlap")
        c.raises(pierce.InputError, lambda: pierce.load(os.path.join(d, "missing.step")), "missing STEP file",
                 contains="missing.step")


fc_check.run("cad_file", body)
