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
           "classify_points", "POINT_CLASSES", "gqa", "HAS_CAD", "report",
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
    # What pierce.report passes to the `pierce` binary, so that it reads the files alike.
    scene.load_options = dict(_core.tessellation_defaults(), **tessellation, paths=[str(p) for p in paths])
    return scene


def _pierce_binary():
    """The `pierce` program: $PIERCE_BINARY, the build tree's bin/pierce next to this package
    (build/python/pierce -> build/bin/pierce), or `pierce` on the PATH."""
    import os
    import shutil
    env = os.environ.get("PIERCE_BINARY")
    if env:
        return env
    here = os.path.dirname(os.path.abspath(__file__))
    built = os.path.join(here, os.pardir, os.pardir, "bin", "pierce")
    if os.access(built, os.X_OK):
        return os.path.normpath(built)
    found = shutil.which("pierce")
    if not found:
        raise FileNotFoundError("pierce.report needs the `pierce` program: install Pierce, or set PIERCE_BINARY")
    return found


def report(scene, path, *, min_thickness=0.0, max_thickness=None, clearance=0.0, method="ray", per="vertex",
           kernel=None, title=None, linear_deflection=None, angular_deflection=None, force=False):
    """Writes the HTML report of `pierce report` (docs/REPORT.md) for `scene` to `path`: one
    self-contained file with the 3D thickness map, thin and thick walls, contact / clash /
    clearance pairs, statistics, model checks and what exactness cost.

    `scene`: a Scene from pierce.load (its files are read again by the `pierce` program with the
    same tessellation options, so CAD solids keep their B-rep), or any other Scene (its meshes are
    written to a temporary OBJ, one object per geometry), or a list of model file paths (CAD ones
    tessellated with linear_deflection and angular_deflection when given, as pierce.load). Raises
    FileExistsError if `path` exists and not force, InputError for what `pierce` rejects. Returns
    `path`."""
    import os
    import subprocess
    import tempfile
    path = str(path)
    if os.path.exists(path) and not force:
        raise FileExistsError(path + " exists (force=True replaces it)")
    args = []
    with tempfile.TemporaryDirectory(prefix="pierce_report.") as tmp:
        options = getattr(scene, "load_options", None) if isinstance(scene, Scene) else None
        if isinstance(scene, (list, tuple)):
            args += [str(p) for p in scene]
            if linear_deflection is not None:
                args += ["--deflection", repr(float(linear_deflection))]
            if angular_deflection is not None:
                args += ["--angular-deflection", repr(float(angular_deflection))]
        elif options is not None and len(scene) == sum(f["geometries"][1] for f in scene.load_info):
            args += options["paths"]
            args += ["--deflection", repr(float(options["linear_deflection"])),
                     "--angular-deflection", repr(float(options["angular_deflection"])),
                     "--fold-remesh-rounds", str(options["fold_remesh_rounds"]),
                     "--max-edge", repr(float(options["max_edge"]))]
        else:
            obj = os.path.join(tmp, "scene.obj")
            with open(obj, "w") as f:
                base = 1
                for i in range(len(scene)):
                    g = scene[i]
                    f.write("o %s\n" % (g.name or "#%d" % i))
                    f.writelines("v %r %r %r\n" % (float(x), float(y), float(z)) for x, y, z in g.vertices)
                    f.writelines("f %d %d %d\n" % (a + base, b + base, c + base) for a, b, c in g.triangles)
                    base += len(g.vertices)
            args.append(obj)
        args += ["--min", repr(float(min_thickness)), "--clearance", repr(float(clearance)), "--method", method,
                 "--per", per, "-o", path]
        if max_thickness is not None:
            args += ["--max", repr(float(max_thickness))]
        if kernel is not None:
            args += ["--kernel", kernel]
        if title is not None:
            args += ["--title", str(title)]
        if force:
            args.append("--force")
        run = subprocess.run([_pierce_binary(), "report"] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, check=False)
    if run.returncode == 2 or run.returncode >= 100:  # pierce's bad input, or an option it rejects (CLI11)
        raise InputError(run.stderr.strip().splitlines()[0].replace("pierce: error: ", ""))
    if run.returncode != 0:
        raise RuntimeError("pierce report failed (exit %d): %s" % (run.returncode, run.stderr.strip()))
    return path


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
