"""Solids to triangle meshes for Pierce, one geometry per solid, keeping which B-rep face each
triangle comes from. The user's shapes are copied first, so their own triangulation (and display)
stays as it was."""
import math

import numpy as np

from .errors import UserError


class MeshedSolid:
    """A solid's triangles: vertices (N, 3) float64, triangles (M, 3) int64, face_of_triangle (M,)
    index into ref.shape.Faces; `geom` is its geometry id in the scene."""

    def __init__(self, ref, vertices, triangles, face_of_triangle, geom):
        self.ref = ref
        self.vertices = vertices
        self.triangles = triangles
        self.face_of_triangle = face_of_triangle
        self.geom = geom


class Model:
    """Meshed solids and the pierce.Scene built from them (geometry id = position in `solids`)."""

    def __init__(self, scene, solids, deflection, warnings):
        self.scene = scene
        self.solids = solids
        self.deflection = deflection
        self.warnings = warnings


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


def build_model(refs, deflection=0.0, angular_deflection_deg=15.0, progress=None):
    """Meshes every SolidRef into one pierce.Scene. deflection 0: auto_deflection.
    progress(done, total) is called after each solid; returning False stops with UserError."""
    from .locate import import_pierce
    pierce = import_pierce()
    if deflection < 0 or not math.isfinite(deflection):
        raise UserError("The deflection must be a positive length (or 0 for automatic).")
    if deflection == 0:
        deflection = auto_deflection([r.shape for r in refs])
    scene = pierce.Scene()
    solids, warnings = [], []
    for k, ref in enumerate(refs):
        v, t, f = mesh_solid(ref.shape, deflection, angular_deflection_deg)
        if len(t) == 0:
            warnings.append("'%s' gave no triangles and is skipped" % ref.label)
        else:
            geom = scene.add_mesh(v, t, name=ref.label, source=ref.obj.Name)
            solids.append(MeshedSolid(ref, v, t, f, geom))
        if progress is not None and progress(k + 1, len(refs)) is False:
            raise UserError("Stopped while meshing.")
    if not solids:
        raise UserError("None of the selected solids could be meshed.")
    for rep in pierce.mesh_report(scene):
        if not rep.closed:
            warnings.append("the mesh of '%s' is not closed (%d open, %d non-manifold edges): rays "
                            "may leave through the gaps" % (rep.name, rep.boundary_edges,
                                                            rep.non_manifold_edges))
    return Model(scene, solids, deflection, warnings)
