"""The demo tests render one pixel per CSS pixel.

What a demo draws, and where, does not depend on how many pixels its picture has: the
figure's layout is set in inches and points, and the pixel count only sets the detail.
One pixel per CSS pixel costs a quarter of the pixels of the course's double density.
``tests/plots/test_density.py`` and the browser suite check the pictures at the density
the course ships.
"""

from __future__ import annotations

import pytest

import kfcourse.demos._base


@pytest.fixture(autouse=True)
def one_pixel_per_css_pixel(monkeypatch):
    monkeypatch.setattr(kfcourse.demos._base, "PIXEL_DENSITY", 1)
