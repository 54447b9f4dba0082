"""freecadcmd: overlap check on touching, interpenetrating, fused and duplicated solids."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD
    import Part

    import solids
    from pierce_fc import overlap_check
    from pierce_fc.overlap_check import OverlapOptions

    doc = FreeCAD.newDocument("PierceOverlaps")
    opts = OverlapOptions(grid=32)

    # Interpenetrating boxes: B starts 2.5 mm inside A along x.
    a = solids.box(doc, "A", (10, 10, 10))
    b = solids.box(doc, "B", (10, 10, 10), at=(7.5, 2, 3))
    far = solids.box(doc, "Far", (3, 3, 3), at=(40, 0, 0))
    run = overlap_check.run([a, b, far], opts, doc=doc)
    inter = run.of_kind("interference")
    c.check(len(inter) == 1, "one interpenetrating pair (got %d)" % len(inter))
    if inter:
        f = inter[0]
        c.check({f.a.label, f.b.label} == {"A", "B"}, "the pair is A, B (got %s, %s)" % (f.a.label, f.b.label))
        c.near(f.depth, 2.5, 1e-3, "interpenetration depth")
        c.check("Face2" in f.faces_a, "A's face at x = 10 (Face2) bounds the overlap: %s" % f.faces_a)
        c.check("Face1" in f.faces_b, "B's face at x = 7.5 (Face1) bounds the overlap: %s" % f.faces_b)
        sel = dict((o.Name, subs) for o, subs in f.selection())
        c.check(set(sel) == {a.Name, b.Name}, "selection targets both objects")
        c.check(f.result_object is not None and f.result_object.Shape.Length > 0, "a marker segment was created")
        c.check("depth 2.5" in f.describe(), "row text: " + f.describe())
    c.check(not run.of_kind("contact"), "no contacts between interpenetrating boxes")

    # Touching boxes: a contact, not an overlap.
    t1 = solids.box(doc, "Left", (10, 10, 10), at=(0, 30, 0))
    t2 = solids.box(doc, "Right", (4, 10, 10), at=(10, 30, 0))
    run = overlap_check.run([t1, t2], opts, doc=doc)
    c.check(not run.of_kind("interference"), "touching boxes do not interpenetrate")
    contacts = run.of_kind("contact")
    c.check(len(contacts) == 1, "one contact (got %d)" % len(contacts))
    if contacts:
        f = contacts[0]
        c.near(f.area, 100.0, 1e-6, "contact area")
        c.check(f.faces_a == ["Face2"] and f.faces_b == ["Face1"],
                "contact faces Left.Face2 / Right.Face1 (got %s / %s)" % (f.faces_a, f.faces_b))

    # Fused solids are one solid: nothing to report. The same boxes as a compound of two solids
    # in one object interpenetrate, reported as solids 1 and 2 of that object.
    fused = solids.add(doc, "Fused", a.Shape.fuse(b.Shape).removeSplitter())
    run = overlap_check.run([fused], opts, doc=doc)
    c.check(len(run.model.solids) == 1 and not run.findings, "fused solid: one solid, no findings")
    comp = solids.add(doc, "Compound", Part.makeCompound([a.Shape, b.Shape]))
    run = overlap_check.run([comp], opts, doc=doc)
    inter = run.of_kind("interference")
    c.check(len(inter) == 1 and inter and inter[0].a.obj is comp and inter[0].b.obj is comp,
            "compound: its two solids interpenetrate")
    if inter:
        c.near(inter[0].depth, 2.5, 1e-3, "compound interpenetration depth")
        c.check(inter[0].a.label == "Compound (solid 1)", "solid labels: %s" % inter[0].a.label)

    # A sphere inside a box: interpenetration depth is the sphere's diameter on axis rays.
    box = solids.box(doc, "Housing", (20, 20, 20), at=(100, 0, 0))
    ball = solids.add(doc, "Ball", Part.makeSphere(3, FreeCAD.Vector(110, 10, 10)))
    run = overlap_check.run([box, ball], OverlapOptions(grid=48, create_objects=False), doc=doc)
    inter = run.of_kind("interference")
    c.check(len(inter) == 1, "ball in box: one pair")
    if inter:
        # Axis rays of a 48-cell grid pass within half a cell (0.21 mm) of the centre: chord >= 5.9.
        c.near(inter[0].depth, 6.0, 0.1, "ball in box: depth ~ diameter")

    # Identical boxes: coincident faces on the same side, and a full-depth overlap.
    d1 = solids.box(doc, "Twin1", (5, 5, 5), at=(0, 100, 0))
    d2 = solids.box(doc, "Twin2", (5, 5, 5), at=(0, 100, 0))
    run = overlap_check.run([d1, d2], OverlapOptions(grid=16, create_objects=False), doc=doc)
    c.check(len(run.of_kind("coincident")) == 1, "twins: coincident faces reported")
    inter = run.of_kind("interference")
    c.check(len(inter) == 1 and abs(inter[0].depth - 5.0) < 1e-3, "twins: overlap depth 5")

    # Pairs by kind (pierce.clearance, as `pierce overlaps --clearance 1`): A/B clash 2.5 deep,
    # Left/Right touch, a 0.3 gap is a clearance of exactly 0.3; Far is not reported.
    g1 = solids.box(doc, "GapLeft", (10, 10, 10), at=(0, 60, 0))
    g2 = solids.box(doc, "GapRight", (10, 10, 10), at=(10.3, 60, 0))
    run = overlap_check.run([a, b, far, t1, t2, g1, g2], OverlapOptions(grid=32, clearance=1.0), doc=doc)
    got = sorted((p.kind, p.a.label, p.b.label) for p in run.pairs)
    c.check(got == [("clash", "A", "B"), ("clearance", "GapLeft", "GapRight"), ("contact", "Left", "Right")],
            "pairs by kind: %s" % got)
    c.check([p.number for p in run.pairs] == list(range(1, len(run.pairs) + 1)), "pairs are numbered from 1")
    for p in run.pairs:
        if p.kind == "clash":
            c.near(p.depth, 2.5, 0.025, "clash depth")
            c.check(p.finding is not None and p.finding.kind == "interference", "the clash row selects its faces")
        elif p.kind == "contact":
            c.check(p.gap == 0.0, "contact gap 0: %r" % p.gap)
        else:
            c.near(p.gap, 0.3, 1e-9, "clearance gap")
            c.check(p.point_b is not None and abs(p.point_b[0] - p.point[0]) > 0.29, "clearance has both points")
    text = run.summary()
    c.check("1 clash, 1 contact, 1 clearance" in text and "(%.4g, " % run.pairs[0].point[0] in text,
            "the summary has the counts and each pair's point: %s" % text.splitlines()[:2])
    markers = [o for o in doc.Objects if getattr(o, "PierceAnalysis", None) == "overlaps"]
    run = overlap_check.run([a, b, far, t1, t2, g1, g2], OverlapOptions(grid=32, clearance=1.0), doc=doc)
    again = [o for o in doc.Objects if getattr(o, "PierceAnalysis", None) == "overlaps" and
             o.PierceSources == run.group.PierceSources]
    c.check(len(again) == 1 and len(markers) >= 1, "re-running replaces the markers' folder: %d" % len(again))
    labels = sorted(o.Label for o in run.group.Group)
    want = sorted("Pair %d %s" % (p.number, p.kind) for p in run.pairs if p.kind != "clearance")
    # (FreeCAD appends a number to a label another result in the document already has.)
    c.check(len(labels) == len(want) == 2 and all(x.startswith(w) for x, w in zip(labels, want)),
            "marker labels are short and name the rows: %s" % labels)

    # Solids of a compound are named as the tree names them, numbered from 1.
    k1 = solids.box(doc, "Solid", (4, 4, 4), at=(0, 200, 0))
    k2 = solids.box(doc, "Solid001", (4, 4, 4), at=(3, 200, 0))
    doc.recompute()
    assy = doc.addObject("Part::Compound", "Assembly")
    assy.Links = [k1, k2]
    doc.recompute()
    run = overlap_check.run([assy], OverlapOptions(grid=16, create_objects=False), doc=doc)
    c.check([(p.a.label, p.b.label) for p in run.pairs] == [("Solid", "Solid001")],
            "compound's solids named by their tree Labels: %s" % [(p.a.label, p.b.label) for p in run.pairs])
    c.check("'Assembly' (2 solids)" in run.summary().splitlines()[0], "header names the compound once: %s"
            % run.summary().splitlines()[0])

    c.check(a.Shape.isValid() and abs(a.Shape.Volume - 1000) < 1e-9, "inputs unchanged")


fc_check.run("overlaps", body)
