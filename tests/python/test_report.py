"""pierce.report: the HTML report of `pierce report` from a loaded scene, a scene built in Python,
and a list of files (the page's data checked through tests/report/report_models.py)."""
import os
import sys
import tempfile
import unittest

import pierce

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "report"))
from report_models import report_data, write_blocks  # noqa: E402


class ReportTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_scene_built_in_python(self):
        scene = pierce.Scene()
        scene.add(pierce.gen.box((0, 0, 0), (4, 4, 0.25), "plate"))
        path = pierce.report(scene, os.path.join(self.dir, "plate.html"), min_thickness=0.5, per="face")
        with open(path, encoding="utf-8") as f:
            data = report_data(f.read())
        self.assertEqual(data["solid_names"], ["plate"])
        thin = [f for f in data["findings"] if f["kind"] == "thin"]
        self.assertEqual(len(thin), 1)
        self.assertAlmostEqual(thin[0]["thickness"], 0.25, places=12)
        with self.assertRaises(FileExistsError):
            pierce.report(scene, path)
        pierce.report(scene, path, force=True)
        with self.assertRaises(pierce.InputError):
            pierce.report(scene, os.path.join(self.dir, "x.html"), method="bogus")
        self.assertFalse(os.path.exists(os.path.join(self.dir, "x.html")))

    def test_loaded_scene_and_files(self):
        obj = os.path.join(self.dir, "blocks.obj")
        write_blocks(obj)
        for source in (pierce.load(obj), [obj]):
            path = pierce.report(source, os.path.join(self.dir, "blocks.html"), clearance=0.5, force=True)
            with open(path, encoding="utf-8") as f:
                data = report_data(f.read())
            kinds = [f["kind"] for f in data["findings"] if "solid_b" in f]
            self.assertEqual(kinds, ["clash", "contact", "clearance"])
            self.assertEqual(data["provenance"]["inputs"][0]["path"], obj)


if __name__ == "__main__":
    unittest.main()
