"""Ray classification / shotlines: along a ray (a point and a direction, or a grid of rays entering
through a face), the solids it passes through, overlaps and gaps, with entry and exit points,
line-of-sight length, obliquity and normal thickness (BRL-CAD nirt).

GUI-free: shoot() returns a ShotRun; create_objects() adds coloured line segments to the document
(one object per solid, overlaps red, gaps grey dashed), leaving the analysed objects untouched.
"""
import math
from dataclasses import dataclass

import numpy as np

from .errors import SelectionError, UserError
from .progress import start_stage
from .tessellate import mesh_objects

# Distinct colours for the solids' segments (overlaps are red, gaps grey).
PALETTE = [(0.12, 0.47, 0.71), (0.17, 0.63, 0.17), (1.0, 0.5, 0.05), (0.58, 0.40, 0.74), (0.55, 0.34, 0.29),
           (0.89, 0.47, 0.76), (0.09, 0.75, 0.81), (0.74, 0.74, 0.13)]
OVERLAP = (1.0, 0.0, 0.0)
GAP = (0.6, 0.6, 0.6)


class ShotOptions:
    def __init__(self, deflection=None, angular_deflection=None, csg=None, create_objects=True):
        self.deflection = deflection
        self.angular_deflection = angular_deflection
        self.csg = csg  # e.g. "difference(Plate, Hole)" over solid labels; None: plain partitions
        self.create_objects = create_objects


@dataclass(eq=False)
class ShotRun:
    """rows: dicts per interval (ray, kind, solids as SolidRefs, labels, t_in, t_out, in_point,
    out_point, los, obliquity_in/out in degrees, normal_thickness); per_solid: {label: total
    line of sight}; rays: (origins, directions)."""

    model: object  # tessellate.Model
    rows: list
    rays: tuple
    warnings: list
    group: object = None  # the document group of the result objects, once created

    def per_solid(self):
        out = {}
        for r in self.rows:
            if r["kind"] == "solid":
                out[r["labels"][0]] = out.get(r["labels"][0], 0.0) + r["los"]
        return out

    def table(self):
        """Rows as strings for a table: ray, kind, solids, in, out, LOS, obliquity in/out, normal thickness."""
        def pt(p):
            return "(%.4g, %.4g, %.4g)" % tuple(p)

        def num(x):
            return "" if x is None or (isinstance(x, float) and math.isnan(x)) else "%.4g" % x
        return [[str(r["ray"]), r["kind"], ", ".join(r["labels"]), pt(r["in_point"]), pt(r["out_point"]),
                 num(r["los"]), num(r["obliquity_in"]), num(r["obliquity_out"]), num(r["normal_thickness"])]
                for r in self.rows]

    def summary(self):
        lines = ["Pierce shotline: %d rays, %d intervals" % (len(self.rays[0]), len(self.rows))]
        for label, los in sorted(self.per_solid().items()):
            lines.append("  %s: line of sight %.4g mm" % (label, los))
        for r in self.rows:
            if r["kind"] in ("overlap", "gap"):
                lines.append("  ray %d: %s %s, %.4g mm from %s" % (r["ray"], r["kind"], " / ".join(r["labels"]),
                                                                     r["los"], tuple(round(x, 4) for x in r["in_point"])))
        lines += ["Pierce: warning: " + w for w in self.warnings]
        return "\n".join(lines)


def face_grid(face, n, margin):
    """Rays entering the material through `face`: for an n x n grid over its (u, v) range, the
    points inside the trimmed face, each ray starting `margin` outside along the normal and going
    inward. Returns (origins, directions) arrays."""
    if n < 1:
        raise UserError("The grid needs at least 1 ray per side.")
    u0, u1, v0, v1 = face.ParameterRange
    org, dirs = [], []
    for i in range(n):
        for j in range(n):
            u = u0 + (u1 - u0) * (i + 0.5) / n
            v = v0 + (v1 - v0) * (j + 0.5) / n
            if not face.isPartOfDomain(u, v):
                continue
            p = face.valueAt(u, v)
            nrm = face.normalAt(u, v)
            if nrm.Length == 0:
                continue
            nrm.normalize()
            org.append(tuple(p + nrm * margin))
            dirs.append(tuple(-nrm))
    if not org:
        raise SelectionError("No grid point falls inside the selected face; use a finer grid.")
    return np.asarray(org, dtype=float), np.asarray(dirs, dtype=float)


def shoot(objects, origins, directions, options, progress=None, cancel=None):
    """Shotlines of the rays origins[i] + t * directions[i], t >= 0, through the solids of `objects`."""
    from .locate import import_pierce
    pierce = import_pierce()
    origins = np.atleast_2d(np.asarray(origins, dtype=float))
    directions = np.atleast_2d(np.asarray(directions, dtype=float))
    if origins.shape != directions.shape or origins.shape[1:] != (3,):
        raise UserError("Give one direction per starting point.")
    if np.any(np.linalg.norm(directions, axis=1) == 0):
        raise UserError("The ray direction must not be zero.")
    model, warnings = mesh_objects(objects, options.deflection, options.angular_deflection,
                                   progress=progress, cancel=cancel)
    start_stage(progress, "Pierce: shotlines")
    csg = options.csg.strip() if options.csg else None
    try:
        shots = pierce.shotlines(model.scene, origins, directions, csg=csg, progress=progress, cancel=cancel)
    except pierce.InputError as e:
        raise UserError(str(e)) from e
    rows = []
    for r in shots.rows():
        ids = r["solids"]
        refs_of = [model.solids[g].ref for g in ids]
        row = dict(r)
        row["solids"] = refs_of
        row["labels"] = tuple(x.label for x in refs_of)
        rows.append(row)
    if shots.unclosed or shots.unmatched_leaves:
        warnings.append("open or inconsistent meshes: %d unclosed, %d unmatched crossings"
                        % (shots.unclosed, shots.unmatched_leaves))
    return ShotRun(model, rows, (origins, directions), warnings + model.warnings)


def create_objects(doc, run):
    """A group 'PierceShotline' with one line object per solid (its colour), one for overlaps (red)
    and one for gaps (grey)."""
    import FreeCAD
    import Part
    group = doc.addObject("App::DocumentObjectGroup", "PierceShotline")
    group.Label = "Shotline"
    buckets = {}
    for r in run.rows:
        key = r["kind"] if r["kind"] in ("overlap", "gap") else ("solid", r["labels"])
        p, q = FreeCAD.Vector(*r["in_point"]), FreeCAD.Vector(*r["out_point"])
        if (q - p).Length > 0:
            buckets.setdefault(key, []).append(Part.makeLine(p, q))
    k = 0
    for key, edges in buckets.items():
        obj = doc.addObject("Part::Feature", "Shot")
        if key == "overlap":
            obj.Label, colour, width = "Shot overlaps", OVERLAP, 5.0
        elif key == "gap":
            obj.Label, colour, width = "Shot gaps", GAP, 1.0
        else:
            obj.Label, colour, width = "Shot in %s" % ", ".join(key[1]), PALETTE[k % len(PALETTE)], 4.0
            k += 1
        obj.Shape = Part.makeCompound(edges)
        obj.addProperty("App::PropertyFloat", "LineOfSight", "Pierce", "Summed length (mm)").LineOfSight = sum(
            e.Length for e in edges)
        vo = getattr(obj, "ViewObject", None)
        if vo is not None:
            vo.LineColor = colour
            vo.PointColor = colour
            vo.LineWidth = width
            if key == "gap" and hasattr(vo, "DrawStyle"):
                vo.DrawStyle = "Dashed"
        group.addObject(obj)
    run.group = group
    doc.recompute()
    return group


def run(objects, origins, directions, options, doc=None, progress=None, cancel=None):
    result = shoot(objects, origins, directions, options, progress=progress, cancel=cancel)
    if options.create_objects:
        create_objects(doc or objects[0].Document, result)
    return result


def run_face_grid(objects, face, n, options, doc=None, progress=None, cancel=None):
    """Shotlines entering through `face` on an n x n grid (see face_grid)."""
    shapes = [o.Shape for o in objects if hasattr(o, "Shape")]
    bb = face.BoundBox
    for s in shapes:
        bb = bb.united(s.BoundBox)
    org, dirs = face_grid(face, n, margin=max(bb.DiagonalLength * 0.01, 1e-6))
    return run(objects, org, dirs, options, doc=doc, progress=progress, cancel=cancel)
