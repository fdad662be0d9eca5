"""Figure creation and fast rendering to PNG and JPEG.

Figures are plain :class:`matplotlib.figure.Figure` objects on an Agg canvas, not
pyplot figures: nothing is registered globally, nothing is shown by itself, and
the notebook's matplotlib backend does not matter.

A figure is drawn at ``dpi`` pixels per inch; a renderer can draw it with more
pixels (:meth:`FigureRenderer.set_pixel_width`) for a screen that shows two device
pixels per CSS pixel, while the page still shows it at the same size.
"""

from __future__ import annotations

import base64
import html
import io

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter
from PIL import Image

from . import palette
from .describe import figure_alt

STYLE = {
    "font.size": 10,
    "axes.edgecolor": palette.INK,
    "axes.labelcolor": palette.INK,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.grid": True,
    "grid.color": palette.GRID,
    "xtick.color": palette.INK,
    "ytick.color": palette.INK,
    "legend.frameon": False,
}


class CourseFigure(Figure):
    """A Figure that shows itself as a PNG when it is the last value of a notebook cell.

    The notebook gets a PNG with ``PIXEL_DENSITY`` pixels per CSS pixel, shown at the
    figure's own size (``width`` x ``dpi`` CSS pixels): sharp on a HiDPI screen.  It comes
    as an HTML ``<img>`` whose alt text (:func:`~kfcourse.plots.describe.figure_alt`) says
    what the figure shows, for a screen reader; a frontend that shows only text shows that.
    """

    def _repr_png_(self) -> bytes:
        return FigureRenderer(self).png()

    def _repr_mimebundle_(self, include=None, exclude=None):
        width, dpi = self.get_figwidth() * self.dpi, self.dpi  # CSS px
        renderer = FigureRenderer(self)
        renderer.set_pixel_width(PIXEL_DENSITY * width)
        try:
            png = renderer.png()
        finally:
            self.set_dpi(dpi)
        alt = figure_alt(self)
        src = "data:image/png;base64," + base64.b64encode(png).decode("ascii")
        img = f'<img src="{src}" width="{round(width)}" alt="{html.escape(alt)}">'
        return {"text/html": img, "text/plain": alt}, {}


def new_figure(width: float = 8.0, height: float = 3.6, dpi: int = 80, **subplots) -> tuple[Figure, object]:
    """A styled figure and its axes (``Figure.subplots`` keywords pass through).

    Returns
    -------
    (fig, axes)
    """
    import matplotlib as mpl

    with mpl.rc_context(STYLE):
        fig = CourseFigure(figsize=(width, height), dpi=dpi, layout="constrained")
        FigureCanvasAgg(fig)
        axes = fig.subplots(**subplots)
    return fig, axes


def nice_limit(value: float) -> float:
    """The next power of two above ``value``: an axis limit that changes rarely
    while dragging, so the static background need not be redrawn often."""
    return float(2.0 ** np.ceil(np.log2(max(value, 1e-12))))


def set_limits(ax: Axes, xlim=None, ylim=None) -> bool:
    """Set the limits of ``ax`` that differ from the ones it has; returns whether any did.

    Setting a limit marks the figure stale, and so the background for a full redraw
    (:class:`FigureRenderer`), even when the value is the same: a picture updated at
    every slider step sets only the limits that changed.
    """
    changed = False
    if xlim is not None and tuple(ax.get_xlim()) != tuple(map(float, xlim)):
        ax.set_xlim(*xlim)
        changed = True
    if ylim is not None and tuple(ax.get_ylim()) != tuple(map(float, ylim)):
        ax.set_ylim(*ylim)
        changed = True
    return changed


FIGURE_SPACE = "\u2007"  # a space as wide as a digit


def fixed_width_ticks(axis, width: int = 6) -> None:
    """Give every tick label of ``axis`` the same width, ``width`` digits.

    A renderer lays the figure out once (:class:`FigureRenderer`), for the tick
    labels it sees first.  If the limits change later and the labels get wider
    ("0.5" becomes "1.75"), they would push the axis label off the figure.
    Padding every label on the left with digit-wide spaces keeps their width,
    and so the layout, the same whatever the limits.  Introduced in chapter 3.

    Parameters
    ----------
    axis : matplotlib.axis.Axis
        E.g. ``ax.yaxis``.
    width : int
        Characters each label is padded to (labels up to 4 significant digits).
    """
    axis.set_major_formatter(FuncFormatter(lambda value, _: tick_text(value).rjust(width, FIGURE_SPACE)))


def tick_text(value: float) -> str:
    """A tick label for ``value`` as matplotlib writes one: up to 4 significant digits and a true minus sign."""
    return f"{value:.4g}".replace("-", "\u2212")


PIXEL_DENSITY = 2  # device pixels per CSS pixel on a HiDPI screen ("2x", "Retina")
JPEG_QUALITY = 90  # with full-resolution colour: text and thin lines stay clean at 2x
LIGHT_QUALITY = 80  # WebP quality of the half-size pictures sent while something moves


class FigureRenderer:
    """Render a figure to PNG, JPEG or WebP bytes, redrawing only what moves.

    Artists listed in ``dynamic`` are marked animated: a full draw caches the
    static background once, and each later picture restores it and draws only
    the dynamic artists (blitting), which is what makes a slider feel immediate.

    The renderer decides by itself when the background must be drawn again.
    Matplotlib marks a figure *stale* whenever one of its static artists changes
    (an axis limit, a tick, a label, a title, any text or line not in ``dynamic``)
    and does not for animated artists, so a picture is blitted while the figure
    is not stale and drawn in full when it is.  Plots then draw their real data
    with real ticks and never keep books on what the background shows.

    :meth:`jpeg` is the crisp picture (a 1900-pixel-wide picture encodes in a few ms,
    a PNG of it takes several times longer); :meth:`light` is the same picture at
    half the pixels as a lossy WebP, about a seventh of the bytes, for pictures that
    last a fraction of a second on their way over a network link; :meth:`png` is
    lossless, for pictures stored once.

    Attributes
    ----------
    full_draws : int
        How many times the whole figure was drawn (the first picture, then once per
        change to the background).
    """

    def __init__(self, fig: Figure, dynamic: list[Artist] = ()):
        self.fig = fig
        self.dynamic = list(dynamic)
        for artist in self.dynamic:
            artist.set_animated(True)
        self._background = None
        self.full_draws = 0

    @property
    def pixel_width(self) -> int:
        """Width of the rendered picture in pixels."""
        return round(self.fig.get_figwidth() * self.fig.dpi)

    def set_pixel_width(self, width: float) -> None:
        """Render the figure ``width`` pixels wide from now on (the layout and the
        font sizes relative to the figure stay the same; only the detail grows).

        Parameters
        ----------
        width : float
            Pixels, > 0.  E.g. ``PIXEL_DENSITY * 950`` for a picture shown 950
            CSS pixels wide on a HiDPI screen.
        """
        if not np.isfinite(width) or width <= 0:
            raise ValueError(f"width must be a positive number of pixels, got {width!r}")
        self.fig.set_dpi(width / self.fig.get_figwidth())  # marks the figure stale: drawn in full next time

    def png(self) -> bytes:
        """The current picture as PNG bytes (lossless)."""
        buf = io.BytesIO()
        self.image().save(buf, format="png", compress_level=1)
        return buf.getvalue()

    def jpeg(self) -> bytes:
        """The current picture as JPEG bytes, every pixel: the crisp picture a student studies."""
        buf = io.BytesIO()
        self._render("RGBX").save(buf, format="jpeg", quality=JPEG_QUALITY, subsampling=0)  # RGBX: no copy
        return buf.getvalue()

    def light(self) -> bytes:
        """The current picture at half the pixels in each direction, as lossy WebP bytes.

        For a picture that is replaced within a fraction of a second (a slider being
        dragged, a run playing): a fifth to a tenth of :meth:`jpeg`'s bytes, so that
        it crosses a slow link in time for the next one.
        """
        buf = io.BytesIO()
        self._render("RGBX").reduce(2).save(buf, format="webp", quality=LIGHT_QUALITY, method=0)
        return buf.getvalue()

    def image(self) -> Image.Image:
        """The current picture as an RGB :class:`PIL.Image.Image`."""
        return self._render("RGBA").convert("RGB")

    def _render(self, mode: str) -> Image.Image:
        """Draw what changed; the canvas as an image in ``mode`` (RGBA or RGBX) sharing its memory."""
        canvas = self.fig.canvas
        if self._background is None or self.fig.stale:
            canvas.draw()  # static artists only: animated ones are skipped
            self.fig.set_layout_engine("none")  # keep the layout found once; it is slow to redo
            self._background = canvas.copy_from_bbox(self.fig.bbox)
            self.fig.stale = False  # from here, any change to a static artist marks it stale again
            self.full_draws += 1
        else:
            canvas.restore_region(self._background)
        for artist in self.dynamic:
            if artist.get_visible():
                self.fig.draw_artist(artist)
        width, height = canvas.get_width_height(physical=True)
        return Image.frombuffer(mode, (width, height), canvas.buffer_rgba(), "raw", mode, 0, 1)
