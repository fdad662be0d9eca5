"""Finding a demo's widgets wherever the demo places them: under its picture or beside it."""

from __future__ import annotations

import ipywidgets as widgets


def widgets_in(widget: widgets.Widget) -> list[widgets.Widget]:
    """``widget`` and every widget inside it, depth first."""
    found, todo = [], [widget]
    while todo:
        w = todo.pop()
        found.append(w)
        todo.extend(reversed(getattr(w, "children", ())))
    return found


def readout(demo) -> str:
    """The text of the demo's readout (the HTML widget with the class ``kf-readout``)."""
    (shown,) = [w for w in widgets_in(demo) if "kf-readout" in w._dom_classes]
    return shown.value
