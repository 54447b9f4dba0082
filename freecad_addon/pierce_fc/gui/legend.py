"""Colour legend of a thickness map: the ramp with its range, and the thin and no-value colours."""
from .. import colormap
from .qt import QtCore, QtGui, QtWidgets


class Legend(QtWidgets.QWidget):
    """The ramp from its low (thin, red) to its high (thick, blue) end, with the end values below
    it ("<=" / ">=" when values beyond that end are drawn in its colour), then the swatches of the
    thin and no-value colours, each on its own line when the panel is narrow."""

    def __init__(self):
        super().__init__()
        self.range = None
        self.threshold = 0.0
        self.clamped = (False, False)
        self.setMinimumHeight(62)

    def set_range(self, lo, hi, threshold=0.0, clamped=(False, False)):
        self.range = (lo, hi)
        self.threshold = threshold
        self.clamped = tuple(bool(c) for c in clamped)
        self.setMinimumHeight(self._height())
        self.updateGeometry()
        self.update()

    def end_texts(self):
        """The texts under the low and high ends of the ramp."""
        lo, hi = self.range
        return (("\u2264 " if self.clamped[0] else "") + "%.4g mm" % lo,
                ("\u2265 " if self.clamped[1] else "") + "%.4g mm" % hi)

    def swatches(self):
        out = []
        if self.threshold > 0:
            out.append((colormap.THIN, "thin: < %.4g mm" % self.threshold))
        out.append((colormap.NONE, "no thickness"))
        return out

    def _lines(self, width):
        """The swatches laid out in lines that fit `width`: [[(x, colour, label)]]."""
        fm = self.fontMetrics()
        lines, line, x = [], [], 4
        for colour, label in self.swatches():
            w = 16 + fm.horizontalAdvance(label)
            if line and x + w > width - 4:
                lines.append(line)
                line, x = [], 4
            line.append((x, colour, label))
            x += w + 8
        if line:
            lines.append(line)
        return lines

    def _height(self):
        line = self.fontMetrics().height() + 4
        return 4 + 18 + line + 4 + line * len(self._lines(max(self.width(), 120)))

    def resizeEvent(self, event):
        super().resizeEvent(event)
        if self.range is not None and self.minimumHeight() != self._height():
            self.setMinimumHeight(self._height())

    def paintEvent(self, event):
        if self.range is None:
            return
        p = QtGui.QPainter(self)
        w = self.width()
        fm = p.fontMetrics()
        bar = QtCore.QRect(4, 4, w - 8, 18)
        grad = QtGui.QLinearGradient(bar.left(), 0, bar.right(), 0)
        for k, (r, g, b) in enumerate(colormap.RAMP):
            grad.setColorAt(k / (len(colormap.RAMP) - 1), QtGui.QColor.fromRgbF(r, g, b))
        p.fillRect(bar, grad)
        p.setPen(self.palette().color(QtGui.QPalette.WindowText))
        for k, clamped in enumerate(self.clamped):  # an arrow head on an end that holds clamped values
            if clamped:
                x = bar.left() if k == 0 else bar.right()
                d = 6 if k == 0 else -6
                p.setBrush(self.palette().color(QtGui.QPalette.WindowText))
                p.drawPolygon(QtGui.QPolygon([QtCore.QPoint(x, bar.center().y()),
                                              QtCore.QPoint(x + d, bar.top() + 3),
                                              QtCore.QPoint(x + d, bar.bottom() - 3)]))
        low, high = self.end_texts()
        y = bar.bottom() + 4 + fm.ascent()
        p.drawText(bar.left(), y, low)
        p.drawText(bar.right() - fm.horizontalAdvance(high), y, high)
        line = fm.height() + 4
        y2 = bar.bottom() + 4 + line + 4
        for row in self._lines(w):
            for x, colour, label in row:
                p.fillRect(QtCore.QRect(x, y2, 12, 12), QtGui.QColor.fromRgbF(*colour))
                p.drawText(x + 16, y2 + fm.ascent() - 1, label)
            y2 += line
        p.end()

    def sizeHint(self):
        return QtCore.QSize(200, self._height())

    def minimumSizeHint(self):
        return QtCore.QSize(160, self._height())
