"""Solids to triangle meshes for Pierce, one geometry per solid, keeping which B-rep face each
triangle comes from. The user's shapes are copied first, so their own triangulation (and display)
stays as it was."""
import math
import os
from dataclasses import dataclass

import numpy as np

from .errors import UserError


@dataclass(eq=False)
class MeshedSolid:
    """A solid's triangles: vertices (N, 3) float64, triangles (M, 3) int64, face_of_triangle (M,)
    index into ref.shape.Faces (None for brep_model's meshes); `geom` is its geometry id in the
    scene."""

    ref: object  # selection.SolidRef
    vertices: object
    triangles: object
    face_of_triangle: object
    geom: int


@dataclass(eq=False)
class Model:
    """Meshed solids and the pierce.Scene built from them (geometry id = position in `solids`)."""

    scene: object  # pierce.Scene
    solids: list  # MeshedSolid per geometry
    deflection: float
    warnings: list
    max_edge: float = 0.0
    on_brep: bool = False  # Pierce's CAD tessellation with the exact B-rep (brep_model)


def auto_deflection(shapes):
    """0.1% of the diagonal of the shapes' common bounding box."""
    bb = None
    for s in shapes:
        bb = s.BoundBox if bb is None else bb.united(s.BoundBox)
    return max(bb.DiagonalLength * 1e-3, 1e-6) if bb is not None else 0.01


def mesh_solid(shape, deflection, angular_deflection_deg=15.0):
    """(vertices, triangles, face_of_triangle) of a solid; vertices welded by exact position so
    neighbouring faces share their edge vertices."""
    import MeshPart
    work = shape.copy()
    # Triangulates `work` in place with both deflections; face.tessellate() below then reuses it.
    MeshPart.meshFromShape(Shape=work, LinearDeflection=deflection,
                           AngularDeflection=math.radians(angular_deflection_deg), Relative=False)
    pts, tris, owner = [], [], []
    base = 0
    for fi, face in enumerate(work.Faces):
        fp, ft = face.tessellate(deflection)
        if not ft:
            continue
        pts.extend((p.x, p.y, p.z) for p in fp)
        tris.extend((a + base, b + base, c + base) for a, b, c in ft)
        owner.extend([fi] * len(ft))
        base += len(fp)
    if not tris:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64), np.zeros(0, dtype=np.int64)
    pts = np.asarray(pts, dtype=np.float64)
    welded, inverse = np.unique(pts, axis=0, return_inverse=True)
    tri = inverse.reshape(-1)[np.asarray(tris, dtype=np.int64)]
    keep = (tri[:, 0] != tri[:, 1]) & (tri[:, 1] != tri[:, 2]) & (tri[:, 2] != tri[:, 0])
    return welded, tri[keep], np.asarray(owner, dtype=np.int64)[keep]


def checked_deflection(deflection, refs):
    """The deflection to mesh `refs` with: a positive length as given, or for 0 auto_deflection."""
    if deflection < 0 or not math.isfinite(deflection):
        raise UserError("The deflection must be a positive length (or 0 for automatic).")
    return deflection if deflection > 0 else auto_deflection([r.shape for r in refs])


def auto_max_edge(shapes):
    """4% of the diagonal of the shapes' common bounding box: a few thousand triangles per part."""
    return auto_deflection(shapes) * 40.0


def checked_max_edge(max_edge, refs):
    """max_edge as the meshers take it: "auto" becomes auto_max_edge; a negative or non-finite
    length is a UserError."""
    if max_edge == "auto":
        return auto_max_edge([r.shape for r in refs])
    if max_edge < 0 or not math.isfinite(max_edge):
        raise UserError("The maximum edge length must be a positive length (or 0 for no limit).")
    return max_edge


def build_model(refs, deflection=0.0, angular_deflection_deg=15.0, max_edge=0.0, progress=None):
    """Meshes every SolidRef into one pierce.Scene. deflection 0: auto_deflection. max_edge > 0:
    triangles are split until no edge is longer ("auto": auto_max_edge; 0: no splitting).
    progress(done, total) is called after each solid; returning False stops with pierce.Cancelled."""
    from .locate import import_pierce
    pierce = import_pierce()
    deflection = checked_deflection(deflection, refs)
    max_edge = checked_max_edge(max_edge, refs)
    scene = pierce.Scene()
    solids, warnings = [], []
    for k, ref in enumerate(refs):
        v, t, f = mesh_solid(ref.shape, deflection, angular_deflection_deg)
        v, t, f = refine(v, t, f, max_edge)
        if len(t) == 0:
            warnings.append("'%s' gave no triangles and is skipped" % ref.label)
        else:
            geom = scene.add_mesh(v, t, name=ref.label, source=ref.obj.Name)
            solids.append(MeshedSolid(ref, v, t, f, geom))
        if progress is not None and progress(k + 1, len(refs)) is False:
            raise pierce.Cancelled("stopped while meshing")
    if not solids:
        raise UserError("None of the selected solids could be meshed.")
    for rep in pierce.mesh_report(scene):
        if not rep.closed:
            warnings.append("the mesh of '%s' is not closed (%d open, %d non-manifold edges): rays "
                            "may leave through the gaps" % (rep.name, rep.boundary_edges,
                                                            rep.non_manifold_edges))
    return Model(scene, solids, deflection, warnings, max_edge)


def brep_model(refs, deflection=0.0, angular_deflection_deg=15.0, max_edge=0.0, progress=None):
    """Every SolidRef through Pierce's own CAD loader, all solids written as one BREP compound, as
    the CLI reads a CAD file of them: Pierce's tessellation (deflection 0: 0.1% of the diagonal of
    all of them, computed by Pierce as for the CLI), checked against the B-rep (a solid that folds
    is meshed again, finer; folds left are flagged), with the exact surfaces kept, so that
    thickness samples start on the exact faces and their exits are refined on them
    (docs/THICKNESS.md). max_edge > 0: Pierce splits longer triangle edges ("auto": auto_max_edge; 0:
    no splitting), the triangles staying linked to their faces. face_of_triangle is None (Pierce
    keeps that link itself)."""
    import tempfile
    import Part
    from .locate import import_pierce
    pierce = import_pierce()
    if not getattr(pierce, "HAS_CAD", False):
        raise UserError("This Pierce build has no OpenCASCADE: sampling on the exact B-rep needs it.")
    if deflection < 0 or not math.isfinite(deflection):
        raise UserError("The deflection must be a positive length (or 0 for automatic).")
    max_edge = checked_max_edge(max_edge, refs)
    scene = pierce.Scene()
    solids, warnings = [], []
    stem = "selection"
    with tempfile.TemporaryDirectory(prefix="pierce_brep_") as d:
        path = os.path.join(d, stem + ".brep")
        # Copies: adding a shape to a compound marks its TShape as not free, which would change
        # the user's solid.
        Part.makeCompound([ref.shape.copy(False) for ref in refs]).exportBrep(path)
        if progress is not None and progress(len(refs), len(refs)) is False:
            raise pierce.Cancelled("stopped while writing the solids")
        info = pierce.add_model_files(scene, [path], linear_deflection=deflection,
                                      angular_deflection=angular_deflection_deg, max_edge=max_edge)
    f = info[0]
    first, count = f["geometries"]
    # Pierce names the solids of the file stem, stem#2, stem#3...: messages name them by label.
    names = [(stem if k == 0 else "%s#%d" % (stem, k + 1), ref.label) for k, ref in enumerate(refs)]
    for w in f["warnings"]:
        for name, label in sorted(names, key=lambda n: -len(n[0])):
            w = w.replace(name + ":", "'%s':" % label)
        warnings.append(w)
    if count != len(refs):
        raise UserError("Pierce read %d solids back from the %d selected; select fewer solids or turn off "
                        "'On the exact B-rep'." % (count, len(refs)))
    for k, ref in enumerate(refs):
        g = scene.geometry(first + k)
        solids.append(MeshedSolid(ref, np.array(g.vertices, dtype=np.float64), np.array(g.triangles, dtype=np.int64),
                                  None, first + k))
        chk = f["tessellation"][k] if k < len(f["tessellation"]) else None
        if chk and chk["folded"]:
            warnings.append("'%s': %d folded triangles left after remeshing; samples on them are excluded "
                            "(status tessellation)" % (ref.label, chk["folded"]))
    return Model(scene, solids, f["linear_deflection"], warnings, max_edge, on_brep=True)


def tessellation_defaults():
    """The tessellation defaults of every Pierce front end (pierce.tessellation_defaults(): the
    CLI's --deflection, --angular-deflection and --max-edge)."""
    from .locate import import_pierce
    return dict(import_pierce().tessellation_defaults())


def mesh_objects(objects, deflection, angular_deflection_deg, max_edge=0.0, progress=None, cancel=None,
                 on_brep=False):
    """The first step of every analysis: the solids of `objects` (selection.collect_solids),
    meshed into one Model (build_model; brep_model when on_brep). deflection, angular_deflection_deg,
    max_edge: None takes tessellation_defaults(); max_edge "auto": auto_max_edge. Returns (model, the selection's
    warnings); raises pierce.Cancelled when cancel was set before the meshing started."""
    from .locate import import_pierce
    from .progress import start_stage
    from .selection import collect_solids
    pierce = import_pierce()
    defaults = tessellation_defaults()
    if deflection is None:
        deflection = defaults["linear_deflection"]
    if angular_deflection_deg is None:
        angular_deflection_deg = defaults["angular_deflection"]
    if max_edge is None:
        max_edge = defaults["max_edge"]
    refs, warnings = collect_solids(objects)
    if cancel is not None and cancel.cancelled:
        raise pierce.Cancelled("cancelled before start")
    start_stage(progress, "Pierce: meshing solids")
    if on_brep:
        return brep_model(refs, deflection, angular_deflection_deg, max_edge, progress=progress), warnings
    return build_model(refs, deflection, angular_deflection_deg, max_edge, progress=progress), warnings


def refine(vertices, triangles, face_of_triangle, max_edge, max_triangles=2_000_000):
    """Splits triangles until no edge is longer than max_edge, keeping the mesh conforming
    (neighbours are split along the same edges: Rivara's longest-edge bisection). New vertices are
    edge midpoints, so flat faces stay exactly flat. Returns new (vertices, triangles,
    face_of_triangle)."""
    if not max_edge > 0 or len(triangles) == 0:
        return vertices, triangles, face_of_triangle
    limit2 = max_edge * max_edge
    v, t = np.asarray(vertices, dtype=np.float64), np.asarray(triangles, dtype=np.int64)
    edge2 = np.max([np.sum((v[t[:, i]] - v[t[:, (i + 1) % 3]]) ** 2, axis=1) for i in range(3)], axis=0)
    too_long = np.nonzero(edge2 > limit2)[0]
    if len(too_long) == 0:  # the usual case on finely tessellated curved faces: nothing to do
        return vertices, triangles, face_of_triangle
    verts = [tuple(v) for v in vertices]
    tris = [list(map(int, t)) for t in triangles]
    owner = list(map(int, face_of_triangle))

    def length2(a, b):
        pa, pb = verts[a], verts[b]
        return (pa[0] - pb[0]) ** 2 + (pa[1] - pb[1]) ** 2 + (pa[2] - pb[2]) ** 2

    def longest(t):
        """(length2, edge key) of t's longest edge; ties broken by vertex ids so both triangles
        sharing an edge agree."""
        a, b, c = tris[t]
        return max((length2(a, b), (min(a, b), max(a, b))), (length2(b, c), (min(b, c), max(b, c))),
                   (length2(c, a), (min(c, a), max(c, a))))

    edge_tris = {}
    for t, (a, b, c) in enumerate(tris):
        for e in ((a, b), (b, c), (c, a)):
            edge_tris.setdefault((min(e), max(e)), []).append(t)

    def split(t, key, m):
        """Replaces t by two triangles across the midpoint m of its edge key (winding kept)."""
        a, b, c = tris[t]
        # Rotate so the split edge is (a, b).
        while (min(a, b), max(a, b)) != key:
            a, b, c = b, c, a
        for e in ((a, b), (b, c), (c, a)):
            edge_tris[(min(e), max(e))].remove(t)
        tris[t] = [a, m, c]
        tris.append([m, b, c])
        owner.append(owner[t])
        n = len(tris) - 1
        for tt, (x, y, z) in ((t, tris[t]), (n, tris[n])):
            for e in ((x, y), (y, z), (z, x)):
                edge_tris.setdefault((min(e), max(e)), []).append(tt)

    def bisect(key):
        a, b = key
        pa, pb = verts[a], verts[b]
        verts.append(((pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2, (pa[2] + pb[2]) / 2))
        m = len(verts) - 1
        for t in list(edge_tris.get(key, [])):
            split(t, key, m)

    work = [int(i) for i in too_long]
    while work:
        t = work.pop()
        if longest(t)[0] <= limit2:
            continue
        # Walk the longest-edge propagation path to a pair of triangles sharing their longest edge
        # (each step goes to a longer edge, so the walk ends), bisect that edge, then retry t.
        cur, visited = t, set()
        while True:
            _, key = longest(cur)
            others = [u for u in edge_tris[key] if u != cur]
            if not others or longest(others[0])[1] == key or others[0] in visited:
                before = len(tris)
                work.extend(edge_tris[key])
                bisect(key)
                work.extend(range(before, len(tris)))
                break
            visited.add(cur)
            cur = others[0]
        work.append(t)
        if len(tris) > max_triangles:
            raise UserError("Refining to a %.4g mm edge length would make over %d triangles; choose a longer "
                            "maximum edge length." % (max_edge, max_triangles))
    return (np.asarray(verts, dtype=np.float64), np.asarray(tris, dtype=np.int64),
            np.asarray(owner, dtype=np.int64))
