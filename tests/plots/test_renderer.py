"""The renderer's rule: blit while only the dynamic artists changed, draw in full when the
background did (a limit, a tick, a label, any static artist), and say which it did."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from kfcourse.plots.style import FigureRenderer, new_figure


@pytest.fixture
def scene():
    fig, ax = new_figure(4.0, 3.0)
    (moving,) = ax.plot([0, 1], [0, 1], lw=2)
    (still,) = ax.plot([0, 1], [1, 0], lw=1)
    label = ax.text(0.1, 0.9, "a")
    ax.set_xlabel("x")
    ax.set_title("one")
    renderer = FigureRenderer(fig, [moving])
    renderer.image()
    return ax, moving, still, label, renderer


def pixels(renderer) -> np.ndarray:
    return np.asarray(renderer.image(), dtype=float)


def full_redraw(renderer) -> np.ndarray:
    renderer.fig.stale = True
    return pixels(renderer)


def test_the_first_picture_is_drawn_in_full(scene):
    *_, renderer = scene
    assert renderer.full_draws == 1


def test_a_moving_artist_is_blitted(scene):
    _, moving, _, _, renderer = scene
    moving.set_ydata([1, 0.5])
    shown = pixels(renderer)
    assert renderer.full_draws == 1
    assert np.array_equal(shown, full_redraw(renderer))


@pytest.mark.parametrize(
    "change",
    [
        lambda ax, still, label: ax.set_ylim(0, 3),
        lambda ax, still, label: ax.set_xticks([0, 0.25, 1]),
        lambda ax, still, label: ax.set_xlabel("metres"),
        lambda ax, still, label: ax.set_title("two"),
        lambda ax, still, label: label.set_text("b"),
        lambda ax, still, label: still.set_ydata([0.5, 0.5]),
    ],
    ids=["limit", "ticks", "axis label", "title", "text", "static line"],
)
def test_a_change_to_the_background_is_drawn_in_full(scene, change):
    ax, _, still, label, renderer = scene
    before = pixels(renderer)
    change(ax, still, label)
    shown = pixels(renderer)
    assert renderer.full_draws == 2  # the first picture and this one; the one before was blitted
    assert not np.array_equal(shown, before)
    assert np.array_equal(shown, full_redraw(renderer))


def test_a_new_pixel_width_is_drawn_in_full(scene):
    *_, renderer = scene
    renderer.set_pixel_width(640)
    assert renderer.image().size[0] == 640
    assert renderer.full_draws == 2


def test_the_light_picture_is_half_the_size_and_close_to_the_crisp_one(scene):
    *_, renderer = scene
    renderer.set_pixel_width(1200)
    crisp = Image.open(io.BytesIO(renderer.jpeg()))
    light = Image.open(io.BytesIO(renderer.light()))
    assert light.format == "WEBP" and crisp.format == "JPEG"
    assert light.size == (crisp.size[0] // 2, crisp.size[1] // 2)
    down = np.asarray(crisp.convert("RGB").reduce(2), float)
    assert np.abs(np.asarray(light.convert("RGB"), float) - down).mean() < 3.0
    assert len(renderer.light()) < len(renderer.jpeg()) / 3
