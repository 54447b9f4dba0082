"""Analyses through the bindings: thickness, overlaps, partitions, shotlines, CSG, gqa, mesh report,
file loading; results checked against known geometry."""
import math
import os
import tempfile
import unittest

import numpy as np

import pierce

gen = pierce.gen


def scene_of(*meshes):
    s = pierce.Scene()
    for m in meshes:
        s.add(m)
    return s


def sphere_mesh(radius, subdivisions=4, inward=False, name="sphere"):
    """Icosphere from the blob generator's topology, projected onto a sphere."""
    b = gen.blob(subdivisions, 7, 0.0)
    v = b.vertices - b.vertices.mean(axis=0)
    v = v / np.linalg.norm(v, axis=1)[:, None] * radius
    t = b.triangles[:, ::-1] if inward else b.triangles
    return gen.Mesh(v, t, name)


class ThicknessTest(unittest.TestCase):
    def test_option_names_come_from_core_and_are_accepted(self):
        self.assertEqual(pierce.thickness_methods(), ["ray", "cone", "sphere"])
        self.assertEqual(pierce.thickness_samplings(), ["vertex", "face"])
        self.assertEqual(pierce.cone_aggregates(), ["shapira", "median"])
        self.assertEqual(pierce.THICKNESS_STATUS, ("ok", "no_exit", "no_normal", "tessellation"))
        s = scene_of(gen.box((0, 0, 0), (1, 1, 1), "a"))
        for method in pierce.thickness_methods():
            for per in pierce.thickness_samplings():
                self.assertEqual(pierce.thickness(s, method=method, per=per, cone_rays=4).per, per)
        with self.assertRaisesRegex(ValueError, r"unknown thickness method 'laser' \(expected one of: ray, cone, sphere\)"):
            pierce.thickness(s, method="laser")

    def test_touching_boxes_each_their_own_width(self):
        s = scene_of(gen.box((0, 0, 0), (10, 10, 10), "a"), gen.box((10, 0, 0), (13, 10, 10), "b"))
        r = pierce.thickness(s, per="face")
        self.assertEqual(len(r), 24)
        self.assertEqual(r.per, "face")
        along_x = np.abs(r.normal[:, 0]) > 0.99
        a, b = r.solid == 0, r.solid == 1
        np.testing.assert_allclose(r.thickness[a & along_x], 10.0, rtol=1e-6)
        np.testing.assert_allclose(r.thickness[b & along_x], 3.0, rtol=1e-6)
        self.assertEqual([x.name for x in r.solids], ["a", "b"])
        self.assertAlmostEqual(r.solids[1].summary.min, 3.0, places=5)
        self.assertAlmostEqual(r.solids[1].summary.percentile(50), 10.0, places=5)

    def test_hollow_sphere_shell(self):
        outer = sphere_mesh(1.0)
        inner = sphere_mesh(0.95, inward=True)
        shell = gen.Mesh(np.vstack([outer.vertices, inner.vertices]),
                         np.vstack([outer.triangles, inner.triangles + len(outer.vertices)]), "shell")
        r = pierce.thickness(scene_of(shell), per="vertex")
        ok = np.abs(r.thickness - 0.05) < 0.005
        self.assertGreaterEqual(ok.mean(), 0.99)
        self.assertTrue(r.completed)

    def test_thin_flag_max_distance_and_views(self):
        s = scene_of(gen.box((0, 0, 0), (10, 10, 1)))
        r = pierce.thickness(s, per="face", min_thickness=2.0, max_distance=5.0)
        z = np.abs(r.normal[:, 2]) > 0.99
        self.assertTrue(np.all(r.thin[z]))
        self.assertTrue(np.all(np.isnan(r.thickness[~z])))  # 10 mm across: beyond max_distance
        self.assertTrue(np.all(r.status[~z] == pierce.THICKNESS_STATUS.index("no_exit")))
        self.assertFalse(r.thickness.flags.writeable)
        self.assertEqual(r.point.shape, (12, 3))

    def test_thin_and_thick_regions(self):
        # A 10 x 10 x 1 plate: the top and bottom (1 thick) are one thin region, both sides; the
        # four sides (10 across) one thick region.
        s = scene_of(gen.box((0, 0, 0), (10, 10, 1)))
        r = pierce.thickness(s, per="face", min_thickness=2.0, max_thickness=5.0)
        self.assertEqual(r.region.dtype, np.int32)
        self.assertFalse(r.region.flags.writeable)
        self.assertEqual(len(r.thin_regions), 1)
        self.assertEqual(len(r.thick_regions), 1)
        z = np.abs(r.normal[:, 2]) > 0.99
        self.assertTrue(np.all(r.region[z] == 0))
        self.assertTrue(np.all(r.region[~z] == 1))
        thin, thick = r.thin_regions[0], r.thick_regions[0]
        self.assertEqual(thin.solid, 0)
        self.assertAlmostEqual(thin.thickness, 1.0, delta=1e-12)
        self.assertEqual(thin.min_thickness, thin.thickness)
        self.assertIsNone(thin.max_thickness)
        self.assertFalse(thin.thick)
        self.assertAlmostEqual(thin.area, 200.0, delta=20.0)
        self.assertEqual(thin.area_sides, "both")
        self.assertEqual(thin.samples, 4)
        self.assertAlmostEqual(abs(thin.point[2] - thin.exit[2]), 1.0, delta=1e-12)
        self.assertEqual(thin.faces, [])
        self.assertAlmostEqual(thick.thickness, 10.0, delta=1e-11)
        self.assertEqual(thick.max_thickness, thick.thickness)
        self.assertIsNone(thick.min_thickness)
        self.assertTrue(thick.thick)
        self.assertAlmostEqual(thick.area, 40.0, delta=4.0)
        self.assertEqual(thick.samples, 8)
        # Exactly the threshold is not thin; nothing flagged without thresholds.
        self.assertEqual(len(pierce.thickness(s, per="face", min_thickness=1.0).thin_regions), 0)
        r0 = pierce.thickness(s, per="face")
        self.assertTrue(np.all(r0.region == -1))
        with self.assertRaises(ValueError):
            pierce.thickness(s, min_thickness=2.0, max_thickness=1.0)

    def test_only_selected_solids_are_sampled(self):
        s = scene_of(gen.box((0, 0, 0), (1, 1, 1)), gen.box((5, 0, 0), (6, 1, 1)))
        r = pierce.thickness(s, solids=[1])
        self.assertTrue(np.all(r.solid == 1))
        with self.assertRaisesRegex(ValueError, "solid 7 is not in the scene"):
            pierce.thickness(s, solids=[7])
        with self.assertRaisesRegex(ValueError, "unknown thickness method"):
            pierce.thickness(s, method="laser")

    def test_thickness_along_given_normals(self):
        s = scene_of(gen.box((0, 0, 0), (10, 4, 2)))
        t = pierce.thickness_along(s, 0, [[5, 2, 0], [0, 2, 1], [5, 0, 1]], [[0, 0, 3], [1, 0, 0], [0, 1, 0]])
        np.testing.assert_allclose(t, [2.0, 10.0, 4.0], rtol=1e-6)

    def test_cancel(self):
        s = scene_of(gen.blob(5))
        tok = pierce.CancelToken()
        tok.cancel()
        with self.assertRaises(pierce.Cancelled):
            pierce.thickness(s, cancel=tok)


class SharedDefaultsTest(unittest.TestCase):
    def test_default_color_range(self):
        values = np.arange(1.0, 101.0)  # 1..100: P2 = 2.98, P98 = 98.02 (linear interpolation)
        lo, hi = pierce.default_color_range(values)
        self.assertAlmostEqual(lo, np.percentile(values, 2), places=12)
        self.assertAlmostEqual(hi, np.percentile(values, 98), places=12)
        self.assertEqual(pierce.COLOR_RANGE_PERCENTILES, (2.0, 98.0))
        # A thin threshold T: 0 to 4 T, whatever the values.
        self.assertEqual(pierce.default_color_range(values, 1.5), (0.0, 4.0 * 1.5))
        self.assertEqual(pierce.COLOR_RANGE_THIN_FACTOR, 4.0)
        # Non-finite values are left out; none at all gives (0, 1); one value a non-empty range.
        self.assertEqual(pierce.default_color_range([math.nan, 2.0, math.inf, 2.0])[0], 2.0)
        self.assertGreater(*reversed(pierce.default_color_range([2.0, 2.0])))
        self.assertEqual(pierce.default_color_range([]), (0.0, 1.0))

    def test_thickness_defaults_are_the_functions_defaults(self):
        d = pierce.thickness_defaults()
        self.assertEqual(d, {"method": "ray", "per": "vertex"})
        scene = scene_of(gen.cube_grid(1)[0])
        self.assertEqual(pierce.thickness(scene).per, d["per"])

    def test_tessellation_defaults(self):
        d = pierce.tessellation_defaults()
        self.assertEqual(set(d), {"linear_deflection", "angular_deflection", "fold_remesh_rounds", "max_edge"})
        self.assertEqual(d["max_edge"], 0.0)  # long edges are not split unless asked
        with self.assertRaises(TypeError):
            pierce.load("x.stl", deflection=1.0)  # a misspelt option is an error, not ignored


class OverlapTest(unittest.TestCase):
    def test_interpenetration_depth_and_contacts(self):
        s = scene_of(gen.box((0, 0, 0), (10, 10, 10), "a"), gen.box((7.5, 1, 1), (17.5, 9, 9), "b"),
                     gen.box((17.5, 1, 1), (20, 9, 9), "c"))
        r = pierce.ray_overlaps(s, grid=16)
        self.assertEqual([(p.a, p.b) for p in r.interferences], [(0, 1)])
        self.assertAlmostEqual(r.interferences[0].penetration, 2.5, places=4)
        self.assertEqual([(p.a, p.b) for p in r.contacts], [(1, 2)])
        self.assertGreater(len(r.intervals), 0)
        self.assertTrue(np.all(r.intervals["depth"] > 0))
        cop = pierce.coplanar_overlaps(s)
        self.assertEqual([(p.a, p.b) for p in cop.solid_pairs], [(1, 2)])
        self.assertAlmostEqual(cop.solid_pairs[0].area, 64.0)
        self.assertTrue(np.all(~cop.pairs["same_facing"]))
        heat = pierce.triangle_overlap_arrays(s, cop, r)
        self.assertEqual(len(heat["overlap_count"]), s.triangle_count)
        self.assertGreater(heat["interference_hits"][:24].sum(), 0)

    def test_duplicated_face_and_statistic(self):
        box = gen.box((0, 0, 0), (1, 1, 1))
        s = scene_of(gen.duplicated(box, 2, False))
        cop = pierce.coplanar_overlaps(s)
        self.assertEqual(len(cop.pairs), 12)
        self.assertTrue(np.all(cop.pairs["same_facing"]))
        r = pierce.ray_overlaps(s, grid=4)
        self.assertEqual(r.coplanar.share_equal, 1.0)

    def test_clearance_pairs(self):
        # a-b touch on x = 1, b-c 0.3 apart along x, c-d clash 0.5 deep along x, b-d 0.8 apart, e far.
        s = scene_of(gen.box((0, 0, 0), (1, 1, 1), "a"), gen.box((1, 0, 0), (2, 1, 1), "b"),
                     gen.box((2.3, 0, 0), (3.3, 1, 1), "c"), gen.box((2.8, -5, -5), (12.8, 5, 5), "d"),
                     gen.box((40, 0, 0), (41, 1, 1), "e"))
        r = pierce.clearance(s, clearance=0.5, grid=64)
        self.assertTrue(r.completed)
        self.assertEqual([(p.kind, p.solid_a, p.solid_b) for p in r.pairs],
                         [("clash", 2, 3), ("contact", 0, 1), ("clearance", 1, 2)])
        clash, contact, gap = r.pairs
        self.assertAlmostEqual(clash.depth, 0.5, delta=0.005)
        self.assertTrue(math.isnan(clash.gap))
        self.assertEqual(contact.gap, 0.0)
        self.assertAlmostEqual(gap.gap, 0.3, delta=1e-9)
        self.assertEqual(gap.point[0], 2.0)
        self.assertEqual(gap.point_b[0], 2.3)
        self.assertEqual(len(r.triangle_clearance), s.triangle_count)
        self.assertTrue(np.all(r.triangle_clearance <= 0.5))
        # e's triangles have no other solid within the clearance.
        self.assertTrue(np.all(r.triangle_clearance[r.tri_offset[4]:r.tri_offset[5]] == 0.5))
        # Clearance 0: clash and contact only.
        self.assertEqual([p.kind for p in pierce.clearance(s, grid=64).pairs], ["clash", "contact"])
        with self.assertRaises(ValueError):
            pierce.clearance(s, clearance=-1)

    def test_axis_grid_rays(self):
        s = scene_of(gen.box((0, 0, 0), (1, 2, 3)))
        o, d, lo, hi = pierce.axis_grid_rays(s, 4, axes=[2])
        self.assertEqual(o.shape, (16, 3))
        self.assertTrue(np.all(d == [0, 0, 1]))
        with self.assertRaises(ValueError):
            pierce.axis_grid_rays(s, 4, axes=[3])


class PartitionTest(unittest.TestCase):
    def test_touching_nested_and_ray_starting_inside(self):
        plates = gen.stacked_plates(3, 1.0, 0.5)
        s = scene_of(*plates)
        p = pierce.partitions(s, [[0.5, 0.5, -1], [0.5, 0.5, 0.75]], [[0, 0, 1], [0, 0, 1]])
        r0 = p.for_ray(0)
        np.testing.assert_allclose(r0["t_in"], [1.0, 1.5, 2.0])
        np.testing.assert_allclose(r0["t_out"], [1.5, 2.0, 2.5])
        self.assertEqual([list(p.solids_of(x)) for x in r0], [[0], [1], [2]])
        r1 = p.for_ray(1)  # starts inside plate 1: clipped at t = 0, no entry crossing
        self.assertEqual(r1["t_in"][0], 0.0)
        self.assertEqual(r1["in_geom"][0], -1)
        self.assertEqual(int(r1["out_geom"][0]), 1)

    def test_shotline_rows(self):
        s = scene_of(gen.box((0, 0, 0), (10, 10, 10), "a"), gen.box((8, 0, 0), (13, 10, 10), "b"),
                     gen.box((15, 0, 0), (16, 10, 10), "c"))
        rows = pierce.shotline(s, (-1, 5, 5), (1, 0, 0))
        self.assertEqual([r["kind"] for r in rows], ["solid", "overlap", "solid", "gap", "solid"])
        self.assertEqual(rows[1]["names"], ("a", "b"))
        self.assertAlmostEqual(rows[1]["los"], 2.0)
        self.assertAlmostEqual(rows[3]["los"], 2.0)
        diag = pierce.shotline(s, (-1, 5, 4), (1, 0, 1))[0]
        self.assertAlmostEqual(diag["obliquity_in"], 45.0)
        self.assertAlmostEqual(diag["normal_thickness"], diag["los"] * math.cos(math.radians(45)))
        shots = pierce.shotlines(s, [[-1, 5, 5], [-1, 50, 5]], [[1, 0, 0], [1, 0, 0]])
        self.assertEqual(shots.rays, 2)
        self.assertEqual(shots.rays_hitting, 1)

    def test_csg(self):
        s = scene_of(gen.box((0, 0, 0), (10, 10, 10), "a"), gen.box((8, 0, 0), (13, 10, 10), "b"))
        rows = pierce.shotline(s, (-1, 5, 5), (1, 0, 0), csg="intersection(a, b)")
        regions = [r for r in rows if r["kind"] == "region"]
        self.assertEqual(len(regions), 1)
        self.assertAlmostEqual(regions[0]["los"], 2.0)
        cls = pierce.classify_points(s, [[1, 5, 5], [9, 5, 5], [12, 5, 5], [30, 5, 5]], "difference(a, b)")
        self.assertEqual([pierce.POINT_CLASSES[c] for c in cls], ["inside", "outside", "outside", "outside"])
        with self.assertRaisesRegex(pierce.InputError, "unknown solid name 'z'"):
            pierce.check_csg(s, "union(a, z)")

    def test_gqa_volume(self):
        s = scene_of(gen.box((0, 0, 0), (2, 3, 4), "a"))
        g = pierce.gqa(s, tolerance=1e-3)
        self.assertTrue(g.converged)
        self.assertAlmostEqual(g.solids[0].volume, 24.0, delta=24.0 * 1e-3)
        np.testing.assert_allclose(g.solids[0].centroid, [1, 1.5, 2], atol=1e-2)


class FilesAndReportTest(unittest.TestCase):
    def test_obj_groups_load_with_names_and_report(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "two.obj")
            lines, base = [], 1
            for name, lo, hi in (("left", (0, 0, 0), (1, 1, 1)), ("right", (1, 0, 0), (2, 1, 1))):
                m = gen.box(lo, hi, name)
                lines.append("o " + name)
                lines += ["v %r %r %r" % tuple(v) for v in m.vertices]
                lines += ["f %d %d %d" % tuple(t + base) for t in m.triangles]
                base += len(m.vertices)
            with open(path, "w") as f:
                f.write("\n".join(lines) + "\n")
            s = pierce.load(path)
            self.assertEqual(s.names, ["left", "right"])
            self.assertEqual(s[0].source, path)
            rep = pierce.mesh_report(s)
            self.assertTrue(all(r.closed for r in rep))
            self.assertAlmostEqual(rep[1].volume, 1.0)
            bad = os.path.join(d, "bad.obj")
            with open(bad, "w") as f:
                f.write("v 0 0 0\nv 1 0 0\nf 1 2 9\n")
            with self.assertRaisesRegex(pierce.InputError, "bad.obj"):
                pierce.load(bad)
            with self.assertRaisesRegex(pierce.InputError, "missing.stl"):
                pierce.load(os.path.join(d, "missing.stl"))
            s2 = pierce.Scene()
            with self.assertRaises(pierce.InputError):
                pierce.add_model_files(s2, [path, bad])
            self.assertEqual(len(s2), 0)  # a bad file leaves the scene as it was

    def test_open_mesh_reported(self):
        box = gen.box((0, 0, 0), (1, 1, 1))
        s = pierce.Scene()
        s.add_mesh(box.vertices, box.triangles[:10], name="open")
        rep = pierce.mesh_report(s)[0]
        self.assertFalse(rep.closed)
        self.assertEqual(rep.boundary_edges, 4)
        r = pierce.thickness(s, per="face")
        self.assertGreater(r.solids[0].no_exit, 0)  # rays escaping through the hole: no thickness


if __name__ == "__main__":
    unittest.main()
