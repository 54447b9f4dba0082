"""Tiny test harness for freecadcmd scripts: freecadcmd exits 0 even when a script raises, so each
script collects failures with Checker and ends with raise SystemExit(code) through run(). GUI
scripts (the freecad binary) start theirs with run_in_gui()."""
import math
import os
import sys
import traceback


class Checker:
    def __init__(self, name):
        self.name = name
        self.failures = 0
        self.checks = 0

    def check(self, cond, what):
        self.checks += 1
        status = "ok  " if cond else "FAIL"
        print("[%s] %s: %s" % (status, self.name, what), flush=True)
        if not cond:
            self.failures += 1
        return cond

    def near(self, value, expected, tol, what):
        ok = value is not None and not math.isnan(value) and abs(value - expected) <= tol
        return self.check(ok, "%s: %r, expected %r +- %g" % (what, value, expected, tol))

    def raises(self, exc_type, fn, what, contains=None):
        try:
            fn()
        except exc_type as e:
            ok = contains is None or contains.lower() in str(e).lower()
            return self.check(ok, "%s raises %s: %s" % (what, exc_type.__name__, e))
        except Exception as e:  # wrong exception type
            return self.check(False, "%s raised %s instead of %s: %s" % (what, type(e).__name__,
                                                                       exc_type.__name__, e))
        return self.check(False, "%s did not raise %s" % (what, exc_type.__name__))


def run(name, body):
    """Runs body(checker) and exits with 0 only if it finished and every check passed."""
    c = Checker(name)
    try:
        body(c)
    except SystemExit:
        raise
    except BaseException:
        traceback.print_exc()
        print("[FAIL] %s: exception" % name, flush=True)
        c.failures += 1
    print("%s: %d checks, %d failures" % (name, c.checks, c.failures), flush=True)
    sys.stdout.flush()
    raise SystemExit(1 if c.failures or c.checks == 0 else 0)


def run_in_gui(name, body):
    """For scripts run by the freecad GUI: runs run(name, body) once the event loop has started
    (the workbenches and the 3D view need it), then ends the process with run's code: os._exit,
    since a SystemExit raised inside the event loop does not end the GUI."""
    from PySide2 import QtCore

    def main():
        code = 1
        try:
            run(name, body)
        except SystemExit as e:
            code = e.code
        except BaseException:
            traceback.print_exc()
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)

    QtCore.QTimer.singleShot(0, main)


def window_screenshot(path):
    """Saves the FreeCAD window as the user sees it to `path`: under xvfb a grab of the window
    leaves the OpenGL 3D view blank, so the view is rendered (saveImage) and drawn into its place.
    Returns whether the file was written."""
    import tempfile
    import FreeCADGui as Gui
    from PySide2 import QtCore, QtGui, QtWidgets
    mw = Gui.getMainWindow()
    for _ in range(3):
        QtWidgets.QApplication.processEvents()
    shot = mw.grab()
    mdi = mw.findChild(QtWidgets.QMdiArea)
    sub = mdi.activeSubWindow() if mdi is not None else None
    view = getattr(Gui.ActiveDocument, "ActiveView", None) if Gui.ActiveDocument else None
    if sub is not None and view is not None and hasattr(view, "saveImage"):
        target = sub.widget().centralWidget() if hasattr(sub.widget(), "centralWidget") else sub.widget()
        target = target or sub.widget()
        rect = QtCore.QRect(target.mapTo(mw, QtCore.QPoint(0, 0)), target.size())
        with tempfile.TemporaryDirectory() as d:
            img = os.path.join(d, "view.png")
            view.saveImage(img, rect.width(), rect.height(), "Current")
            painter = QtGui.QPainter(shot)
            painter.drawImage(rect, QtGui.QImage(img))
            painter.end()
    return shot.save(path)


def fitted_view_shot(path, width, height):
    """The active 3D view turned isometric and fitted to the whole document, saved to `path` on
    white (GUI tests only); returns `path`."""
    import FreeCADGui as Gui
    from PySide2 import QtWidgets
    QtWidgets.QApplication.processEvents()
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    QtWidgets.QApplication.processEvents()
    view.saveImage(path, width, height, "White")
    return path


def clipped_widgets(form):
    """Visible widgets of a task panel that reach past the visible width of the task view, or are
    narrower than their minimum size hint (their text or buttons cut off): [(name, why)]."""
    from PySide2 import QtWidgets
    area = form.parent()
    while area is not None and not isinstance(area, QtWidgets.QScrollArea):
        area = area.parent()
    viewport = area.viewport() if area is not None else form
    width = viewport.width()
    out = []
    if area is not None and area.horizontalScrollBar().maximum() > 0:
        out.append(("task view", "scrolls sideways by %d px" % area.horizontalScrollBar().maximum()))
    for w in [form] + form.findChildren(QtWidgets.QWidget):
        if not w.isVisibleTo(form) or isinstance(w, (QtWidgets.QScrollBar,)) or w.width() == 0:
            continue
        if w.parent() is not None and isinstance(w.parent(), (QtWidgets.QAbstractScrollArea,)) and w is not form:
            continue  # viewports and scroll bars of lists and text boxes scroll their own content
        left = w.mapTo(viewport, w.rect().topLeft()).x()
        right = left + w.width()
        name = "%s %r" % (type(w).__name__, (w.text() if hasattr(w, "text") and callable(w.text) else
                                            w.title() if hasattr(w, "title") else w.objectName()))
        if left < 0 or right > width + 1:
            out.append((name, "spans x %d..%d of a %d px view" % (left, right, width)))
        hint = w.minimumSizeHint()
        if hint.isValid() and w.width() + 1 < hint.width() and not (isinstance(w, QtWidgets.QLabel) and w.wordWrap()):
            out.append((name, "%d px wide, needs %d" % (w.width(), hint.width())))
    return out, width
