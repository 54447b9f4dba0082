"""From document objects (Part, PartDesign, containers) to the solids Pierce analyses.

Shapes are taken in global coordinates (container placements applied). Problems the user can fix
raise SelectionError with a message naming the object; problems with some objects while others
are fine are returned as warnings.
"""
from .errors import SelectionError


class SolidRef:
    """One solid of a document object: `shape` is a Part.Solid in global coordinates; `index` is
    its position in the object's Shape.Solids; `face_ids` maps the solid's faces (in
    shape.Faces order) to 1-based face numbers of the object's shape ("Face<n>" sub-elements)."""

    def __init__(self, obj, index, shape, face_ids, count, tree_obj=None):
        self.obj = obj
        self.index = index
        self.shape = shape
        self.face_ids = face_ids
        self.count = count  # solids in the object
        # The object the tree shows for this solid when `obj` is a compound of other objects
        # (Part::Compound, an imported STEP assembly): its Label names the solid.
        self.tree_obj = tree_obj

    @property
    def label(self):
        """The solid as the tree names it: the object's Label; for a solid of a compound, the
        Label of the tree object it comes from, else "Label (solid N)" counting from 1."""
        if self.tree_obj is not None:
            return self.tree_obj.Label
        if self.count > 1:
            return "%s (solid %d)" % (self.obj.Label, self.index + 1)
        return self.obj.Label

    def face_names(self, local_faces):
        """Sub-element names ("Face3", ...) of the object for faces given by index in shape.Faces."""
        return sorted({"Face%d" % self.face_ids[f] for f in local_faces if 0 <= f < len(self.face_ids)},
                      key=lambda s: int(s[4:]))

    def __repr__(self):
        return "<SolidRef %s>" % self.label


def _global_shape(obj):
    import Part
    try:
        return Part.getShape(obj)
    except Exception:  # objects Part cannot interpret
        shape = getattr(obj, "Shape", None)
        return shape


def _is_container(obj):
    return obj.isDerivedFrom("App::DocumentObjectGroup") or obj.isDerivedFrom("App::Part")


def _expand(objects):
    """Objects with containers replaced by their contents (recursively), each object once, and
    PartDesign features dropped when their Body is also selected."""
    seen, out = set(), []

    def add(o):
        if o.Name in seen:
            return
        seen.add(o.Name)
        if _is_container(o):
            for child in getattr(o, "Group", []):
                add(child)
            return
        out.append(o)

    for o in objects:
        add(o)
    names = {o.Name for o in out}
    kept = []
    for o in out:
        body = getattr(o, "_Body", None)
        if body is None and hasattr(o, "getParentGeoFeatureGroup"):
            parent = o.getParentGeoFeatureGroup()
            body = parent if parent is not None and parent.isDerivedFrom("PartDesign::Body") else None
        if body is not None and body.Name in names and body.Name != o.Name:
            continue
        kept.append(o)
    return kept


def _face_index_map(whole, solid):
    """1-based indices in whole.Faces of each face of `solid` (same TShape and location)."""
    by_hash = {}
    for j, f in enumerate(whole.Faces):
        by_hash.setdefault(f.hashCode(), []).append((j, f))
    ids = []
    for f in solid.Faces:
        match = next((j for j, g in by_hash.get(f.hashCode(), []) if g.isSame(f)), None)
        ids.append(match + 1 if match is not None else 0)
    return ids


def _tree_objects(obj, solids):
    """For each of `solids` (the solids of compound `obj`, global), the object below `obj` in the
    tree it comes from (a child holding exactly one solid, the same one: same shape, or the same
    volume and centre of mass), or None."""
    import Part
    children = []
    for child in getattr(obj, "OutList", []):
        try:
            cs = Part.getShape(child).Solids
        except Exception:  # children without a Part shape
            continue
        if len(cs) == 1:
            children.append((child, cs[0]))
    out = []
    for s in solids:
        match = next((c for c, cs in children if cs.isSame(s)), None)
        if match is None:
            tol = 1e-9 * max(s.BoundBox.DiagonalLength, 1e-12)
            close = [c for c, cs in children if abs(cs.Volume - s.Volume) <= 1e-9 * max(abs(s.Volume), 1e-12) and
                     (cs.CenterOfMass - s.CenterOfMass).Length <= tol]
            match = close[0] if len(close) == 1 else None
        out.append(match)
    if len({o.Name for o in out if o is not None}) < len([o for o in out if o is not None]):
        return [None] * len(solids)  # one child matched twice: do not guess
    return out


def collect_solids(objects, accept_closed_shells=True):
    """Returns (solids, warnings). Raises SelectionError when no solid can be analysed."""
    import Part
    if not objects:
        raise SelectionError("Nothing is selected: select one or more solids (Part or PartDesign "
                             "objects) in the 3D view or the tree view.")
    solids, problems = [], []
    for obj in _expand(objects):
        shape = _global_shape(obj)
        if shape is None or shape.isNull():
            problems.append("'%s' has no shape" % obj.Label)
            continue
        if shape.Solids:
            owners = _tree_objects(obj, shape.Solids) if len(shape.Solids) > 1 else [None]
            for i, s in enumerate(shape.Solids):
                solids.append(SolidRef(obj, i, s, _face_index_map(shape, s), len(shape.Solids), owners[i]))
            continue
        shells = shape.Shells
        open_shells = [sh for sh in shells if not sh.isClosed()]
        if shells and not open_shells and accept_closed_shells:
            for i, sh in enumerate(shells):
                s = Part.Solid(sh)
                solids.append(SolidRef(obj, i, s, _face_index_map(shape, s), len(shells)))
            problems.append("'%s' is a closed shell, analysed as a solid" % obj.Label)
        elif open_shells:
            problems.append("'%s' is an open shell (%d free edges): thickness and overlaps need "
                            "closed solids" % (obj.Label, sum(1 for e in shape.Edges
                                                              if len(shape.ancestorsOfType(e, Part.Face)) < 2)))
        elif shape.Faces:
            problems.append("'%s' has faces but no solid" % obj.Label)
        else:
            problems.append("'%s' has no solid (only %s)" % (
                obj.Label, "edges" if shape.Edges else "vertices" if shape.Vertexes else "an empty shape"))
    if not solids:
        raise SelectionError("No solid to analyse: " + "; ".join(problems) + "." if problems
                             else "No solid to analyse in the selection.")
    return solids, problems
