"""What every demo shares: a caption, the picture, its description, the controls, and Run/Pause.

A demo is a model, a view and a few lines of wiring.  The model holds the state and
the methods the controls call; the view (in ``kfcourse.plots``) is a make function that
draws the figure and an update function that moves its artists from the model.  Each
control is bound to a model method: a slider or toggle to a setter called with the new
value, a button to an action called with nothing.  After every call the demo redraws by
itself: ``draw`` updates the artists and the renderer re-renders only what moves, or the
whole figure when something static changed.  While a control moves or Run plays the page
gets a light picture; once the student stops, the crisp one.  The wiring::

    view = my_view()
    Demo(
        name="my-demo",
        caption="<b>My demo.</b> ...",
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=partial(update_my_view, view, model),
        describe=model.describe,
        controls={"noise": (slider(...), model.set_noise), "again": (button("Again"), model.new_run)},
    )
"""

from __future__ import annotations

import asyncio
import base64
from collections.abc import Callable
from pathlib import Path

import anywidget
import ipywidgets as widgets
import traitlets

from ..plots.style import PIXEL_DENSITY, FigureRenderer

FRAME_INTERVAL = 0.08  # s between frames while running: 12.5 pictures a second
REST_AFTER = 0.3  # s without a change after which the light picture gives way to the crisp one
FRAME_GAP = 0.02  # s the kernel always rests between frames, to hear Pause and slider moves
DISPLAY_WIDTH = 950  # CSS px: a demo's picture at most (JupyterLab's output is 848 px on a 1280 px laptop)


class Description(anywidget.AnyWidget):
    """The demo's state in one sentence, under its picture.

    The page shows ``text`` in a polite live region (a screen reader reads each new state once)
    and makes it the picture's alt text.  The same view names the demo's sliders from their
    labels, has them announce the value they show, and exposes toggles' pressed state
    (``describe.js``; the focus ring is in ``describe.css``).
    """

    _esm = Path(__file__).with_name("describe.js")
    _css = Path(__file__).with_name("describe.css")
    text = traitlets.Unicode("").tag(sync=True)
    names = traitlets.Dict().tag(sync=True)  # each control's key -> its name: its label, else its tooltip


def folded(caption: str) -> str:
    """The caption as HTML folded under its title: the title and "key" on one line, the rest a
    click (or Enter) away, so that a 1280x800 laptop shows the picture, its controls and its
    description at once.  ``caption`` starts with its title in ``<b>...</b>``."""
    title, bold, key = caption.partition("</b>")
    if not caption.startswith("<b>") or not bold or not key.strip():
        raise ValueError(f"caption must start with its title in <b>...</b> and go on after it, got {caption[:40]!r}")
    return (
        "<details style='color:#333;font-size:13px;line-height:1.4'>"
        f"<summary>{title}</b> <span style='color:#555'>key: what the colours and the controls mean</span></summary>"
        f"{key.strip()}</details>"
    )


class Demo(widgets.VBox):
    """A demo widget: caption, picture, description, controls.

    Parameters
    ----------
    name : str
        Short name; the widget gets the CSS classes ``kf-demo`` and ``kf-demo-<name>``.
    caption : str
        HTML shown above the picture, starting with its title in ``<b>...</b>``: the rest, the
        key to the colours and controls, is folded under the title (:func:`folded`).
    model : object
        The demo's state.  With ``frames`` it needs an integer attribute ``frame``.
    renderer : FigureRenderer
        The figure and its moving (``dynamic``) artists.
    draw : callable
        ``draw()`` updates the artists from the model.
    describe : callable
        ``describe()`` says in one sentence what the picture shows now, from the model's
        numbers (the gain, the means and variances, the error, the readings used): the
        picture's alt text and the text under it, renewed whenever the demo comes to rest.
    controls : dict[str, (ipywidgets.Widget, callable)]
        Each control by name with the model method it is bound to: a button calls
        ``action()``, any other widget calls ``setter(new_value)``.
    layout : list, optional
        The rows under the picture; each row is a list of control names (or
        widgets, e.g. a table that ``draw`` fills), or a single one.  By default
        one row per control (none if ``beside`` places them all).
    beside : list, optional
        Rows in the same form, in a column to the right of the picture: for a
        demo whose picture is tall, so that the picture and its controls fit a
        laptop's screen together.
    frames : int, optional
        Number of animation frames.  Adds the controls ``play`` (Run/Pause) and
        ``frame`` (a slider to scrub); they set ``model.frame``.
    display_width : int
        CSS pixels the picture is shown at, at most: ``DISPLAY_WIDTH`` unless the
        demo keeps its picture narrower.  A narrower page shrinks it; nothing
        enlarges it.  The picture is rendered ``PIXEL_DENSITY`` times as many
        pixels wide.

    Attributes
    ----------
    model : object
    controls : dict[str, ipywidgets.Widget]
        Every slider, button and toggle, by name (tests drive them through this).
    renderer : FigureRenderer
        Turns the figure into PNG bytes.
    description : Description
        The sentence under the picture (``description.text``).
    image : ipywidgets.Image
        The picture.  At rest, a JPEG ``PIXEL_DENSITY * display_width`` pixels wide, so that
        it stays sharp where it is shown about ``display_width`` CSS pixels wide on a HiDPI
        screen.  While a control moves or Run plays, a light WebP of half the pixels
        (:meth:`FigureRenderer.light`); the crisp picture replaces it on Pause, at the end of
        a run, and ``REST_AFTER`` seconds after the last change.
    display_width : int
        CSS pixels the picture is shown at.

    Notes
    -----
    Shown as the last value of a cell, a demo also hands the notebook a PNG of its
    current (first) frame beside the widget: a page without a kernel (GitHub, nbviewer,
    nbconvert) shows that picture where JupyterLab shows the live widget.
    """

    def __init__(
        self,
        *,
        name: str,
        caption: str,
        model,
        renderer: FigureRenderer,
        draw: Callable[[], None],
        describe: Callable[[], str],
        controls: dict,
        layout: list | None = None,
        beside: list | None = None,
        frames: int | None = None,
        display_width: int = DISPLAY_WIDTH,
    ):
        self.model = model
        self.renderer = renderer
        self._draw = draw
        self._describe = describe
        self._task = None
        self._rest_timer = None
        try:  # the kernel's event loop: the demo's pictures, its rest timer and its Run task live on it
            self._loop = asyncio.get_running_loop()
        except RuntimeError:  # a script or a test: every change is drawn at once, crisp
            self._loop = None
        bound = dict(controls)
        if frames is not None:
            bound = {**self._player(frames), **bound}
        self.controls = {key: control for key, (control, _) in bound.items()}
        for key, (control, method) in bound.items():
            control.add_class(f"kf-control-{key}")
            if isinstance(control, widgets.ToggleButtons):  # its label and its buttons on one line
                control.layout.display = "flex"
                control.layout.align_items = "center"
                control.style.description_width = "initial"
            self._bind(control, method)
        self.display_width = display_width
        renderer.set_pixel_width(PIXEL_DENSITY * display_width)
        # Shown at display_width CSS px, shrunk to fit a narrower page, never enlarged (an app's
        # full window would otherwise stretch it); the height follows the picture's shape.
        size = widgets.Layout(width="100%", max_width=f"{display_width}px", min_width="0", height="auto", margin="0")
        self.image = widgets.Image(format="jpeg", layout=size)
        self.image.add_class("kf-figure")
        self.description = Description(
            names={key: c.description or c.tooltip or key for key, c in self.controls.items()}
        )
        self.caption = caption
        cap = widgets.HTML(folded(caption))
        cap.add_class("kf-caption")
        if layout is None:
            layout = [] if beside is not None else list(self.controls)
        picture = self.image
        if beside is not None:
            column = widgets.VBox([self._row(row) for row in beside], layout=widgets.Layout(flex="0 0 auto"))
            picture = widgets.HBox([self.image, column], layout=widgets.Layout(align_items="flex-start"))
        super().__init__([cap, picture, self.description, *(self._row(row) for row in layout)])
        self.add_class("kf-demo")
        self.add_class(f"kf-demo-{name}")
        self.refresh()

    def refresh(self, *_) -> None:
        """Update the artists from the model and show the crisp picture."""
        self._draw()
        self._show_crisp()

    def _moved(self) -> None:
        """After a change: a light picture now, the crisp one once nothing has changed for a while.

        Without an event loop to wait on (a script, a test), the crisp picture follows at once.
        """
        self._draw()
        if self._loop is None:
            self._show_crisp()
            return
        self._cancel_rest()
        with self.image.hold_sync():  # the format and the bytes reach the page in one message
            self.image.format = "webp"
            self.image.value = self.renderer.light()
        self._rest_timer = self._loop.call_later(REST_AFTER, self._show_crisp)

    def _on_demo_loop(self, action: Callable, *args) -> None:
        """Call ``action(*args)`` on the demo's event loop.

        JupyterLab may deliver widget messages to a kernel subshell, which handles them in a
        thread of its own.  A change that arrives there is handed to the demo's loop, so that a
        picture, the rest timer and the Run task never run at once on two threads.
        """
        try:
            here = asyncio.get_running_loop()
        except RuntimeError:
            here = None
        if self._loop is None or self._loop.is_closed():  # made outside a loop: it lives on the first one
            self._loop = here
        if self._loop is None or here is self._loop:
            action(*args)
        else:
            self._loop.call_soon_threadsafe(action, *args)

    def _cancel_rest(self) -> None:
        if self._rest_timer is not None:
            self._rest_timer.cancel()
            self._rest_timer = None

    def _show_crisp(self) -> None:
        """The picture at rest, and its description: a live region is told each resting state once."""
        self._cancel_rest()
        with self.image.hold_sync():
            self.image.format = "jpeg"
            self.image.value = self.renderer.jpeg()
        self.description.text = self._describe()

    # --- Pictures for pages without a kernel ------------------------------------------------------

    def _repr_mimebundle_(self, **kwargs):
        """The widget view, plus a PNG of the picture shown now, with its description as alt text,
        for frontends that cannot show widgets."""
        data = super()._repr_mimebundle_(**kwargs)
        data["image/png"] = base64.b64encode(self.renderer.png()).decode("ascii")
        return data, {"image/png": {"width": self.display_width, "alt": self.description.text}}

    def _bind(self, control: widgets.Widget, method: Callable | None) -> None:
        if method is None:
            return
        if isinstance(control, widgets.Button):

            def clicked() -> None:
                method()
                self._moved()

            control.on_click(lambda _: self._on_demo_loop(clicked))
        else:

            def changed(value) -> None:
                method(value)
                self._moved()

            control.observe(lambda change: self._on_demo_loop(changed, change["new"]), "value")

    def _row(self, row) -> widgets.Widget:
        items = row if isinstance(row, list | tuple) else [row]
        children = [self.controls[item] if isinstance(item, str) else item for item in items]
        return children[0] if len(children) == 1 else widgets.HBox(children)

    # --- Run/Pause -------------------------------------------------------------------------------
    # The kernel drives the animation: a task on the kernel's event loop sets the frame, renders,
    # then sleeps.  Frames never queue up anywhere: a slow render makes the next frame skip ahead
    # to keep real time, and Pause takes effect before the next frame is drawn.

    def _player(self, n_frames: int) -> dict:
        play = widgets.ToggleButton(
            value=False, description="Run", icon="play", tooltip="Run / pause time", layout=widgets.Layout(width="90px")
        )
        frame = widgets.IntSlider(
            value=self.model.frame, min=0, max=n_frames - 1, description="step", layout=widgets.Layout(width="340px")
        )
        play.observe(lambda change: self._on_demo_loop(self._on_play, change["new"]), "value")
        return {"play": (play, None), "frame": (frame, self._set_frame)}

    def _set_frame(self, k: int) -> None:
        self.model.frame = int(k)

    def step(self, frames: int = 1) -> bool:
        """Advance the animation by ``frames`` (at most to the last frame) and redraw.

        Returns
        -------
        bool
            False if already at the last frame (nothing changed).
        """
        frame = self.controls["frame"]
        if frame.value >= frame.max:
            return False
        frame.value = min(frame.value + frames, frame.max)
        return True

    def _on_play(self, running: bool) -> None:
        play = self.controls["play"]
        play.description, play.icon = ("Pause", "pause") if running else ("Run", "play")
        if self._task is not None:
            self._task.cancel()
            self._task = None
        if not running:
            self._show_crisp()  # paused, or at the last frame: the picture to study
            return
        if self._loop is None:  # no event loop (a plain script or test): use step() instead
            play.value = False
            return
        frame = self.controls["frame"]
        if frame.value >= frame.max:
            frame.value = frame.min  # Run at the end starts again
        # The sentence describes a picture at rest: while Run plays it says so, never a past step as the one shown.
        self.description.text = running_sentence(frame.value)
        self._task = self._loop.create_task(self._run(self._loop))

    async def _run(self, loop: asyncio.AbstractEventLoop) -> None:
        """Show one frame per FRAME_INTERVAL until paused or at the last frame."""
        frame = self.controls["frame"]
        start, t0 = frame.value, loop.time()
        while self.controls["play"].value and frame.value < frame.max:
            n = 1 + int((loop.time() - t0) / FRAME_INTERVAL)  # frames real time asks for since start
            self.step(max(start + n - frame.value, 1))  # a slow render skips frames instead of lagging
            drawn = frame.value
            await asyncio.sleep(max(FRAME_GAP, t0 + n * FRAME_INTERVAL - loop.time()))
            if frame.value != drawn:  # scrubbed while running: restart the clock from there
                start, t0 = frame.value, loop.time()
        self._task = None
        self.controls["play"].value = False


def running_sentence(start: int) -> str:
    """What the description says while Run plays: the picture moves too fast to describe each step,
    so it names the step Run started from and when the sentence returns."""
    return f"Run is playing from step {start}; press Pause, or wait for the last step, to read the step shown."


def slider(
    cls, description: str, value, min, max, step, readout_format: str = ".2f", continuous_update: bool = True, **kwargs
):
    """A slider that reports every value while it is dragged, or with ``continuous_update=False``
    only where it is let go (for a control whose change costs more than a frame)."""
    return cls(
        value=value,
        min=min,
        max=max,
        step=step,
        description=description,
        readout_format=readout_format,
        continuous_update=continuous_update,
        style={"description_width": "initial"},
        layout=widgets.Layout(width="340px"),
        **kwargs,
    )


def button(description: str, icon: str = "", tooltip: str = "") -> widgets.Button:
    return widgets.Button(description=description, icon=icon, tooltip=tooltip, layout=widgets.Layout(width="110px"))


def shown(value: float, fmt: str) -> str:
    """``value`` as a slider's readout shows it with ``readout_format`` ``fmt`` (".2f", ".3g", ...),
    so that a description names the value the student sees.

    The page formats with d3-format: a true minus sign (−), no sign on a number that rounds to
    zero, and "g" as JavaScript's ``toPrecision``, which keeps trailing zeros (0.200, 10.0) and
    writes large or tiny numbers with an exponent (1.00e+4).
    """
    if not (len(fmt) >= 3 and fmt[0] == "." and fmt[-1] in "fg" and fmt[1:-1].isdigit()):
        raise ValueError(f"fmt: expected a format like '.2f' or '.3g', got {fmt!r}")
    digits = int(fmt[1:-1])
    if fmt.endswith("g"):
        mantissa, exponent = f"{value:.{max(digits - 1, 0)}e}".split("e")
        if -7 < int(exponent) < digits:
            text = f"{value:.{digits - 1 - int(exponent)}f}"
        else:
            text = f"{mantissa}e{int(exponent):+d}"
    else:
        text = format(value, fmt)
    if float(text) == 0:
        text = text.lstrip("-")
    return "\u2212" + text[1:] if text.startswith("-") else text
