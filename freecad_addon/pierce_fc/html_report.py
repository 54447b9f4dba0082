"""Export report...: the HTML report of `pierce report` (docs/REPORT.md) for FreeCAD solids, one
self-contained file with the 3D thickness map, thin walls, contact / clash / clearance pairs,
statistics, model checks and what exactness cost. GUI-free: the task panels call export()."""
import os
import re
import tempfile

from .errors import UserError
from .selection import collect_solids


def export(objects, path, min_thickness=0.0, max_thickness=None, clearance=0.0, method="ray", per="face",
           deflection=0.0, angular_deflection=15.0, title=None):
    """Writes the report of the solids of `objects` (containers expanded, as the panels select) to
    `path`, replacing it (the save dialog has asked). Each solid is handed to Pierce as BREP named
    after its label, so the report measures the exact B-rep and names the solids as the tree does.
    deflection 0: 0.1% of the model's size. Returns `path`."""
    from .locate import import_pierce
    pierce = import_pierce()
    refs, _ = collect_solids(objects)  # raises SelectionError (a UserError) when there is none
    with tempfile.TemporaryDirectory(prefix="pierce_report_") as d:
        paths, used = [], set()
        for ref in refs:
            stem = re.sub(r"[^\w.-]+", "_", ref.label) or "solid"
            while stem in used:
                stem += "_"
            used.add(stem)
            brep = os.path.join(d, stem + ".brep")
            ref.shape.exportBrep(brep)
            paths.append(brep)
        try:
            return pierce.report(paths, path, min_thickness=min_thickness, max_thickness=max_thickness,
                                 clearance=clearance, method=method, per=per, title=title,
                                 linear_deflection=deflection, angular_deflection=angular_deflection, force=True)
        except (pierce.InputError, FileNotFoundError, RuntimeError) as e:
            raise UserError("The report could not be written: %s" % e)
