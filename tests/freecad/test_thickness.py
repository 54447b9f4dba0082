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
    run = thickness_map.run([b], ThicknessOptions(per="face", threshold=5.0, on_brep=False, max_edge="auto"), doc=doc)
    s = run.solids[0]
    m = s.meshed
    n = np.cross(m.vertices[m.triangles[:, 1]] - m.vertices[m.triangles[:, 0]],
                 m.vertices[m.triangles[:, 2]] - m.vertices[m.triangles[:, 0]])
    x_facing = int(np.count_nonzero(np.abs(n[:, 0]) > 0.99 * np.linalg.norm(n, axis=1)))
    c.check(len(m.triangles) > 12, "long edges were split (%d triangles)" % len(m.triangles))
    c.check(s.thin_count == x_facing, "narrow box: the %d x-facing triangles are thin below 5 mm (got %d)"
            % (x_facing, s.thin_count))
    # The x-facing walls are one thin region, both sides: 4 thick, 2 x 100 mm^2.
    c.check(len(run.thin_regions) == 1, "narrow box: one thin region (got %d)" % len(run.thin_regions))
    if run.thin_regions:
        g = run.thin_regions[0]
        c.near(g.thickness, 4.0, 1e-9 * 4, "narrow box: thin region minimum")
        c.near(g.area, 200.0, 20.0, "narrow box: thin region area, both sides")
        c.check(run.region_label(g) == "Narrow", "thin region names its solid: " + run.region_label(g))
    c.check("1 thin region(s) (thickness < 5" in run.summary(), "summary lists the regions: " + run.summary())
    colours = {tuple(round(x, 3) for x in col[:3]) for col in s.result_object.ThicknessColors}
    c.check((1.0, 0.0, 1.0) in colours, "thin triangles are magenta (colours %s)" % sorted(colours))

    # On the exact B-rep (the default with a CAD-reading Pierce): a thin plate with 0.01 blends on
    # its edges. FreeCAD's mesh, measured as a mesh, reads false thin spots where rays start on the
    # blends' chords; on the B-rep every sample reads the sheet's 0.3 or more, and the minimum is 0.3.
    plate = solids.thin_blended_plate(doc)
    brep = thickness_map.run([plate], ThicknessOptions(per="face", max_edge="auto", create_objects=False))
    mesh = thickness_map.run([plate], ThicknessOptions(per="face", on_brep=False, create_objects=False))
    c.check(brep.model.on_brep and not mesh.model.on_brep, "on_brep: default on, off when asked")
    bv, mv = brep.solids[0].valid, mesh.solids[0].valid
    c.check(len(bv) > 100, "plate on the B-rep: %d valid samples" % len(bv))
    c.near(float(bv.min()), 0.3, 1e-6 * 43, "plate on the B-rep: min is the sheet")
    c.check(bool(np.all(bv >= 0.3 * (1 - 1e-6))), "plate on the B-rep: no sample under the sheet's 0.3")
    c.near(brep.solids[0].stats.summary.min, 0.3, 1e-6 * 43, "plate on the B-rep: summary minimum")
    c.check(float(mv.min()) < 0.5 * 0.3, "plate on FreeCAD's mesh: the false thin spots this is about (min %.4g)"
            % float(mv.min()))
    # Split on the B-rep too (max_edge "auto": 4% of the size), each piece still on its face: more
    # samples on the big flat faces, the same minimum. Not split by default, as in the CLI.
    whole = thickness_map.run([plate], ThicknessOptions(per="face", create_objects=False))
    c.check(whole.model.max_edge == 0, "long edges are not split by default (max_edge %r)" % whole.model.max_edge)
    c.check(len(bv) > 4 * len(whole.solids[0].valid), "plate on the B-rep, split: %d samples, unsplit %d"
            % (len(bv), len(whole.solids[0].valid)))
    c.near(float(whole.solids[0].valid.min()), 0.3, 1e-6 * 43, "plate on the B-rep, unsplit: min is the sheet")
    c.check("on the exact B-rep" in brep.summary() and "on FreeCAD's mesh" in mesh.summary(),
            "the summary says where it sampled: " + brep.summary().splitlines()[0])
    run = thickness_map.run([plate], ThicknessOptions(per="vertex"), doc=doc)
    s = run.solids[0]
    c.check(s.result_object.OnBrep, "result object: OnBrep")
    c.check(len(s.result_object.ThicknessColors) == s.result_object.Mesh.CountPoints,
            "B-rep mesh, per vertex: one colour per vertex of Pierce's mesh")
    c.check(bool(np.all(s.valid >= 0.3 * (1 - 1e-6))), "plate per vertex on the B-rep: no sample under 0.3 (min %.6g)"
            % float(s.valid.min()))

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

    # The default legend: the 2nd to 98th percentile of the samples without a threshold, 0 to 4x
    # the threshold with one; walls beyond an end are clamped, and the legend says so.
    tall = solids.box(doc, "Tall", (2, 10, 100))  # walls 2 (most samples), 10, and 100 (under 2%)
    doc.recompute()
    run = thickness_map.run([tall], ThicknessOptions(per="face", max_edge="auto", create_objects=False))
    v = np.concatenate([s.valid for s in run.solids])
    lo, hi = run.color_range
    c.near(lo, float(np.percentile(v, 2)), 1e-12, "default legend low end is P2")
    c.near(hi, float(np.percentile(v, 98)), 1e-12, "default legend high end is P98")
    c.check(lo == 2.0 and hi == 10.0 and run.clamped == (False, True),
            "the 100 mm end walls are clamped to the high end: range (%.4g, %.4g), clamped %s" % (lo, hi, run.clamped))
    c.check("P2 to P98" in run.summary() and "thicker walls drawn as its high end" in run.summary(),
            "the summary says how the legend was chosen: " + run.legend_text())
    run = thickness_map.run([tall], ThicknessOptions(per="face", threshold=1.5, create_objects=False))
    c.check(run.color_range == (0.0, 6.0) and run.clamped == (False, True), "with a 1.5 mm threshold the legend is 0 to 6: %s" % (run.color_range,))
    run = thickness_map.run([tall], ThicknessOptions(per="face", color_min=1.0, color_max=3.0, create_objects=False))
    c.check(run.color_range == (1.0, 3.0), "a legend range set by the user is kept: %s" % (run.color_range,))

    # The same defaults as the CLI and Python: Pierce's tessellation_defaults().
    from pierce_fc.tessellate import tessellation_defaults
    pierce_defaults = __import__("pierce_fc.locate", fromlist=["import_pierce"]).import_pierce().tessellation_defaults()
    c.check(tessellation_defaults() == dict(pierce_defaults) and pierce_defaults["max_edge"] == 0,
            "FreeCAD takes Pierce's tessellation defaults: %s" % tessellation_defaults())

    # Re-running on the same solids replaces the previous result (unless asked to keep it); results
    # are labelled with the source's Label, also one ending in digits.
    fillet = solids.box(doc, "Fillet006", (3, 3, 3), at=(0, 50, 0))
    fillet.Label = "Fillet006"
    doc.recompute()

    def maps():
        return [g for g in doc.Objects if getattr(g, "PierceAnalysis", None) == "thickness" and
                getattr(g, "PierceSources", "").startswith(fillet.Name + ":")]
    for _ in range(2):
        run = thickness_map.run([fillet], ThicknessOptions(per="face"), doc=doc)
    c.check(len(maps()) == 1, "re-running leaves one result: %s" % [g.Label for g in maps()])
    c.check(run.solids[0].result_object.Label == "Thickness Fillet006" and run.group.Label == "Thickness map Fillet006",
            "labels name the source by its Label: %r, %r" % (run.solids[0].result_object.Label, run.group.Label))
    thickness_map.run([fillet], ThicknessOptions(per="face", keep_previous=True), doc=doc)
    c.check(len(maps()) == 2, "keep_previous keeps the previous result: %d" % len(maps()))

    # The caliper on the map: a point picked on the result mesh is measured on its source solid.
    mesh_obj = run.solids[0].result_object
    reading = thickness_map.caliper_on_map(mesh_obj, (1.0, 51.0, 3.0))
    c.check(reading.status == "ok" and abs(reading.thickness - 3.0) < 1e-9 and reading.label == "Fillet006",
            "caliper on the map reads the 3 mm box: " + reading.text())
    fillet.Placement.Base = FreeCAD.Vector(100, 0, 0)
    doc.recompute()
    c.raises(thickness_map.UserError, lambda: thickness_map.caliper_on_map(mesh_obj, (1.0, 51.0, 3.0)),
             "caliper on the map of a moved solid", contains="moved or edited")

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
