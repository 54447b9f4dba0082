"""Pierce progress callbacks on FreeCAD's progress bar, with cancellation.

Pierce calls progress(done, total) on the calling (GUI) thread a few times a second while the work
runs on other threads; this forwards it to Base.ProgressIndicator (the status-bar progress bar in
the GUI, whose Esc/abort raises), lets Qt process events so a Stop button stays clickable, and
returns False to stop when the user cancelled.
"""


class Progress:
    STEPS = 100

    def __init__(self, text, cancel=None, process_events=None):
        self.text = text
        self.cancel = cancel  # a pierce.CancelToken, or None
        self.process_events = process_events
        self._indicator = None
        self._shown = 0
        self.stopped = False

    def __enter__(self):
        try:
            import FreeCAD
            self._indicator = FreeCAD.Base.ProgressIndicator()
            self._indicator.start(self.text, self.STEPS)
        except Exception:  # no progress indicator available: report nothing
            self._indicator = None
        return self

    def __exit__(self, *exc):
        if self._indicator is not None:
            try:
                self._indicator.stop()
            except Exception:
                pass
        return False

    def stage(self, text):
        """A new stage of the run: restarts the bar with another text."""
        self.text = text
        if self._indicator is not None:
            try:
                self._indicator.stop()
                self._indicator.start(text, self.STEPS)
            except Exception:
                pass
        self._shown = 0

    def __call__(self, done, total):
        if self.process_events is not None:
            self.process_events()
        if self.cancel is not None and self.cancel.cancelled:
            self.stopped = True
            return False
        want = int(self.STEPS * done / total) if total else 0
        if self._indicator is not None:
            try:
                while self._shown < min(want, self.STEPS):
                    self._indicator.next(True)  # raises when the user aborts (Esc)
                    self._shown += 1
            except Exception:
                self.stopped = True
                return False
        return True


def start_stage(progress, text):
    """progress.stage(text) when the callback has stages (a Progress), else nothing: the analyses
    also take a plain progress(done, total) callable."""
    stage = getattr(progress, "stage", None)
    if stage:
        stage(text)
