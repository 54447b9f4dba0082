"""pierce.Scene: meshes from numpy arrays, zero-copy views back, input errors with the core's message."""
import unittest

import numpy as np

import pierce


def unit_box(lo=(0, 0, 0), hi=(1, 1, 1)):
    m = pierce.gen.box(lo, hi)
    return m.vertices, m.triangles


class SceneTest(unittest.TestCase):
    def test_add_mesh_returns_ids_in_order_and_counts(self):
        s = pierce.Scene()
        v, t = unit_box()
        self.assertEqual(s.add_mesh(v, t, name="a"), 0)
        self.assertEqual(s.add_mesh(v + 2.0, t.astype(np.int64), name="b", source="here"), 1)
        self.assertEqual(len(s), 2)
        self.assertEqual(s.triangle_count, 24)
        self.assertEqual(s.names, ["a", "b"])
        self.assertEqual(s[1].source, "here")
        np.testing.assert_array_equal(s.bounds, [[0, 0, 0], [3, 3, 3]])
        self.assertAlmostEqual(s.scale, np.sqrt(27.0))

    def test_views_are_zero_copy_readonly_and_outlive_the_python_scene(self):
        s = pierce.Scene()
        v, t = unit_box()
        s.add_mesh(v, t)
        g = s.geometry(0)
        a, b = g.vertices, g.vertices
        self.assertEqual(a.__array_interface__["data"][0], b.__array_interface__["data"][0])  # same memory
        self.assertFalse(a.flags.writeable)
        with self.assertRaises(ValueError):
            a[0, 0] = 5.0
        np.testing.assert_array_equal(a, v)
        np.testing.assert_array_equal(g.triangles, t)
        self.assertEqual(g.triangles.dtype, np.uint32)
        del s, g  # the views keep the scene alive
        np.testing.assert_array_equal(a, v)

    def test_views_stay_valid_when_more_geometry_is_added(self):
        s = pierce.Scene()
        v, t = unit_box()
        s.add_mesh(v, t)
        first = s[0].vertices
        for k in range(20):
            s.add_mesh(v + k, t)
        np.testing.assert_array_equal(first, v)
        np.testing.assert_array_equal(s[-1].vertices, v + 19)

    def test_accepts_lists_float32_and_non_contiguous_input(self):
        s = pierce.Scene()
        v, t = unit_box()
        s.add_mesh(v.tolist(), t.tolist())
        s.add_mesh(v.astype(np.float32), t.astype(np.int32))
        s.add_mesh(np.asfortranarray(v), t[:, :])
        wide = np.zeros((len(v), 6))
        wide[:, ::2] = v
        s.add_mesh(wide[:, ::2], t)
        for i in range(4):
            np.testing.assert_array_equal(s[i].vertices, v)
            np.testing.assert_array_equal(s[i].triangles, t)

    def test_nan_vertex_is_an_input_error_naming_the_element(self):
        s = pierce.Scene()
        v, t = unit_box()
        v = v.copy()
        v[3, 1] = np.nan
        with self.assertRaises(pierce.InputError) as cm:
            s.add_mesh(v, t, name="broken", source="part.stl")
        msg = str(cm.exception)
        self.assertIn("3", msg)
        self.assertTrue("broken" in msg or "part.stl" in msg, msg)
        self.assertIsInstance(cm.exception, ValueError)
        self.assertEqual(len(s), 0)

    def test_bad_indices_are_input_errors(self):
        s = pierce.Scene()
        v, t = unit_box()
        bad = t.astype(np.int64)
        bad[5, 2] = 8  # one past the last vertex
        with self.assertRaises(pierce.InputError):
            s.add_mesh(v, bad)
        bad[5, 2] = -1
        with self.assertRaisesRegex(pierce.InputError, "triangle 5.*negative"):
            s.add_mesh(v, bad)
        with self.assertRaisesRegex(pierce.InputError, "beyond the 32-bit range"):
            s.add_mesh(v, np.full((1, 3), 2**40, dtype=np.uint64))

    def test_wrong_shapes_and_types_are_reported(self):
        s = pierce.Scene()
        v, t = unit_box()
        with self.assertRaisesRegex(ValueError, r"vertices must have shape \(N, 3\), got \(8, 2\)"):
            s.add_mesh(v[:, :2], t)
        with self.assertRaisesRegex(TypeError, "integers"):
            s.add_mesh(v, t.astype(np.float64))
        with self.assertRaises(TypeError):
            s.add_mesh(None, t)
        with self.assertRaises(IndexError):
            s.geometry(0)

    def test_generators(self):
        plates = pierce.gen.stacked_plates(3, 1.0, 0.1)
        self.assertEqual(len(plates), 3)
        s = pierce.Scene()
        for p in plates:
            s.add(p)
        self.assertEqual(s.triangle_count, 36)
        self.assertAlmostEqual(float(s.bounds[1, 2]), 0.3)
        moved = pierce.gen.translated(pierce.gen.box((0, 0, 0), (1, 1, 1)), (5, 0, 0))
        self.assertEqual(float(moved.vertices[:, 0].min()), 5.0)


if __name__ == "__main__":
    unittest.main()
