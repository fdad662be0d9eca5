"""What every demo shares: a caption, the picture, the controls.

A demo is a small model/view pair.  Controls change the model; ``refresh``
updates the figure's artists in place and re-renders only what moves.
"""

from __future__ import annotations

from collections.abc import Callable

import ipywidgets as widgets

from ..plots.style import FigureRenderer


class Demo(widgets.VBox):
    """A demo widget: caption, picture, controls.

    Attributes
    ----------
    model : object
        The demo's state (a run record and a frame, a belief, ...).
    controls : dict[str, ipywidgets.Widget]
        Every slider, button and toggle, by name (tests drive them through this).
    renderer : FigureRenderer
        Turns the figure into PNG bytes.
    """

    def __init__(
        self, name: str, caption: str, model, renderer: FigureRenderer, draw: Callable[[], None], rows, controls
    ):
        self.model = model
        self.renderer = renderer
        self.controls = dict(controls)
        self._draw = draw
        self.image = widgets.Image(format="png")
        self.image.add_class("kf-figure")
        cap = widgets.HTML(f"<div style='color:#333;font-size:13px;line-height:1.4'>{caption}</div>")
        cap.add_class("kf-caption")
        for key, control in self.controls.items():
            control.add_class(f"kf-control-{key}")
        super().__init__([cap, self.image, *rows])
        self.add_class("kf-demo")
        self.add_class(f"kf-demo-{name}")
        self.refresh()

    def refresh(self, *_) -> None:
        """Update the artists from the model and show the new picture."""
        self._draw()
        self.image.value = self.renderer.png()


def slider(cls, description: str, value, min, max, step, readout_format: str = ".2f", **kwargs):
    """A slider that only reports on release-free drags as the value changes."""
    return cls(
        value=value,
        min=min,
        max=max,
        step=step,
        description=description,
        readout_format=readout_format,
        continuous_update=True,
        style={"description_width": "initial"},
        layout=widgets.Layout(width="340px"),
        **kwargs,
    )


def button(description: str, icon: str = "", tooltip: str = "") -> widgets.Button:
    return widgets.Button(description=description, icon=icon, tooltip=tooltip, layout=widgets.Layout(width="110px"))


def play(n_frames: int, interval_ms: int = 90):
    """A Play widget and a frame slider linked in the browser (scrub with the slider)."""
    player = widgets.Play(value=0, min=0, max=n_frames - 1, step=1, interval=interval_ms, description="Run")
    frame = widgets.IntSlider(
        value=0, min=0, max=n_frames - 1, description="step", layout=widgets.Layout(width="340px")
    )
    widgets.jslink((player, "value"), (frame, "value"))
    return player, frame
