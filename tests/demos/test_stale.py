"""No stale pictures: after every change the blitted picture equals a full redraw.

Each demo re-renders only its ``dynamic`` artists over a background its renderer keeps,
and the renderer draws that background again by itself when the figure is stale (a
limit, a tick, a label or any static artist changed).  If the renderer missed such a
change, or an artist that moves were missing from ``dynamic``, the picture shown would
be stale.  Here every demo is driven through every control and, after each change, the
picture the demo shows is compared pixel for pixel with a full redraw of the same state.
The renderer's rule itself is tested in ``tests/plots/test_renderer.py``.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
import pytest

import kfcourse as kf

DEMOS = kf.demos.__all__  # every demo the course ships
SLIDERS = (widgets.IntSlider, widgets.FloatSlider, widgets.FloatLogSlider)


def assert_not_stale(demo, what: str) -> None:
    # The picture shown, lossless: the canvas the demo's JPEG was just encoded from, as RGB pixels
    # (encoding them as a PNG would only double the test's time).
    shown = np.asarray(demo.renderer.fig.canvas.buffer_rgba())[..., :3].copy()
    demo.renderer.fig.stale = True  # what a change to the background does: the next picture is drawn in full
    full = np.asarray(demo.renderer.image())
    assert shown.shape == full.shape, what
    differ = np.any(shown != full, axis=-1)
    assert not differ.any(), f"after {what}: {differ.sum()} pixels differ from a full redraw"


def slider_values(control) -> list:
    """min, max, middle, then min again: the way back matters as much as the way out."""
    values = [control.min, control.max, (control.min + control.max) / 2, control.min]
    if isinstance(control, widgets.IntSlider):
        values = [round(v) for v in values]
    if isinstance(control, widgets.FloatLogSlider):
        values = [control.base**v for v in values]
    return values


def drive(demo):
    """Every change a student can make, one at a time, each named for the failure message."""
    for key, control in demo.controls.items():
        if isinstance(control, SLIDERS):
            for value in slider_values(control):
                control.value = value
                yield f"{key} = {value}"
        elif isinstance(control, widgets.Button):
            for i in range(3):
                control.click()
                yield f"{key} pressed ({i + 1})"
        elif isinstance(control, widgets.ToggleButtons):
            for value in [*control.options[1:], control.options[0]]:
                control.value = value
                yield f"{key} = {value}"
        elif key == "play":
            demo.controls["frame"].value = 0
            while demo.step(7):  # Run without an event loop: frame after frame
                yield f"step to frame {demo.controls['frame'].value}"


@pytest.mark.parametrize("name", DEMOS)
def test_blitted_picture_equals_full_redraw(name):
    demo = getattr(kf.demos, name)(seed=0)
    assert_not_stale(demo, "the first picture")
    changes = 0
    for what in drive(demo):
        assert_not_stale(demo, what)
        changes += 1
    assert changes >= 3 * len(demo.controls)


@pytest.mark.parametrize("name", ["hallway", "step_through"])
def test_buttons_after_slider_extremes(name):
    """Buttons pressed with the sliders at their ends: the belief jumps far, the axes rescale."""
    demo = getattr(kf.demos, name)(seed=0)
    for key, control in demo.controls.items():
        if isinstance(control, SLIDERS):
            for value in slider_values(control)[:2]:
                control.value = value
                for button in ("predict", "update", "update", "predict", "reset"):
                    demo.controls[button].click()
                    assert_not_stale(demo, f"{key} = {value}, then {button}")
