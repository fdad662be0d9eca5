"""Artists shared by the chapters: Gaussian curves, covariance ellipses, belief
bars, the gain gauge, and the robot, its landmarks and its sensor beams.  Each
takes an ``ax`` and returns what it drew; the matching ``update_*`` moves it in place.
"""

from __future__ import annotations

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.patches import Ellipse, Polygon, Rectangle

from .. import _validate as v
from ..filters.gaussian import ellipse_axes, gaussian_pdf
from . import palette


def gaussian_curve(
    ax, x, mu: float, var: float, color: str, label: str | None = None, fill: bool = True, ls: str | None = None
):
    """Draw the density of ``N(mu, var)`` over the grid ``x``.

    The line takes the style of the role whose colour it has (a prediction dashed, a
    measurement dash-dot, an estimate solid: :func:`palette.line_style`) unless ``ls`` is given.

    Returns
    -------
    (line, fill) : the Line2D and the shaded PolyCollection (``None`` without fill)
    """
    y = gaussian_pdf(x, mu, var)
    (line,) = ax.plot(x, y, color=color, lw=2.2, ls=palette.line_style(color) if ls is None else ls, label=label)
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
    """The ``nsig``-sigma contour of ``N(mu, Sig)`` (2-D) as an Ellipse patch.

    Drawn in the line style of the role whose colour it has (a prediction dashed, an
    estimate solid: :func:`palette.line_style`) unless ``ls`` is among ``kwargs``.
    """
    w, h, angle = ellipse_axes(Sig, nsig)
    style = {"fill": False, "lw": 2.0, "edgecolor": color, "ls": palette.line_style(color)} | kwargs
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
    ax.text(0, 1.0, "trust prediction", color=palette.PREDICTION_TEXT, ha="left", va="bottom", fontsize=9)
    ax.text(1, 1.0, "trust measurement", color=palette.MEASUREMENT_TEXT, ha="right", va="bottom", fontsize=9)
    text = ax.text(0.5, 1.0, "", ha="center", va="bottom", fontsize=10, weight="bold", color=palette.INK)
    update_gain_gauge((bar, text), K)
    return bar, text


def update_gain_gauge(gauge, K: float) -> None:
    """Set the gauge made by :func:`gain_gauge` to ``K``."""
    bar, text = gauge
    bar.set_width(float(np.clip(K, 0.0, 1.0)))
    text.set_text(f"K = {K:.3f}")


# The robot's body in its own frame, in units of its size: a triangle whose nose points
# along the heading (+x) and whose centroid, (1 - 0.5 - 0.5)/3 = 0, is the pose's position.
_ROBOT_BODY = np.array([[1.0, 0.0], [-0.5, 0.5], [-0.5, -0.5]])


def _robot_corners(pose, size: float) -> np.ndarray:
    """Corners of the robot's triangle at ``pose``: rotate the body by theta, then shift."""
    x, y, theta = v.vector(pose, "pose", 3)
    c, s = np.cos(theta), np.sin(theta)
    rotation = np.array([[c, -s], [s, c]])
    return size * _ROBOT_BODY @ rotation.T + [x, y]  # p_world = R(theta) p_body + (x, y)


def robot(ax, pose, color: str = palette.ESTIMATE, size: float = 0.4, **kwargs) -> Polygon:
    """A robot at ``pose`` drawn as a triangle pointing along its heading.

    Grey (``palette.TRUTH``) for the true pose, teal (``palette.ESTIMATE``) for the
    filter's estimate.  Introduced in chapter 8.

    Parameters
    ----------
    ax : matplotlib Axes
    pose : array_like, shape (3,)
        ``[x, y, theta]`` (m, m, rad).  The triangle's centroid sits at ``(x, y)``
        and its nose ``size`` metres ahead of it along ``theta``.
    color : str
        Fill and edge colour.
    size : float
        Distance from the centre to the nose (m), > 0.
    **kwargs
        Passed to :class:`matplotlib.patches.Polygon` (e.g. ``alpha``, ``zorder``, ``label``).

    Returns
    -------
    Polygon
        Move it with :func:`update_robot`.
    """
    size = v.scalar(size, "size")
    if size <= 0:
        raise ValueError(f"size must be > 0 (m), got {size}")
    style = {"closed": True, "facecolor": color, "edgecolor": color, "lw": 1.5, "zorder": 3} | kwargs
    patch = Polygon(_robot_corners(pose, size), **style)
    patch._kf_size = size
    ax.add_patch(patch)
    return patch


def update_robot(patch: Polygon, pose) -> None:
    """Move a robot made by :func:`robot` to ``pose`` (shape (3,)), in place."""
    patch.set_xy(_robot_corners(pose, patch._kf_size))


def landmarks(ax, positions, labels=False, color: str = palette.LANDMARK, **kwargs):
    """The map's landmarks as purple squares.

    Introduced in chapter 8.

    Parameters
    ----------
    ax : matplotlib Axes
    positions : array_like, shape (L, 2)
        Landmark positions ``[mx, my]`` (m), one a row.
    labels : bool or sequence of str
        ``True`` writes each landmark's index next to it; a sequence of L strings
        writes those; ``False`` writes nothing.
    color : str
    **kwargs
        Passed to ``ax.scatter`` (e.g. ``s``, ``zorder``, ``label``).

    Returns
    -------
    (points, texts) : the PathCollection of squares and a list of Text (empty without labels)
    """
    m = np.empty((0, 2)) if np.size(positions) == 0 else v.matrix(positions, "positions", cols=2)
    if labels is True:
        names = [str(i) for i in range(len(m))]
    elif labels is False or labels is None:
        names = []
    else:
        names = [str(name) for name in labels]
        if len(names) != len(m):
            raise ValueError(f"labels must name each of the {len(m)} landmarks, got {len(names)} labels")
    style = {"marker": "s", "s": 60, "color": color, "zorder": 2} | kwargs
    points = ax.scatter(m[:, 0], m[:, 1], **style)
    texts = [
        ax.annotate(name, (mx, my), xytext=(6, 6), textcoords="offset points", color=color, fontsize=9)
        for name, (mx, my) in zip(names, m, strict=False)  # no labels: names is empty
    ]
    return points, texts


def beams(ax, color: str = palette.ESTIMATE, **kwargs) -> LineCollection:
    """Sensor beams from the robot to the landmarks it is using, empty at first.

    Introduced in chapter 10.

    Parameters
    ----------
    ax : matplotlib Axes
    color : str
    **kwargs
        Passed to :class:`matplotlib.collections.LineCollection` (e.g. ``lw``, ``alpha``).

    Returns
    -------
    LineCollection
        Draw beams with :func:`update_beams`.
    """
    style = {"colors": color, "lw": 1.2, "alpha": 0.8, "zorder": 1} | kwargs
    lines = LineCollection([], **style)
    ax.add_collection(lines, autolim=False)  # beams never stretch the axes
    return lines


def update_beams(lines: LineCollection, pose, targets) -> None:
    """Point beams made by :func:`beams` from ``pose`` to each of ``targets``, in place.

    Parameters
    ----------
    lines : LineCollection
    pose : array_like, shape (3,) or (2,)
        The robot's pose ``[x, y, theta]`` (only ``x, y`` are used).
    targets : array_like, shape (K, 2)
        The landmarks in use; K = 0 (or an empty list) draws no beam.
    """
    start = v.finite(pose, "pose")
    if start.shape not in ((2,), (3,)):
        raise ValueError(f"pose must have shape (3,) or (2,), got {start.shape}")
    ends = np.empty((0, 2)) if np.size(targets) == 0 else v.matrix(targets, "targets", cols=2)
    lines.set_segments([np.array([start[:2], end]) for end in ends])  # one segment per beam
