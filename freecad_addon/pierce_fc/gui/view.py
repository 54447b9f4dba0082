"""3D-view helpers for findings: frame the camera on a place, and a transient highlight drawn on
top of the scene (no document object; it goes when replaced, cleared or the panel closes)."""
import math

import FreeCADGui as Gui

# Colour of the highlight: cyan, apart from every colour of the thickness ramp.
HIGHLIGHT = (0.0, 0.9, 1.0)


def active_view():
    doc = Gui.ActiveDocument
    view = getattr(doc, "ActiveView", None) if doc is not None else None
    return view if view is not None and hasattr(view, "getCameraNode") else None


def frame(centre, radius, direction=None, view=None, fill=0.5):
    """Points the camera of `view` (default: the active 3D view) at `centre` so that a sphere of
    `radius` around it spans about `fill` of the view's smaller side. direction: the viewing
    direction (from the camera to the centre); None keeps the current one."""
    from pivy import coin
    view = view or active_view()
    if view is None:
        return False
    cam = view.getCameraNode()
    if direction is None:
        d = view.getViewDirection()
        direction = (d.x, d.y, d.z)
    n = math.sqrt(sum(c * c for c in direction))
    if not n > 0:
        return False
    direction = tuple(c / n for c in direction)
    radius = max(radius, 1e-6)
    # Turn the camera to look along `direction`, keeping its up vector as far as possible.
    up = cam.orientation.getValue().multVec(coin.SbVec3f(0, 1, 0))
    look = coin.SbVec3f(*direction)
    if abs(up.dot(look)) > 0.99:
        up = coin.SbVec3f(0, 0, 1) if abs(direction[2]) < 0.9 else coin.SbVec3f(0, 1, 0)
    rot = coin.SbRotation(coin.SbVec3f(0, 0, -1), look)
    up_now = rot.multVec(coin.SbVec3f(0, 1, 0))
    up_want = up - look * up.dot(look)
    up_want.normalize()
    cam.orientation.setValue(rot * coin.SbRotation(up_now, up_want))
    w, h = view.getSize() if hasattr(view, "getSize") else (1, 1)
    aspect = min(w, h) / float(h) if h else 1.0  # the camera's height spans the view's height
    span = 2.0 * radius / fill / aspect
    distance = 4.0 * radius + 1.0 * span
    if cam.getTypeId() == coin.SoOrthographicCamera.getClassTypeId():
        cam.height.setValue(span)
    else:
        angle = cam.heightAngle.getValue()
        distance = max(distance, span / (2.0 * math.tan(angle / 2.0)))
    cam.position.setValue(coin.SbVec3f(*(c - d * distance for c, d in zip(centre, direction))))
    cam.focalDistance.setValue(distance)
    return True


class Highlight:
    """Lines and a marker drawn over everything in the active 3D view (an SoAnnotation)."""

    def __init__(self):
        self.node = None
        self.view = None

    def show(self, segments, points, view=None):
        """segments: [(p, q)] lines; points: [p] crosses. Replaces what was shown."""
        from pivy import coin
        self.clear()
        view = view or active_view()
        if view is None:
            return False
        root = coin.SoAnnotation()
        colour = coin.SoBaseColor()
        colour.rgb.setValue(*HIGHLIGHT)
        root.addChild(colour)
        style = coin.SoDrawStyle()
        style.lineWidth.setValue(3)
        style.pointSize.setValue(9)
        root.addChild(style)
        if segments:
            coords = coin.SoCoordinate3()
            coords.point.setValues(0, len(segments) * 2, [tuple(map(float, p)) for seg in segments for p in seg])
            root.addChild(coords)
            lines = coin.SoLineSet()
            lines.numVertices.setValues(0, len(segments), [2] * len(segments))
            root.addChild(lines)
        if points:
            coords = coin.SoCoordinate3()
            coords.point.setValues(0, len(points), [tuple(map(float, p)) for p in points])
            root.addChild(coords)
            marker = coin.SoMarkerSet()
            marker.markerIndex = coin.SoMarkerSet.CIRCLE_FILLED_9_9
            root.addChild(marker)
        view.getSceneGraph().addChild(root)
        self.node, self.view = root, view
        return True

    def clear(self):
        if self.node is not None:
            try:
                self.view.getSceneGraph().removeChild(self.node)
            except Exception:  # the view was closed meanwhile
                pass
        self.node = self.view = None

    @property
    def shown(self):
        return self.node is not None
