"""Thickness map: per-vertex or per-face wall thickness of solids as false-colour Mesh features.

GUI-free: run() takes document objects and options, returns a ThicknessRun holding the numbers and
the result objects it created (one Mesh::Feature per solid, in a group), and a summary for the
Report view. The analysed objects are not modified.
"""
import hashlib
import math
import os
import tempfile
from dataclasses import dataclass

import numpy as np

from . import colormap
from .errors import UserError
from .progress import start_stage
from .tessellate import mesh_objects


def method_names():
    """The thickness methods, as the Pierce core names them (pierce.thickness_methods())."""
    return tuple(_pierce().thickness_methods())


def thickness_defaults():
    """Pierce's default method and sampling (pierce.thickness_defaults(): the CLI's)."""
    return dict(_pierce().thickness_defaults())


def has_cad():
    """Whether this Pierce build reads CAD (OpenCASCADE): needed to sample on the exact B-rep."""
    return bool(getattr(_pierce(), "HAS_CAD", False))


def sampling_names():
    """The sample locations, as the Pierce core names them (pierce.thickness_samplings())."""
    return tuple(_pierce().thickness_samplings())


class ThicknessOptions:
    def __init__(self, method=None, per=None, deflection=None, angular_deflection=None, max_edge=None,
                 threshold=0.0, max_distance=math.inf, color_min=None, color_max=None, create_objects=True,
                 on_brep=None, keep_previous=False, max_thickness=0.0):
        # None: Pierce's defaults (pierce.thickness_defaults(), the CLI's --method and --per).
        defaults = _pierce().thickness_defaults() if method is None or per is None else {}
        self.method = method or defaults["method"]  # ray | cone | sphere
        self.per = per or defaults["per"]           # vertex | face (triangle centroids)
        # Tessellation: None takes the defaults every Pierce front end shares
        # (tessellate.tessellation_defaults(), the CLI's), so the same part gives the same samples.
        self.deflection = deflection  # mm; 0 = 0.1% of the selection's diagonal
        self.angular_deflection = angular_deflection  # degrees
        # On the exact B-rep (Pierce's CAD tessellation, checked against the B-rep, samples and exits
        # on the exact faces: no false thin spots from the mesh) or on FreeCAD's mesh, as a mesh.
        # None: on the B-rep when this Pierce build reads CAD (pierce.HAS_CAD).
        self.on_brep = on_brep
        self.max_edge = max_edge      # mm: split longer triangle edges (samples on big flat faces);
                                      # "auto" = 4% of the selection's diagonal, 0 = no splitting
        self.threshold = threshold    # thin below this (mm); 0 = no highlight
        self.max_thickness = max_thickness  # thick above this (mm): thick regions; 0 = none
        self.max_distance = max_distance
        self.color_min = color_min    # legend range; None = default_color_range()
        self.color_max = color_max
        self.create_objects = create_objects
        # Re-running on the same solids replaces that analysis' previous result objects unless
        # keep_previous is set.
        self.keep_previous = keep_previous

    def check(self):
        if self.method not in method_names():
            raise UserError("Unknown method '%s' (%s)." % (self.method, ", ".join(method_names())))
        if self.per not in sampling_names():
            raise UserError("Sampling must be per %s, not '%s'." % (" or per ".join(sampling_names()), self.per))
        if self.threshold < 0 or not math.isfinite(self.threshold):
            raise UserError("The thin threshold must be a length >= 0.")
        if self.max_thickness < 0 or not math.isfinite(self.max_thickness):
            raise UserError("The thick threshold must be a length >= 0 (0: none).")
        if not self.max_distance > 0:
            raise UserError("The maximum distance must be positive.")
        if (self.color_min is not None and self.color_max is not None and
                not self.color_max > self.color_min):
            raise UserError("The legend range is empty: its maximum must exceed its minimum.")


class SolidThickness:
    """Thickness of one solid: values per mesh vertex or triangle (NaN: none), statistics, and the
    result object (None when objects were not created)."""

    def __init__(self, meshed, values, status, stats, thin_count, region=None, points=None, normals=None):
        self.meshed = meshed
        self.values = values
        self.status = status
        self.stats = stats  # pierce.SolidThickness
        self.thin_count = thin_count
        # Per sample: region id (-1: none; see ThicknessRun.region) and sample point.
        self.region = region if region is not None else np.full(len(values), -1, dtype=np.int32)
        self.points = points
        self.normals = normals  # unit outward normals per sample (zero where none)
        self.result_object = None

    @property
    def label(self):
        return self.meshed.ref.label

    @property
    def valid(self):
        return self.values[np.isfinite(self.values)]

    def percentile(self, q):
        """Percentile q of the thickness: Pierce's own (as the CLI reports it) for the percentiles
        it summarises, else of the valid values (the same linear interpolation)."""
        for pq, value in self.stats.summary.percentiles:
            if pq == q:
                return float(value) if self.stats.summary.count else math.nan
        v = self.valid
        return float(np.percentile(v, q)) if len(v) else math.nan


@dataclass(eq=False)
class ThicknessRun:
    options: ThicknessOptions
    model: object  # tessellate.Model
    solids: list  # SolidThickness per solid
    color_range: tuple  # (lo, hi) of the legend
    warnings: list
    group: object = None  # the document group of the result objects, once created
    # Thin walls as findings (pierce.ThicknessRegion, thinnest first): samples strictly below the
    # threshold connected on a solid's surface and across the wall; area on both sides.
    thin_regions: list = None
    # Thick walls (pierce.ThicknessRegion, thickest first): samples strictly above max_thickness.
    thick_regions: list = None
    # Whether valid values lie below / above the legend range (shown clamped to its ends).
    clamped: tuple = (False, False)

    def region_solid(self, region):
        """The SolidThickness a region lies on."""
        for s in self.solids:
            if s.meshed.geom == region.solid:
                return s
        return None

    def region(self, k):
        """Region k, as the per-sample ids number them (SolidThickness.region): the thin regions
        first, then the thick ones at len(thin_regions) + their index."""
        thin = self.thin_regions or []
        return thin[k] if k < len(thin) else self.thick_regions[k - len(thin)]

    def region_id(self, thick, index):
        """The id of thin (thick=False) or thick region `index`, as region() takes it."""
        return len(self.thin_regions or []) + index if thick else index

    def region_box(self, k):
        """(lo, hi) corners of the box around region k: its samples' triangles (per face) or
        vertices (per vertex), its extreme point and that ray's exit."""
        g = self.region(k)
        s = self.region_solid(g)
        pts = [np.asarray(g.point, dtype=float), np.asarray(g.exit, dtype=float)]
        if s is not None:
            idx = np.nonzero(s.region == k)[0]
            m = s.meshed
            if self.options.per == "face":
                pts.extend(m.vertices[m.triangles[idx].reshape(-1)])
            else:
                pts.extend(m.vertices[idx])
        pts = np.asarray(pts, dtype=float)
        pts = pts[np.all(np.isfinite(pts), axis=1)]
        return pts.min(axis=0), pts.max(axis=0)

    def region_view(self, k):
        """(centre, radius, direction) to look at region k: the centre and half the diagonal of
        region_box(k), and the outward normal at its extreme sample (the thinnest, or the thickest
        for a thick region; look against it to see that side of the wall; None when unknown)."""
        lo, hi = self.region_box(k)
        g = self.region(k)
        s = self.region_solid(g)
        normal = None
        if s is not None and s.normals is not None:
            idx = np.nonzero(s.region == k)[0]
            if len(idx):
                if g.thick:
                    extreme = int(np.argmax(np.where(np.isfinite(s.values[idx]), s.values[idx], -np.inf)))
                else:
                    extreme = int(np.argmin(np.where(np.isfinite(s.values[idx]), s.values[idx], np.inf)))
                n = s.normals[idx[extreme]]
                if np.linalg.norm(n) > 0.5:
                    normal = tuple(float(c) for c in n / np.linalg.norm(n))
        return tuple(float(c) for c in (lo + hi) / 2), float(np.linalg.norm(hi - lo) / 2), normal

    def region_faces(self, k):
        """(object, ["Face3", ...]) of the analysed object's B-rep faces region k covers (empty on
        FreeCAD's mesh, whose triangles keep their faces in face_of_triangle)."""
        g = self.region(k)
        s = self.region_solid(g)
        if s is None:
            return None, []
        ref = s.meshed.ref
        faces = list(g.faces)
        if not faces and s.meshed.face_of_triangle is not None and self.options.per == "face":
            faces = sorted(set(int(f) for f in s.meshed.face_of_triangle[s.region == k]))
        return ref.obj, ref.face_names(faces)

    def region_label(self, region):
        """The label of the solid a region lies on."""
        for s in self.solids:
            if s.meshed.geom == region.solid:
                return s.label
        return "#%d" % region.solid

    def legend_text(self):
        """One line on the colour range and how it was chosen."""
        lo, hi = self.color_range
        o = self.options
        if o.color_min is not None or o.color_max is not None:
            how = "as set"
        elif o.threshold > 0:
            how = "default: 0 to %g x the thin threshold" % _pierce().COLOR_RANGE_THIN_FACTOR
        else:
            how = "default: P%g to P%g of the samples" % tuple(_pierce().COLOR_RANGE_PERCENTILES)
        clamped = [what for what, c in zip(("thinner walls drawn as its low end", "thicker walls drawn as its high "
                                            "end"), self.clamped) if c]
        return "Legend %.4g to %.4g mm (%s)%s" % (lo, hi, how, "; " + ", ".join(clamped) if clamped else "")

    def summary(self):
        o = self.options
        lines = []
        for s in self.solids:
            st = s.stats.summary
            n = len(s.values)
            line = ("Pierce thickness of '%s' (%s, per %s, %d samples, %s): " %
                    (s.label, o.method, o.per, n, "on the exact B-rep" if self.model.on_brep else "on FreeCAD's mesh"))
            if st.count:
                line += "min %.4g, P5 %.4g, median %.4g, P95 %.4g, max %.4g" % (
                    st.min, s.percentile(5), s.percentile(50), s.percentile(95), st.max)
            else:
                line += "no thickness found"
            if o.threshold > 0:
                line += "; %d thin (< %.4g)" % (s.thin_count, o.threshold)
            tessellation = getattr(s.stats, "tessellation", 0)
            missing = n - st.count - tessellation
            if missing:
                line += "; %d without thickness (ray escaped or no normal)" % missing
            if tessellation:
                line += "; %d excluded as tessellation artefacts (status tessellation)" % tessellation
            lines.append(line)
        if o.threshold > 0 and self.thin_regions is not None:
            lines.append("%d thin region(s) (thickness < %.4g; area both sides)%s" % (
                len(self.thin_regions), o.threshold, ", the ten thinnest:" if len(self.thin_regions) > 10 else ""))
            for k, g in enumerate(self.thin_regions[:10]):
                lines.append("  region %d: '%s' min %.4g, area %.4g, %d samples, at (%.4g, %.4g, %.4g)" % (
                    k + 1, self.region_label(g), g.thickness, g.area, g.samples, *g.point))
        if o.max_thickness > 0 and self.thick_regions is not None:
            lines.append("%d thick region(s) (thickness > %.4g; area both sides)%s" % (
                len(self.thick_regions), o.max_thickness,
                ", the ten thickest:" if len(self.thick_regions) > 10 else ""))
            for k, g in enumerate(self.thick_regions[:10]):
                lines.append("  thick region %d: '%s' max %.4g, area %.4g, %d samples, at (%.4g, %.4g, %.4g)" % (
                    k + 1, self.region_label(g), g.thickness, g.area, g.samples, *g.point))
        lines.append(self.legend_text())
        for w in self.warnings:
            lines.append("Pierce: warning: " + w)
        return "\n".join(lines)


def compute(objects, options, progress=None, cancel=None):
    """Numbers only, no document objects. progress: a pierce_fc.progress.Progress or callable."""
    options.check()
    pierce = _pierce()
    on_brep = options.on_brep if options.on_brep is not None else has_cad()
    model, warnings = mesh_objects(objects, options.deflection, options.angular_deflection, options.max_edge,
                                   progress=progress, cancel=cancel, on_brep=on_brep)
    start_stage(progress, "Pierce: thickness (%s)" % options.method)
    res = pierce.thickness(model.scene, method=options.method, per=options.per,
                           max_distance=options.max_distance, min_thickness=options.threshold,
                           max_thickness=options.max_thickness if options.max_thickness > 0 else math.inf,
                           progress=progress, cancel=cancel)
    solids = []
    geom_of = res.solid
    for m, st in zip(model.solids, res.solids):
        sel = geom_of == m.geom
        values = np.array(res.thickness[sel])
        status = np.array(res.status[sel])
        order = np.argsort(np.array(res.element[sel]), kind="stable")
        region = np.array(res.region[sel])[order] if len(res.region) else None
        solids.append(SolidThickness(m, values[order], status[order], st, int(np.count_nonzero(res.thin[sel])),
                                     region=region, points=np.array(res.point[sel])[order],
                                     normals=np.array(res.normal[sel])[order]))
    valid = np.concatenate([s.valid for s in solids]) if solids else np.zeros(0)
    lo, hi = default_color_range(valid, options.threshold)
    if options.color_min is not None:
        lo = options.color_min
    if options.color_max is not None:
        hi = options.color_max
    if not hi > lo:
        hi = lo + max(abs(lo) * 1e-3, 1e-9)  # a uniform wall: any non-empty range shows one colour
    clamped = (bool(len(valid)) and bool(valid.min() < lo), bool(len(valid)) and bool(valid.max() > hi))
    return ThicknessRun(options, model, solids, (lo, hi), warnings + model.warnings,
                        thin_regions=list(res.thin_regions), thick_regions=list(res.thick_regions),
                        clamped=clamped)


def default_color_range(valid, threshold=0.0):
    """The legend's default (lo, hi) for the valid thickness values, as every Pierce front end
    chooses it (pierce.default_color_range): with a thin threshold T > 0, 0 to
    pierce.COLOR_RANGE_THIN_FACTOR x T; otherwise the pierce.COLOR_RANGE_PERCENTILES of the values.
    Values outside are drawn in the colour of the nearer end (clamped)."""
    return tuple(_pierce().default_color_range([float(v) for v in valid], float(threshold)))


def create_objects(doc, run):
    """One false-colour Mesh::Feature per solid in a group 'PierceThickness'."""
    import FreeCAD
    import Mesh
    o = run.options
    lo, hi = run.color_range
    sources = sources_key(run.solids)
    if not o.keep_previous:
        remove_previous(doc, "thickness", sources)
    group = doc.addObject("App::DocumentObjectGroup", "PierceThickness")
    labels = sorted({s.meshed.ref.obj.Label for s in run.solids})
    group.Label = "Thickness map %s" % labels[0] if len(labels) == 1 else "Thickness map (%d objects)" % len(labels)
    _add(group, "App::PropertyString", "PierceAnalysis", "Pierce", "Analysis that made this result", "thickness")
    _add(group, "App::PropertyString", "PierceSources", "Pierce", "Analysed solids (object names and solid indices)",
         sources)
    group.setEditorMode("PierceAnalysis", 1)
    group.setEditorMode("PierceSources", 1)
    for s in run.solids:
        m = s.meshed
        mesh = Mesh.Mesh()
        mesh.addFacets(([FreeCAD.Vector(*p) for p in m.vertices], [tuple(int(i) for i in t) for t in m.triangles]))
        if mesh.CountFacets != len(m.triangles) or mesh.CountPoints != len(m.vertices):
            raise UserError("FreeCAD's mesh changed the triangles of '%s'; cannot colour it." % s.label)
        obj = doc.addObject("Mesh::Feature", "Thickness")
        obj.Label = "Thickness %s" % s.label
        obj.Mesh = mesh
        _add(obj, "App::PropertyString", "SourceObject", "Pierce", "Analysed object (name)", m.ref.obj.Name)
        _add(obj, "App::PropertyInteger", "SolidIndex", "Pierce", "Solid of that object", m.ref.index)
        _add(obj, "App::PropertyString", "Method", "Pierce", "Thickness method", o.method)
        _add(obj, "App::PropertyString", "Per", "Pierce", "Samples: face (triangle) or vertex", o.per)
        _add(obj, "App::PropertyFloat", "Deflection", "Pierce", "Tessellation deflection (mm)", run.model.deflection)
        _add(obj, "App::PropertyFloat", "MaxEdge", "Pierce", "Longest triangle edge (mm, 0: not limited)",
             run.model.max_edge)
        _add(obj, "App::PropertyBool", "OnBrep", "Pierce",
             "Sampled on the exact B-rep (Pierce's tessellation), not on FreeCAD's mesh", run.model.on_brep)
        _add(obj, "App::PropertyFloatList", "Thickness", "Pierce", "Thickness per sample, NaN where none",
             [float(v) for v in s.values])
        _add(obj, "App::PropertyFloat", "ThinThreshold", "Pierce", "Thin below this (0: off)", o.threshold)
        _add(obj, "App::PropertyInteger", "ThinCount", "Pierce", "Samples below the threshold", s.thin_count)
        st = s.stats.summary
        _add(obj, "App::PropertyFloat", "Minimum", "Pierce", "Smallest thickness", st.min if st.count else math.nan)
        _add(obj, "App::PropertyFloat", "Median", "Pierce", "Median thickness", s.percentile(50))
        _add(obj, "App::PropertyFloat", "Maximum", "Pierce", "Largest thickness", st.max if st.count else math.nan)
        _add(obj, "App::PropertyFloat", "LegendMin", "Pierce", "Colour of the low end (red)", lo)
        _add(obj, "App::PropertyFloat", "LegendMax", "Pierce", "Colour of the high end (blue)", hi)
        rgb = colormap.colours(s.values, lo, hi, o.threshold)
        # The mesh view provider shows the first colour-list property, per vertex or per facet
        # depending on its length, when its Coloring is on.
        _add(obj, "App::PropertyColorList", "ThicknessColors", "Pierce", "False colours",
             [tuple(float(c) for c in row) for row in rgb])
        for name in ("SourceObject", "SolidIndex", "Method", "Per", "Deflection", "MaxEdge", "OnBrep", "Thickness",
                     "ThinThreshold",
                     "ThinCount", "Minimum", "Median", "Maximum", "LegendMin", "LegendMax"):
            obj.setEditorMode(name, 1)  # read-only in the property editor
        group.addObject(obj)
        s.result_object = obj
    run.group = group
    doc.recompute()
    for s in run.solids:  # after the recompute, which rebuilds the mesh display without colours
        show_colours(s.result_object)
    return group


def sources_key(solids):
    """The analysed solids of a result (SolidThickness or tessellate.MeshedSolid) as one string:
    "Name:index" of each solid, sorted."""
    refs = [getattr(s, "meshed", s).ref for s in solids]
    return " ".join(sorted("%s:%d" % (r.obj.Name, r.index) for r in refs))


def remove_previous(doc, analysis, sources):
    """Removes the result groups (and their contents) of `analysis` on the same `sources`
    (sources_key) from `doc`; returns how many groups were removed."""
    old = [g for g in doc.Objects if getattr(g, "PierceAnalysis", None) == analysis and
           getattr(g, "PierceSources", None) == sources]
    for g in old:
        for child in list(getattr(g, "Group", [])):
            doc.removeObject(child.Name)
        doc.removeObject(g.Name)
    return len(old)


def show_colours(obj):
    """Turns on the false colours of a result mesh in the GUI (no-op headless). Coloring is
    switched off and on: the view provider reads the colour list when it turns on, and a
    recompute of the mesh drops the colours while leaving Coloring set."""
    vo = getattr(obj, "ViewObject", None)
    if vo is None:
        return
    for prop, value in (("Lighting", "Two side"), ("DisplayMode", "Shaded"), ("Coloring", False),
                        ("Coloring", True)):
        if hasattr(vo, prop):
            try:
                setattr(vo, prop, value)
            except Exception:
                pass


def run(objects, options, doc=None, progress=None, cancel=None):
    """compute(), then (when options.create_objects) the result objects in `doc` (default: the
    first object's document)."""
    result = compute(objects, options, progress=progress, cancel=cancel)
    if options.create_objects:
        create_objects(doc or objects[0].Document, result)
    return result


class CaliperReading:
    """The wall at one picked point: thickness (NaN: none), status name, the point on the B-rep
    and the outward normal there, and where it was picked."""

    def __init__(self, label, subname, thickness, status, point, normal):
        self.label = label
        self.subname = subname
        self.thickness = thickness
        self.status = status
        self.point = point
        self.normal = normal

    def text(self):
        p = self.point
        where = "'%s' %s at (%.6g, %.6g, %.6g)" % (self.label, self.subname, p[0], p[1], p[2])
        if self.status == "ok":
            return "Pierce caliper: wall %.6g mm on %s (exact B-rep)" % (self.thickness, where)
        return "Pierce caliper: no wall on %s (%s)" % (where, self.status)


def caliper(obj, subname, point, method="ray", max_distance=math.inf):
    """The wall thickness of `obj` at `point` (global coordinates) on its face `subname` (e.g.
    "Face3"), like a caliper: the point is projected onto that solid's exact B-rep face and the
    wall is measured along the face's inward normal there, the exit refined on the B-rep
    (pierce.thickness_at on the solid written as BREP)."""
    pierce = _pierce()
    if not getattr(pierce, "HAS_CAD", False):
        raise UserError("This Pierce build has no OpenCASCADE: the caliper needs it.")
    if not subname.startswith("Face"):
        raise UserError("Pick a point on a face (got '%s')." % subname)
    shape = obj.Shape
    try:
        face = shape.getElement(subname)
    except Exception:
        raise UserError("'%s' has no %s." % (obj.Label, subname))
    solid = None
    for sol in shape.Solids:
        if any(f.isSame(face) for f in sol.Faces):
            solid = sol
            break
    if solid is None:
        raise UserError("%s of '%s' is not on a solid." % (subname, obj.Label))
    scene = _caliper_scene(pierce, solid)
    r = pierce.thickness_at(scene, 0, [[float(point[0]), float(point[1]), float(point[2])]], method=method,
                            max_distance=max_distance)
    status = pierce.THICKNESS_STATUS[int(r.status[0])]
    return CaliperReading(obj.Label, subname, float(r.thickness[0]), status, tuple(float(v) for v in r.point[0]),
                          tuple(float(v) for v in r.normal[0]))


def caliper_on_map(result, point, method="ray", max_distance=math.inf):
    """The caliper at `point` (global coordinates) picked on a thickness map `result` (its
    Mesh::Feature): measured on the analysed solid (the map's SourceObject and SolidIndex) at its
    face nearest to the point. Raises UserError saying why when the source is gone, is not a solid
    any more, or no longer lies under the map (moved or edited since the map was made)."""
    import Part
    doc = result.Document
    source = doc.getObject(result.SourceObject) if result.SourceObject else None
    if source is None or not hasattr(source, "Shape"):
        raise UserError("Caliper: the source '%s' of '%s' is no longer in the document; pick on a solid." % (
            result.SourceObject, result.Label))
    solids = source.Shape.Solids
    if not 0 <= result.SolidIndex < len(solids):
        raise UserError("Caliper: '%s' no longer has the solid '%s' was made from; compute the map again." % (
            source.Label, result.Label))
    solid = solids[result.SolidIndex]
    vertex = Part.Vertex(_vector(point))
    best = None
    for face in solid.Faces:
        d = face.distToShape(vertex)[0]
        if best is None or d < best[0]:
            best = (d, face)
    # The map's triangles lie within the tessellation's deflection of the faces.
    tolerance = max(10.0 * getattr(result, "Deflection", 0.0), 1e-6 * solid.BoundBox.DiagonalLength)
    if best is None or best[0] > tolerance:
        raise UserError("Caliper: the point is %.4g mm from '%s': the solid was moved or edited since '%s' was made; "
                        "compute the map again." % (best[0] if best else math.nan, source.Label, result.Label))
    index = next((i for i, f in enumerate(source.Shape.Faces) if f.isSame(best[1])), None)
    return caliper(source, "Face%d" % (index + 1), point, method=method, max_distance=max_distance)


def _vector(p):
    import FreeCAD
    return FreeCAD.Vector(float(p[0]), float(p[1]), float(p[2]))


# The scene of the solid the caliper read last, by the digest of its BREP text: clicks on one
# part load and mesh it once; any change of the solid (shape or placement) gives another digest.
_caliper_cache = {}


def _caliper_scene(pierce, solid):
    digest = hashlib.sha256(solid.exportBrepToString().encode()).hexdigest()
    scene = _caliper_cache.get(digest)
    if scene is None:
        with tempfile.TemporaryDirectory(prefix="pierce_caliper_") as d:
            path = os.path.join(d, "solid.brep")
            solid.exportBrep(path)
            scene = pierce.Scene()
            pierce.add_model_files(scene, [path])
        _caliper_cache.clear()
        _caliper_cache[digest] = scene
    return scene


def _add(obj, kind, name, group, doc, value):
    obj.addProperty(kind, name, group, doc)
    setattr(obj, name, value)


def _pierce():
    from .locate import import_pierce
    return import_pierce()
