"""freecadcmd: thickness maps of Part solids with known wall thickness."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD
    import numpy as np

    import solids
    from pierce_fc import thickness_map
    from pierce_fc.thickness_map import ThicknessOptions

    doc = FreeCAD.newDocument("PierceThickness")

    # A 10 mm cube: every face sample sees the opposite wall 10 mm away.
    cube = solids.box(doc, "Cube")
    doc.recompute()  # recompute itself rewrites the shape's location: compare after it
    before = cube.Shape.exportBrepToString()
    run = thickness_map.run([cube], ThicknessOptions(per="face"))
    s = run.solids[0]
    c.near(float(np.nanmin(s.values)), 10.0, 1e-4, "cube min thickness")
    c.near(float(np.nanmax(s.values)), 10.0, 1e-4, "cube max thickness")
    c.check(s.result_object is not None and s.result_object.TypeId == "Mesh::Feature", "cube result is a Mesh::Feature")
    obj = s.result_object
    c.check(len(obj.ThicknessColors) == obj.Mesh.CountFacets, "one colour per facet (per-face sampling)")
    c.check(len(obj.Thickness) == obj.Mesh.CountFacets, "one thickness per facet")
    c.near(obj.Minimum, 10.0, 1e-4, "Minimum property")
    c.check(obj.SourceObject == cube.Name, "result names its source object")
    c.check(cube.Shape.exportBrepToString() == before, "the cube itself is unchanged")
    c.check("median 10" in run.summary(), "summary reports the median: " + run.summary().splitlines()[0])

    # Two touching boxes (10 and 4 mm wide along x): each is its own width, not the sum, not 0.
    a = solids.box(doc, "Wide", (10, 10, 10))
    b = solids.box(doc, "Narrow", (4, 10, 10), at=(10, 0, 0))
    run = thickness_map.run([a, b], ThicknessOptions(per="face"), doc=doc)
    by_label = {s.label: s for s in run.solids}
    for label, width in (("Wide", 10.0), ("Narrow", 4.0)):
        s = by_label[label]
        m = s.meshed
        normals = np.cross(m.vertices[m.triangles[:, 1]] - m.vertices[m.triangles[:, 0]],
                           m.vertices[m.triangles[:, 2]] - m.vertices[m.triangles[:, 0]])
        x_faces = np.abs(normals[:, 0]) > 0.99 * np.linalg.norm(normals, axis=1)
        c.check(bool(np.all(np.isfinite(s.values))), "%s: every face has a thickness" % label)
        c.near(float(np.median(s.values[x_faces])), width, 1e-4, "%s thickness across x (own width)" % label)
        c.near(float(np.min(s.values)), min(width, 10.0), 1e-4, "%s min thickness" % label)

    # Thin highlight: the narrow box's triangles facing x (4 mm across) are thin below 5 mm, the
    # others (10 mm across) are not.
    run = thickness_map.run([b], ThicknessOptions(per="face", threshold=5.0), doc=doc)
    s = run.solids[0]
    m = s.meshed
    n = np.cross(m.vertices[m.triangles[:, 1]] - m.vertices[m.triangles[:, 0]],
                 m.vertices[m.triangles[:, 2]] - m.vertices[m.triangles[:, 0]])
    x_facing = int(np.count_nonzero(np.abs(n[:, 0]) > 0.99 * np.linalg.norm(n, axis=1)))
    c.check(len(m.triangles) > 12, "long edges were split (%d triangles)" % len(m.triangles))
    c.check(s.thin_count == x_facing, "narrow box: the %d x-facing triangles are thin below 5 mm (got %d)"
            % (x_facing, s.thin_count))
    colours = {tuple(round(x, 3) for x in col[:3]) for col in s.result_object.ThicknessColors}
    c.check((1.0, 0.0, 1.0) in colours, "thin triangles are magenta (colours %s)" % sorted(colours))

    # Hollow sphere, outer radius 1, inner 0.95: per-vertex ray thickness 0.05 within tessellation error.
    shell = solids.hollow_sphere(doc)
    run = thickness_map.run([shell], ThicknessOptions(per="vertex", deflection=0.0005))
    s = run.solids[0]
    v = s.values
    ok = np.abs(v - 0.05) <= 0.002
    c.check(len(v) > 1000, "sphere has a fine mesh (%d vertices)" % len(v))
    c.check(ok.mean() >= 0.99, "hollow sphere: %.2f%% of vertices within 0.05 +- 0.002" % (100 * ok.mean()))
    c.near(s.percentile(50), 0.05, 0.001, "hollow sphere median")
    obj = s.result_object
    c.check(len(obj.ThicknessColors) == obj.Mesh.CountPoints, "one colour per vertex (per-vertex sampling)")

    # The sphere method (largest inscribed ball) agrees with the ray on a spherical shell; on the
    # cube it is smaller off-centre: a ball touching a triangle centroid (10/3, 10/3) of the bottom
    # face meets the side walls at diameter 20/3.
    run = thickness_map.run([shell], ThicknessOptions(per="vertex", method="sphere", deflection=0.002,
                                                      create_objects=False))
    c.near(run.solids[0].percentile(50), 0.05, 0.002, "hollow sphere, sphere-method median")
    c.check(run.solids[0].result_object is None, "create_objects=False makes no objects")
    run = thickness_map.run([cube], ThicknessOptions(per="face", method="sphere", max_edge=0, create_objects=False))
    c.near(run.solids[0].percentile(50), 20.0 / 3.0, 1e-3, "cube (12 triangles) sphere-method median")
    c.check(len(run.solids[0].values) == 12, "max_edge=0: CAD triangles kept as they are")

    # Cancelling (a token set before or during the run, or a progress callback saying no) raises
    # pierce.Cancelled and adds nothing to the document.
    from pierce_fc.locate import import_pierce
    from pierce_fc.progress import Progress
    pierce = import_pierce()
    count = len(doc.Objects)
    token = pierce.CancelToken()
    token.cancel()
    c.raises(pierce.Cancelled, lambda: thickness_map.run([cube], ThicknessOptions(), doc=doc, cancel=token),
             "run with a cancelled token")
    with Progress("test", cancel=token) as progress:
        c.raises(pierce.Cancelled, lambda: thickness_map.run([cube], ThicknessOptions(), doc=doc, progress=progress),
                 "run whose progress reports a cancelled token")
    c.raises(pierce.Cancelled, lambda: thickness_map.run([cube], ThicknessOptions(), doc=doc,
                                                         progress=lambda done, total: False),
             "run whose progress callback returns False")
    c.check(len(doc.Objects) == count, "cancelled runs add no objects")

    # Results are ordinary objects that can be deleted.
    group = doc.getObject("PierceThickness")
    names = [o.Name for o in group.Group]
    for n in names:
        doc.removeObject(n)
    doc.removeObject(group.Name)
    c.check(doc.getObject(names[0]) is None, "result objects can be deleted")
    c.check(math.isfinite(cube.Shape.Volume), "source still valid after deleting results")


fc_check.run("thickness", body)
