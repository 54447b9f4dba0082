"""Pierce: exact multi-hit ray traversal, from Python.

    import numpy as np, pierce
    scene = pierce.Scene()
    scene.add_mesh(vertices, triangles, name="part")      # (N,3) floats, (M,3) ints
    hits = pierce.trace(scene, origins, directions, kernel="queue")
    for i in range(len(hits)): print(hits.for_ray(i)["t"])

Long calls accept ``progress=callable(done, total)`` (called on the calling thread a few times a
second with the GIL held; return False to stop) and ``cancel=pierce.CancelToken()``; a stopped call
raises ``pierce.Cancelled``. Bad input raises ``pierce.InputError`` (a ValueError) with the core's
message.
"""
from . import _core
from ._core import *  # noqa: F401,F403  (Scene, Geometry, gen, kernels, analyses, errors, ...)
from ._core import CancelToken, Cancelled, InputError, Scene, gen, is_exact, kernels  # noqa: F401

__all__ = ["Scene", "Geometry", "gen", "load", "tessellation_defaults", "thickness_defaults",
           "default_color_range", "COLOR_RANGE_THIN_FACTOR", "COLOR_RANGE_PERCENTILES", "load_mesh", "load_rays", "mesh_report",
           "Hits", "trace", "kernels", "is_exact",
           "thickness", "thickness_at", "thickness_along", "THICKNESS_STATUS",
           "coplanar_overlaps", "ray_overlaps", "axis_grid_rays", "triangle_overlap_arrays", "clearance",
           "Partitions", "partitions", "Shots", "shotlines", "shotline", "SHOT_KINDS", "check_csg",
           "classify_points", "POINT_CLASSES", "gqa", "HAS_CAD",
           "CancelToken", "Cancelled", "InputError"]


class Hits:
    """Hits of a batch of rays: ``records`` is one structured array (fields ray, t, geom, prim,
    u, v, ng[3], enter) sorted by ray then hit order; ray i's hits are
    ``records[offsets[i]:offsets[i+1]]``."""

    def __init__(self, records, offsets):
        self.records = records
        self.offsets = offsets

    def __len__(self):
        """Number of rays."""
        return len(self.offsets) - 1

    @property
    def counts(self):
        """Number of hits per ray."""
        import numpy as np
        return np.diff(self.offsets)

    @property
    def total(self):
        return int(self.offsets[-1])

    def for_ray(self, i):
        return self.records[self.offsets[i]:self.offsets[i + 1]]

    def __repr__(self):
        return f"<pierce.Hits: {len(self)} rays, {self.total} hits>"


def trace(scene, origins, directions, *, tmin=0.0, tmax=float("inf"), kernel=_core.DEFAULT_KERNEL, max_hits=0,
          order="geom_prim", epsilon_rel=1e-5, progress=None, cancel=None):
    """Every hit of each ray origins[i] + t * directions[i], t in [tmin, tmax], in order.

    kernel: one of pierce.kernels() (all exact except 'epsilon'); max_hits: 0 = all;
    order: 'geom_prim' or 'leave_before_enter' (ties at equal t). Returns a Hits."""
    records, offsets = _core.trace(scene, origins, directions, tmin=tmin, tmax=tmax, kernel=kernel,
                                   max_hits=max_hits, order=order, epsilon_rel=epsilon_rel,
                                   progress=progress, cancel=cancel)
    return Hits(records, offsets)


def load(*paths, **tessellation):
    """A new Scene with every solid of the given files, one geometry per solid or part: STL, OBJ, OFF,
    PLY, and STEP/IGES/BREP when pierce.HAS_CAD (tessellated with linear_deflection in model units,
    0 = 0.1% of the diagonal, and angular_deflection in degrees; a solid whose mesh folds against the
    B-rep meshed again up to fold_remesh_rounds times; with max_edge > 0, longer triangle edges split,
    for more samples on big flat faces). Per-file info (units, warnings, per solid the
    tessellation checked against the B-rep) is in scene.load_info. Thickness maps of CAD solids are
    sampled on the exact B-rep (docs/THICKNESS.md). Options not given take
    pierce.tessellation_defaults(), the CLI's defaults."""
    unknown = set(tessellation) - set(_core.tessellation_defaults())
    if unknown:
        raise TypeError("load() got unexpected keyword argument(s): %s" % ", ".join(sorted(unknown)))
    scene = Scene()
    info = _core.add_model_files(scene, [str(p) for p in paths], **tessellation)
    scene.load_info = info
    return scene


class Partitions:
    """Per-ray intervals inside solids. ``records`` fields: ray, t_in, t_out, first, count (>= 2:
    overlap), in_geom, in_prim, in_ng[3], out_geom, out_prim, out_ng[3] (-1 where an interval was
    clipped to the ray's ends); the solids of record r are ``solids[r.first:r.first + r.count]``."""

    def __init__(self, d):
        self.records = d["partitions"]
        self.solids = d["solids"]
        self.offsets = d["offsets"]
        self.unmatched_leaves = d["unmatched_leaves"]
        self.unclosed = d["unclosed"]

    def __len__(self):
        return len(self.offsets) - 1

    def for_ray(self, i):
        return self.records[self.offsets[i]:self.offsets[i + 1]]

    def solids_of(self, record):
        return self.solids[int(record["first"]):int(record["first"]) + int(record["count"])]

    def __repr__(self):
        return f"<pierce.Partitions: {len(self)} rays, {int(self.offsets[-1])} partitions>"


def partitions(scene, origins, directions, *, tmin=0.0, tmax=float("inf"), kernel=_core.DEFAULT_KERNEL, progress=None,
               cancel=None):
    """For each ray, the intervals [t_in, t_out] and the solids whose inside covers each (Roth 1982).
    Touching solids give adjacent intervals with no gap; a solid the ray starts inside is known."""
    return Partitions(_core.partitions(scene, origins, directions, tmin=tmin, tmax=tmax, kernel=kernel,
                                       progress=progress, cancel=cancel))


class Shots:
    """Shotline rows of a batch of rays (BRL-CAD nirt). ``records`` fields: ray, kind (index into
    SHOT_KINDS: solid, overlap, region, gap), t_in, t_out, in_point[3], out_point[3], los,
    obliquity_in, obliquity_out (degrees; NaN where there is no surface), normal_thickness, in_geom,
    out_geom (-1: none), first, count (the row's solids are ``solids[first:first + count]``)."""

    def __init__(self, d, names):
        self.records = d["rows"]
        self.solids = d["solids"]
        self.rays = d["rays"]
        self.rays_hitting = d["rays_hitting"]
        self.unmatched_leaves = d["unmatched_leaves"]
        self.unclosed = d["unclosed"]
        self._names = names

    def __len__(self):
        return len(self.records)

    def rows(self, ray=None):
        """The rows (of one ray, or all) as dicts, with solid names."""
        out = []
        for r in self.records:
            if ray is not None and int(r["ray"]) != ray:
                continue
            ids = tuple(int(g) for g in self.solids[int(r["first"]):int(r["first"]) + int(r["count"])])
            out.append(dict(ray=int(r["ray"]), kind=_core.SHOT_KINDS[int(r["kind"])], solids=ids,
                            names=tuple(self._names[g] for g in ids), t_in=float(r["t_in"]),
                            t_out=float(r["t_out"]), in_point=tuple(float(x) for x in r["in_point"]),
                            out_point=tuple(float(x) for x in r["out_point"]), los=float(r["los"]),
                            obliquity_in=float(r["obliquity_in"]), obliquity_out=float(r["obliquity_out"]),
                            normal_thickness=float(r["normal_thickness"]),
                            in_geom=int(r["in_geom"]), out_geom=int(r["out_geom"])))
        return out

    def __repr__(self):
        return f"<pierce.Shots: {self.rays} rays, {len(self)} rows>"


def shotlines(scene, origins, directions, *, tmin=0.0, tmax=float("inf"), kernel=_core.DEFAULT_KERNEL, csg=None,
              tie_tolerance_rel=1e-6, progress=None, cancel=None):
    """Shotlines of many rays: per ray, the solids (or, with csg="union(a, b)" etc., the expression's
    regions), overlaps and gaps it passes through, with entry/exit points, line-of-sight length,
    obliquity and normal thickness. Returns Shots."""
    d = _core.shoot(scene, origins, directions, tmin=tmin, tmax=tmax, kernel=kernel, csg=csg,
                    tie_tolerance_rel=tie_tolerance_rel, progress=progress, cancel=cancel)
    return Shots(d, scene.names)


def shotline(scene, origin, direction, *, tmin=0.0, tmax=float("inf"), kernel=_core.DEFAULT_KERNEL, csg=None):
    """One ray's shotline rows as dicts (see Shots.rows)."""
    import numpy as np
    o = np.asarray(origin, dtype=float).reshape(1, 3)
    d = np.asarray(direction, dtype=float).reshape(1, 3)
    return shotlines(scene, o, d, tmin=tmin, tmax=tmax, kernel=kernel, csg=csg).rows()
