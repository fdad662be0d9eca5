r"""The landmark localization loop (chapter 10): the map and the error strips.

The map shows the landmarks (purple squares), the true path and robot (faint
grey), the filter's trail and robot (teal, lightly filled), its 2-sigma position
ellipse after the step's readings (teal) and before them (dashed purple, the
prediction), drawn over the robots so that a small ellipse still shows,
teal beams from the estimate to the landmarks the filter used at that step, and
dashed orange beams to those whose readings it rejected (outside its gate).

Under the map, two strips show the position error along x and along y over the
whole run, each with the band of plus or minus two standard deviations of that
coordinate, read from the filter's own covariance.  An honest filter keeps its
error inside the band about 95 % of the time: the x error is Gaussian with
variance :math:`\Sigma_{xx}` if the filter is right about itself.

Every function takes a run record with the fields of
:class:`kfcourse.sim.LoopRun` (``t, dt, start, truth, landmarks, used,
rejected, mu_bar, Sig_bar, mu, Sig, dropout, kidnap``); the ``update_*`` functions move what was drawn to
another step (or another run) in place.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import to_rgba
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse, Polygon, Rectangle
from matplotlib.text import Text

from . import palette
from .artists import (
    beams,
    covariance_ellipse,
    landmarks,
    robot,
    update_beams,
    update_covariance_ellipse,
    update_robot,
)
from .style import moving_tick_labels, new_figure, tick_text

MAP_MARGIN = 1.5  # m of room around the landmarks and the true path
ROBOT_SIZE = 0.45  # m from the robot's centre to its nose
TRUTH_SIZE = 0.65  # m: the true robot is drawn larger, so it shows round an estimate on top of it
ROBOT_FILL = 0.3  # opacity of the estimated robot's fill: a small ellipse on top of it stays visible
NSIG = 2.0  # the map's ellipses and the strips' bands are 2-sigma
AXES = ("x", "y")


def _step(run, k) -> int:
    """``k`` as a step of ``run``; ``None`` means the last step."""
    T = len(run.t)
    k = T - 1 if k is None else int(k)
    if not 0 <= k < T:
        raise ValueError(f"k must be a step of the run, 0 to {T - 1}, got {k}")
    return k


def _kidnap_step(run) -> int | None:
    """The step at which the truth jumps, or ``None``."""
    return None if run.kidnap is None else int(run.kidnap)


def position_errors(run) -> tuple[np.ndarray, np.ndarray]:
    r"""The position error per axis and its 2-sigma bound, at every step.

    The error is truth minus estimate, :math:`e_k = p_k - \hat p_k` (x and y
    separately), and the bound is :math:`2\sqrt{\Sigma_{xx}}` for x and
    :math:`2\sqrt{\Sigma_{yy}}` for y, with Σ the filter's covariance after
    the step's readings.  If the filter is honest, each error is Gaussian with
    that variance and stays within its bound at about 95 % of the steps.
    Introduced in chapter 10.

    Parameters
    ----------
    run : LoopRun

    Returns
    -------
    (error, bound) : ndarray, shape (T, 2) each
        Columns x and y (m).
    """
    error = np.asarray(run.truth)[:, :2] - np.asarray(run.mu)[:, :2]  # e = p - p_hat
    bound = NSIG * np.sqrt(np.diagonal(np.asarray(run.Sig), axis1=1, axis2=2)[:, :2])  # 2 sqrt(Sig_xx), 2 sqrt(Sig_yy)
    return error, bound


def _truth_pieces(run) -> tuple[np.ndarray, np.ndarray]:
    """The true path before and after a kidnap (the second is empty without one)."""
    truth = np.asarray(run.truth)[:, :2]
    k0 = _kidnap_step(run)
    if k0 is None:
        return truth, np.empty((0, 2))
    return truth[:k0], truth[k0:]


def _blind(run, k: int) -> bool:
    return run.dropout is not None and run.dropout[0] <= k < run.dropout[1]


# --------------------------------------------------------------------------- the map


@dataclass(frozen=True)
class LoopMap:
    """What :func:`loop_map` drew; :func:`update_loop_map` moves it."""

    truth_before: Line2D  #: true path (up to a kidnap)
    truth_after: Line2D  #: true path after a kidnap (empty without one)
    trail: Line2D  #: the estimate's path up to the step shown
    truth_robot: Polygon
    robot: Polygon
    prior_ring: Ellipse  #: 2-sigma, before the step's readings
    ring: Ellipse  #: 2-sigma, after them
    beams: LineCollection  #: teal, to the landmarks whose readings were used
    rejected: LineCollection  #: dashed orange, to those whose readings were rejected
    note: Text  #: "sensor blind", "kidnapped", or nothing

    @property
    def moving(self) -> list:
        """Every artist that changes with the step or the run, bottom to top."""
        return [
            self.truth_before,
            self.truth_after,
            self.beams,
            self.rejected,
            self.trail,
            self.truth_robot,
            self.robot,
            self.prior_ring,
            self.ring,
            self.note,
        ]


def loop_map(ax, run, k: int | None = None, legend: bool = True) -> LoopMap:
    """Draw the map of ``run`` at step ``k`` on ``ax``.

    The view spans the landmarks and the true path with a margin; it does not
    follow an estimate that wanders off.  Introduced in chapter 10.

    Parameters
    ----------
    ax : matplotlib Axes
    run : LoopRun
    k : int, optional
        The step shown; by default the last.
    legend : bool
        Add a legend above the map.

    Returns
    -------
    LoopMap
    """
    k = _step(run, k)
    marks = np.asarray(run.landmarks, float).reshape(-1, 2)
    points = np.vstack([marks, np.asarray(run.truth)[:, :2]])
    lo, hi = points.min(axis=0) - MAP_MARGIN, points.max(axis=0) + MAP_MARGIN
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    landmarks(ax, marks, label="landmarks", zorder=2)
    path = {"color": palette.TRUTH, "lw": 4, "alpha": 0.35, "solid_capstyle": "round"}
    (truth_before,) = ax.plot([], [], **path, label="true path")
    (truth_after,) = ax.plot([], [], **path)
    (trail,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.6, alpha=0.9, label="estimate so far")
    start = np.asarray(run.start, float)
    truth_robot = robot(ax, start, color=palette.TRUTH, size=TRUTH_SIZE, alpha=0.8, zorder=3, label="true robot")
    est_robot = robot(
        ax,
        start,
        color=palette.ESTIMATE,
        facecolor=to_rgba(palette.ESTIMATE, ROBOT_FILL),
        size=ROBOT_SIZE,
        zorder=4,
        label="estimated robot",
    )
    eye = np.eye(2)
    prior_ring = covariance_ellipse(
        ax, start, eye, nsig=NSIG, color=palette.PREDICTION, lw=1.3, ls="--", zorder=5, label="2σ before readings"
    )
    ring = covariance_ellipse(ax, start, eye, nsig=NSIG, lw=2.0, zorder=6, label="2σ after readings")
    lines = beams(ax)
    refused = beams(ax, color=palette.MEASUREMENT, linestyles="--", lw=1.4)
    note = ax.text(
        0.5, 0.97, "", transform=ax.transAxes, ha="center", va="top", fontsize=11, weight="bold", color=palette.INK
    )
    view = LoopMap(truth_before, truth_after, trail, truth_robot, est_robot, prior_ring, ring, lines, refused, note)
    if legend:
        handles = [
            ax.scatter([], [], marker="s", color=palette.LANDMARK, s=40),
            Line2D([], [], **path),
            Line2D([], [], color=palette.ESTIMATE, lw=1.6),
            Ellipse((0, 0), 1, 1, fill=False, edgecolor=palette.ESTIMATE, lw=2),
            Ellipse((0, 0), 1, 1, fill=False, edgecolor=palette.PREDICTION, lw=1.3, ls="--"),
            Line2D([], [], color=palette.ESTIMATE, lw=1.2),
            Line2D([], [], color=palette.MEASUREMENT, lw=1.4, ls="--"),
        ]
        labels = ["landmark", "truth", "estimate", "2σ estimate", "2σ prediction", "reading used", "reading rejected"]
        ax.legend(
            handles, labels, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=4, fontsize=8.5, columnspacing=1.2
        )
    update_loop_map(view, run, k)
    return view


def update_loop_map(view: LoopMap, run, k: int) -> None:
    """Show step ``k`` of ``run`` (the same run or another one) on a map made by :func:`loop_map`."""
    k = _step(run, k)
    before, after = _truth_pieces(run)
    view.truth_before.set_data(before[:, 0], before[:, 1])
    view.truth_after.set_data(after[:, 0], after[:, 1])
    mu = np.asarray(run.mu)
    view.trail.set_data(mu[: k + 1, 0], mu[: k + 1, 1])
    update_robot(view.truth_robot, run.truth[k])
    update_robot(view.robot, mu[k])
    update_covariance_ellipse(view.prior_ring, run.mu_bar[k], np.asarray(run.Sig_bar[k])[:2, :2])
    update_covariance_ellipse(view.ring, mu[k], np.asarray(run.Sig[k])[:2, :2])
    marks = np.asarray(run.landmarks)
    update_beams(view.beams, mu[k], marks[np.asarray(run.used[k], bool)])
    update_beams(view.rejected, mu[k], marks[np.asarray(run.rejected[k], bool)])
    k0 = _kidnap_step(run)
    if _blind(run, k):
        view.note.set_text("sensor blind")
    elif k0 is not None and k >= k0:
        view.note.set_text("kidnapped: the truth jumped, the filter was not told")
    else:
        view.note.set_text("")


# --------------------------------------------------------------------------- the error strips


STRIP_TICKS = (-1.0, 0.0, 1.0)  # the strips' y ticks, as fractions of their limit
TICK_WIDTH = 6  # characters a strip's tick label may take, as in "\u22120.005"


def strip_limit(run) -> float:
    """The strips' y limit (m): the first of 1, 2, 5, 10, 20, ... times a power of ten (0.01, 0.02, 0.05,
    0.1, ...) at or above 1.15 times the largest error or bound of ``run``.

    Such a limit changes rarely as the run changes, so the tick labels keep their
    values while a student drags a slider a little, and it reads as a round number.
    Introduced in chapter 10.
    """
    return _limit(*position_errors(run))


def _limit(error, bound) -> float:
    """:func:`strip_limit` of the errors and bounds :func:`position_errors` gave."""
    value = 1.15 * max(float(np.abs(error).max()), float(bound.max()), 1e-12)
    decade = 10.0 ** np.floor(np.log10(value))
    return next(float(step * decade) for step in (1.0, 2.0, 5.0, 10.0) if step * decade >= value)


@dataclass(frozen=True)
class ErrorStrips:
    """What :func:`error_strips` drew, one entry per axis (x, then y).

    The strips plot in units of their limit, :func:`strip_limit`: their axes
    always run from -1 to 1, so their ticks and grid never move, and the tick
    labels are moving text that says what -1, 0 and 1 stand for in metres.  A
    new run changes that text, never the axes.
    """

    axes: tuple
    past: tuple[Line2D, ...]  #: the error up to the step shown
    future: tuple[Line2D, ...]  #: the rest of the run, faint
    bands: tuple[PolyCollection, ...]  #: plus or minus 2 sigma
    cursors: tuple[Line2D, ...]  #: the step shown
    blind: tuple[Rectangle, ...]  #: the steps without readings (hidden without dropout)
    kidnap: tuple[Line2D, ...]  #: the kidnap step (hidden without one)
    labels: tuple[tuple[Text, ...], ...]  #: the y tick labels of each axis, at STRIP_TICKS

    @property
    def moving(self) -> list:
        """Every artist that changes with the step or the run, bottom to top."""
        per_axis = zip(self.blind, self.bands, self.kidnap, self.future, self.past, self.cursors, strict=True)
        return [artist for group in per_axis for artist in group] + [text for axis in self.labels for text in axis]


def _band_verts(t, bound) -> np.ndarray:
    """The outline of the band -bound..+bound over t, as one closed polygon."""
    return np.concatenate([np.column_stack([t, bound]), np.column_stack([t[::-1], -bound[::-1]])])


def error_strips(axes, run, k: int | None = None) -> ErrorStrips:
    """Draw the x and y position errors of ``run`` with their 2-sigma bands.

    See :func:`position_errors` for the definitions and :func:`strip_limit`
    for the shared y limit.  Introduced in chapter 10.

    Parameters
    ----------
    axes : pair of matplotlib Axes
        For the x error and the y error (sharing their time axis).
    run : LoopRun
    k : int, optional
        The step marked by the cursor; by default the last.

    Returns
    -------
    ErrorStrips
    """
    k = _step(run, k)
    t = np.asarray(run.t, float)
    parts: dict[str, list] = {name: [] for name in ("past", "future", "bands", "cursors", "blind", "kidnap", "labels")}
    for ax, name in zip(axes, AXES, strict=True):
        ax.set_xlim(t[0], t[-1])
        ax.set_ylim(-1.0, 1.0)  # in units of the strips' limit
        ax.axhline(0.0, color=palette.INK, lw=0.8, alpha=0.5)
        ax.set_ylabel(f"{name} error (m)")
        labels = moving_tick_labels(ax, STRIP_TICKS, TICK_WIDTH)
        blind = Rectangle((t[0], -1e3), 0.0, 2e3, color=palette.TRUTH, alpha=0.25, lw=0, visible=False)
        ax.add_patch(blind)
        band = PolyCollection([], facecolors=palette.ESTIMATE, alpha=0.18, lw=0)
        ax.add_collection(band, autolim=False)
        (kidnap,) = ax.plot([t[0], t[0]], [-1e3, 1e3], color=palette.INK, lw=1.2, ls=":", visible=False)
        (future,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.2, alpha=0.35)
        (past,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.8)
        (cursor,) = ax.plot([t[0], t[0]], [-1e3, 1e3], color=palette.INK, lw=1.0, alpha=0.6)
        for key, artist in zip(parts, (past, future, band, cursor, blind, kidnap, labels), strict=True):
            parts[key].append(artist)
    axes[-1].set_xlabel("time (s)")
    strips = ErrorStrips(tuple(axes), **{key: tuple(value) for key, value in parts.items()})
    update_error_strips(strips, run, k)
    return strips


def update_error_strips(strips: ErrorStrips, run, k: int) -> None:
    """Show ``run`` with the cursor at step ``k`` on strips made by :func:`error_strips`.

    Only artists in :attr:`ErrorStrips.moving` change: a renderer that keeps the
    static background need not redraw it, whatever the run.
    """
    k = _step(run, k)
    t = np.asarray(run.t, float)
    error, bound = position_errors(run)
    top = _limit(error, bound)
    error, bound = error / top, bound / top  # in units of the limit
    k0 = _kidnap_step(run)
    for i in range(len(strips.axes)):
        strips.past[i].set_data(t[: k + 1], error[: k + 1, i])
        strips.future[i].set_data(t[k:], error[k:, i])
        strips.bands[i].set_verts([_band_verts(t, bound[:, i])])
        strips.cursors[i].set_xdata([t[k], t[k]])
        for label, y in zip(strips.labels[i], STRIP_TICKS, strict=True):
            label.set_text(tick_text(y * top))
        blind = strips.blind[i]
        blind.set_visible(run.dropout is not None)
        if run.dropout is not None:
            t0, t1 = run.dropout
            first, last = t[min(t0, len(t) - 1)], t[min(max(t1 - 1, t0), len(t) - 1)]
            blind.set_x(first - 0.5 * run.dt)
            blind.set_width(last - first + run.dt)
        strips.kidnap[i].set_visible(k0 is not None)
        if k0 is not None:
            strips.kidnap[i].set_xdata([t[k0], t[k0]])


# --------------------------------------------------------------------------- the whole picture


def loop_figure(run, width: float = 6.4, strip_height: float = 0.95, legend: bool = True):
    """A figure with the map above and the two error strips under it.

    Introduced in chapter 10.

    Returns
    -------
    (fig, ax_map, (ax_x, ax_y))
    """
    marks = np.asarray(run.landmarks, float).reshape(-1, 2)
    points = np.vstack([marks, np.asarray(run.truth)[:, :2]])
    span = points.max(axis=0) - points.min(axis=0) + 2 * MAP_MARGIN
    map_height = (width - 0.8) * span[1] / span[0] + 0.5  # metres square across the width, room for the x label
    fig, axes = new_figure(
        width,
        map_height + 2 * strip_height + (0.45 if legend else 0.0),
        nrows=3,
        gridspec_kw={"height_ratios": [map_height, strip_height, strip_height]},
    )
    axes[2].sharex(axes[1])
    axes[1].tick_params(labelbottom=False)
    return fig, axes[0], (axes[1], axes[2])


def loop_chart(run, k: int | None = None):
    """Chapter 10: one step of a landmark-loop run, the map above and the error strips below.

    Introduced in chapter 10.

    Parameters
    ----------
    run : LoopRun
    k : int, optional
        The step shown on the map and marked on the strips; by default the last.

    Returns
    -------
    matplotlib.figure.Figure
    """
    k = _step(run, k)
    fig, ax_map, strip_axes = loop_figure(run)
    loop_map(ax_map, run, k)
    error_strips(strip_axes, run, k)
    return fig
