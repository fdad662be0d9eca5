"""Pictures rendered for HiDPI screens: more pixels, the same picture.

A demo's picture is rendered ``PIXEL_DENSITY * display_width`` pixels wide and shown
``display_width`` CSS pixels wide (``DISPLAY_WIDTH`` unless the demo limits its picture's
width); a page without a kernel gets a PNG of the first frame.
"""

from __future__ import annotations

import base64
import html
import io
import re

import numpy as np
import pytest
from PIL import Image

import kfcourse as kf
from kfcourse.demos._base import DISPLAY_WIDTH
from kfcourse.plots.style import PIXEL_DENSITY, FigureRenderer, new_figure

DEMOS = kf.demos.__all__
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"


def picture(data: bytes) -> Image.Image:
    return Image.open(io.BytesIO(bytes(data)))


def chart(width=8.0, height=3.6):
    fig, ax = new_figure(width, height)
    (line,) = ax.plot([0, 1, 2], [0, 1, 0], lw=2)
    ax.set_xlabel("x (m)")
    ax.set_title("a title")
    return fig, ax, line


def test_set_pixel_width_sets_the_size_and_keeps_the_layout():
    fig, ax, line = chart()
    renderer = FigureRenderer(fig, [line])
    small = picture(renderer.png())
    box_small = ax.get_position().bounds
    renderer.set_pixel_width(1900)
    assert renderer.pixel_width == 1900
    big = picture(renderer.png())
    assert big.size[0] == 1900
    assert big.size[1] == pytest.approx(small.size[1] * 1900 / small.size[0], abs=1)
    assert ax.get_position().bounds == pytest.approx(box_small)  # same layout, finer pixels
    # The same picture: the big one scaled down looks like the small one.
    down = np.asarray(big.convert("L").resize(small.size, Image.Resampling.BOX), float)
    assert np.abs(down - np.asarray(small.convert("L"), float)).mean() < 6.0


def test_text_gets_more_pixels_not_bigger():
    """The title's height grows with the pixel width, as a fraction of the figure it stays."""
    fig, ax, line = chart()
    renderer = FigureRenderer(fig, [line])
    renderer.png()
    title = ax.title
    h1 = title.get_window_extent().height / fig.bbox.height
    renderer.set_pixel_width(3 * renderer.pixel_width)
    renderer.png()
    h3 = title.get_window_extent().height / fig.bbox.height
    assert h3 == pytest.approx(h1, rel=0.08)


@pytest.mark.parametrize("width", [0, -10, float("nan"), float("inf")])
def test_bad_pixel_width(width):
    fig, _, line = chart()
    with pytest.raises(ValueError, match="width"):
        FigureRenderer(fig, [line]).set_pixel_width(width)


def test_jpeg_is_close_to_the_lossless_picture():
    fig, _, line = chart()
    renderer = FigureRenderer(fig, [line])
    renderer.set_pixel_width(1900)
    jpeg, png = renderer.jpeg(), renderer.png()
    assert jpeg[:3] == b"\xff\xd8\xff" and png[:8] == b"\x89PNG\r\n\x1a\n"
    a = np.asarray(picture(jpeg).convert("RGB"), float)
    b = np.asarray(picture(png).convert("RGB"), float)
    assert a.shape == b.shape
    assert np.abs(a - b).mean() < 1.5  # quality 90, full colour resolution
    assert np.percentile(np.abs(a - b), 99.9) < 60


@pytest.mark.parametrize("name", DEMOS)
def test_demo_picture_is_rendered_for_a_hidpi_screen(name):
    demo = getattr(kf.demos, name)(seed=0)
    assert demo.image.format == "jpeg"
    shown = picture(demo.image.value)
    assert shown.format == "JPEG"
    assert demo.display_width <= DISPLAY_WIDTH
    assert shown.size[0] == PIXEL_DENSITY * demo.display_width


@pytest.mark.parametrize("name", DEMOS)
def test_demo_hands_pages_without_a_kernel_its_first_frame(name):
    demo = getattr(kf.demos, name)(seed=0)
    data, metadata = demo._repr_mimebundle_()
    assert WIDGET_VIEW in data and "text/plain" in data  # the live widget is still there for JupyterLab
    assert metadata["image/png"]["width"] == demo.display_width  # shown at the widget's size
    png = picture(base64.b64decode(data["image/png"]))
    assert png.format == "PNG"
    first = picture(demo.image.value)
    assert png.size == first.size
    a, b = np.asarray(png.convert("RGB"), float), np.asarray(first.convert("RGB"), float)
    assert np.abs(a - b).mean() < 1.5  # the very picture the widget shows


def test_the_static_picture_follows_the_demo():
    demo = kf.demos.tracker(seed=0)
    before = base64.b64decode(demo._repr_mimebundle_()[0]["image/png"])
    demo.controls["frame"].value = 10
    after = base64.b64decode(demo._repr_mimebundle_()[0]["image/png"])
    assert before != after


def test_a_chart_in_a_notebook_is_drawn_for_a_hidpi_screen_at_its_own_size():
    fig, _, _ = chart(8.0, 3.6)  # 640 x 288 CSS px at 80 dpi
    data, _ = fig._repr_mimebundle_()
    img = re.fullmatch(r'<img src="data:image/png;base64,([^"]+)" width="(\d+)" alt="([^"]+)">', data["text/html"])
    assert img is not None, data["text/html"][:200]
    png = picture(base64.b64decode(img[1]))
    assert int(img[2]) == 640
    assert html.unescape(img[3]) == data["text/plain"] and img[3].startswith("Figure")
    assert png.size == (PIXEL_DENSITY * 640, PIXEL_DENSITY * 288)
    assert fig.dpi == 80  # the figure itself is left as it was
    assert picture(fig._repr_png_()).size == (640, 288)
