"""Overlap check: interpenetrating solids (with depth), touching solids (coplanar contacts) and
coincident faces, on selected solids or a whole assembly.

GUI-free: run() returns an OverlapRun whose findings name the solids and the faces involved (so the
GUI can select them) and, when asked, adds marker objects to the document (a red segment along the
deepest interpenetration of each pair, the shared triangles of each contact). The analysed objects
are not modified.
"""
import math
from dataclasses import dataclass

import numpy as np

from .errors import UserError
from .progress import start_stage
from .tessellate import mesh_objects

SHORT = {"interference": "Clash", "contact": "Contact", "coincident": "Coincident", "duplicate": "Duplicate"}
KINDS = {
    "interference": "Interpenetration",
    "contact": "Coplanar contact",
    "coincident": "Coincident faces (same side)",
    "duplicate": "Duplicate faces in one solid",
}


class OverlapOptions:
    def __init__(self, tolerance=1e-3, grid=64, deflection=None, angular_deflection=None, create_objects=True,
                 clearance=0.0):
        self.tolerance = tolerance    # mm: faces closer than this to each other's plane are coplanar
        self.grid = grid              # rays per axis side: grid x grid rays along x, y and z
        # mm: pairs of solids closer than this are reported as "clearance" (0: clashes and contacts
        # only), as `pierce overlaps --clearance D`.
        self.clearance = clearance
        self.deflection = deflection  # mm; 0 = 0.1% of the selection's diagonal; None: Pierce's default
        self.angular_deflection = angular_deflection
        self.create_objects = create_objects

    def check(self):
        if self.tolerance < 0 or not math.isfinite(self.tolerance):
            raise UserError("The coplanar tolerance must be a length >= 0.")
        if not 1 <= self.grid <= 4096:
            raise UserError("The ray grid must have between 1 and 4096 rays per side.")
        if not (self.clearance >= 0 and math.isfinite(self.clearance)):
            raise UserError("The clearance must be a length >= 0.")


class Finding:
    """One row of the report. a, b: SolidRef (b is a for duplicates inside one solid); faces_a,
    faces_b: sub-element names ("Face3") of a.obj and b.obj; depth: how far the solids
    interpenetrate (smallest over the axes of the largest depth along axis-parallel rays), None
    for contacts; max_los: longest line of sight inside both; area: shared coplanar area."""

    def __init__(self, kind, a, b):
        self.kind = kind
        self.a = a
        self.b = b
        self.faces_a = []
        self.faces_b = []
        self.depth = None
        self.max_los = None
        self.count = 0
        self.area = 0.0
        self.where = None
        self.segment = None  # (entry, exit) of the deepest interval, interference only
        self.triangles = []  # [(p0, p1, p2)] shared coplanar triangles of a (contacts)
        self.result_object = None

    @property
    def title(self):
        return KINDS[self.kind]

    def describe(self):
        pair = self.a.label if self.a is self.b else "%s / %s" % (self.a.label, self.b.label)
        if self.kind == "interference":
            return "%s: %s, depth %.4g mm (longest line of sight %.4g mm, %d rays)" % (
                self.title, pair, self.depth, self.max_los, self.count)
        return "%s: %s, area %.4g mm^2 (%d triangle pairs)" % (self.title, pair, self.area, self.count)

    def selection(self):
        """[(object, [sub-element names])] to select for this finding."""
        out = []
        if self.a.obj is self.b.obj:
            out.append((self.a.obj, sorted(set(self.faces_a) | set(self.faces_b), key=lambda s: int(s[4:]))))
        else:
            out.append((self.a.obj, self.faces_a))
            out.append((self.b.obj, self.faces_b))
        return out


PAIR_KINDS = ("clash", "contact", "clearance")


class Pair:
    """Two solids that clash, touch or come within the clearance (pierce.clearance; the CLI's
    `pairs`): a, b are SolidRefs; number is the pair's row (from 1); gap (contact 0, clearance the
    exact smallest distance), depth, overlap_length and volume (clash) are None where they do not
    apply; point (and point_b: the closest point on b for a clearance) is where it is."""

    def __init__(self, number, a, b, p):
        self.number = number
        self.a = a
        self.b = b
        self.kind = p.kind
        nan = lambda x: None if x is None or math.isnan(x) else float(x)  # noqa: E731
        self.gap = nan(p.gap)
        self.depth = nan(p.depth)
        self.overlap_length = nan(p.overlap_length)
        self.volume = nan(p.volume)
        self.point = tuple(float(x) for x in p.point)
        pb = tuple(float(x) for x in p.point_b)
        self.point_b = None if any(math.isnan(x) for x in pb) else pb
        self.finding = None  # the matching interference or contact Finding, for its faces

    def value_text(self):
        if self.kind == "clash":
            return "depth %.4g" % self.depth if self.depth is not None else "clash"
        return "gap %.4g" % (self.gap or 0.0)

    def describe(self):
        p = self.point
        text = "%d. %s: %s / %s, %s mm at (%.4g, %.4g, %.4g)" % (
            self.number, self.kind, self.a.label, self.b.label, self.value_text(), p[0], p[1], p[2])
        if self.kind == "clash" and self.overlap_length is not None:
            text += ", longest overlap %.4g mm" % self.overlap_length
            if self.volume is not None:
                text += ", about %.4g mm^3 shared" % self.volume
        return text

    def selection(self):
        """[(object, [sub-element names])]: the faces of the matching finding, else both solids'
        objects."""
        if self.finding is not None and any(subs for _, subs in self.finding.selection()):
            return self.finding.selection()
        return [(self.a.obj, []), (self.b.obj, [])] if self.a.obj is not self.b.obj else [(self.a.obj, [])]


@dataclass(eq=False)
class OverlapRun:
    options: OverlapOptions
    model: object  # tessellate.Model
    findings: list
    ray_report: object  # pierce.RayOverlapReport
    coplanar_report: object  # pierce.CoplanarReport
    warnings: list
    group: object = None  # the document group of the result objects, once created
    pairs: list = None  # Pair per pair of solids that clash, touch or come within the clearance

    def of_kind(self, kind):
        return [f for f in self.findings if f.kind == kind]

    def pairs_of_kind(self, kind):
        return [p for p in self.pairs or [] if p.kind == kind]

    def header(self):
        """The analysed objects, each once: "'Assembly' (36 solids)", or the solids' labels."""
        objs = []
        for m in self.model.solids:
            if m.ref.obj not in objs:
                objs.append(m.ref.obj)
        parts = []
        for o in objs:
            n = sum(1 for m in self.model.solids if m.ref.obj is o)
            parts.append("'%s' (%d solids)" % (o.Label, n) if n > 1 else "'%s'" % o.Label)
        if len(objs) > 1:
            parts[-1] += "; %d solids" % len(self.model.solids)
        return ", ".join(parts)

    def summary(self):
        o = self.options
        lines = ["Pierce overlap check of %s: %d clash, %d contact, %d clearance pair(s) (%s)" % (
            self.header(), len(self.pairs_of_kind("clash")),
            len(self.pairs_of_kind("contact")), len(self.pairs_of_kind("clearance")),
            "closer than %.4g mm" % o.clearance if o.clearance > 0 else "clearance off")]
        lines += ["  " + p.describe() for p in self.pairs or []]
        lines.append("Faces: %d interpenetrating pairs, %d contacts, %d coincident, %d duplicate" % (
            len(self.of_kind("interference")), len(self.of_kind("contact")), len(self.of_kind("coincident")),
            len(self.of_kind("duplicate"))))
        lines += ["  " + f.describe() for f in self.findings]
        lines += ["Pierce: warning: " + w for w in self.warnings]
        return "\n".join(lines)


def _faces(meshed, prims):
    ref = meshed.ref
    return ref.face_names(meshed.face_of_triangle[np.asarray(sorted(set(prims)), dtype=np.int64)]) if prims else []


def compute(objects, options, progress=None, cancel=None):
    options.check()
    from .locate import import_pierce
    pierce = import_pierce()
    model, warnings = mesh_objects(objects, options.deflection, options.angular_deflection,
                                   progress=progress, cancel=cancel)
    scene, solids = model.scene, model.solids

    start_stage(progress, "Pierce: coplanar faces")
    cop = pierce.coplanar_overlaps(scene, tolerance=options.tolerance, progress=progress, cancel=cancel)
    start_stage(progress, "Pierce: interference along rays")
    org, dirs, tmin, tmax = pierce.axis_grid_rays(scene, options.grid)
    rays = pierce.ray_overlaps(scene, org, dirs, tmin=tmin, tmax=tmax, progress=progress, cancel=cancel)
    parts = pierce.partitions(scene, org, dirs, tmin=tmin, tmax=tmax, progress=progress, cancel=cancel)

    findings = []
    # Interpenetrations, with the faces bounding the shared intervals.
    recs, psol = parts.records, parts.solids
    for pair in rays.interferences:
        f = Finding("interference", solids[pair.a].ref, solids[pair.b].ref)
        f.depth = pair.penetration if not math.isnan(pair.penetration) else pair.max_depth
        f.max_los = pair.max_depth
        f.count = pair.count
        f.where = tuple(pair.max_depth_entry)
        prims = {pair.a: [], pair.b: []}
        for r in recs[recs["count"] >= 2]:
            ids = set(int(g) for g in psol[int(r["first"]):int(r["first"]) + int(r["count"])])
            if pair.a in ids and pair.b in ids:
                for g, p in ((r["in_geom"], r["in_prim"]), (r["out_geom"], r["out_prim"])):
                    if int(g) in prims:
                        prims[int(g)].append(int(p))
        f.faces_a = _faces(solids[pair.a], prims[pair.a])
        f.faces_b = _faces(solids[pair.b], prims[pair.b])
        iv = rays.intervals
        sel = iv[(iv["ray"] == pair.max_depth_ray) & (iv["a"] == pair.a) & (iv["b"] == pair.b)]
        if len(sel):
            k = int(np.argmax(sel["depth"]))
            f.segment = (tuple(sel["entry"][k]), tuple(sel["exit"][k]))
        findings.append(f)

    # Coplanar pairs, per solid pair and facing.
    groups = {}
    for p in cop.pairs:
        a, b = int(p["geom_a"]), int(p["geom_b"])
        kind = "duplicate" if a == b else ("coincident" if p["same_facing"] else "contact")
        groups.setdefault((kind, a, b), []).append(p)
    for (kind, a, b), pairs in sorted(groups.items(), key=lambda kv: (kv[0][1], kv[0][2], kv[0][0])):
        f = Finding(kind, solids[a].ref, solids[b].ref)
        f.count = len(pairs)
        f.area = float(sum(float(p["area"]) for p in pairs))
        biggest = max(pairs, key=lambda p: float(p["area"]))
        f.where = tuple(float(x) for x in biggest["centroid"])
        f.faces_a = _faces(solids[a], [int(p["prim_a"]) for p in pairs])
        f.faces_b = _faces(solids[b], [int(p["prim_b"]) for p in pairs])
        m = solids[a]
        for pa in sorted({int(p["prim_a"]) for p in pairs})[:5000]:
            f.triangles.append(tuple(tuple(m.vertices[i]) for i in m.triangles[pa]))
        findings.append(f)

    # Touching solids seen by the rays but not as coplanar triangles (curved contacts).
    known = {(f.a, f.b) for f in findings if f.kind == "contact"}
    for cp in rays.contacts:
        ra, rb = solids[cp.a].ref, solids[cp.b].ref
        if (ra, rb) in known:
            continue
        f = Finding("contact", ra, rb)
        f.count = cp.count
        f.where = tuple(cp.where)
        f.area = math.nan
        findings.append(f)
    if rays.rays_ending_inside:
        warnings.append("%d rays ended inside a solid (open mesh?)" % rays.rays_ending_inside)

    # Pairs by kind, as `pierce overlaps --clearance D` reports them.
    start_stage(progress, "Pierce: contact, clash and clearance")
    report = pierce.clearance(scene, clearance=options.clearance, grid=options.grid, progress=progress,
                              cancel=cancel)
    by_geom = {m.geom: m.ref for m in solids}
    pairs = []
    for p in report.pairs:
        pair = Pair(len(pairs) + 1, by_geom[p.solid_a], by_geom[p.solid_b], p)
        want = {"clash": "interference", "contact": "contact"}.get(pair.kind)
        pair.finding = next((f for f in findings if f.kind == want and {f.a, f.b} == {pair.a, pair.b}), None)
        pairs.append(pair)
    return OverlapRun(options, model, findings, rays, cop, warnings + model.warnings, pairs=pairs)


def create_objects(doc, run):
    """Markers in a group 'PierceOverlaps': a red segment along each pair's deepest interval, the
    shared triangles of each contact or coincidence in orange."""
    import FreeCAD
    import Part
    from .thickness_map import remove_previous, sources_key
    sources = sources_key(run.model.solids)
    remove_previous(doc, "overlaps", sources)
    group = doc.addObject("App::DocumentObjectGroup", "PierceOverlaps")
    group.Label = "Overlap check"
    for prop, value in (("PierceAnalysis", "overlaps"), ("PierceSources", sources)):
        group.addProperty("App::PropertyString", prop, "Pierce", "Result of this analysis on these solids")
        setattr(group, prop, value)
        group.setEditorMode(prop, 1)
    for f in run.findings:
        shape = None
        if f.kind == "interference" and f.segment is not None:
            p, q = (FreeCAD.Vector(*x) for x in f.segment)
            if (q - p).Length > 0:
                shape = Part.makeLine(p, q)
        elif f.triangles:
            faces = []
            for tri in f.triangles:
                pts = [FreeCAD.Vector(*x) for x in tri]
                try:
                    faces.append(Part.Face(Part.makePolygon(pts + [pts[0]])))
                except Exception:  # a sliver FreeCAD cannot make a face of
                    continue
            shape = Part.makeCompound(faces) if faces else None
        if shape is None:
            continue
        obj = doc.addObject("Part::Feature", "Overlap")
        # Short labels: the pair's row in the table, or the solids' numbers (from 1) for faces
        # without a pair; ending in a letter, so FreeCAD does not renumber them.
        pair = next((p for p in run.pairs or [] if p.finding is f), None)
        numbers = {m.ref: k + 1 for k, m in enumerate(run.model.solids)}
        obj.Label = ("Pair %d %s" % (pair.number, pair.kind) if pair is not None else
                     "Solids %d, %d %s" % (numbers.get(f.a, 0), numbers.get(f.b, 0), SHORT[f.kind].lower()))
        obj.Shape = shape
        obj.addProperty("App::PropertyString", "Kind", "Pierce", "Finding kind").Kind = f.kind
        obj.addProperty("App::PropertyString", "Solids", "Pierce", "Solids involved").Solids = (
            "%s, %s" % (f.a.label, f.b.label))
        if f.depth is not None:
            obj.addProperty("App::PropertyFloat", "Depth", "Pierce", "Interpenetration depth (mm)").Depth = f.depth
        vo = getattr(obj, "ViewObject", None)
        if vo is not None:
            colour = (1.0, 0.0, 0.0) if f.kind == "interference" else (1.0, 0.55, 0.0)
            vo.LineColor = colour
            vo.PointColor = colour
            vo.ShapeColor = colour
            vo.LineWidth = 4.0
        group.addObject(obj)
        f.result_object = obj
    run.group = group
    doc.recompute()
    return group


def run(objects, options, doc=None, progress=None, cancel=None):
    result = compute(objects, options, progress=progress, cancel=cancel)
    if options.create_objects:
        create_objects(doc or objects[0].Document, result)
    return result
