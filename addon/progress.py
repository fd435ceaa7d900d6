"""Progress for long work: the window manager's progress indicator (the cursor turns into a
counter) and a line of text in the status bar. Headless (``blender -b``, the bpy module) there
is neither; every call is then harmless."""

import bpy

# Work whose last run took longer than this (ms) shows progress the next time it runs.
SLOW_MS = 200.0


def _wm():
    return getattr(bpy.context, "window_manager", None)


def status(text):
    """Show text in the status bar (None clears it)."""
    ws = getattr(bpy.context, "workspace", None)
    if ws is not None and not bpy.app.background:
        try:
            ws.status_text_set(text)
        except (AttributeError, RuntimeError, TypeError):
            pass  # no status bar in this context (a timer outside any window)


class Progress:
    """``with Progress("Exporting", 10) as p: p.update(3, "faces")``: the progress indicator
    counts to total; the status bar reads "Fairlines: <label> <done>/<total> <detail>"."""

    def __init__(self, label, total=1):
        self.label, self.total = label, max(int(total), 1)

    def __enter__(self):
        wm = _wm()
        if wm is not None and not bpy.app.background:
            wm.progress_begin(0, self.total)
        status("Fairlines: %s ..." % self.label)
        return self

    def update(self, done, detail="", total=None):
        if total is not None and int(total) > 0:
            self.total = int(total)
        wm = _wm()
        if wm is not None and not bpy.app.background:
            wm.progress_update(min(int(done), self.total))
        status("Fairlines: %s %d/%d %s" % (self.label, done, self.total, detail))

    def __exit__(self, *exc):
        wm = _wm()
        if wm is not None and not bpy.app.background:
            wm.progress_end()
        status(None)
        return False
