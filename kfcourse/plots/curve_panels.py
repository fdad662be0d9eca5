"""A Gaussian through a curve: the four panels the demos of chapters 7 and 9 share.

Top left, the curve f over the input axis; under it, on the same x, the input
density; top right, on f's own y axis, the output densities drawn sideways; bottom
right, a panel for the numbers.  Every density is drawn as what it is, a
probability density on real ticks.  The output axis is set by the caller (it
changes with the function); the density axes follow the tallest density shown in
coarse steps (powers of two, :func:`~kfcourse.plots.style.nice_limit`).  Every
limit is set only when it changes (:func:`set_limits`): a slider step that changes
no limit redraws only what moves, and when one does change, the figure's renderer
redraws the rest by itself.  Introduced in chapter 7.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator

from .. import _validate as v
from ..filters.gaussian import gaussian_pdf
from .style import fixed_width_ticks, new_figure, nice_limit, set_limits

__all__ = [
    "FunctionPanels",
    "axis_range",
    "function_panels",
    "show_input_density",
    "show_sampled_output",
    "show_sideways_gaussian",
    "sideways_histogram",
]

HEADROOM = 1.15  # a density axis reaches at least this many times the tallest density it shows
CUT = 1.05  # a Gaussian too tall for its panel is drawn up to here (times the axis), off the panel's edge
ARROW = 0.2  # a variance of 0 is an arrow this fraction of the density axis long
GRID_POINTS = 600  # points along the output axis at which an output Gaussian is drawn


@dataclass(frozen=True)
class FunctionPanels:
    """The figure and the four axes :func:`function_panels` made."""

    fig: Figure
    ax_f: Axes  #: the curve f; its y axis is the output axis
    ax_out: Axes  #: the output densities, sideways, on f's y axis
    ax_in: Axes  #: the input density, on f's x axis
    ax_txt: Axes  #: the numbers (no axes drawn)


def axis_range(pair, name: str) -> tuple[float, float]:
    """``pair`` as the (low, high) of an axis: two finite numbers, low < high."""
    low, high = v.vector(pair, name, 2)
    if not low < high:
        raise ValueError(f"{name} must be (low, high) with low < high, got {(float(low), float(high))}")
    return float(low), float(high)


def function_panels(width: float, height: float, x_range, width_ratio: float, height_ratio: float) -> FunctionPanels:
    """The four panels, each labelled, with the input axis ``x_range`` and no output range yet.

    Parameters
    ----------
    width, height : float
        Figure size (inches).
    x_range : (float, float)
        The input axis.
    width_ratio : float
        Width of the right column against 3 for the left one.
    height_ratio : float
        Height of the bottom row against 3 for the top one.

    Returns
    -------
    FunctionPanels
    """
    x_range = axis_range(x_range, "x_range")
    fig, axes = new_figure(
        width,
        height,
        nrows=2,
        ncols=2,
        gridspec_kw={"width_ratios": [3, width_ratio], "height_ratios": [3, height_ratio]},
    )
    (ax_f, ax_out), (ax_in, ax_txt) = axes
    ax_in.sharex(ax_f)
    ax_out.sharey(ax_f)
    ax_f.tick_params(labelbottom=False)  # the input panel under it labels x
    ax_out.tick_params(labelleft=False)  # f's panel beside it labels y
    ax_f.set_xlim(*x_range)
    # Labels of one width whatever the limits, so that the layout found once still holds.
    fixed_width_ticks(ax_f.yaxis, 5)
    fixed_width_ticks(ax_in.yaxis, 5)
    ax_f.set_ylabel("output y = f(x)")
    ax_in.set_xlabel("input x")
    ax_in.set_ylabel("density")
    ax_out.set_xlabel("density")
    ax_in.set_ylim(0.0, 1.0)  # until a density is shown
    ax_out.set_xlim(0.0, 1.0)
    ax_in.yaxis.set_major_locator(MaxNLocator(nbins=4, steps=[1, 2, 4, 5, 10]))  # a power-of-two top: 0, 4, 8, 12, 16
    # The layout is found once, for the first frame; the density axis's last label would sit on the figure's right
    # edge whenever its limit changes, so no label is drawn at that end.
    ax_out.xaxis.set_major_locator(MaxNLocator(nbins=4, steps=[1, 2, 4, 5, 10], prune="upper"))
    ax_txt.axis("off")
    return FunctionPanels(fig, ax_f, ax_out, ax_in, ax_txt)


def sideways_histogram(y, lo: float, hi: float, bins: int) -> tuple[np.ndarray, np.ndarray, float]:
    """The samples ``y`` as a density histogram on ``bins`` equal bins from ``lo`` to ``hi``, drawn sideways.

    Each bin's height is the fraction of *all* the samples in it divided by its width,
    so samples beyond the axis count too: the outline shows the real density of ``y``
    where the axis shows it.

    Returns
    -------
    (density, output, peak)
        The outline's coordinates (density along x, output along y) and its tallest bin.
    """
    lo, hi = axis_range((lo, hi), "(lo, hi)")
    bins = v.whole(bins, "bins", 1)
    edges = np.linspace(lo, hi, bins + 1)
    counts, _ = np.histogram(y, bins=edges)
    dens = counts / (np.size(y) * (edges[1] - edges[0]))  # fraction of the samples per unit of output
    outline = np.concatenate([[0.0], np.repeat(dens, 2), [0.0]])
    return outline, np.repeat(edges, 2), float(dens.max())


def show_sideways_gaussian(line: Line2D, mean: float, var: float, lo: float, hi: float, top: float) -> None:
    """Draw N(mean, var) sideways on ``line`` over the output axis ``lo`` to ``hi``, on a density axis up to ``top``.

    A Gaussian taller than the axis runs off its edge (it is drawn up to ``CUT * top``,
    where the panel clips it).  A variance of 0, all the probability at one value, is a
    short arrow at the mean.
    """
    var = v.variance(var, "var")
    top = v.positive(top, "top", "the top of a density axis")
    if var > 1e-12 * (hi - lo) ** 2:
        grid = np.linspace(lo, hi, GRID_POINTS)
        line.set_data(np.minimum(gaussian_pdf(grid, mean, var), CUT * top), grid)
        line.set_marker("None")
    else:
        line.set_data([0.0, ARROW * top], [mean, mean])
        line.set_marker(">")
        line.set_markevery([1])


def show_function(panels: FunctionPanels, curve: Line2D, tangent: Line2D, model, limits) -> tuple[float, float]:
    """f and the EKF's tangent at m on the function panel, whose output axis is ``limits``.

    ``model`` needs ``m``, ``f`` and ``df`` (f and f').  The axis is set only when it
    changes (:func:`~kfcourse.plots.style.set_limits`).  Returns f(m) and the slope f'(m).
    """
    set_limits(panels.ax_f, ylim=limits)
    x, m = curve.get_xdata(), model.m
    fm, slope = float(model.f(m)), float(model.df(m))
    curve.set_ydata(model.f(x))
    tangent.set_ydata(fm + slope * (x - m))  # f(m) + f'(m) (x - m)
    return fm, slope


def show_input_density(panels: FunctionPanels, line: Line2D, m: float, s: float) -> np.ndarray:
    """Draw the input density N(m, s²) on ``line`` (its x data is the grid); returns the densities.

    The input axis's top is the power of two above the peak, 1 / (s √(2π)), with ``HEADROOM``.
    """
    peak = 1.0 / (s * np.sqrt(2.0 * np.pi))
    set_limits(panels.ax_in, ylim=(0.0, nice_limit(HEADROOM * peak)))
    dens = gaussian_pdf(line.get_xdata(), m, s * s)
    line.set_ydata(dens)
    return dens


def show_sampled_output(panels: FunctionPanels, y, bins: int) -> tuple[np.ndarray, np.ndarray, float]:
    """The histogram of the output samples ``y`` over the output axis, sideways, and the top of the density axis.

    The density axis's top is the power of two above the tallest bin, with ``HEADROOM``
    (or above the density of the samples spread evenly over the output axis, if higher),
    and is set here.

    Returns
    -------
    (density, output, top)
        The histogram's outline (density along x, output along y) and the density axis's top.
    """
    lo, hi = panels.ax_f.get_ylim()
    dens, out, peak = sideways_histogram(y, lo, hi, bins)
    top = nice_limit(HEADROOM * max(peak, 1.0 / (hi - lo)))
    set_limits(panels.ax_out, xlim=(0.0, top))
    return dens, out, top
