"""Artists shared by the chapters: Gaussian curves, covariance ellipses, belief
bars and the gain gauge.  Each takes an ``ax`` and returns what it drew; the
matching ``update_*`` moves it in place.
"""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Ellipse, Rectangle

from ..filters.gaussian import ellipse_axes, gaussian_pdf
from . import palette


def gaussian_curve(ax, x, mu: float, var: float, color: str, label: str | None = None, fill: bool = True):
    """Draw the density of ``N(mu, var)`` over the grid ``x``.

    Returns
    -------
    (line, fill) : the Line2D and the shaded PolyCollection (``None`` without fill)
    """
    y = gaussian_pdf(x, mu, var)
    (line,) = ax.plot(x, y, color=color, lw=2.2, label=label)
    shade = ax.fill_between(x, y, color=color, alpha=0.15, lw=0) if fill else None
    return line, shade


def update_gaussian_curve(curve, mu: float, var: float) -> np.ndarray:
    """Move a curve made by :func:`gaussian_curve`; returns the new densities."""
    line, shade = curve
    x = line.get_xdata()
    y = gaussian_pdf(x, mu, var)
    line.set_ydata(y)
    if shade is not None:
        verts = np.concatenate([np.column_stack([x, y]), np.column_stack([x[::-1], np.zeros_like(x)])])
        shade.set_verts([verts])
    return y


def covariance_ellipse(ax, mu, Sig, nsig: float = 1.0, color: str = palette.ESTIMATE, **kwargs) -> Ellipse:
    """The ``nsig``-sigma contour of ``N(mu, Sig)`` (2-D) as an Ellipse patch."""
    w, h, angle = ellipse_axes(Sig, nsig)
    style = {"fill": False, "lw": 2.0, "edgecolor": color} | kwargs
    patch = Ellipse(tuple(np.asarray(mu, float)[:2]), w, h, angle=angle, **style)
    patch._kf_nsig = nsig
    ax.add_patch(patch)
    return patch


def update_covariance_ellipse(patch: Ellipse, mu, Sig) -> None:
    """Move an ellipse made by :func:`covariance_ellipse` to a new mean and covariance."""
    w, h, angle = ellipse_axes(Sig, patch._kf_nsig)
    patch.set_center(tuple(np.asarray(mu, float)[:2]))
    patch.set_width(w)
    patch.set_height(h)
    patch.set_angle(angle)


def belief_bars(ax, belief, color: str = palette.ESTIMATE, **kwargs):
    """Bars of a discrete belief, one per cell (the histogram filter's picture)."""
    belief = np.asarray(belief, float)
    return ax.bar(np.arange(belief.size), belief, width=0.8, color=color, **kwargs)


def update_belief_bars(bars, values) -> None:
    """Set the heights of bars made by :func:`belief_bars`."""
    for bar, val in zip(bars, np.asarray(values, float), strict=True):
        bar.set_height(val)


def gain_gauge(ax, K: float = 0.0):
    """A horizontal 0-1 gauge for the Kalman gain, purple end "trust prediction",
    orange end "trust measurement".

    Returns
    -------
    (bar, text)
    """
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_yticks([])
    ax.set_xticks([0, 0.5, 1])
    ax.grid(False)
    for side in ("left", "top", "right"):
        ax.spines[side].set_visible(False)
    ax.add_patch(Rectangle((0, 0.25), 1, 0.5, color=palette.GRID, lw=0))
    bar = Rectangle((0, 0.25), K, 0.5, color=palette.ESTIMATE, lw=0)
    ax.add_patch(bar)
    ax.text(0, 1.0, "trust prediction", color=palette.PREDICTION, ha="left", va="bottom", fontsize=9)
    ax.text(1, 1.0, "trust measurement", color=palette.MEASUREMENT, ha="right", va="bottom", fontsize=9)
    text = ax.text(0.5, 1.0, "", ha="center", va="bottom", fontsize=10, weight="bold", color=palette.INK)
    update_gain_gauge((bar, text), K)
    return bar, text


def update_gain_gauge(gauge, K: float) -> None:
    """Set the gauge made by :func:`gain_gauge` to ``K``."""
    bar, text = gauge
    bar.set_width(float(np.clip(K, 0.0, 1.0)))
    text.set_text(f"K = {K:.3f}")
