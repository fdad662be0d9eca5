"""Redrawing only the rows of a figure whose axes changed gives the picture a full redraw gives."""

from __future__ import annotations

import numpy as np

import kfcourse as kf
from kfcourse.plots.style import FigureRenderer, new_figure


def pixels(renderer: FigureRenderer) -> np.ndarray:
    return np.asarray(renderer.image(), dtype=float)


def full_redraw(renderer: FigureRenderer) -> np.ndarray:
    renderer.invalidate()
    return pixels(renderer)


def marks_off(a: np.ndarray, b: np.ndarray) -> int:
    """Pixels that differ visibly (a remnant of an old tick label, say)."""
    return int((np.abs(a - b).max(axis=2) > 40).sum())


def test_new_y_limits_redrawn_in_their_row_only():
    fig, (top, bottom) = new_figure(6.0, 5.0, nrows=2)
    top.plot([0, 1], [0, 1])
    top.set_xlabel("x (m)")
    (line,) = bottom.plot([0, 1], [0.1, -0.1])
    bottom.set_ylim(-0.125, 0.125)
    bottom.set_ylabel("error (m)")
    renderer = FigureRenderer(fig, [line])
    pixels(renderer)
    for limit in (16.0, 0.5, 1000.0, 0.03125):
        bottom.set_ylim(-limit, limit)
        stale = pixels(renderer)
        renderer.invalidate(bottom)
        row = pixels(renderer)
        assert marks_off(stale, full_redraw(renderer)) > 100  # without it the old ticks stay
        assert marks_off(row, full_redraw(renderer)) == 0


def test_landmark_loop_strips_follow_every_change_of_run():
    demo = kf.demos.landmark_loop(seed=0)
    strip = demo.renderer.fig.axes[1]
    changes = [
        lambda: demo.controls["kidnap"].click(),
        lambda: demo.controls["kidnap"].click(),
        lambda: setattr(demo.controls["dropout"], "value", True),
        lambda: setattr(demo.controls["sensor"], "value", 10.0),
        lambda: setattr(demo.controls["motion"], "value", 0.1),
        lambda: setattr(demo.controls["dropout"], "value", False),
    ]
    limits = set()
    for change in changes:
        change()
        limits.add(strip.get_ylim())
        shown = pixels(demo.renderer)
        assert marks_off(shown, full_redraw(demo.renderer)) == 0
    assert len(limits) >= 4  # the strips' limits did change on the way
