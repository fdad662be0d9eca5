"""What a demo's picture weighs, and costs to encode, in each way it could be sent.

Run by hand or by ``make bench`` (not part of the test suite):

    .venv/bin/python benchmarks/bench_pictures.py [demo ...]   (default: every demo)

Each demo's first slider is moved through ten positions; every picture on the way is
encoded in each candidate way, and the table gives the median bytes and milliseconds.
"2x" is the picture at rest (two device pixels per CSS pixel), "1x" the same canvas
halved in each direction (the milliseconds include the halving).  The course sends
``light`` (1x WebP, quality 80) while a control moves or Run plays, and ``crisp`` (2x
JPEG, quality 90, full colour resolution) when the student stops.  Target while moving:
at most 60 KB, so that a 10 Mbit/s link carries a picture in under 50 ms.
"""

from __future__ import annotations

import io
import time

import ipywidgets as widgets
import numpy as np
from PIL import Image

import kfcourse as kf
from kfcourse.plots.style import JPEG_QUALITY, LIGHT_QUALITY

DEMOS = kf.demos.__all__
POSITIONS = 10
SLIDERS = (widgets.IntSlider, widgets.FloatSlider, widgets.FloatLogSlider)
LIGHT_TARGET = 60_000  # bytes


def encoder(fmt: str, halve: bool = False, colours: int | None = None, **options):
    """A way to send a picture: halved or not, reduced to a palette or not, then encoded as ``fmt``."""

    def encode(picture: Image.Image) -> bytes:
        if halve:
            picture = picture.reduce(2)
        if colours:
            picture = picture.quantize(colours, method=Image.Quantize.FASTOCTREE)
        buf = io.BytesIO()
        picture.save(buf, format=fmt, **options)
        return buf.getvalue()

    return encode


# What the course sends ("crisp" at rest, "light" while moving) and the alternatives measured.
WAYS = {
    "crisp: 2x JPEG 90 4:4:4": encoder("jpeg", quality=JPEG_QUALITY, subsampling=0),
    "2x WebP 70": encoder("webp", quality=70, method=0),
    "1x JPEG 85 4:4:4": encoder("jpeg", halve=True, quality=85, subsampling=0),
    "1x JPEG 80 4:2:0": encoder("jpeg", halve=True, quality=80, subsampling=2),
    "light: 1x WebP 80": encoder("webp", halve=True, quality=LIGHT_QUALITY, method=0),
    "1x PNG 64 colours": encoder("png", halve=True, colours=64),
}


def timed(encode, picture: Image.Image) -> tuple[int, float]:
    """Bytes, and milliseconds to halve and encode."""
    t0 = time.perf_counter()
    data = encode(picture)
    return len(data), 1e3 * (time.perf_counter() - t0)


def pictures(name: str) -> list[Image.Image]:
    """The demo's pictures while its first slider moves through POSITIONS positions."""
    demo = getattr(kf.demos, name)(seed=0)
    control = next(c for c in demo.controls.values() if isinstance(c, SLIDERS))
    values = np.linspace(control.min, control.max, POSITIONS)
    if isinstance(control, widgets.FloatLogSlider):
        values = control.base**values
    shown = []
    for value in values:
        control.value = round(value) if isinstance(control, widgets.IntSlider) else float(value)
        shown.append(demo.renderer.image())
    return shown


def main(names=DEMOS) -> None:
    print(f"{'demo':<20}" + "".join(f"{way:>26}" for way in WAYS))
    light = []
    for name in names:
        shots = pictures(name)
        cells = []
        for way, encode in WAYS.items():
            sizes, ms = zip(*(timed(encode, p) for p in shots), strict=True)
            cells.append(f"{np.median(sizes) / 1e3:>14.0f} KB {np.median(ms):>5.1f} ms")
            if way.startswith("light"):
                light.append(np.median(sizes))
        print(f"{name:<20}" + "".join(f"{cell:>26}" for cell in cells))
    verdict = "met" if max(light) <= LIGHT_TARGET else "NOT met"
    print(
        f"light pictures: median {np.median(light) / 1e3:.0f} KB, at most {max(light) / 1e3:.0f} KB per demo;"
        f" target <= {LIGHT_TARGET / 1e3:.0f} KB: {verdict}"
    )


if __name__ == "__main__":
    import sys

    main(sys.argv[1:] or DEMOS)
