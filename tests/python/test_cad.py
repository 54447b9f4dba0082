"""CAD input in Python: thickness on the exact B-rep, the tessellation status and thickness_at.
The models are written by the tests' OpenCASCADE builder (PIERCE_MAKE_MODELS)."""
import math
import os
import subprocess
import tempfile
import unittest

import numpy as np

import pierce


@unittest.skipUnless(pierce.HAS_CAD, "built without OpenCASCADE")
class CadThicknessTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        subprocess.run([os.environ["PIERCE_MAKE_MODELS"], cls.tmp.name], check=True)
        cls.sheet = os.path.join(cls.tmp.name, "sheet.brep")
        cls.folded = os.path.join(cls.tmp.name, "folded.brep")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_status_names_include_tessellation(self):
        self.assertEqual(pierce.THICKNESS_STATUS, ("ok", "no_exit", "no_normal", "tessellation"))

    def test_sheet_per_face_is_brep_true(self):
        s = pierce.Scene()
        pierce.add_model_files(s, [self.sheet])
        r = pierce.thickness(s, per="face")
        st = r.solids[0]
        self.assertTrue(st.exact)
        self.assertEqual(st.tessellation, 0)
        self.assertEqual(len(r.brep_faces), len(r))
        # Samples on the big faces (normal in the x-z plane, not at the legs' ends) read 0.5.
        n = r.normal
        big = (np.abs(n[:, 1]) < 0.5) & ~((np.abs(n[:, 0]) > 0.99) & (r.point[:, 0] > 11.99)) & \
            ~((np.abs(n[:, 2]) > 0.99) & (r.point[:, 2] > 11.99))
        self.assertGreater(big.sum(), 40)
        np.testing.assert_allclose(r.thickness[big], 0.5, atol=1e-9)
        self.assertGreaterEqual(st.summary.min, 0.5 - 1e-9)

    def test_folded_flagged_is_excluded_and_counted(self):
        s = pierce.Scene()
        pierce.add_model_files(s, [self.folded], linear_deflection=0.05, fold_remesh_rounds=0)
        r = pierce.thickness(s, per="face")
        tess = r.status == pierce.THICKNESS_STATUS.index("tessellation")
        self.assertGreaterEqual(tess.sum(), 1)
        self.assertEqual(r.solids[0].tessellation, tess.sum())
        self.assertTrue(np.all(np.isnan(r.thickness[tess])))
        self.assertEqual(r.solids[0].valid, np.isfinite(r.thickness).sum())
        self.assertGreaterEqual(r.solids[0].summary.min, 1 - 1e-6)
        # Meshed again (the default), no fold is left.
        s2 = pierce.Scene()
        info = pierce.add_model_files(s2, [self.folded], linear_deflection=0.05)
        self.assertEqual(info[0]["tessellation"][0]["folded_found"], 1)
        self.assertEqual(info[0]["tessellation"][0]["folded"], 0)
        self.assertEqual(pierce.thickness(s2, per="face").solids[0].tessellation, 0)
        # pierce.load passes the option on and keeps the report.
        s3 = pierce.load(self.folded, linear_deflection=0.05, fold_remesh_rounds=0)
        t = s3.load_info[0]["tessellation"][0]
        self.assertEqual((t["folded"], t["folded_found"], t["remesh_rounds"], t["brep_faces"]), (1, 1, 0, 26))

    def test_thickness_at_points(self):
        s = pierce.Scene()
        pierce.add_model_files(s, [self.sheet])
        pts = [[6, 4, -0.01], [0.5, 3, 6], [6, 4, 0.2]]
        r = pierce.thickness_at(s, 0, pts)
        self.assertEqual(len(r), 3)
        np.testing.assert_allclose(r.thickness, 0.5, atol=1e-9)
        self.assertTrue(np.all(r.status == 0))
        self.assertAlmostEqual(r.point[0, 2], 0.0, places=12)
        r2 = pierce.thickness_at(s, [0, 0], pts[:2], normals=[[0, 0, -1], [1, 0, 0]])
        np.testing.assert_allclose(r2.thickness, 0.5, atol=1e-9)
        with self.assertRaises(ValueError):
            pierce.thickness_at(s, 5, pts)
        with self.assertRaises(ValueError):
            pierce.thickness_at(s, [0, 0], pts)


if __name__ == "__main__":
    unittest.main()
