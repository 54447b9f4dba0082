"""pierce.trace: hits as structured arrays, kernel agreement, progress on the caller's thread, cancel."""
import threading
import unittest

import numpy as np

import pierce

EXACT = [k for k in pierce.kernels() if pierce.is_exact(k)]


def plates_scene(layers=10, thickness=0.1):
    s = pierce.Scene()
    for p in pierce.gen.stacked_plates(layers, 1.0, thickness):
        s.add(p)
    return s


def z_grid(n, z=-1.0, lo=0.0, hi=1.0):
    """n*n rays along +z through a grid that includes the plates' edges (x, y in {0, 1})."""
    xs = np.linspace(lo, hi, n)
    x, y = np.meshgrid(xs, xs)
    org = np.stack([x.ravel(), y.ravel(), np.full(x.size, z)], axis=1)
    return org, np.tile([0.0, 0.0, 1.0], (len(org), 1))


class TraceTest(unittest.TestCase):
    def test_box_hits_in_order_with_enter_flags(self):
        s = pierce.Scene()
        s.add(pierce.gen.box((0, 0, 0), (2, 3, 4), "b"))
        h = pierce.trace(s, [[0.5, 0.5, -1.0]], [[0, 0, 1]])
        self.assertEqual(len(h), 1)
        r = h.for_ray(0)
        np.testing.assert_allclose(r["t"], [1.0, 5.0])
        self.assertEqual(r["enter"].tolist(), [True, False])
        self.assertEqual(r["geom"].tolist(), [0, 0])
        self.assertEqual(r["ray"].tolist(), [0, 0])
        self.assertEqual(r["ng"].shape, (2, 3))
        self.assertLess(r["ng"][0, 2], 0)  # bottom face normal points down (outward)

    def test_touching_plates_every_exact_kernel_gives_every_surface_once(self):
        s = plates_scene(10)
        org, d = z_grid(17)  # 289 rays, some exactly along the plates' side faces and edges
        ref = pierce.trace(s, org, d, kernel="restart")
        inside = (org[:, 0] > 0) & (org[:, 0] < 1) & (org[:, 1] > 0) & (org[:, 1] < 1)
        self.assertTrue(np.all(ref.counts[inside] == 20))
        for k in EXACT:
            with self.subTest(kernel=k):
                h = pierce.trace(s, org, d, kernel=k)
                np.testing.assert_array_equal(h.offsets, ref.offsets)
                for f in ("ray", "t", "geom", "prim", "enter"):
                    np.testing.assert_array_equal(h.records[f], ref.records[f])

    def test_leave_before_enter_order_at_shared_faces(self):
        s = plates_scene(2, thickness=0.5)
        h = pierce.trace(s, [[0.5, 0.5, -1]], [[0, 0, 1]], order="leave_before_enter").for_ray(0)
        self.assertEqual(h["enter"].tolist(), [True, False, True, False])
        self.assertEqual(h["geom"].tolist(), [0, 0, 1, 1])
        np.testing.assert_allclose(h["t"], [1.0, 1.5, 1.5, 2.0])

    def test_max_hits_tmin_tmax(self):
        s = plates_scene(10)
        org, d = z_grid(3, lo=0.25, hi=0.75)
        self.assertTrue(np.all(pierce.trace(s, org, d, max_hits=3).counts == 3))
        # t in [1.05, 1.55]: the faces at z = 0.1 .. 0.5 , each shared by two plates -> 10 hits.
        h = pierce.trace(s, org, d, tmin=1.05, tmax=np.full(len(org), 1.55))
        self.assertTrue(np.all(h.counts == 10), h.counts)
        self.assertTrue(np.all((h.records["t"] >= 1.05) & (h.records["t"] <= 1.55)))

    def test_empty_batch(self):
        h = pierce.trace(plates_scene(1), np.zeros((0, 3)), np.zeros((0, 3)))
        self.assertEqual(len(h), 0)
        self.assertEqual(h.total, 0)

    def test_bad_rays_and_options(self):
        s = plates_scene(1)
        with self.assertRaisesRegex(pierce.InputError, "ray 1: direction is zero"):
            pierce.trace(s, [[0, 0, 0], [0, 0, 0]], [[0, 0, 1], [0, 0, 0]])
        with self.assertRaisesRegex(pierce.InputError, "ray 0: origin is not finite"):
            pierce.trace(s, [[np.inf, 0, 0]], [[0, 0, 1]])
        with self.assertRaisesRegex(ValueError, r"unknown kernel 'fast' \(expected one of: epsilon, .*queue"):
            pierce.trace(s, [[0, 0, 0]], [[0, 0, 1]], kernel="fast")
        with self.assertRaisesRegex(ValueError, "same length"):
            pierce.trace(s, [[0, 0, 0]], [[0, 0, 1], [0, 0, 1]])
        with self.assertRaisesRegex(ValueError, r"tmax must be a number or have shape \(1,\)"):
            pierce.trace(s, [[0, 0, 0]], [[0, 0, 1]], tmax=[1.0, 2.0])
        with self.assertRaises(TypeError):
            pierce.trace(s, [[0, 0, 0]], [[0, 0, 1]], progress=5)

    def test_scene_cannot_change_while_in_use_but_can_afterwards(self):
        s = plates_scene(1)
        pierce.trace(s, [[0.5, 0.5, -1]], [[0, 0, 1]])
        s.add(pierce.gen.box((0, 0, 5), (1, 1, 6)))  # invalidates the acceleration structures
        self.assertEqual(pierce.trace(s, [[0.5, 0.5, -1]], [[0, 0, 1]]).total, 4)


def assert_same_hits(test, want, got):
    """Same offsets and every record field bit for bit (floats compared as their bits)."""
    np.testing.assert_array_equal(got.offsets, want.offsets)
    for f in want.records.dtype.names:
        a, b = want.records[f], got.records[f]
        if a.dtype.kind == "f":
            a, b = a.view(f"u{a.dtype.itemsize}"), b.view(f"u{b.dtype.itemsize}")
        np.testing.assert_array_equal(b, a, err_msg=f)
    test.assertGreater(want.total, len(want))


class ArrayInputTest(unittest.TestCase):
    """Rays are read from the caller's arrays through their strides; any array-like is converted once."""

    @classmethod
    def setUpClass(cls):
        cls.scene = plates_scene(6)
        cls.scene.add(pierce.gen.box((0.3, 0.3, 0.1), (0.7, 0.7, 0.5), "box"))
        rng = np.random.default_rng(3)
        n = 5000  # many chunks per thread
        # Half on a grid through the plates' edges, half random through the scene.
        grid = np.column_stack([np.round(rng.uniform(0, 1, n // 2) * 8) / 8, rng.uniform(0, 1, n // 2),
                                np.full(n // 2, -1.0)])
        cls.org = np.vstack([grid, rng.uniform(-0.5, 1.5, (n - n // 2, 3))])
        cls.dir = np.vstack([np.column_stack([rng.uniform(-0.2, 0.2, n // 2), np.zeros(n // 2), np.ones(n // 2)]),
                             rng.normal(size=(n - n // 2, 3))])
        cls.tmin = rng.uniform(0.0, 0.8, n)
        cls.tmax = rng.uniform(1.2, 4.0, n)

    def trace(self, org, d, **kw):
        return pierce.trace(self.scene, org, d, **kw)

    def test_strided_and_converted_inputs_give_the_same_hits(self):
        want = self.trace(self.org, self.dir, tmin=self.tmin, tmax=self.tmax)
        n = len(self.org)
        wide = np.zeros((n, 6))
        wide[:, ::2] = self.org  # component stride 16 bytes
        reversed_dir = self.dir[::-1].copy()[::-1]  # negative row stride
        bounds = np.zeros((2, n))
        bounds[0], bounds[1] = self.tmin, self.tmax
        inputs = {
            "strided": (wide[:, ::2], reversed_dir, bounds[0, :], bounds[1, :]),
            "column strided": (wide[:, ::2], reversed_dir, bounds.T[:, 0], bounds.T[:, 1]),
            "fortran order": (np.asfortranarray(self.org), np.asfortranarray(self.dir), self.tmin, self.tmax),
            "big endian": (self.org.astype(">f8"), self.dir.astype(">f8"), self.tmin.astype(">f8"), self.tmax),
            "lists": (self.org.tolist(), self.dir.tolist(), self.tmin.tolist(), self.tmax.tolist()),
            "read-only": (np.lib.stride_tricks.as_strided(self.org, writeable=False), self.dir, self.tmin, self.tmax),
        }
        self.assertFalse(wide[:, ::2].flags.c_contiguous or reversed_dir.flags.c_contiguous)
        for name, (o, d, lo, hi) in inputs.items():
            with self.subTest(input=name):
                assert_same_hits(self, want, self.trace(o, d, tmin=lo, tmax=hi))
        with self.subTest(input="float32"):
            o32, d32 = self.org.astype(np.float32), self.dir.astype(np.float32)
            assert_same_hits(self, self.trace(o32.astype(float), d32.astype(float)), self.trace(o32, d32))

    def test_every_kernel_and_max_hits_on_strided_input(self):
        wide = np.zeros((len(self.org), 6))
        wide[:, 1::2] = self.org
        for k in pierce.kernels(include_double=True):
            for max_hits in (0, 2):
                with self.subTest(kernel=k, max_hits=max_hits):
                    assert_same_hits(self, self.trace(self.org, self.dir, kernel=k, max_hits=max_hits, tmax=self.tmax),
                                     self.trace(wide[:, 1::2], self.dir, kernel=k, max_hits=max_hits,
                                                tmax=self.tmax[::-1].copy()[::-1]))

    def test_one_value_for_every_ray_equals_that_value_per_ray(self):
        n = len(self.org)
        want = self.trace(self.org, self.dir, tmin=np.full(n, 0.25), tmax=np.full(n, 2.5))
        assert_same_hits(self, want, self.trace(self.org, self.dir, tmin=0.25, tmax=2.5))
        assert_same_hits(self, want, self.trace(self.org, self.dir, tmin=np.float32(0.25), tmax=np.array(2.5)))
        assert_same_hits(self, want, self.trace(self.org, self.dir, tmin=np.broadcast_to(0.25, (n,)), tmax=2.5))

    def test_inputs_are_not_changed(self):
        org, d = self.org.copy(), self.dir.copy()
        self.trace(org, d, tmin=self.tmin, tmax=self.tmax)
        np.testing.assert_array_equal(org, self.org)
        np.testing.assert_array_equal(d, self.dir)

    def test_bad_rays_in_strided_input_are_named(self):
        wide = np.zeros((40, 6))
        wide[:, ::2] = [0.5, 0.5, -1.0]
        dirs = np.tile([0.0, 0.0, 1.0], (40, 1))
        dirs[17] = [-0.0, 0.0, -0.0]
        dirs[30] = 0.0
        with self.assertRaisesRegex(pierce.InputError, "^ray 17: direction is zero$"):
            self.trace(wide[:, ::2], dirs[::-1][::-1])
        dirs[17] = [0.0, 0.0, 1.0]
        wide[3, 2] = np.nan
        with self.assertRaisesRegex(pierce.InputError, "^ray 3: origin is not finite$"):
            self.trace(wide[:, ::2], dirs)
        wide[3, 2] = 0.5
        tmax = np.full((40, 2), 3.0)
        tmax[9, 1] = np.nan
        with self.assertRaisesRegex(pierce.InputError, "^ray 9: tmin/tmax is NaN$"):
            self.trace(wide[:, ::2], dirs, tmax=tmax[:, 1])
        with self.assertRaisesRegex(pierce.InputError, "^ray 30: direction is zero$"):
            self.trace(wide[:, ::2], dirs)
        with self.assertRaisesRegex(ValueError, r"origins must have shape \(N, 3\), got \(40, 2\)"):
            self.trace(wide[:, ::3], dirs)
        with self.assertRaisesRegex(ValueError, r"tmin must be a number or have shape \(40,\)"):
            self.trace(wide[:, ::2], dirs, tmin=tmax)


class ProgressAndCancelTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # Big enough to run for several progress intervals (0.1 s) on any machine.
        cls.scene = pierce.Scene()
        for c in pierce.gen.cube_grid(6):
            cls.scene.add(c)
        rng = np.random.default_rng(1)
        n = 400_000
        cls.org = np.column_stack([rng.uniform(0, 6, n), rng.uniform(0, 6, n), np.full(n, -1.0)])
        cls.dir = np.tile([0.0, 0.0, 1.0], (n, 1))

    def test_progress_runs_on_calling_thread_and_ends_at_total(self):
        calls = []
        main = threading.get_ident()

        def progress(done, total):
            calls.append((threading.get_ident(), done, total))

        n = 20000
        pierce.trace(self.scene, self.org[:n], self.dir[:n], progress=progress)
        self.assertTrue(calls)
        self.assertTrue(all(t == main for t, _, _ in calls))
        self.assertEqual(calls[-1][1:], (n, n))
        self.assertTrue(all(a[1] <= b[1] for a, b in zip(calls, calls[1:])))

    def test_callback_returning_false_cancels(self):
        calls = []

        def stop(done, total):
            calls.append(done)
            return False

        with self.assertRaises(pierce.Cancelled):
            pierce.trace(self.scene, self.org, self.dir, kernel="restart", progress=stop)
        self.assertEqual(len(calls), 1)  # the first report stops it; no final report

    def test_exception_in_callback_propagates_and_stops(self):
        def boom(done, total):
            raise KeyError("from callback")

        with self.assertRaisesRegex(KeyError, "from callback"):
            pierce.trace(self.scene, self.org, self.dir, kernel="restart", progress=boom)

    def test_cancel_token_from_another_thread(self):
        token = pierce.CancelToken()
        timer = threading.Timer(0.05, token.cancel)
        timer.start()
        with self.assertRaises(pierce.Cancelled):
            pierce.trace(self.scene, self.org, self.dir, kernel="restart", cancel=token)
        timer.join()
        self.assertTrue(token.cancelled)
        token.reset()
        h = pierce.trace(self.scene, self.org[:10], self.dir[:10], cancel=token)
        self.assertEqual(len(h), 10)

    def test_other_python_threads_run_during_a_call(self):
        ticks = []
        stop = threading.Event()

        def ticker():
            while not stop.is_set():
                ticks.append(1)
                stop.wait(0.01)

        t = threading.Thread(target=ticker)
        t.start()
        try:
            pierce.trace(self.scene, self.org[:200000], self.dir[:200000], kernel="restart")
        finally:
            stop.set()
            t.join()
        self.assertGreater(len(ticks), 1)  # the GIL was released while tracing


if __name__ == "__main__":
    unittest.main()
