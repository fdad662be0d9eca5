r"""The landmark localization loop (chapter 10): the map and the error strips.

The map shows the landmarks (purple squares), the true path (grey, dotted) and
robot (grey), the filter's trail and robot (teal, lightly filled), its 2-sigma position
ellipse after the step's readings (teal) and before them (dashed purple, the
prediction), drawn over the robots so that a small ellipse still shows,
teal beams from the estimate to the landmarks the filter used at that step (to the
landmark it matched each reading to, when the readings carry no labels: chapter 11), and
dash-dot orange beams to those whose readings it rejected (outside its gate).

Under the map, two strips show the position error along x and along y over the
whole run, in metres, each with its band of plus or minus two standard deviations,
read from the filter's own covariance: they are drawn by
:mod:`kfcourse.plots.loop_strips`, whose functions this module offers too.

:func:`loop_view` draws the whole picture for a demo's model (anything with a run
record ``run`` and a step ``frame``), :func:`update_loop_view` shows the model's run and
step on it again; :func:`loop_chart` is the same picture once, for a notebook.

Every function takes a run record with the fields of
:class:`kfcourse.sim.LoopRun` (``t, dt, start, truth, landmarks, used,
rejected, matched, mu_bar, Sig_bar, mu, Sig, dropout, kidnap``); the ``update_*`` functions move what was drawn to
another step (or another run) in place.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse, Polygon
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
from .loop_strips import (
    NSIG,
    ErrorStrips,
    error_strips,
    kidnap_step,
    position_errors,
    run_step,
    strip_limit,
    update_error_strips,
)
from .style import new_figure

__all__ = [
    "ErrorStrips",
    "LoopMap",
    "LoopView",
    "error_strips",
    "loop_chart",
    "loop_figure",
    "loop_map",
    "loop_view",
    "position_errors",
    "strip_limit",
    "update_error_strips",
    "update_loop_map",
    "update_loop_view",
]

MAP_MARGIN = 1.5  # m of room around the landmarks and the true path
ROBOT_SIZE = 0.45  # m from the robot's centre to its nose
TRUTH_SIZE = 0.65  # m: the true robot is drawn larger, so it shows round an estimate on top of it
ROBOT_FILL = 0.3  # opacity of the estimated robot's fill: a small ellipse on top of it stays visible


def _truth_pieces(run) -> tuple[np.ndarray, np.ndarray]:
    """The true path before and after a kidnap (the second is empty without one)."""
    truth = np.asarray(run.truth)[:, :2]
    k0 = kidnap_step(run)
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
    beams: LineCollection  #: teal, to the landmarks the filter used its readings as
    rejected: LineCollection  #: dash-dot orange, to those whose readings were rejected
    note: Text  #: "sensor blind", "sight back", "kidnapped", or nothing

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
    k = run_step(run, k)
    marks = np.asarray(run.landmarks, float).reshape(-1, 2)
    points = np.vstack([marks, np.asarray(run.truth)[:, :2]])
    lo, hi = points.min(axis=0) - MAP_MARGIN, points.max(axis=0) + MAP_MARGIN
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    landmarks(ax, marks, label="landmarks", zorder=2)
    path = {"color": palette.TRUTH, "ls": palette.TRUTH_LINE, "lw": 3}
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
        ax, start, eye, nsig=NSIG, color=palette.PREDICTION, lw=1.3, zorder=5, label="2σ before readings"
    )
    ring = covariance_ellipse(ax, start, eye, nsig=NSIG, lw=2.0, zorder=6, label="2σ after readings")
    lines = beams(ax)
    refused = beams(ax, color=palette.MEASUREMENT, linestyles=palette.MEASUREMENT_LINE, lw=1.4)
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
            Ellipse((0, 0), 1, 1, fill=False, edgecolor=palette.PREDICTION, lw=1.3, ls=palette.PREDICTION_LINE),
            Line2D([], [], color=palette.ESTIMATE, lw=1.2),
            Line2D([], [], color=palette.MEASUREMENT, lw=1.4, ls=palette.MEASUREMENT_LINE),
        ]
        labels = ["landmark", "truth", "estimate", "2σ estimate", "2σ prediction", "reading used", "reading rejected"]
        ax.legend(
            handles, labels, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=4, fontsize=8.5, columnspacing=1.2
        )
    update_loop_map(view, run, k)
    return view


def update_loop_map(view: LoopMap, run, k: int) -> None:
    """Show step ``k`` of ``run`` (the same run or another one) on a map made by :func:`loop_map`."""
    k = run_step(run, k)
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
    used = np.asarray(run.used[k], bool)
    update_beams(view.beams, mu[k], marks[np.asarray(run.matched[k])[used]])  # to the landmark each was matched to
    update_beams(view.rejected, mu[k], marks[np.asarray(run.rejected[k], bool)])
    k0 = kidnap_step(run)
    if _blind(run, k):
        view.note.set_text("sensor blind")
    elif run.dropout is not None and k == run.dropout[1] and getattr(run, "one_back", False):
        view.note.set_text("sight back: one landmark first")
    elif k0 is not None and k >= k0:
        view.note.set_text("kidnapped: the truth jumped, the filter was not told")
    else:
        view.note.set_text("")


# --------------------------------------------------------------------------- the whole picture

STRIP_HEIGHT = 1.15  # inches per error strip
LEGEND_HEIGHT = 0.45  # inches above the map for its legend (two rows)


def loop_figure(run, width: float = 6.4, strip_height: float = STRIP_HEIGHT, legend: bool = True):
    """A figure with the map above and the two error strips under it.

    The map shows metres at the same scale across and up; the figure is as tall as
    that needs, plus the strips and the legend.  Introduced in chapter 10.

    Parameters
    ----------
    run : LoopRun
        Its landmarks and true path set the map's extent.
    width : float
        Inches.
    strip_height : float
        Inches per strip.
    legend : bool
        Leave room for the map's legend above it.

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
        map_height + 2 * strip_height + (LEGEND_HEIGHT if legend else 0.0),
        nrows=3,
        gridspec_kw={"height_ratios": [map_height, strip_height, strip_height]},
    )
    axes[2].sharex(axes[1])
    axes[1].tick_params(labelbottom=False)
    return fig, axes[0], (axes[1], axes[2])


@dataclass(frozen=True)
class LoopView:
    """What :func:`loop_view` drew: the figure, its map and its error strips."""

    fig: Figure
    map: LoopMap
    strips: ErrorStrips

    @property
    def moving(self) -> list:
        """Every artist that changes with the step or the run: the map's, then the strips'."""
        return [*self.map.moving, *self.strips.moving]


def loop_view(model) -> LoopView:
    """The map with the error strips under it, at the model's run and step.

    Introduced in chapter 10.

    Parameters
    ----------
    model : object
        Anything with a run record ``run`` (fields of :class:`kfcourse.sim.LoopRun`)
        and the step shown, ``frame``.  The map's extent comes from this run's map
        and true path; later runs must drive the same loop.

    Returns
    -------
    LoopView
    """
    fig, ax_map, strip_axes = loop_figure(model.run)
    view = loop_map(ax_map, model.run, model.frame)
    strips = error_strips(strip_axes, model.run, model.frame)
    return LoopView(fig, view, strips)


def update_loop_view(view: LoopView, model) -> None:
    """Show the model's run at its step ``frame`` on a picture made by :func:`loop_view`.

    A new step moves only the artists in :attr:`LoopView.moving`; a new run may also
    change the strips' limits (:func:`strip_limit`), set only when they change.
    """
    update_loop_map(view.map, model.run, model.frame)
    update_error_strips(view.strips, model.run, model.frame)


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
    k = run_step(run, k)
    fig, ax_map, strip_axes = loop_figure(run)
    loop_map(ax_map, run, k)
    error_strips(strip_axes, run, k)
    return fig
