"""Task panel: shotline from a point along a direction, or a grid of rays entering through a face."""
import FreeCAD
import FreeCADGui as Gui

from .. import shotline
from ..errors import SelectionError
from ..shotline import ShotOptions
from .panel_base import PanelBase, check_box, double_spin
from .qt import QtWidgets

COLUMNS = ["Ray", "Kind", "Solids", "In", "Out", "LOS (mm)", "Obliquity in", "Obliquity out", "Normal thickness"]


class ShotlinePanel(PanelBase):
    TITLE = "Pierce shotline"
    RUN_TEXT = "Shoot"

    def build_options(self, layout):
        f = self.options_form(layout, "Ray")
        self.mode_point = QtWidgets.QRadioButton("Point and direction")
        self.mode_point.setToolTip("One ray from a point along a direction")
        self.mode_grid = QtWidgets.QRadioButton("Grid through a face")
        self.mode_grid.setToolTip("A grid of rays entering through the selected face")
        self.mode_point.setChecked(True)
        self.origin = [double_spin(0.0, -1e9, 1e9, suffix="") for _ in range(3)]
        self.direction = [double_spin(v, -1e9, 1e9, suffix="") for v in (0.0, 0.0, 1.0)]
        pick = QtWidgets.QPushButton("From selection")
        pick.setToolTip("Point picked on a face (or a selected vertex); direction into the face")
        pick.clicked.connect(self.on_pick)
        self.grid = QtWidgets.QSpinBox()
        self.grid.setRange(1, 256)
        self.grid.setValue(8)
        self.all_visible = check_box("Through all visible solids", True,
                                     tooltip="All visible solids of the document; otherwise the selected ones")
        self.csg = QtWidgets.QLineEdit()
        self.csg.setPlaceholderText("optional, e.g. difference(Plate, Hole)")
        self.markers = check_box("Add line segments", True, tooltip="Adds the intervals to the document as lines")
        f.addRow(self.mode_point)
        f.addRow("Point", _row(self.origin))
        f.addRow("Direction", _row(self.direction))
        f.addRow(pick)
        f.addRow(self.mode_grid)
        f.addRow("Rays per side", self.grid)
        f.addRow(self.all_visible)
        f.addRow("CSG expression", self.csg)
        f.addRow(self.markers)

    def build_results(self, layout):
        self.table = self.results_table(layout, COLUMNS)

    def on_pick(self):
        for sel in Gui.Selection.getSelectionEx():
            for sub, pts in zip(sel.SubObjects, sel.PickedPoints or [None] * len(sel.SubObjects)):
                if sub.ShapeType == "Face" and pts is not None:
                    u, v = sub.Surface.parameter(pts)
                    n = sub.normalAt(u, v)
                    self._set(pts, -n)
                    return
                if sub.ShapeType == "Vertex":
                    self._set(sub.Point, FreeCAD.Vector(*[w.value() for w in self.direction]))
                    return
        self.set_message("Select a point on a face (click it in the 3D view) or a vertex first.", error=True)

    def _set(self, point, direction):
        for w, x in zip(self.origin, point):
            w.setValue(x)
        for w, x in zip(self.direction, direction):
            w.setValue(x)
        self.set_message("")

    def compute(self, progress, cancel):
        opts = ShotOptions(csg=self.csg.text() or None, create_objects=self.markers.isChecked())
        objects = self.solids_to_analyse(self.all_visible.isChecked())

        def shoot(doc):
            if self.mode_grid.isChecked():
                faces = [s for sel in Gui.Selection.getSelectionEx() for s in sel.SubObjects if s.ShapeType == "Face"]
                if not faces:
                    raise SelectionError("Select a face for the grid of rays.")
                return shotline.run_face_grid(objects, faces[0], self.grid.value(), opts, doc=doc,
                                              progress=progress, cancel=cancel)
            o = [w.value() for w in self.origin]
            d = [w.value() for w in self.direction]
            return shotline.run(objects, [o], [d], opts, doc=doc, progress=progress, cancel=cancel)

        return self.in_transaction("Pierce shotline", shoot)

    def show_result(self, run):
        rows = run.table()
        self.table.setRowCount(len(rows))
        for r, row in enumerate(rows):
            for c, text in enumerate(row):
                self.table.setItem(r, c, QtWidgets.QTableWidgetItem(text))
        self.table.resizeColumnsToContents()
        text = run.summary()
        self.report(text)
        self.set_message("%d ray(s), %d interval(s); see the table and the Report view." % (
            len(run.rays[0]), len(run.rows)))


def _row(widgets):
    """x, y and z fields stacked, each with its axis name: three side by side do not fit the
    default Combo View."""
    w = QtWidgets.QWidget()
    f = QtWidgets.QFormLayout(w)
    f.setContentsMargins(0, 0, 0, 0)
    for axis, x in zip("xyz", widgets):
        f.addRow(axis, x)
    return w
