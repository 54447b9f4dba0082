"""Colour legend of a thickness map: the ramp with its range, and the thin and no-value colours."""
from .. import colormap
from .qt import QtCore, QtGui, QtWidgets


class Legend(QtWidgets.QWidget):
    def __init__(self):
        super().__init__()
        self.range = None
        self.threshold = 0.0
        self.setMinimumHeight(62)

    def set_range(self, lo, hi, threshold=0.0):
        self.range = (lo, hi)
        self.threshold = threshold
        self.update()

    def paintEvent(self, event):
        if self.range is None:
            return
        p = QtGui.QPainter(self)
        w = self.width()
        bar = QtCore.QRect(4, 4, w - 8, 18)
        grad = QtGui.QLinearGradient(bar.left(), 0, bar.right(), 0)
        for k, (r, g, b) in enumerate(colormap.RAMP):
            grad.setColorAt(k / (len(colormap.RAMP) - 1), QtGui.QColor.fromRgbF(r, g, b))
        p.fillRect(bar, grad)
        p.setPen(self.palette().color(QtGui.QPalette.WindowText))
        lo, hi = self.range
        y = bar.bottom() + 16
        p.drawText(bar.left(), y, "%.4g mm (thin)" % lo)
        text = "%.4g mm (thick)" % hi
        p.drawText(bar.right() - p.fontMetrics().horizontalAdvance(text), y, text)
        x = bar.left()
        y2 = y + 6
        for colour, label in ((colormap.THIN, "< %.4g mm" % self.threshold if self.threshold > 0 else None),
                              (colormap.NONE, "no thickness")):
            if label is None:
                continue
            p.fillRect(QtCore.QRect(x, y2, 12, 12), QtGui.QColor.fromRgbF(*colour))
            p.drawText(x + 16, y2 + 11, label)
            x += 24 + p.fontMetrics().horizontalAdvance(label)
        p.end()

    def sizeHint(self):
        return QtCore.QSize(240, 62)
